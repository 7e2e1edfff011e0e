"""The platform libraries every FMU carries (docs/platforms.md):

- binaries/linux64 loads on any x86_64 Linux with glibc 2.17 or later: the versioned symbols it
  needs (read with readelf, from binutils) name nothing newer, no mathematical function comes
  from the system's C library (the libm crate gives the same bits everywhere), no symbol table;
- it gives the same bits as this machine's own build on BuckledBeam's default experiment;
- `georod fmu --binary PLATFORM=FILE` packs a library built elsewhere after checking its format,
  architecture and FMI 2.0 exports, and refuses a wrong one with a message naming the file.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import zipfile
from pathlib import Path

import fmpy
import numpy as np
import pytest

from helpers import C_MATH, GEOROD_CLI, LIBS_DIR, REPO, SCENES, FmuInfo, run_cmd, trajectory

#: This machine's own library (its toolchain and glibc), quick profile: scripts/test builds it
#: beside the Rust tests and copies it to target/libs/native/; built here when missing.
NATIVE_LIB = LIBS_DIR / "native" / "libgeorod.so"

GLIBC_BASELINE = (2, 17)


def win64_library(info: FmuInfo) -> Path:
    """binaries/win64/<model>.dll of the extracted FMU (scripts/install_test_deps installs the
    toolchain that builds it)."""
    dll = info.unzipdir / "binaries" / "win64" / f"{info.md.coSimulation.modelIdentifier}.dll"
    if not dll.is_file():
        pytest.fail(f"{info.path.name} has no binaries/win64: run scripts/install_test_deps")
    return dll


def readelf(args: list[str], lib: Path) -> str:
    exe = shutil.which("readelf")
    if exe is None:
        pytest.fail("readelf not found: install binutils (apt-get install binutils)")
    r = subprocess.run([exe, "-W", *args, str(lib)], capture_output=True, text=True, check=False)
    assert r.returncode == 0, f"readelf {args} {lib}: {r.stderr}"
    return r.stdout


def linux64_library(fmu: Path, out: Path) -> Path:
    """binaries/linux64/<model>.so of `fmu`, written to `out`."""
    with zipfile.ZipFile(fmu) as z:
        names = [n for n in z.namelist() if n.startswith("binaries/linux64/")]
        assert len(names) == 1, f"{fmu.name}: binaries/linux64 holds {names}"
        out.write_bytes(z.read(names[0]))
    return out


@pytest.mark.parametrize("scene", SCENES)
def test_linux64_library_needs_glibc_2_17_at_most(
    fmu_paths: dict[str, Path], tmp_path: Path, scene: str
) -> None:
    lib = linux64_library(fmu_paths[scene], tmp_path / "lib.so")
    needs = {
        tuple(int(x) for x in v.split("."))
        for v in re.findall(r"Name: GLIBC_([0-9.]+)", readelf(["--version-info"], lib))
    }
    assert needs, f"{scene}: no glibc version needs read (readelf output changed?)"
    newer = sorted(v for v in needs if v > GLIBC_BASELINE)
    assert not newer, f"{scene}: binaries/linux64 needs glibc {newer}, newer than 2.17"

    undefined = set(re.findall(r"\bUND\s+(\w+)", readelf(["--dyn-syms"], lib)))
    math = sorted(undefined & C_MATH)
    assert not math, f"{scene}: math functions from the C library: {math}"
    assert ".symtab" not in readelf(["--section-headers"], lib), f"{scene}: not stripped"


def test_linux64_library_same_bits_as_native_build(
    fmus: dict[str, FmuInfo], tmp_path: Path
) -> None:
    """BuckledBeam's default experiment (0.1 s in steps of 1e-4, chaotic) with the packed
    library and with this machine's own (its toolchain and glibc, NATIVE_LIB)."""
    native = NATIVE_LIB
    if not native.is_file():
        build = run_cmd(["cargo", "build", "--profile", "quick", "--lib"], timeout=1200)
        native = REPO / "target" / "quick" / "libgeorod.so"
        assert build.returncode == 0 and native.is_file(), build.stderr[-3000:]
    native_fmu = tmp_path / "BuckledBeam.fmu"
    r = run_cmd(
        [GEOROD_CLI, "fmu", REPO / "scenes" / "BuckledBeam.toml", "-o", native_fmu]
        + ["--lib", native]
    )
    assert r.returncode == 0, r.stderr
    unzipdir = Path(fmpy.extract(str(native_fmu), unzipdir=str(tmp_path / "native")))
    packed = fmus["BuckledBeam"]
    native = FmuInfo.from_model_description(
        "BuckledBeam", native_fmu, unzipdir, fmpy.read_model_description(str(unzipdir))
    )
    experiment = packed.md.defaultExperiment
    h, stop = float(experiment.stepSize), float(experiment.stopTime)
    n = round(stop / h)
    a = trajectory(packed, None, h, n, names=["w_mid"])
    b = trajectory(native, None, h, n, names=["w_mid"])
    assert a.tobytes() == b.tobytes(), f"w_mid differs from step {np.argmax(a != b)}"


def fmu_command(tmp_path: Path, *binaries: str) -> subprocess.CompletedProcess[str]:
    out = tmp_path / "Beam.fmu"
    args = [a for b in binaries for a in ("--binary", b)]
    return run_cmd([GEOROD_CLI, "fmu", REPO / "scenes" / "BuckledBeam.toml", "-o", out, *args])


def test_binary_packs_the_given_libraries_and_names_the_missing(
    fmus: dict[str, FmuInfo], tmp_path: Path
) -> None:
    linux = fmus["BuckledBeam"].library
    dll = win64_library(fmus["BuckledBeam"])
    r = fmu_command(tmp_path, f"linux64={linux}", f"win64={dll}")
    assert r.returncode == 0, r.stderr
    with zipfile.ZipFile(tmp_path / "Beam.fmu") as z:
        binaries = sorted(n for n in z.namelist() if n.startswith("binaries/"))
    assert binaries == ["binaries/linux64/BuckledBeam.so", "binaries/win64/BuckledBeam.dll"]
    assert "no darwin64 library, binaries/darwin64 left out" in r.stderr
    assert "--binary darwin64=" in r.stderr


@pytest.mark.parametrize(
    ("binary", "message"),
    [
        ("win64={linux}", "not a win64 library: expected a PE32+ DLL for x86_64, found Elf"),
        ("linux64={dll}", "not a linux64 library: expected an ELF shared library"),
        ("darwin64={linux}", "not a darwin64 library: expected a Mach-O dynamic library"),
        ("linux64={scene}", "not a linux64 library: expected an ELF shared library for x86_64, "),
        ("linux64={other}", "the linux64 library does not export 34 of the FMI 2.0 functions"),
        ("win32={linux}", "--binary unknown platform `win32`: use linux64, win64 or darwin64"),
        ("linux64", "--binary takes PLATFORM=FILE (linux64, win64, darwin64), not `linux64`"),
        ("linux64={tmp}/none.so", "cannot read the linux64 library"),
    ],
    ids=[
        "elf-as-win64",
        "dll-as-linux64",
        "elf-as-darwin64",
        "text",
        "no-fmi",
        "win32",
        "form",
        "none",
    ],
)
def test_binary_refuses_a_wrong_library(
    fmus: dict[str, FmuInfo], tmp_path: Path, binary: str, message: str
) -> None:
    other = Path(fmpy.__file__).parent / "logging" / "linux64" / "logging.so"
    if not other.is_file():
        pytest.fail(
            f"{other}: fmpy's own shared library (a library without FMI functions) is missing"
        )
    spec = binary.format(
        linux=fmus["BuckledBeam"].library,
        dll=win64_library(fmus["BuckledBeam"]),
        scene=REPO / "scenes" / "BuckledBeam.toml",
        other=other,
        tmp=tmp_path,
    )
    r = fmu_command(tmp_path, spec)
    assert r.returncode != 0, r.stdout
    assert message in r.stderr, r.stderr
    assert not (tmp_path / "Beam.fmu").exists()


def test_fmu_without_binary_packs_what_build_fmus_built(
    fmu_paths: dict[str, Path], tmp_path: Path
) -> None:
    """Without --binary or --lib, `georod fmu` takes the linux64 (glibc 2.17) and win64 libraries
    that scripts/build_libs left in target/libs, and says darwin64 is left out."""
    out = tmp_path / "Beam.fmu"
    r = run_cmd([GEOROD_CLI, "fmu", REPO / "scenes" / "BuckledBeam.toml", "-o", out])
    assert r.returncode == 0, r.stderr
    assert f"binaries/linux64: {LIBS_DIR / 'libgeorod.so'}" in r.stdout, r.stdout
    assert f"binaries/win64: {LIBS_DIR / 'georod.dll'}" in r.stdout, r.stdout
    assert "no darwin64 library" in r.stderr
    with zipfile.ZipFile(out) as z, zipfile.ZipFile(fmu_paths["BuckledBeam"]) as built:
        for name in ("binaries/linux64/BuckledBeam.so", "binaries/win64/BuckledBeam.dll"):
            assert z.read(name) == built.read(name), name
