"""Requirement 8: scripts/valgrind_fmu runs a full instance life cycle of an FMU's library under
valgrind (memcheck, definite leaks are errors) through a small C host.

Every FMU carries the same library; the scenes differ in the paths through it they take. The
suite runs the scenes below, one for each kind of path (about 5 s each under valgrind); the
others are marked `exhaustive` (scripts/test_exhaustive runs them; ``scripts/valgrind_fmu`` with
no argument runs every scene too).

valgrind and gcc are test dependencies: scripts/install_test_deps (run by scripts/test) installs
them when missing; without them this test fails (it is never skipped)."""

from __future__ import annotations

import shutil

import pytest

from helpers import REPO, SCENE_FILES, run_cmd

SCRIPT = REPO / "scripts" / "valgrind_fmu"


#: One scene per kind of path through the library: the paper's rod (harmonic load, Lyapunov
#: exponents), a moving load, springs with dashpots (their bases input-driven), a frame (joints,
#: an input load, a joint mass, shape fields) and a rod on a stop (contact's semi-smooth
#: Newton). The C boundary they cross is the same for every scene; what differs between the
#: others (foundations, moving supports, truss bars) is safe Rust behind it.
SCENES = (
    "BuckledBeam",
    "Bridge",
    "ElasticBearings",
    "PortalFrame",
    "ImpactingCantilever",
)


def test_the_scenes_exist() -> None:
    names = {f.stem for f in SCENE_FILES}
    assert set(SCENES) <= names, set(SCENES) - names


@pytest.mark.usefixtures("fmu_paths")  # builds every scene's FMU when missing or stale
@pytest.mark.parametrize(
    "scene",
    [
        s if s in SCENES else pytest.param(s, marks=pytest.mark.exhaustive)
        for s in sorted(f.stem for f in SCENE_FILES)
    ],
)
def test_valgrind_clean(scene: str) -> None:
    """FMI 2.0 and 3.0, one scene a test: the pytest-xdist workers share them out."""
    missing = [tool for tool in ("valgrind", "gcc") if shutil.which(tool) is None]
    assert not missing, f"{', '.join(missing)} not on PATH: run scripts/install_test_deps"
    r = run_cmd([SCRIPT, scene], timeout=300)
    assert r.returncode == 0, (
        f"scripts/valgrind_fmu {scene} failed:\n{r.stdout[-4000:]}\n{r.stderr[-6000:]}"
    )
    assert f"== {scene}: clean" in r.stdout, r.stdout
    assert f"== {scene} FMI 3.0: clean" in r.stdout, r.stdout
