"""The wheels and source distribution that scripts/build_wheels writes into dist/, as a user gets
them (run by scripts/test_wheels, marker `wheels`: not in the normal suite, whose smoke version
is test_wheel_smoke.py):

- every ELF of the Linux wheel needs GLIBC_2.17 at most (readelf); the Windows wheel holds PE32+
  files; both carry the same linux64 and win64 libraries;
- the Linux wheel, installed with its declared dependencies into a fresh venv whose PATH has no
  Rust, runs `georod --version | fmu | check | modes | simulate` and `georod-tools case | sweep
  | animate`, and its FMU simulated by that venv's fmpy gives the cantilever's closed form;
- `georod.exe fmu` of the Windows wheel under wine writes FMUs (FMI 2.0 and 3.0) byte-identical
  to the Linux wheel's, and refuses a bad scene with the same message;
- the source distribution installs with cargo at hand and stops, without it, saying that Rust
  is needed.
"""

from __future__ import annotations

import hashlib
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from helpers import REPO
from test_fmu_win64 import MINGW, WINE, wine_env
from wheel_env import VERSION, Venv, bundle_of, fresh_venv, run

pytestmark = [pytest.mark.wheels, pytest.mark.timeout(900)]

DIST = REPO / "dist"
LINUX_TAG = "manylinux_2_17_x86_64.manylinux2014_x86_64"
CANTILEVER = REPO / "examples" / "Cantilever.toml"


def dist_file(name: str) -> Path:
    path = DIST / name
    if not path.is_file():
        pytest.fail(f"{path} missing: run scripts/build_wheels (scripts/test_wheels does)")
    return path


@pytest.fixture(scope="module")
def linux_wheel() -> Path:
    return dist_file(f"georod-{VERSION}-py3-none-{LINUX_TAG}.whl")


@pytest.fixture(scope="module")
def windows_wheel() -> Path:
    return dist_file(f"georod-{VERSION}-py3-none-win_amd64.whl")


@pytest.fixture(scope="module")
def venv(tmp_path_factory: pytest.TempPathFactory, linux_wheel: Path) -> Venv:
    """The Linux wheel with its dependencies resolved by pip, as a user installs it."""
    return fresh_venv(tmp_path_factory.mktemp("venv") / "user", linux_wheel, "installed")


def entries(archive: Path) -> set[str]:
    with zipfile.ZipFile(archive) as z:
        return set(z.namelist())


def glibc_needs(elf: Path) -> set[tuple[int, ...]]:
    r = run(["readelf", "-W", "--version-info", elf])
    assert r.returncode == 0, r.stderr
    return {tuple(map(int, v.split("."))) for v in re.findall(r"Name: GLIBC_([0-9.]+)", r.stdout)}


def test_every_elf_of_the_linux_wheel_needs_glibc_2_17_at_most(
    linux_wheel: Path, windows_wheel: Path, tmp_path: Path
) -> None:
    elves = 0
    with zipfile.ZipFile(linux_wheel) as z:
        for name in z.namelist():
            data = z.read(name)
            if data[:4] == b"\x7fELF":
                elves += 1
                (tmp_path / "elf").write_bytes(data)
                needs = glibc_needs(tmp_path / "elf")
                assert needs and max(needs) <= (2, 17), f"{name} needs glibc {sorted(needs)}"
    assert elves == 2, "the command and the linux64 library"
    linux, windows = bundle_of(linux_wheel), bundle_of(windows_wheel)
    libraries = ["linux64/libgeorod.so", "win64/georod.dll"]
    assert sorted(windows) == ["bundle.toml", "georod.exe", *libraries]
    assert windows["georod.exe"][:2] == b"MZ" and windows["win64/georod.dll"][:2] == b"MZ"
    for lib in ("linux64/libgeorod.so", "win64/georod.dll", "bundle.toml"):
        assert linux[lib] == windows[lib], f"{lib}: the same in both wheels"


def test_the_installed_wheel_runs_every_command_without_rust(venv: Venv, tmp_path: Path) -> None:
    r = venv.run("python", "-c", "import importlib.metadata as m; print(m.version('georod'))")
    assert r.stdout.strip() == VERSION, r.stderr
    assert venv.run("georod", "--version").stdout == f"georod {VERSION}\n"
    scene = tmp_path / "my.toml"
    shutil.copy(CANTILEVER, scene)
    for args in (["fmu", "my.toml"], ["fmu", "my.toml", "--fmi", "3", "-o", "my3.fmu"]):
        r = venv.run("georod", *args, cwd=tmp_path)
        assert r.returncode == 0, r.stderr
    two = {"binaries/linux64/Cantilever.so", "binaries/win64/Cantilever.dll"}
    assert two <= entries(tmp_path / "Cantilever.fmu")
    three = {"binaries/x86_64-linux/Cantilever.so", "binaries/x86_64-windows/Cantilever.dll"}
    assert three <= entries(tmp_path / "my3.fmu")
    r = venv.run("georod", "check", "my.toml", cwd=tmp_path)
    assert r.returncode == 0 and "scene Cantilever is valid" in r.stdout, r.stderr
    r = venv.run("georod", "modes", "my.toml", "--count", "2", cwd=tmp_path)
    assert r.returncode == 0 and (tmp_path / "my_modes.csv").is_file(), r.stderr
    simulate = ["simulate", "--scene", "my.toml", "--step", "1e-3", "--stop", "0.01"]
    r = venv.run("georod", *simulate, "--outputs", "w_tip", cwd=tmp_path)
    assert r.returncode == 0 and r.stdout.startswith("time,w_tip\n"), r.stderr

    fmu = tmp_path / "Cantilever.fmu"
    quick = ["--substeps", "16", "--transient", "2", "--periods", "4", "--no-lyapunov"]
    for args in (
        ["case", "--fmu", fmu, "--period", "0.05", *quick, "--dense-periods", "2"]
        + ["--out", tmp_path / "case"],
        ["sweep", "--fmu", fmu, "--period", "0.05", *quick, "--workers", "1", "--param", "P"]
        + ["--start", "0.5", "--stop", "1", "--count", "2", "--out", tmp_path / "sweep"],
        ["animate", fmu, "--stop", "2e-3", "--step", "1e-3", "-o", tmp_path / "a.gif"],
    ):
        r = venv.run("georod-tools", *args, cwd=tmp_path, timeout=600)
        assert r.returncode == 0, f"georod-tools {args[0]}:\n{r.stderr[-3000:]}"
    assert (tmp_path / "a.gif").is_file()


def test_the_wheels_fmu_in_the_wheels_fmpy_meets_the_closed_form(
    venv: Venv, tmp_path: Path
) -> None:
    """Static tip deflection under a small tip load: P L^3 / (3 EI) + P L / (G A) (80 elements:
    4e-5 off, test_wheel_smoke.py says why)."""
    assert venv.run("georod", "fmu", CANTILEVER, "-o", tmp_path / "c.fmu").returncode == 0
    P, L, E, nu, b, h = 0.5, 2.0, 210e9, 0.3, 0.05, 0.01
    expected = -(P * L**3 / (3 * E * b * h**3 / 12) + P * L / (E / (2 * (1 + nu)) * b * h))
    script = (
        "import fmpy; r = fmpy.simulate_fmu('c.fmu', stop_time=1e-3, output_interval=1e-3, "
        f"start_values={{'P': {P!r}, 'elements': 80}}, output=['w_tip']); "
        "print(repr(float(r['w_tip'][0])))"
    )
    r = venv.run("python", "-c", script, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert float(r.stdout) == pytest.approx(expected, rel=1e-4)


@pytest.fixture(scope="module")
def windows_georod(tmp_path_factory: pytest.TempPathFactory, windows_wheel: Path) -> Path:
    """The Windows wheel's bundle, extracted, with wine's missing bcryptprimitives.dll (a
    test-only stand-in, python/tests/wine_bcryptprimitives.c) beside georod.exe."""
    if shutil.which(MINGW) is None or not WINE.exists():
        pytest.fail("mingw-w64 and wine64 missing: run scripts/install_platform_deps")
    bundle = tmp_path_factory.mktemp("windows") / "bin"
    for path, data in bundle_of(windows_wheel).items():
        (bundle / path).parent.mkdir(parents=True, exist_ok=True)
        (bundle / path).write_bytes(data)
    source = REPO / "python" / "tests" / "wine_bcryptprimitives.c"
    cmd = [MINGW, "-O2", "-shared", "-o", bundle / "bcryptprimitives.dll", source, "-ladvapi32"]
    r = run(cmd)
    assert r.returncode == 0, r.stderr
    return bundle / "georod.exe"


def wine(exe: Path, *args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return run([WINE, exe, *args], cwd=cwd, env=wine_env(), timeout=600)


@pytest.mark.parametrize("fmi", ["2", "3"])
def test_windows_and_linux_wheels_write_byte_identical_fmus(
    venv: Venv, windows_georod: Path, tmp_path: Path, fmi: str
) -> None:
    shutil.copy(CANTILEVER, tmp_path / "my.toml")
    args = ["fmu", "my.toml", "--fmi", fmi, "-o"]
    r = wine(windows_georod, *args, "windows.fmu", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r = venv.run("georod", *args, "linux.fmu", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    windows, linux = (zipfile.ZipFile(tmp_path / f) for f in ("windows.fmu", "linux.fmu"))
    with windows, linux:
        assert windows.namelist() == linux.namelist()
        for name in windows.namelist():
            assert windows.read(name) == linux.read(name), f"{name} differs"
    assert (tmp_path / "windows.fmu").read_bytes() == (tmp_path / "linux.fmu").read_bytes()


def test_windows_wheel_refuses_a_bad_scene_as_the_linux_wheel(
    venv: Venv, windows_georod: Path, tmp_path: Path
) -> None:
    (tmp_path / "bad.toml").write_text(CANTILEVER.read_text().replace("L = 2.0", "L = -2.0"))
    windows = wine(windows_georod, "fmu", "bad.toml", "-o", "bad.fmu", cwd=tmp_path)
    linux = venv.run("georod", "fmu", "bad.toml", "-o", "bad.fmu", cwd=tmp_path)
    assert windows.returncode == linux.returncode == 1
    assert windows.stderr == linux.stderr and "bad.toml" in linux.stderr
    assert not (tmp_path / "bad.fmu").exists()


def test_the_source_distribution_needs_rust_and_builds_with_it(tmp_path: Path) -> None:
    """pip falls back to the source distribution where no wheel fits (forced here with
    --no-binary): without cargo it stops saying that Rust is needed; with cargo it builds the
    command and this machine's library."""
    sdist = dist_file(f"georod-{VERSION}.tar.gz")
    house = tmp_path / "wheelhouse"  # the build backend, for pip's isolated build environment
    pip_download = [sys.executable, "-m", "pip", "download", "--quiet", "-d", house]
    r = run([*pip_download, "hatchling==1.33.0"], timeout=600)
    assert r.returncode == 0, r.stderr
    run([getattr(sys, "_base_executable", sys.executable), "-m", "venv", tmp_path / "src"])
    # --no-cache-dir: a wheel pip built from the same sdist before would skip the build.
    pip = [
        tmp_path / "src" / "bin" / "python",
        "-m",
        "pip",
        "install",
        "--no-deps",
        "--no-cache-dir",
    ]
    pip += ["--no-index", "--find-links", house, sdist]
    # Only the venv's bin/: Debian's /bin and /usr/bin hold a cargo (cargo-web).
    no_rust = {"PATH": str(tmp_path / "src" / "bin"), "HOME": str(tmp_path)}
    r = run(pip, env=no_rust, timeout=600)
    assert r.returncode != 0
    assert "has no wheel for this platform" in r.stdout + r.stderr
    assert "needs Rust (cargo on PATH" in r.stdout + r.stderr

    cargo = Path(shutil.which("cargo") or "cargo").parent
    # rustup's cargo finds its toolchains under the real HOME; /usr/bin has the C linker.
    with_rust = {"PATH": f"{no_rust['PATH']}:{cargo}:/usr/bin", "HOME": str(Path.home())}
    # The sources of an sdist all carry one fixed date, so cargo cannot see a change in them:
    # one target folder per sdist content (the same sdist rebuilt reuses its build).
    builds = REPO / "target" / "sdist"
    digest = hashlib.sha256(sdist.read_bytes()).hexdigest()[:16]
    for old in builds.glob("*"):
        if old.name != digest:
            shutil.rmtree(old)
    with_rust["CARGO_TARGET_DIR"] = str(builds / digest)
    r = run(pip, env=with_rust, timeout=890)
    assert r.returncode == 0, r.stderr[-3000:]
    georod = tmp_path / "src" / "bin" / "georod"
    r = run([georod, "fmu", CANTILEVER, "-o", tmp_path / "c.fmu"])
    assert r.returncode == 0, r.stderr
    assert "no win64 library, binaries/win64 left out" in r.stderr
