"""Wheels of georod for the tests: packing one from a stage folder (python/hatch_build.py, the
same hook scripts/build_wheels runs) and installing it into a fresh virtual environment whose
PATH holds no Rust (test_wheel_smoke.py in the suite, test_wheels.py in scripts/test_wheels)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
import zipfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import pytest

from helpers import REPO

#: Where the bundle lies in a wheel (python/hatch_build.py).
BUNDLE = "georod_tools/bin"
VERSION = next(
    line.split('"')[1]
    for line in (REPO / "Cargo.toml").read_text().splitlines()
    if line.startswith("version = ")
)


def run(
    cmd: Sequence[str | os.PathLike[str]],
    cwd: Path | None = None,
    env: Mapping[str, str] | None = None,
    timeout: float = 120.0,
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(c) for c in cmd],
        cwd=cwd or REPO,
        env=dict(env) if env is not None else None,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


def stage(folder: Path, exe: Path, libraries: Mapping[str, Path]) -> Path:
    """A wheel's bundle in `folder`: the command `exe` and each platform's library."""
    names = {"linux64": "libgeorod.so", "win64": "georod.dll"}
    folder.mkdir(parents=True)
    shutil.copy2(exe, folder / exe.name)
    for platform, lib in libraries.items():
        (folder / platform).mkdir()
        shutil.copy2(lib, folder / platform / names[platform])
    return folder


def pack(stage_dir: Path, tag: str, out: Path) -> Path:
    """The wheel of platform `tag` from `stage_dir`, packed by hatchling into `out`."""
    env = {**os.environ, "GEOROD_WHEEL_STAGE": str(stage_dir), "GEOROD_WHEEL_TAG": tag}
    r = run([sys.executable, "-m", "hatchling", "build", "-t", "wheel", "-d", out], env=env)
    assert r.returncode == 0, f"hatchling build:\n{r.stdout}\n{r.stderr}"
    (wheel,) = out.glob(f"georod-{VERSION}-py3-none-{tag}.whl")
    return wheel


def bundle_of(wheel: Path) -> dict[str, bytes]:
    """The files of the wheel's bundle, by path under georod_tools/bin/."""
    with zipfile.ZipFile(wheel) as z:
        prefix = f"{BUNDLE}/"
        return {n[len(prefix) :]: z.read(n) for n in z.namelist() if n.startswith(prefix)}


@dataclass
class Venv:
    """A fresh virtual environment with a wheel installed; its commands run with a PATH of its
    own bin/ folder alone (no cargo, no rustc)."""

    root: Path

    @property
    def bin(self) -> Path:
        return self.root / "bin"

    @property
    def python(self) -> Path:
        return self.bin / "python"

    @property
    def site_packages(self) -> Path:
        (found,) = self.root.glob("lib/python3*/site-packages")
        return found

    @property
    def env(self) -> dict[str, str]:
        keep = {k: v for k, v in os.environ.items() if k in ("HOME", "LANG", "TMPDIR")}
        return {**keep, "PATH": str(self.bin), "MPLBACKEND": "Agg"}

    def run(
        self, *cmd: str | os.PathLike[str], cwd: Path | None = None, timeout: float = 120.0
    ) -> subprocess.CompletedProcess[str]:
        """`cmd`, a command of this venv's bin/ (by name) or a path, with its own PATH."""
        first = self.bin / str(cmd[0]) if (self.bin / str(cmd[0])).exists() else cmd[0]
        return run([first, *cmd[1:]], cwd=cwd, env=self.env, timeout=timeout)


def fresh_venv(root: Path, wheel: Path, dependencies: str) -> Venv:
    """A new venv at `root` with `wheel` installed. `dependencies`: "installed" (pip resolves the
    wheel's declared dependencies, from the index), or "borrowed" (the wheel alone, with the
    test environment's site-packages appended to sys.path by a .pth file, whose own .pth files
    are not read: the editable georod_tools of the source checkout stays out)."""
    base = getattr(sys, "_base_executable", sys.executable)
    r = run([base, "-m", "venv", "--without-pip", root])
    assert r.returncode == 0, f"python -m venv: {r.stderr}"
    venv = Venv(root)
    pip = [sys.executable, "-m", "pip", "--python", venv.python, "install", "--quiet"]
    pip += ["--disable-pip-version-check"]
    if dependencies == "borrowed":
        ours = Path(sysconfig.get_paths()["purelib"])
        (venv.site_packages / "zz_test_dependencies.pth").write_text(f"{ours}\n")
        pip += ["--no-deps", "--no-index"]
    r = run([*pip, wheel], timeout=900)
    assert r.returncode == 0, f"pip install {wheel.name}:\n{r.stdout}\n{r.stderr}"
    assert shutil.which("cargo", path=venv.env["PATH"]) is None
    assert shutil.which("rustc", path=venv.env["PATH"]) is None
    return venv


def require(*paths: Path) -> None:
    """Fails (never skips) naming what builds a missing file."""
    missing = [str(p) for p in paths if not p.is_file()]
    if missing:
        pytest.fail(f"missing {', '.join(missing)}: run scripts/build_fmus (or scripts/test)")
