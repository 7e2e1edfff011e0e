"""georod_tools: Python analyses around the georod FMUs (geometrically exact planar rod, FMI 2.0
Co-Simulation).

The FMUs are built by ``scripts/build_fmus`` into ``target/fmu/<Scene>.fmu``; the helpers below
locate them. Analyses (Poincaré sections, parameter sweeps, co-simulation) live in submodules.
"""

from __future__ import annotations

from pathlib import Path

__version__ = "0.1.0"

#: The scenes, one FMU each (``modelIdentifier`` = scene name).
SCENES: tuple[str, ...] = ("BuckledBeam", "PinnedArch", "ClampedArch")

#: The repository root (this file is python/georod_tools/__init__.py).
REPO_ROOT: Path = Path(__file__).resolve().parents[2]

#: Where scripts/build_fmus writes the FMUs.
FMU_DIR: Path = REPO_ROOT / "target" / "fmu"


def fmu_path(scene: str) -> Path:
    """``target/fmu/<scene>.fmu``; raises ``ValueError`` for an unknown scene."""
    if scene not in SCENES:
        raise ValueError(f"unknown scene {scene!r}; expected one of {', '.join(SCENES)}")
    return FMU_DIR / f"{scene}.fmu"


__all__ = ["FMU_DIR", "REPO_ROOT", "SCENES", "fmu_path", "__version__"]
