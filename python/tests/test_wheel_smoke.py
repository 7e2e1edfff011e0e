"""A wheel of georod, smoke version (docs/python.md; the full one is scripts/test_wheels): packed
by python/hatch_build.py from what scripts/build_fmus built (this machine's georod command, the
glibc-2.17 linux64 and the win64 libraries, nothing rebuilt: tag linux_x86_64, since this
command needs this machine's glibc), installed into a fresh venv whose PATH holds no Rust:

- `georod --version` is the package's version; `georod fmu` packs the bundle's linux64 and win64
  libraries (FMI 3.0 names too) into the same bytes as the source checkout's command given the
  same libraries, and its FMU runs in fmpy to the cantilever's closed-form tip deflection;
- a bad scene is refused with the checkout's message; a bundle library missing or damaged is
  named, with how to rebuild; the Python API (georod_tools.package/check/simulate) and
  `georod-tools` run from the wheel.
"""

from __future__ import annotations

import shutil
import zipfile
from pathlib import Path

import fmpy
import pytest

from helpers import GEOROD_CLI, REPO
from wheel_env import VERSION, Venv, bundle_of, fresh_venv, pack, require, run, stage

pytestmark = pytest.mark.timeout(120)

TARGET = REPO / "target"


def built(*places: Path) -> Path:
    """The first of `places` that exists (target/libs/, where scripts/build_libs puts what it
    builds, then cargo's own target folder), else the last (require() names it)."""
    return next((p for p in places if p.is_file()), places[-1])


LINUX64 = built(
    TARGET / "libs" / "libgeorod.so",
    TARGET / "x86_64-unknown-linux-gnu" / "release" / "libgeorod.so",
)
WIN64 = built(
    TARGET / "libs" / "georod.dll", TARGET / "x86_64-pc-windows-gnu" / "release" / "georod.dll"
)
CANTILEVER = REPO / "examples" / "Cantilever.toml"


@pytest.fixture(scope="module")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    require(GEOROD_CLI, LINUX64, WIN64)
    root = tmp_path_factory.mktemp("wheel")
    bundle = stage(root / "stage", GEOROD_CLI, {"linux64": LINUX64, "win64": WIN64})
    return pack(bundle, "linux_x86_64", root / "dist")


@pytest.fixture(scope="module")
def venv(tmp_path_factory: pytest.TempPathFactory, wheel: Path) -> Venv:
    return fresh_venv(tmp_path_factory.mktemp("venv") / "fresh", wheel, "borrowed")


def test_the_wheel_holds_the_command_every_library_and_their_manifest(wheel: Path) -> None:
    files = bundle_of(wheel)
    assert sorted(files) == ["bundle.toml", "georod", "linux64/libgeorod.so", "win64/georod.dll"]
    assert files["linux64/libgeorod.so"] == LINUX64.read_bytes()
    assert files["win64/georod.dll"] == WIN64.read_bytes()
    with zipfile.ZipFile(wheel) as z:
        mode = z.getinfo("georod_tools/bin/georod").external_attr >> 16
        entry_points = z.read(f"georod-{VERSION}.dist-info/entry_points.txt").decode()
    assert mode & 0o111, "the command is executable"
    assert "georod = georod_tools.command:start" in entry_points
    assert "georod-tools = georod_tools.cli:entry" in entry_points


def test_installed_georod_packs_every_platform_like_the_checkout(
    venv: Venv, tmp_path: Path
) -> None:
    r = venv.run("georod", "--version")
    assert (r.returncode, r.stdout) == (0, f"georod {VERSION}\n"), r.stderr
    # Default output: the working directory (never the installation).
    r = venv.run("georod", "fmu", CANTILEVER, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    fmu = tmp_path / "Cantilever.fmu"
    with zipfile.ZipFile(fmu) as z:
        assert z.read("binaries/linux64/Cantilever.so") == LINUX64.read_bytes()
        assert z.read("binaries/win64/Cantilever.dll") == WIN64.read_bytes()
    assert "no darwin64 library" in r.stderr
    checkout = tmp_path / "checkout.fmu"
    binaries = ["--binary", f"linux64={LINUX64}", "--binary", f"win64={WIN64}"]
    r = run([GEOROD_CLI, "fmu", CANTILEVER, "-o", checkout, *binaries])
    assert r.returncode == 0, r.stderr
    assert fmu.read_bytes() == checkout.read_bytes(), "the same FMU, byte for byte"

    r = venv.run("georod", "fmu", CANTILEVER, "--fmi", "3", "-o", tmp_path / "c3.fmu")
    assert r.returncode == 0, r.stderr
    with zipfile.ZipFile(tmp_path / "c3.fmu") as z:
        names = set(z.namelist())
    assert "binaries/x86_64-linux/Cantilever.so" in names
    assert "binaries/x86_64-windows/Cantilever.dll" in names


def test_fmu_from_the_wheel_gives_the_cantilever_tip_deflection(venv: Venv, tmp_path: Path) -> None:
    """Static tip deflection under a small tip load P: P L^3 / (3 EI) + P L / (G A) (shear
    factor 1, docs/model.md), from the FMU's initial state in fmpy. The element converges as
    1 / n^2: 6e-4 off at the scene's 20 elements, 4e-5 at 80."""
    fmu = tmp_path / "Cantilever.fmu"
    assert venv.run("georod", "fmu", CANTILEVER, "-o", fmu).returncode == 0
    P, L, E, nu, b, h = 0.5, 2.0, 210e9, 0.3, 0.05, 0.01
    EI, GA = E * b * h**3 / 12, E / (2 * (1 + nu)) * b * h
    expected = -(P * L**3 / (3 * EI) + P * L / GA)
    result = fmpy.simulate_fmu(
        str(fmu),
        stop_time=1e-3,
        output_interval=1e-3,
        start_values={"P": P, "elements": 80},
        output=["w_tip"],
    )
    w0 = float(result["w_tip"][0])
    assert w0 == pytest.approx(expected, rel=1e-4), (w0, expected)


def test_bad_scene_is_refused_with_the_checkouts_message(venv: Venv, tmp_path: Path) -> None:
    scene = tmp_path / "bad.toml"
    scene.write_text(CANTILEVER.read_text().replace('shape = "straight"', 'shape = "twisted"'))
    wheel_run = venv.run("georod", "fmu", scene, "-o", tmp_path / "bad.fmu")
    source_run = run([GEOROD_CLI, "fmu", scene, "-o", tmp_path / "bad.fmu"])
    assert wheel_run.returncode == source_run.returncode == 1
    assert wheel_run.stderr == source_run.stderr and "twisted" in wheel_run.stderr
    assert not (tmp_path / "bad.fmu").exists()


@pytest.mark.parametrize("damage", ["missing", "damaged"])
def test_a_missing_or_damaged_bundle_library_is_named_with_how_to_rebuild(
    venv: Venv, tmp_path: Path, damage: str
) -> None:
    dll = venv.site_packages / "georod_tools" / "bin" / "win64" / "georod.dll"
    kept = tmp_path / "georod.dll"
    shutil.copy2(dll, kept)
    try:
        if damage == "missing":
            dll.unlink()
        else:
            data = bytearray(kept.read_bytes())
            data[len(data) // 2] ^= 0xFF
            dll.write_bytes(bytes(data))
        r = venv.run("georod", "fmu", CANTILEVER, "-o", tmp_path / "x.fmu")
    finally:
        shutil.copy2(kept, dll)
    assert r.returncode == 1
    assert f"the win64 library of this installation is {damage}: {dll}" in r.stderr
    assert "scripts/build_wheels" in r.stderr and "pip install --force-reinstall" in r.stderr
    assert not (tmp_path / "x.fmu").exists()


def test_python_api_and_tools_from_the_wheel(venv: Venv, tmp_path: Path) -> None:
    script = f"""
import georod_tools as georod
from georod_tools import command
assert command.is_installed() and not command.is_checkout(), command.BUNDLE_DIR
fmu = georod.package({str(CANTILEVER)!r}, {str(tmp_path / "api.fmu")!r}, fmi=3)
print(fmu)
check = georod.check({str(CANTILEVER)!r})
run = georod.simulate({str(CANTILEVER)!r}, step=1e-3, stop=2e-3, outputs=["w_tip"])
print(check.sensors["w_tip"], run["w_tip"][0], len(run["time"]))
try:
    georod.check({str(REPO / "README.md")!r})
except georod.GeorodError as e:
    print("refused", e.status)
"""
    r = venv.run("python", "-c", script, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == str(tmp_path / "api.fmu")
    w_check, w_run, steps = lines[1].split()
    assert float(w_check) == pytest.approx(float(w_run), rel=1e-6) and steps == "3"
    assert lines[2] == "refused 1"
    r = venv.run("georod-tools", "--help")
    assert r.returncode == 0 and "animate" in r.stdout, r.stderr
