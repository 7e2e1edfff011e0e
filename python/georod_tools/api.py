"""georod from Python: package a scene file into an FMU, check it, simulate it, get its natural
modes, with the results as numpy arrays (docs/python.md).

    import georod_tools as georod

    fmu = georod.package("my_rod.toml")                      # Path of MyRod.fmu
    report = georod.check("my_rod.toml")                     # report.sensors["w_tip"], ...
    run = georod.simulate("my_rod.toml", step=1e-3, stop=1.0, outputs=["w_tip"])
    run["time"], run["w_tip"]                                # numpy arrays
    modes = georod.modes("my_rod.toml", count=3)             # modes.frequencies in Hz

Each function runs the `georod` command of this installation (:mod:`georod_tools.command`:
the wheel's bundled one, or a source checkout's target/release/georod) and raises
:class:`GeorodError` with georod's own message when it refuses or fails: the same messages as
on the command line.
"""

from __future__ import annotations

import os
import re
import subprocess
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from georod_tools.command import executable

PathLike = str | os.PathLike[str]
Values = Mapping[str, float] | None


class GeorodError(RuntimeError):
    """georod refused or failed: `status` 2 for bad arguments, 1 for a failed run."""

    def __init__(self, message: str, status: int) -> None:
        super().__init__(message)
        self.status = status


def run(*args: PathLike, cwd: PathLike | None = None) -> str:
    """Runs ``georod ARGS`` and returns what it printed; raises GeorodError on failure."""
    argv = [str(executable()), *map(str, args)]
    r = subprocess.run(argv, capture_output=True, text=True, cwd=cwd, check=False)
    if r.returncode != 0:
        message = r.stderr.strip().removeprefix("georod: ")
        raise GeorodError(message or f"georod exited with status {r.returncode}", r.returncode)
    return r.stdout


def _pairs(flag: str, values: Values) -> list[str]:
    """``FLAG NAME=VALUE`` for each item (floats written exactly)."""
    return [a for k, v in (values or {}).items() for a in (flag, f"{k}={float(v)!r}")]


def package(
    scene: PathLike,
    out: PathLike | None = None,
    *,
    fmi: int = 2,
    binaries: Mapping[str, PathLike] | None = None,
) -> Path:
    """Packages the scene file into an FMI `fmi` (2 or 3) Co-Simulation FMU at `out` (default:
    ``<name>.fmu`` in the working directory from a wheel, ``target/fmu/`` in a checkout), with
    the library of every platform this installation carries, or exactly `binaries`
    (``{"linux64": path, ...}``). Returns the FMU's path."""
    args: list[PathLike] = ["fmu", scene, "--fmi", str(fmi)]
    if out is not None:
        args += ["-o", out]
    for platform, path in (binaries or {}).items():
        args += ["--binary", f"{platform}={path}"]
    found = re.search(r"^wrote (.+) \(\d+ bytes", run(*args), re.MULTILINE)
    if found is None:
        raise GeorodError("georod fmu did not say which file it wrote", 1)
    return Path(found.group(1))


@dataclass(frozen=True)
class Check:
    """What ``georod check`` says of a valid scene: its variables and initial state."""

    text: str
    #: Each sensor's value in the initial state (default parameters), in SI units.
    sensors: dict[str, float] = field(default_factory=dict)
    #: Each support's static reaction (Rx, Ry, M).
    reactions: dict[str, tuple[float, float, float]] = field(default_factory=dict)


_NUMBER = r"[-+]?\d\S*"


def check(scene: PathLike) -> Check:
    """Checks the scene file and its initial state; raises GeorodError with the file, the key
    and what is allowed when it is not a valid scene."""
    text = run("check", scene)
    sensors = {
        m[1]: float(m[2]) for m in re.finditer(rf"^  sensor +(\S+) +({_NUMBER})", text, re.M)
    }
    reactions = {
        m[1]: (float(m[2]), float(m[3]), float(m[4]))
        for m in re.finditer(
            rf"^  support +(\S+) +Rx = ({_NUMBER}) +Ry = ({_NUMBER}) +M = ({_NUMBER})", text, re.M
        )
    }
    return Check(text, sensors, reactions)


def _table(csv_text: str) -> np.ndarray:
    """A CSV with a header line as a structured array (one float field per column)."""
    lines = csv_text.strip().splitlines()
    names = lines[0].split(",")
    rows = np.loadtxt(lines[1:], delimiter=",", ndmin=2) if len(lines) > 1 else np.empty((0, 0))
    table = np.empty(len(rows), dtype=[(name, "f8") for name in names])
    for i, name in enumerate(names):
        table[name] = rows[:, i] if len(rows) else []
    return table


def simulate(
    scene: PathLike,
    *,
    step: float,
    stop: float,
    outputs: Sequence[str] = (),
    parameters: Values = None,
    inputs: Values = None,
) -> np.ndarray:
    """Simulates the scene file through the core (no FMU) in communication steps of `step` up
    to `stop`, with `parameters` and constant `inputs` set by name; returns a structured array
    with ``time`` and each output (default: every sensor, every support reaction, E_kin,
    E_strain, newton_iterations), like ``fmpy.simulate_fmu``."""
    args: list[PathLike] = ["simulate", "--scene", scene, "--step", repr(step), "--stop"]
    args += [repr(stop), *_pairs("--set", parameters), *_pairs("--input", inputs)]
    if outputs:
        args += ["--outputs", ",".join(outputs)]
    with tempfile.TemporaryDirectory(prefix="georod_simulate_") as tmp:
        csv = Path(tmp) / "run.csv"
        run(*args, "--output", csv)
        return _table(csv.read_text())


@dataclass(frozen=True)
class Modes:
    """Natural modes of a scene's initial state (undamped; constant loads on)."""

    #: Frequencies in Hz, lowest first.
    frequencies: np.ndarray
    #: The mode shapes: node, s, x, y, then u1_k, u2_k, w_k of each mode k = 1, 2, ...
    shapes: np.ndarray


def modes(scene: PathLike, *, count: int = 6, parameters: Values = None) -> Modes:
    """The `count` lowest natural frequencies and mode shapes of the scene's initial state."""
    with tempfile.TemporaryDirectory(prefix="georod_modes_") as tmp:
        csv = Path(tmp) / "shapes.csv"
        args = ["modes", scene, "--count", str(count), *_pairs("--set", parameters)]
        text = run(*args, "--output", csv)
        shapes = _table(csv.read_text())
    rows = re.findall(rf"^ +\d+ +({_NUMBER}) +{_NUMBER}$", text, re.M)
    return Modes(np.array([float(f) for f in rows]), shapes)
