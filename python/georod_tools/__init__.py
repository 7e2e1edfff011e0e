"""georod_tools: georod from Python (geometrically exact planar rod, FMI 2.0 and 3.0
Co-Simulation FMUs) and the analyses around its FMUs.

The functions of :mod:`georod_tools.api` are here too: ``package``, ``check``, ``simulate``,
``modes`` and ``GeorodError`` (docs/python.md). A scene is a TOML file (``scenes/<Scene>.toml``
for the repository's own); ``scripts/build_fmus`` packages each into ``target/fmu/<Scene>.fmu``,
and the helpers below locate them in a source checkout. Analyses (Poincaré sections, parameter
sweeps, co-simulation, animations) live in submodules.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

__version__ = "0.1.0"

#: The repository root (this file is python/georod_tools/__init__.py).
REPO_ROOT: Path = Path(__file__).resolve().parents[2]

#: The repository's scene files.
SCENE_DIR: Path = REPO_ROOT / "scenes"

#: Where scripts/build_fmus writes the FMUs.
FMU_DIR: Path = REPO_ROOT / "target" / "fmu"


def scenes() -> tuple[str, ...]:
    """The names of the repository's scenes: ``scenes/*.toml`` (one FMU each)."""
    return tuple(sorted(p.stem for p in SCENE_DIR.glob("*.toml")))


def fmu_path(scene: str) -> Path:
    """``target/fmu/<scene>.fmu`` for a scene of ``scenes/`` or an FMU already packaged there;
    raises ``ValueError`` otherwise."""
    path = FMU_DIR / f"{scene}.fmu"
    if scene not in scenes() and not path.is_file():
        if not SCENE_DIR.is_dir():
            raise ValueError(
                f"no FMU for scene {scene!r}: this installation has no scenes/ folder (that is a "
                "source checkout's); pass --fmu FILE.fmu (georod fmu SCENE.toml packages one)"
            )
        raise ValueError(
            f"unknown scene {scene!r}: not in scenes/ ({', '.join(scenes())}) and no {path}"
        )
    return path


#: The names of :mod:`georod_tools.api` offered here, imported on first use (numpy with them):
#: the `georod` console script imports this package and stays quick.
_API = ("GeorodError", "check", "modes", "package", "simulate")


def __getattr__(name: str) -> Any:
    if name in _API:
        from georod_tools import api

        return getattr(api, name)
    raise AttributeError(f"module 'georod_tools' has no attribute {name!r}")


__all__ = [
    "FMU_DIR",
    "REPO_ROOT",
    "SCENE_DIR",
    "fmu_path",
    "scenes",
    "__version__",
    *_API,
]
