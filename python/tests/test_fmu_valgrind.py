"""Requirement 8: scripts/valgrind_fmu runs a full instance life cycle of each FMU's library under
valgrind (memcheck, definite leaks are errors) through a small C host."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from helpers import REPO, run_cmd

SCRIPT = REPO / "scripts" / "valgrind_fmu"


@pytest.mark.skipif(shutil.which("valgrind") is None, reason="valgrind not on PATH")
@pytest.mark.skipif(shutil.which("gcc") is None, reason="gcc not on PATH")
def test_valgrind_clean(fmu_paths: dict[str, Path]) -> None:
    r = run_cmd([SCRIPT, *fmu_paths], timeout=600)
    assert r.returncode == 0, (
        f"scripts/valgrind_fmu failed:\n{r.stdout[-4000:]}\n{r.stderr[-6000:]}"
    )
    for scene in fmu_paths:
        assert f"== {scene}: clean" in r.stdout
