"""Frames through packaged FMUs (fmpy's FMU2Slave on python/tests/scenes/), against statics and
closed forms; the core runs its own checks in tests/frames_*.rs.

- TriangleTruss: three truss bars on a pin and a roller on a 30 degree incline: the bar forces
  `<bar>_N_start`, `_N_end` and the roller's reaction in its own frame (`_R1`, `_R2`) against
  statics.
- PortalSway: a fixed-base portal frame's sway under a lateral load against slope deflection.
- DeckPath: a load moving slowly along a path of two members: the roller's reaction follows the
  lever rule as the load crosses from the first member to the second.
- TiedFrame: a three-hinged portal frame whose feet are tied by a link: the tie's tension
  against statics (the moment about the crown hinge).
- A frame that is a mechanism is refused by `georod fmu` with the file and the key, and nothing
  is written.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import pytest

from helpers import GEOROD_CLI, FmuInfo, get_reals, instantiate, release, run_cmd, run_steps
from scene_fmus import SCENE_DIR, ensure_georod, package_scene

E = 2.1e11


@pytest.fixture(scope="module")
def fmus(tmp_path_factory: pytest.TempPathFactory) -> Callable[[str], FmuInfo]:
    out = Path(tmp_path_factory.mktemp("frames"))
    return lambda name: package_scene(name, out)


def initial(info: FmuInfo, names: list[str], params: dict[str, float] | None = None) -> list[float]:
    slave = instantiate(info, params)
    try:
        return get_reals(slave, info, names)
    finally:
        release(slave)


def test_truss_bar_forces_and_an_inclined_roller_follow_statics(
    fmus: Callable[[str], FmuInfo],
) -> None:
    """P = 100 N on a 4 x 3 m triangle: the joints move by 1e-7 of the lengths, so statics on
    the reference geometry holds to that (tolerance 1e-5 of P)."""
    info = fmus("TriangleTruss")
    p = 100.0
    names = ["LT_N_start", "LT_N_end", "TR_N_start", "LR_N_end", "roller_R1", "roller_R2"]
    lt, lt_end, tr, lr, r1, r2 = initial(info, names)
    sin = 3.0 / math.sqrt(13.0)
    # The roller's normal at 30 degrees: the vertical reactions P/2 each; the roller pushes along
    # its normal (-sin 30, cos 30) with R = P / (2 cos 30), the pin takes the horizontal rest.
    roller = p / (2.0 * math.cos(math.radians(30.0)))
    # Horizontal equilibrium at R: the bottom bar's P / 3 less the roller's push along -e1.
    bottom = p / 3.0 - roller * math.sin(math.radians(30.0))
    checks = [
        ("LT", lt, -p / (2.0 * sin)),
        ("LT end", lt_end, -p / (2.0 * sin)),
        ("TR", tr, -p / (2.0 * sin)),
        ("LR", lr, bottom),
        ("roller R1", r1, 0.0),
        ("roller R2", r2, roller),
    ]
    for what, got, want in checks:
        assert abs(got - want) < 1e-5 * p, f"{what}: {got} vs {want}"


@pytest.mark.parametrize("beam_ratio", [None, 0.5, 8.0])
def test_portal_sway_follows_slope_deflection(
    fmus: Callable[[str], FmuInfo], beam_ratio: float | None
) -> None:
    """80 elements per member leave -1.3e-4 of mesh error (second order, docs in
    tests/suite/frames_statics.rs); the tolerance 3e-4 covers it. The beam's own section is a
    set of parameters: `beam_I` set to another ratio of the columns' I gives that ratio's sway
    (None: the file's, twice the columns')."""
    info = fmus("PortalSway")
    h, span, ic = 4.0, 6.0, 8.356e-5
    ratio = 2.0 if beam_ratio is None else beam_ratio
    params = None if beam_ratio is None else {"beam_I": beam_ratio * ic}
    (sway,) = initial(info, ["sway"], params)
    r = (ratio * ic / span) / (ic / h)
    k = 24.0 * E * ic / h**3 * (1.0 + 6.0 * r) / (4.0 + 6.0 * r)
    assert abs(sway * k - 1.0) < 3e-4, f"sway {sway} vs {1.0 / k}"


def test_a_load_crossing_a_path_of_members_follows_the_lever_rule(
    fmus: Callable[[str], FmuInfo],
) -> None:
    """1 kN at 1 m/s over 10 m, entering at 0.5 s: the roller carries P x / L; the girder's
    dynamic response (5 % mass-proportional damping, first period 0.095 s) adds 4e-4 of P (the
    tolerance 1e-3 of P)."""
    info = fmus("DeckPath")
    slave = instantiate(info)
    try:
        step = 0.05
        rows = run_steps(slave, info, step, 200, names=["roller_Ry"])
    finally:
        release(slave)
    worst = 0.0
    for k, (ry,) in enumerate(rows):
        # The reaction averaged over the step ending at t: the load at its middle.
        t = (k - 0.5) * step
        if 1.0 < t < 10.0:  # the load inside the span, away from its jumps on and off
            x = t - 0.5
            worst = max(worst, abs(ry - 1000.0 * x / 10.0))
    assert worst < 1.0, f"the roller's reaction is off the lever rule by {worst} N"


def test_a_tie_carries_the_thrust_of_a_three_hinged_frame(fmus: Callable[[str], FmuInfo]) -> None:
    """P down at the crown hinge of a frame of span L and height h: the tie's tension P L / (4 h)
    and P / 2 on each foot. The joints move by under 1e-6 of the lengths (stiff members, a stiff
    tie), so statics on the reference geometry holds to that: tolerance 1e-5 of P."""
    info = fmus("TiedFrame")
    p, span, h = 1000.0, 6.0, 4.0
    tie, pin_x, pin_y, roller_y = initial(info, ["tie_force", "pin_Rx", "pin_Ry", "roller_Ry"])
    for what, got, want in [
        ("tie", tie, p * span / (4.0 * h)),
        ("pin Rx", pin_x, 0.0),
        ("pin Ry", pin_y, p / 2.0),
        ("roller Ry", roller_y, p / 2.0),
    ]:
        assert abs(got - want) < 1e-5 * p, f"{what}: {got} vs {want}"


def test_a_mechanism_frame_is_refused_and_nothing_is_written(tmp_path: Path) -> None:
    ensure_georod()
    # Pinned feet and a beam hinged at both corners: the frame sways freely.
    scene = (
        (SCENE_DIR / "PortalSway.toml")
        .read_text()
        .replace('fix = ["u1", "u2", "w"]', 'fix = ["u1", "u2"]')
        .replace('name = "beam"', 'name = "beam"\nhinges = ["start", "end"]')
    )
    bad = tmp_path / "Mechanism.toml"
    bad.write_text(scene)
    out = tmp_path / "Mechanism.fmu"
    r = run_cmd([GEOROD_CLI, "fmu", bad, "-o", out], timeout=60)
    assert r.returncode != 0
    assert "Mechanism.toml" in r.stderr and "mechanism" in r.stderr, r.stderr
    assert not out.exists()
