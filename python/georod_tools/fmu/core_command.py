"""The core's own command line, ``georod`` (:func:`georod_tools.command.executable`: a wheel's
bundled command, or a source checkout's ``target/libs/georod``): model
quantities the FMUs do not output (static load paths, equilibria and their natural frequencies)
and the cost of the core's step loop without FMI.

Every function runs one ``georod`` subcommand and parses its CSV; a failure raises
RuntimeError with georod's own message.
"""

from __future__ import annotations

import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from georod_tools.api import run

Overrides = Mapping[str, float] | None


def georod(*args: str) -> str:
    """Runs ``georod ARGS`` and returns its standard output (raises
    :class:`georod_tools.api.GeorodError`, a RuntimeError, with georod's message)."""
    return run(*args)


def set_options(overrides: Overrides) -> list[str]:
    """``--set NAME=VALUE`` for each override (floats written exactly)."""
    out: list[str] = []
    for k, v in (overrides or {}).items():
        out += ["--set", f"{k}={v!r}"]
    return out


@dataclass(frozen=True)
class Mode:
    """One row of ``georod modes``: natural mode `mode` (1 = lowest) about the equilibrium
    `equilibrium` (w_mid of its branch sensor, number of negative stiffness eigenvalues);
    `omega` in rad/s (NaN for an unstable direction, whose omega^2 < 0)."""

    equilibrium: str
    w_mid: float
    negative: int
    mode: int
    omega_squared: float
    omega: float
    symmetric: bool


def modes(scene: str, overrides: Overrides = None, count: int = 3, load: float = 0.0) -> list[Mode]:
    """Natural frequencies about every equilibrium of the scene's static path at `load`."""
    text = georod(
        "modes",
        "--scene",
        scene,
        "--count",
        str(count),
        "--load",
        repr(load),
        *set_options(overrides),
    )
    rows = []
    for line in text.splitlines()[1:]:
        name, w, neg, mode, w2, omega, _hz, sym = line.split(",")
        rows.append(
            Mode(name, float(w), int(neg), int(mode), float(w2), float(omega), sym == "true")
        )
    return rows


def equilibrium_states(
    scene: str, overrides: Overrides = None, load: float = 0.0
) -> dict[str, np.ndarray]:
    """Displacement vectors (u1, u2, w per node) of the equilibria at `load`, by name (z1 is
    the one the path starts from)."""
    with tempfile.TemporaryDirectory(prefix="georod_states_") as tmp:
        path = Path(tmp) / "states.csv"
        georod(
            "modes",
            "--scene",
            scene,
            "--count",
            "1",
            "--load",
            repr(load),
            "--states",
            str(path),
            *set_options(overrides),
        )
        states = {}
        for line in path.read_text().splitlines():
            parts = line.split(",")
            states[parts[0]] = np.asarray([float(x) for x in parts[3:]])
    return states


def static_path(
    scene: str, overrides: Overrides = None, max_load: float = 60.0, imperfection: float = 0.0
) -> str:
    """The CSV of ``georod path`` (the static path of the scene's point load through its limit
    points, with ``# critical`` and ``# equilibrium`` lines)."""
    args = ["path", "--scene", scene, "--stop", repr(max_load), *set_options(overrides)]
    if imperfection:
        args += ["--imperfection", repr(imperfection)]
    return georod(*args)


def bench_steps(scene: str, overrides: Overrides, steps: int, dt: float) -> float:
    """Seconds of `steps` midpoint steps of `dt` in the core's own loop (no FMI, no Python)."""
    text = georod(
        "bench-steps",
        "--scene",
        scene,
        "--steps",
        str(steps),
        "--dt",
        repr(dt),
        *set_options(overrides),
    )
    return float(text.split()[0])
