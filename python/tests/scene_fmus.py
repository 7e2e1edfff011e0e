"""Test scene files (python/tests/scenes/*.toml) packaged into FMUs for a test session.

`package_scene` runs `target/libs/georod fmu SCENE.toml -o DIR/SCENE.fmu` (the same command a
user runs) and extracts the result once. The georod command and library are built by
scripts/build_libs when they are missing or older than the Rust sources; a failed build or a
refused scene fails the test with the build's or georod's own message (no skips: conftest.py turns
any skip into a failure).
"""

from __future__ import annotations

import os
from pathlib import Path

import fmpy
import pytest

from helpers import GEOROD_CLI, GEOROD_LIB, REPO, FmuInfo, run_cmd

SCENE_DIR = Path(__file__).resolve().parent / "scenes"
BUILD_LIBS = REPO / "scripts" / "build_libs"


def _newest_source() -> float:
    """mtime of the newest Rust source or manifest (what the command and library are built from)."""
    sources = [*(REPO / "src").rglob("*.rs"), REPO / "Cargo.toml", REPO / "Cargo.lock"]
    return max(p.stat().st_mtime for p in sources if p.exists())


def ensure_georod() -> Path:
    """target/libs/georod and libgeorod.so, built by scripts/build_libs (the quick profile, as
    scripts/test builds them) when missing or stale."""
    built = [GEOROD_CLI, GEOROD_LIB]
    if all(p.exists() for p in built) and min(p.stat().st_mtime for p in built) >= _newest_source():
        return GEOROD_CLI
    cmd = [str(BUILD_LIBS)]
    r = run_cmd(cmd, timeout=1800, env=dict(os.environ, PROFILE="quick"))
    if r.returncode != 0:
        pytest.fail(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stderr[-3000:]}")
    missing = [str(p) for p in built if not p.exists()]
    if missing:
        pytest.fail(f"{' '.join(cmd)} succeeded but did not produce {missing}")
    return GEOROD_CLI


#: The scenes packaged in this test session: each is packaged once, whoever asks again gets it.
_PACKAGED: dict[str, FmuInfo] = {}


def package_scene(name: str, out_dir: Path) -> FmuInfo:
    """python/tests/scenes/<name>.toml packaged by `georod fmu` into out_dir and extracted, once
    per session (a second call returns the first call's FMU, in the first call's out_dir)."""
    if name in _PACKAGED:
        return _PACKAGED[name]
    scene = SCENE_DIR / f"{name}.toml"
    if not scene.is_file():
        pytest.fail(f"scene file {scene} is missing")
    cli = ensure_georod()
    fmu = out_dir / f"{name}.fmu"
    r = run_cmd([cli, "fmu", scene, "-o", fmu, "--lib", GEOROD_LIB], timeout=300)
    if r.returncode != 0 or not fmu.is_file():
        pytest.fail(
            f"georod fmu {scene.name} failed ({r.returncode}):\n"
            f"{r.stdout[-2000:]}\n{r.stderr[-3000:]}"
        )
    unzipdir = Path(fmpy.extract(str(fmu), unzipdir=str(out_dir / name)))
    md = fmpy.read_model_description(str(unzipdir))
    _PACKAGED[name] = FmuInfo.from_model_description(name, fmu, unzipdir, md)
    return _PACKAGED[name]
