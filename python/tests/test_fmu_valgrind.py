"""Requirement 8: scripts/valgrind_fmu runs a full instance life cycle of each FMU's library under
valgrind (memcheck, definite leaks are errors) through a small C host.

valgrind and gcc are test dependencies: scripts/install_test_deps (run by scripts/test) installs
them when missing; without them this test fails (it is never skipped)."""

from __future__ import annotations

import shutil

import pytest

from helpers import REPO, SCENE_FILES, run_cmd

SCRIPT = REPO / "scripts" / "valgrind_fmu"


@pytest.mark.usefixtures("fmu_paths")  # builds every scene's FMU when missing or stale
@pytest.mark.parametrize("scene", [f.stem for f in SCENE_FILES])
def test_valgrind_clean(scene: str) -> None:
    """Every FMU of scenes/ and examples/ (the script's default list), FMI 2.0 and 3.0, one scene
    a test: the pytest-xdist workers share them out (the whole list in one run of the script took
    half the Python suite's time on one worker)."""
    missing = [tool for tool in ("valgrind", "gcc") if shutil.which(tool) is None]
    assert not missing, f"{', '.join(missing)} not on PATH: run scripts/install_test_deps"
    r = run_cmd([SCRIPT, scene], timeout=300)
    assert r.returncode == 0, (
        f"scripts/valgrind_fmu {scene} failed:\n{r.stdout[-4000:]}\n{r.stderr[-6000:]}"
    )
    assert f"== {scene}: clean" in r.stdout, r.stdout
    assert f"== {scene} FMI 3.0: clean" in r.stdout, r.stdout
