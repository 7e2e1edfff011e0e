"""Every FMU's binaries/win64 library, run under wine by a small C host (win64_host.c, compiled
with mingw-w64) from the extracted FMU, against the linux64 library run through fmpy: the same
bits at every step, get/set state, a state serialized on one platform continuing bit for bit on
the other, and a refused bad value.

The bits agree by construction: both libraries are built from the same Rust code by rustc (no
floating-point contraction or reordering) and take every mathematical function from the libm
crate, never from the platform's C library. Wine 8 lacks bcryptprimitives.dll (ProcessPrng, on
every Windows since 10): a test-only stand-in (wine_bcryptprimitives.c) lies beside the host.

Needs gcc-mingw-w64-x86-64 and wine64 (scripts/install_platform_deps, which scripts/test runs).
"""

from __future__ import annotations

import os
import re
import shutil
import struct
import subprocess
from collections.abc import Iterator
from pathlib import Path

import fmpy
import pytest

from helpers import C_MATH, FMU_DIR, REPO, SCENE_FILES, FmuInfo, instantiate, release

HERE = Path(__file__).resolve().parent
WINE = Path("/usr/lib/wine/wine64")
MINGW = "x86_64-w64-mingw32-gcc"
#: The wine prefix, made once and kept with the build outputs.
PREFIX = REPO / "target" / "wine"
STEPS = 40  # per FMU; BuckledBeam's whole default experiment has its own test
REFUSED = 3  # fmi2Error


@pytest.fixture(scope="session")
def host(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The host executable, with the ProcessPrng stand-in beside it."""
    missing = [t for t in (MINGW,) if shutil.which(t) is None]
    missing += [str(WINE)] if not WINE.exists() else []
    if missing:
        pytest.fail(
            f"{', '.join(missing)} missing: install gcc-mingw-w64-x86-64 and wine64 "
            "(scripts/install_platform_deps)"
        )
    out = tmp_path_factory.mktemp("win64_host")
    for cmd in (
        [MINGW, "-O2", "-Wall", "-Werror", "-o", out / "host.exe", HERE / "win64_host.c"],
        [MINGW, "-O2", "-Wall", "-Werror", "-shared", "-o", out / "bcryptprimitives.dll"]
        + [HERE / "wine_bcryptprimitives.c", "-ladvapi32"],
    ):
        r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, check=False)
        assert r.returncode == 0, f"{' '.join(map(str, cmd))}:\n{r.stderr}"
    return out / "host.exe"


def wine_env() -> dict[str, str]:
    return {
        **os.environ,
        "WINEPREFIX": str(PREFIX),
        "WINEDEBUG": "-all",
        # No Mono or Gecko install prompt when the prefix is made.
        "WINEDLLOVERRIDES": "mscoree,mshtml=",
    }


@pytest.fixture(scope="session")
def extracted(
    tmp_path_factory: pytest.TempPathFactory, fmu_paths: dict[str, Path]
) -> Iterator[dict[str, FmuInfo]]:
    """Every FMU that scripts/build_fmus packs (scenes and examples), extracted once."""
    root = tmp_path_factory.mktemp("win64_fmus")
    infos = {}
    for scene in SCENE_FILES:
        fmu = FMU_DIR / f"{scene.stem}.fmu"
        unzipdir = Path(fmpy.extract(str(fmu), unzipdir=str(root / scene.stem)))
        md = fmpy.read_model_description(str(unzipdir))
        info = FmuInfo.from_model_description(scene.stem, fmu, unzipdir, md)
        dll = unzipdir / "binaries" / "win64" / f"{md.coSimulation.modelIdentifier}.dll"
        if not dll.is_file():
            pytest.fail(f"{fmu.name} has no binaries/win64: run scripts/install_platform_deps")
        infos[scene.stem] = info
    yield infos


def run_host(
    host: Path,
    info: FmuInfo,
    h: float,
    n: int,
    state_in: Path | None = None,
    state_out: Path | None = None,
    k0: int = 0,
) -> tuple[list[int], list[str]]:
    """The host's bits of the watched output after each of n steps from step k0, and its
    other lines."""
    args = [str(WINE), str(host), "Z:" + str(info.unzipdir).replace("/", "\\")]
    args += [info.md.coSimulation.modelIdentifier, info.md.guid]
    args += [str(watched(info)), str(info.vr["E"]), repr(h), str(k0), str(n)]
    if state_in or state_out:
        args.append("Z:" + str(state_in) if state_in else "-")
    if state_out:
        args.append("Z:" + str(state_out))
    r = subprocess.run(args, capture_output=True, text=True, env=wine_env(), timeout=600)
    assert r.returncode == 0, f"win64 host on {info.scene} ({r.returncode}):\n{r.stderr[-3000:]}"
    bits, other = [], []
    for line in r.stdout.splitlines():
        if line.startswith("step "):
            bits.append(int(line.split()[2], 16))
        else:
            other.append(line)
    return bits, other


def watched(info: FmuInfo) -> int:
    """The value reference compared at each step: w_mid, else the scene's first Real output."""
    if "w_mid" in info.vr:
        return info.vr["w_mid"]
    outputs = [v for v in info.md.modelVariables if v.causality == "output" and v.type == "Real"]
    assert outputs, f"{info.scene}: no Real output"
    return outputs[0].valueReference


def as_bits(x: float) -> int:
    return struct.unpack("<Q", struct.pack("<d", x))[0]


def linux64_run(
    info: FmuInfo, h: float, n: int, state_in: bytes | None = None, k0: int = 0
) -> tuple[list[int], bytes]:
    """The linux64 library through fmpy: the watched output's bits after each of n steps (from
    step k0, after deserializing `state_in` when given), and the state serialized at the end."""
    slave = instantiate(info)
    try:
        if state_in is not None:
            slave.setFMUstate(slave.deSerializeFMUstate(state_in))
        out = []
        for k in range(k0, k0 + n):
            slave.doStep(k * h, h)
            out.append(as_bits(slave.getReal([watched(info)])[0]))
        return out, bytes(slave.serializeFMUstate(slave.getFMUstate()))
    finally:
        release(slave)


@pytest.mark.parametrize("scene", [s.stem for s in SCENE_FILES])
def test_win64_library_steps_like_linux64(
    host: Path, extracted: dict[str, FmuInfo], tmp_path: Path, scene: str
) -> None:
    info = extracted[scene]
    h = float(info.md.defaultExperiment.stepSize)
    expected, linux_state = linux64_run(info, h, STEPS)
    state_file = tmp_path / "win64.state"
    bits, lines = run_host(host, info, h, STEPS, state_out=state_file)
    assert bits == expected, (
        f"{scene}: the output differs from step {first_difference(bits, expected)}"
    )
    assert "states identical" in lines
    assert f"bad value refused {REFUSED}" in lines, lines

    # The win64 state, restored in the linux64 library, continues as linux64's own state does.
    then_linux, _ = linux64_run(info, h, STEPS, linux_state, k0=STEPS)
    then_win, _ = linux64_run(info, h, STEPS, state_file.read_bytes(), k0=STEPS)
    assert then_win == then_linux, f"{scene}: the win64 state continues differently on linux64"


def first_difference(a: list[int], b: list[int]) -> int:
    return next((i for i, (x, y) in enumerate(zip(a, b, strict=False)) if x != y), len(a))


def test_buckled_beam_default_experiment_bit_identical_and_state_crosses(
    host: Path, extracted: dict[str, FmuInfo], tmp_path: Path
) -> None:
    """The chaotic BuckledBeam over its whole default experiment (0.1 s in steps of 1e-4): every
    w_mid bit-identical; then a state serialized by linux64 continues on win64 bit for bit."""
    info = extracted["BuckledBeam"]
    experiment = info.md.defaultExperiment
    h = float(experiment.stepSize)
    n = round(float(experiment.stopTime) / h)
    expected, state = linux64_run(info, h, n)
    bits, _ = run_host(host, info, h, n)
    assert len(bits) == n
    assert bits == expected, f"w_mid differs from step {first_difference(bits, expected)}"

    state_file = tmp_path / "linux64.state"
    state_file.write_bytes(state)
    later = 200
    then_linux, _ = linux64_run(info, h, later, state, k0=n)
    then_win, _ = run_host(host, info, h, later, state_in=state_file, k0=n)
    assert then_win == then_linux, "a linux64 state continues differently on win64"


#: C-library functions the win64 library may import: exact by definition (no rounding), so they
#: cannot make a platform difference; every other mathematical function comes from libm (crate).
EXACT_C_MATH = {"floor", "ceil", "fmod", "trunc", "round", "fabs", "copysign"}


def test_win64_library_imports_no_inexact_c_math(extracted: dict[str, FmuInfo]) -> None:
    objdump = shutil.which("x86_64-w64-mingw32-objdump")
    if objdump is None:
        pytest.fail("x86_64-w64-mingw32-objdump missing: install binutils-mingw-w64-x86-64")
    info = extracted["BuckledBeam"]
    dll = info.unzipdir / "binaries" / "win64" / f"{info.md.coSimulation.modelIdentifier}.dll"
    r = subprocess.run([objdump, "-p", str(dll)], capture_output=True, text=True, check=False)
    assert r.returncode == 0, r.stderr
    imported = set(re.findall(r"^\s+[0-9a-f]+\s+\d+\s+(\w+)$", r.stdout, flags=re.MULTILINE))
    assert "ProcessPrng" in imported, "the import table was not read (objdump output changed?)"
    math = sorted((imported & C_MATH) - EXACT_C_MATH)
    assert not math, f"the win64 library takes {math} from the C library"
