"""Regression guard for the move from built-in scenes to scene files: the paper's three scenes,
now `scenes/*.toml` packaged by `georod fmu`, give the trajectories recorded through the FMUs of
main at commit 65820cf (before the change), for six cases covering both wells, both integrators,
an odd element count (point load and sensor shared by two nodes), a crown preload and a control
input (`data/before_scene_files/*.csv`, written by the same driving loop as below).

This proves the refactor kept the numbers; it is not evidence of correctness (the physics tests
check the model against closed forms).

Tolerance: 1e-9 of each output's range, for every case. The recording predates two changes of
the solver's round-off: Newton now stops when the error left after its last correction is
estimated a hundred times below its tolerance (1e-12 of the step's increment or less) instead of
taking one more correction, and the model's sines and cosines come from Rust's libm instead of
the system's. Over the 200 recorded steps (11 forcing periods of the beam) these show as
differences of at most 3e-10 of an output's range (BuckledBeam_default, E_strain), 1e-13 for the
energy-momentum cases (which still iterate to round-off); a change of the model shows at 1e-4
and above.
"""

from __future__ import annotations

import ast
import math
import re
from pathlib import Path

import numpy as np
import pytest

from helpers import FmuInfo, instantiate, release

DATA = Path(__file__).parent / "data" / "before_scene_files"
NAMES = ["w_mid", "v_mid", "E_kin", "E_strain", "W_ext", "W_ctrl", "E_damped"]


def recorded(path: Path) -> tuple[str, dict[str, float], bool, float, int, np.ndarray]:
    """The case of a recorded file (its comment line) and its table."""
    with path.open() as f:
        comment = f.readline()
    m = re.match(r"# scene=(\w+) params=(\{.*\}) f_ctrl=(.*) h=(\S+) steps=(\d+)", comment)
    assert m, f"{path}: unexpected header {comment!r}"
    scene, params, control, h, n = m.groups()
    table = np.genfromtxt(path, delimiter=",", names=True, skip_header=1)
    return scene, ast.literal_eval(params), "sin" in control, float(h), int(n), table


@pytest.mark.parametrize("path", sorted(DATA.glob("*.csv")), ids=lambda p: p.stem)
def test_paper_scenes_keep_their_trajectories(fmus: dict[str, FmuInfo], path: Path) -> None:
    scene, params, control, h, n, before = recorded(path)
    info = fmus[scene]
    slave = instantiate(info, params)
    try:
        vrs = [info.vr[name] for name in NAMES]
        rows = [slave.getReal(vrs)]
        for k in range(n):
            t = k * h
            slave.setReal([info.vr["f_ctrl"]], [0.05 * math.sin(2000.0 * t) if control else 0.0])
            slave.doStep(t, h)
            rows.append(slave.getReal(vrs))
    finally:
        release(slave)
    now = np.array(rows)
    for j, name in enumerate(NAMES):
        ref = before[name]
        scale = float(np.ptp(ref)) or 1.0
        worst = float(np.max(np.abs(now[:, j] - ref))) / scale
        assert worst <= 1e-9, f"{name}: differs by {worst:.2e} of its range"
