"""Regression guard for the move from built-in scenes to scene files: the paper's three scenes,
now `scenes/*.toml` packaged by `georod fmu`, give the trajectories recorded through the FMUs of
main at commit 65820cf (before the change), for six cases covering both wells, both integrators,
an odd element count (point load and sensor shared by two nodes), a crown preload and a control
input (`data/before_scene_files/*.csv`, written by the same driving loop as below).

This proves the refactor kept the numbers; it is not evidence of correctness (the physics tests
check the model against closed forms).

Tolerances: the arches take exactly the floating-point operations they took before, so they must
agree bit for bit. The buckled beam reaches its initial buckled state by a different path now
(load stepping with an imperfection instead of a closed-form guess); both Newton solves stop at
round-off of the same equilibrium, and 200 steps (11 forcing periods) amplify that difference
to the 1e-13 level measured; 1e-10 of each output's range leaves room for compiler and libm
differences while catching any change of the model (which shows at 1e-4 and above).
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
        if scene != "BuckledBeam":
            assert np.array_equal(now[:, j], ref), f"{name}: not bit-identical"
        else:
            scale = float(np.ptp(ref)) or 1.0
            worst = float(np.max(np.abs(now[:, j] - ref))) / scale
            assert worst <= 1e-10, f"{name}: differs by {worst:.2e} of its range"
