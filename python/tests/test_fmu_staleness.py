"""conftest's fmu_paths rebuilds the FMUs when stale_fmus says so: an FMU that is missing, older
than the library, or older than its scene file (an edited scenes/*.toml or examples/*.toml)."""

from __future__ import annotations

import os
from pathlib import Path

from helpers import REPO, SCENE_FILES, stale_fmus


def _touch(path: Path, mtime: float) -> Path:
    path.write_text("x")
    os.utime(path, (mtime, mtime))
    return path


def test_stale_fmus(tmp_path: Path) -> None:
    scene = _touch(tmp_path / "Rod.toml", 1000.0)
    lib = _touch(tmp_path / "libgeorod.so", 1000.0)
    fmu_dir = tmp_path / "fmu"
    fmu_dir.mkdir()
    assert stale_fmus([scene], fmu_dir, lib) == ["Rod.fmu is missing"]
    fmu = _touch(fmu_dir / "Rod.fmu", 2000.0)
    assert stale_fmus([scene], fmu_dir, lib) == []
    os.utime(scene, (3000.0, 3000.0))  # the scene file was edited after packaging
    assert stale_fmus([scene], fmu_dir, lib) == ["Rod.fmu is older than its scene file Rod.toml"]
    os.utime(fmu, (4000.0, 4000.0))
    os.utime(lib, (5000.0, 5000.0))  # the library was rebuilt
    assert stale_fmus([scene], fmu_dir, lib) == ["Rod.fmu is older than libgeorod.so"]
    lib.unlink()  # no library: only the scene files count
    assert stale_fmus([scene], fmu_dir, lib) == []


def test_scene_files_are_the_ones_build_fmus_packages() -> None:
    names = {p.relative_to(REPO).as_posix() for p in SCENE_FILES}
    assert {"scenes/BuckledBeam.toml", "examples/Cantilever.toml"} <= names
    assert all(n.startswith(("scenes/", "examples/")) and n.endswith(".toml") for n in names)
