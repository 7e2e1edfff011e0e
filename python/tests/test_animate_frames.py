"""``georod-tools animate`` on frames: every member its own line (no line or coloured segment
joins two members), the scene's items at their joints or on their members, a moving load along
its path member after member, hinges and links marked, and a motion too small to see magnified by
a stated factor.

- examples/PortalFrame.toml (3 members, 11 samples each, coloured by M): supports at the feet
  (the first samples of `left` and `right`), loads at the corners.
- python/tests/scenes/DeckPath.toml: a load at 1 m/s entering at 0.5 s on the path of `first`
  (6 m) then `second` (4 m).
- python/tests/scenes/TiedFrame.toml: a hinge at the crown, a link between the feet.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import matplotlib
import numpy as np
import pytest

from georod_tools.report.animation import VISIBLE, figure, magnified, record, segments
from georod_tools.report.marks import STYLES, positions
from georod_tools.report.places import Piece, arc
from helpers import FmuInfo
from scene_fmus import package_scene

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def scenes(tmp_path_factory: pytest.TempPathFactory) -> Callable[[str], FmuInfo]:
    out = Path(tmp_path_factory.mktemp("animate_frames"))
    return lambda name: package_scene(name, out)


def drawn(fig: object, legend: str) -> tuple[np.ndarray, np.ndarray]:
    line = next(a for a in fig.axes[0].lines if a.get_label() == legend)  # type: ignore[attr-defined]
    xs, ys = line.get_data()
    return np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)


def test_each_member_is_its_own_line(examples: dict[str, FmuInfo]) -> None:
    motion = record(examples["PortalFrame"].path, {}, 0.2, 1e-3, 4, field="M")
    assert motion.pieces == 3 and motion.x.shape == (5, 33)
    fig, frame = figure(motion)
    frame(2)
    xs, _ = drawn(fig, "deformed frame")
    # 3 x 11 samples and a NaN between consecutive members, nowhere else.
    assert len(xs) == 35 and np.flatnonzero(np.isnan(xs)).tolist() == [11, 23]
    # Coloured segments within each member: 3 x 10, every one between consecutive samples of
    # one member.
    segs = segments(motion.x[2], motion.y[2], motion.pieces)
    assert segs.shape == (30, 2, 2)
    starts = [i for m in range(3) for i in range(11 * m, 11 * m + 10)]
    assert np.array_equal(segs[:, 0, 0], motion.x[2, starts])
    assert np.array_equal(segs[:, 1, 0], motion.x[2, [i + 1 for i in starts]])
    # The feet: footA at the first sample of `left`, footD at the first of `right` (D to C).
    feet = {m.name: positions(m, motion.x, motion.y, 3) for m in motion.marks}
    assert np.array_equal(feet["footA"][2], [motion.x[2, 0], motion.y[2, 0]])
    assert np.array_equal(feet["footD"][2], [motion.x[2, 22], motion.y[2, 22]])
    # wind at joint B: the end of `left` (its last sample) and the start of `beam`.
    assert np.array_equal(feet["wind"][2], [motion.x[2, 10], motion.y[2, 10]])
    assert math.dist(feet["wind"][2], (motion.x[2, 11], motion.y[2, 11])) < 1e-12
    matplotlib.pyplot.close(fig)


def test_a_small_motion_is_magnified_by_a_stated_factor(examples: dict[str, FmuInfo]) -> None:
    """The portal's sway is millimetres on a 6 m frame: magnified by f in {1, 2, 5} x 10^n, the
    largest such that the largest motion stays within VISIBLE of the frame's size."""
    motion = record(examples["PortalFrame"].path, {}, 0.5, 1e-3, 10)
    shown, factor = magnified(motion)
    amplitude = np.max(np.hypot(motion.x - motion.x[0], motion.y - motion.y[0]))
    wanted = VISIBLE * 6.0 / amplitude
    mantissa = factor / 10.0 ** math.floor(math.log10(factor))
    assert mantissa in (1.0, 2.0, 5.0) and wanted / 2.5 <= factor <= wanted, (factor, wanted)
    assert np.allclose(shown.x, motion.x[0] + factor * (motion.x - motion.x[0]), atol=1e-12)
    fig, _ = figure(motion)
    assert f"magnified x{factor:g}" in fig.axes[0].get_xlabel()
    matplotlib.pyplot.close(fig)


def test_a_moving_load_follows_its_path(scenes: Callable[[str], FmuInfo]) -> None:
    motion = record(scenes("DeckPath").path, {}, 11.0, 0.01, 44)
    (load,) = [m for m in motion.marks if m.kind == "moving load"]
    s = 1.0 * (motion.times - 0.5)
    on = (s >= 0.0) & (s <= 10.0)
    assert on.any() and (~on).any()
    assert np.all(np.isnan(load.stations[~on]))
    first = on & (s <= 6.0)
    second = on & (s > 6.0)
    assert first.any() and second.any()
    assert np.all(load.pieces[first] == 0) and np.all(load.pieces[second] == 1)
    assert np.allclose(load.stations[first], s[first] / 6.0, atol=1e-12)
    assert np.allclose(load.stations[second], (s[second] - 6.0) / 4.0, atol=1e-12)
    # On the deformed deck at x = s: the girder's ends move along it by far less than 1 um.
    at = positions(load, motion.x, motion.y, motion.pieces)
    assert np.allclose(at[on, 0], s[on], atol=1e-6)
    # Drawn on the magnified deck (its deflection, ~0.1 mm on 10 m, is magnified).
    shown, factor = magnified(motion)
    assert factor > 1.0
    fig, frame = figure(motion)
    expected = positions(load, shown.x, shown.y, shown.pieces)
    for k in np.flatnonzero(on):
        frame(k)
        xs, ys = drawn(fig, STYLES["moving load"].legend)
        assert (xs[0], ys[0]) == pytest.approx(tuple(expected[k]), abs=1e-12), k
    matplotlib.pyplot.close(fig)


def test_hinges_and_links_are_marked(scenes: Callable[[str], FmuInfo]) -> None:
    motion = record(scenes("TiedFrame").path, {}, 0.01, 1e-3, 2)
    kinds = {m.kind: m for m in motion.marks if m.kind in ("hinge", "link")}
    assert set(kinds) == {"hinge", "link"}
    fig, frame = figure(motion)
    frame(1)
    shown, _ = magnified(motion)
    # The crown hinge: the end of beam_left (samples 6..10), at joint C.
    hx, hy = drawn(fig, STYLES["hinge"].legend)
    assert (hx[0], hy[0]) == (shown.x[1, 9], shown.y[1, 9])
    # The tie from A (the first sample of `left`) to E (the first of `right`), one segment.
    lx, ly = drawn(fig, STYLES["link"].legend)
    assert len(lx) == 3 and math.isnan(lx[2])
    assert (lx[0], ly[0]) == (shown.x[1, 0], shown.y[1, 0])
    assert (lx[1], ly[1]) == (shown.x[1, 15], shown.y[1, 15])
    names = [t.get_text() for t in fig.axes[0].texts]
    assert names.count("tie") == 1, names
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert {STYLES["hinge"].legend, STYLES["link"].legend} <= set(legend), legend
    matplotlib.pyplot.close(fig)


@pytest.mark.parametrize("rise", [0.5, -0.5, 1.5, 2.0, -2.0])
def test_an_arc_member_runs_from_its_from_joint_through_its_crown(rise: float) -> None:
    """A member's reference arc (a chord of 4 at 30 degrees, rise to its left): its ends at its
    joints, its middle the chord's middle moved by the rise along the chord's left normal, and
    equal stations equal arcs (equal chords between them). Round-off: 1e-12."""
    angle = math.radians(30.0)
    head = (1.0, 1.0)
    tail = (1.0 + 4.0 * math.cos(angle), 1.0 + 4.0 * math.sin(angle))
    piece = Piece("arch", "A", "B", arc(4.0, rise), (), head, tail, rise)
    assert piece.reference(0.0) == pytest.approx(head, abs=1e-12)
    assert piece.reference(1.0) == pytest.approx(tail, abs=1e-12)
    normal = (-math.sin(angle), math.cos(angle))
    crown = (
        0.5 * (head[0] + tail[0]) + rise * normal[0],
        0.5 * (head[1] + tail[1]) + rise * normal[1],
    )
    assert piece.reference(0.5) == pytest.approx(crown, abs=1e-12)
    steps = [math.dist(piece.reference(i / 8), piece.reference((i + 1) / 8)) for i in range(8)]
    assert max(steps) - min(steps) < 1e-12, steps


def test_a_stop_keeps_its_magnified_distance_from_its_node() -> None:
    """A frame magnified by f draws a stop (a point fixed in space) at its node's initial
    position plus f times their distance, so a node reaching its stop is drawn touching it."""
    from georod_tools.report.animation import Motion
    from georod_tools.report.marks import Mark

    # Two members of 3 samples: (0, 0)-(0, 2) and (0, 2)-(4, 2); the second sags by 1 mm.
    x0 = np.array([0.0, 0.0, 0.0, 0.0, 2.0, 4.0])
    y0 = np.array([0.0, 1.0, 2.0, 2.0, 2.0, 2.0])
    sag = np.array([0.0, 0.0, 0.0, 0.0, -1e-3, 0.0])
    stop = Mark("stop", "bumper", np.full(2, 0.5), np.full(2, 1), anchor=(2.0, 2.0 - 1e-3))
    motion = Motion(
        "m", "g", np.array([0.0, 1.0]), np.stack([x0, x0]), np.stack([y0, y0 + sag]), [stop]
    )
    motion.pieces = 2
    shown, factor = magnified(motion)
    assert factor == 200.0  # the largest 1, 2, 5 x 10^n with f 1e-3 <= 0.1 x 4 m
    (drawn_stop,) = shown.marks
    assert drawn_stop.anchor == pytest.approx((2.0, 2.0 - factor * 1e-3), abs=1e-12)
    # In the last frame the node touches its stop, drawn as touching.
    at = positions(drawn_stop, shown.x, shown.y, 2)
    node = (shown.x[1, 4], shown.y[1, 4])
    assert tuple(at[1]) == pytest.approx(node, abs=1e-12)
