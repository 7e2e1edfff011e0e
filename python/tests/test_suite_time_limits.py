"""A Python test that passes its time limit fails with its name and a stack, also on the
pytest-xdist workers that scripts/test runs (pytest -n 2): this project's pytest settings
(python/pyproject.toml: pytest-timeout, signal method) on a test that sleeps past a 1 s limit."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from helpers import REPO, run_cmd

HANGS = """
import time

import pytest


def wait_forever() -> None:
    time.sleep(60)


@pytest.mark.timeout(1)
def test_sleeps_past_its_limit() -> None:
    wait_forever()


def test_next_one_still_runs() -> None:
    pass
"""


@pytest.mark.timeout(60)
def test_a_test_past_its_limit_fails_with_its_name_and_stack(tmp_path: Path) -> None:
    test_file = tmp_path / "test_hangs.py"
    test_file.write_text(HANGS)
    config = REPO / "python" / "pyproject.toml"
    cmd = [sys.executable, "-m", "pytest", "-c", config, "-v", "-n", "2"]
    r = run_cmd([*cmd, "-p", "no:cacheprovider", test_file], timeout=50)
    out = r.stdout + r.stderr
    assert r.returncode == 1, out
    assert re.search(r"FAILED \S*::test_sleeps_past_its_limit", out), out
    assert "Timeout" in out, out
    assert "wait_forever()" in out and "time.sleep(60)" in out, f"no stack:\n{out}"
    assert "1 failed, 1 passed" in out, out
