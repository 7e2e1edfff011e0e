"""``georod-tools animate`` marks the scene's items where they are in each frame: a moving load at
``speed (t - enter)`` along the rod (examples/Bridge.toml: 30 m/s, entering at 0.1 s, over 20 m),
absent before it enters and after it leaves; point loads and springs at their stations
(examples/ElasticBearings.toml); a stop fixed where its node touches it
(examples/ImpactingCantilever.toml); and the legend, below the axes, never covers a support's name
(every example, every frame)."""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest

from georod_tools.report.animation import figure, record
from georod_tools.report.marks import STYLES
from helpers import FmuInfo

matplotlib.use("Agg")


def test_a_moving_load_is_drawn_where_it_is_in_each_frame(examples: dict[str, FmuInfo]) -> None:
    speed, enter, span = 30.0, 0.1, 20.0  # examples/Bridge.toml
    motion = record(examples["Bridge"].path, {}, 1.0, 1e-2, 50)
    (load,) = [m for m in motion.marks if m.kind == "moving load"]
    expected = speed * (motion.times - enter) / span
    on = (expected >= 0.0) & (expected <= 1.0)
    assert on.any() and (~on).any(), "the frames should see the load before, on and after"
    assert np.allclose(load.stations[on], expected[on], rtol=0.0, atol=1e-12)
    assert np.all(np.isnan(load.stations[~on]))

    fig, frame = figure(motion)
    line = next(a for a in fig.axes[0].lines if a.get_label() == STYLES["moving load"].legend)
    for k in range(len(motion.times)):
        frame(k)
        xs, ys = line.get_data()
        if not on[k]:
            assert np.all(np.isnan(xs)), f"frame {k}: drawn off the rod"
            continue
        # On the deformed rod at its station: the girder's x moves by far less than 1 mm.
        assert xs[0] == pytest.approx(expected[k] * span, abs=1e-3), k
        s = np.linspace(0.0, 1.0, motion.x.shape[1])
        assert ys[0] == pytest.approx(np.interp(expected[k], s, motion.y[k]), abs=1e-12), k
    matplotlib.pyplot.close(fig)


def test_point_loads_and_springs_are_marked(examples: dict[str, FmuInfo]) -> None:
    motion = record(examples["ElasticBearings"].path, {}, 0.01, 1e-3, 2)
    kinds = {m.kind for m in motion.marks}
    assert {"support", "spring", "point load"} <= kinds, kinds
    fig, frame = figure(motion)
    frame(1)
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    for kind in ("spring", "point load"):
        assert STYLES[kind].legend in legend, legend
    names = {t.get_text() for t in fig.axes[0].texts}
    assert {m.name for m in motion.marks} <= names, names
    matplotlib.pyplot.close(fig)


def test_a_stop_stands_where_its_node_touches_it(examples: dict[str, FmuInfo]) -> None:
    """The stop at 0.9 of the 0.3 m strip, 0.5 mm below it (examples/ImpactingCantilever.toml):
    at (0.27, -5e-4) in every frame, while the strip moves."""
    motion = record(examples["ImpactingCantilever"].path, {}, 0.05, 1e-3, 5)
    (stop,) = [m for m in motion.marks if m.kind == "stop"]
    assert stop.anchor == pytest.approx((0.27, -5e-4), abs=1e-15)
    fig, frame = figure(motion)
    line = next(a for a in fig.axes[0].lines if a.get_label() == STYLES["stop"].legend)
    for k in range(len(motion.times)):
        frame(k)
        xs, ys = line.get_data()
        assert (xs[0], ys[0]) == stop.anchor, k
    assert np.ptp(motion.y[:, -1]) > 1e-4, "the strip should move"
    matplotlib.pyplot.close(fig)


@pytest.mark.parametrize("name", ["Cantilever", "ThreeSpan", "ElasticBearings", "Bridge"])
def test_the_legend_never_covers_a_supports_name(examples: dict[str, FmuInfo], name: str) -> None:
    info = examples[name]
    stop = float(info.md.defaultExperiment.stopTime)
    motion = record(info.path, {}, stop, stop / 20, 20)
    supports = {m.name for m in motion.marks if m.kind == "support"}
    assert supports, f"{name} has no support"
    fig, frame = figure(motion)
    renderer = fig.canvas.get_renderer()
    for k in range(len(motion.times)):
        frame(k)
        fig.canvas.draw()
        box = fig.axes[0].get_legend().get_window_extent(renderer)
        for text in fig.axes[0].texts:
            if text.get_text() in supports and text.get_visible():
                label = text.get_window_extent(renderer)
                assert not box.overlaps(label), f"{name}, frame {k}: legend covers {text}"
    matplotlib.pyplot.close(fig)
