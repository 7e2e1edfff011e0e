"""What the georod distribution declares (pyproject.toml at the root) agrees with the tested
environment (python/requirements.txt) and with the crate: each declared dependency's range holds
the exact pin the tests run, the wheel builder is the pinned hatchling, one version everywhere,
the same `georod-tools` entry point as the development install, and a source distribution that
holds what cargo needs."""

from __future__ import annotations

import subprocess
import sys
import tarfile
import tomllib
from pathlib import Path

import pytest
from packaging.requirements import Requirement

import georod_tools
from helpers import REPO
from wheel_env import VERSION

pytestmark = pytest.mark.timeout(60)

ROOT = tomllib.loads((REPO / "pyproject.toml").read_text())
DEV = tomllib.loads((REPO / "python" / "pyproject.toml").read_text())


def pins() -> dict[str, str]:
    """python/requirements.txt's exact pins, by lower-case name (extras dropped)."""
    out = {}
    for line in (REPO / "python" / "requirements.txt").read_text().splitlines():
        line = line.split("#")[0].strip()
        if line:
            req = Requirement(line)
            (spec,) = req.specifier
            assert spec.operator == "==", f"{line}: not an exact pin"
            out[req.name.lower()] = spec.version
    return out


def test_every_declared_dependency_holds_the_tested_pin() -> None:
    pinned = pins()
    declared = [Requirement(d) for d in ROOT["project"]["dependencies"]]
    for req in declared:
        version = pinned.get(req.name.lower())
        assert version is not None, f"{req.name} is declared but not pinned in requirements.txt"
        assert req.specifier.contains(version), f"{req}: the tested {version} is outside"
        bounded = {s.operator for s in req.specifier} >= {">=", "<"}
        assert bounded, f"{req}: a range from the tested minor release to the next major one"
    dev = {Requirement(d).name for d in DEV["project"]["dependencies"]}
    assert {r.name for r in declared} == dev, "the wheel and the development install agree"


def test_the_wheel_builder_is_the_pinned_hatchling() -> None:
    assert ROOT["build-system"]["requires"] == [f"hatchling=={pins()['hatchling']}"]


def test_one_version_and_one_tools_command() -> None:
    assert VERSION == georod_tools.__version__ == DEV["project"]["version"]
    assert ROOT["project"]["dynamic"] == ["version"]
    assert ROOT["tool"]["hatch"]["version"]["path"] == "Cargo.toml"
    tools = ROOT["project"]["scripts"]["georod-tools"]
    assert tools == DEV["project"]["scripts"]["georod-tools"]
    assert ROOT["project"]["scripts"]["georod"] == "georod_tools.command:start"


def test_the_source_distribution_holds_what_cargo_needs(tmp_path: Path) -> None:
    cmd = [sys.executable, "-m", "hatchling", "build", "-t", "sdist", "-d", str(tmp_path)]
    r = subprocess.run(cmd, cwd=REPO, capture_output=True, text=True, timeout=60, check=False)
    assert r.returncode == 0, r.stderr
    with tarfile.open(tmp_path / f"georod-{VERSION}.tar.gz") as t:
        names = {n.split("/", 1)[1] for n in t.getnames() if "/" in n}
    for needed in ("Cargo.toml", "Cargo.lock", "src/lib.rs", "src/bin/georod/main.rs"):
        assert needed in names, needed
    assert "benches/scaling.rs" in names, "Cargo.toml names this bench: cargo needs it"
    assert "python/georod_tools/command.py" in names and "python/hatch_build.py" in names
    assert not any(n.startswith(("target/", ".venv/", "python/tests/")) for n in names)
