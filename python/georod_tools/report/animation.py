"""The deformed rod or frame over time, from an FMU's shape outputs (``shape_x[i]``,
``shape_y[i]``; on a frame ``points`` per member, member by member, each member drawn as its own
line).

:func:`record` runs the FMU from its initial state (communication step `step`, default: the FMU's
default experiment) and samples the shape at `frames` equally spaced times, with its inputs
constant or following a :class:`InputTable` (``--inputs FILE``); :func:`render` writes a GIF
(matplotlib + Pillow) with the initial shape in grey, the scene's supports, springs, point loads
and moving loads (and a frame's hinges and links) marked where they are in each frame
(:mod:`georod_tools.report.marks`), the legend below the plot (it covers nothing), the time
shown, and the factor by which the y axis is stretched when the motion is too flat to see in
true proportions. The command is ``georod-tools animate`` (:mod:`georod_tools.cli.animate`).
"""

from __future__ import annotations

import math
import re
import tomllib
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from georod_tools.report.marks import STYLES, Mark, marks, on_shape, positions, resolver

SHAPE = re.compile(r"shape_([xy])\[(\d+)\]$")
#: The y axis is stretched when the motion's height is below this fraction of its width.
FLAT = 0.15
#: A frame's motion is magnified when it stays below this fraction of the frame's size.
VISIBLE = 0.1


@dataclass
class InputTable:
    """Inputs over time from a CSV file: a first column ``time`` (s, increasing) and one column
    per FMU input, named like it. Before each communication step each input is set to its value
    linearly interpolated at the step's end (held beyond the table's ends): a moving support
    reaches it at the end of the step, a load input is held at it over the step."""

    times: np.ndarray
    values: dict[str, np.ndarray]

    @classmethod
    def read(cls, path: Path, inputs: list[str]) -> InputTable:
        """The table in `path`; ValueError naming the file and what is wrong."""
        import csv

        try:
            with path.open(newline="") as f:
                rows = list(csv.reader(f))
        except OSError as e:
            raise ValueError(f"--inputs {path}: {e}") from e
        if len(rows) < 2 or not rows[0] or rows[0][0].strip() != "time":
            raise ValueError(
                f"--inputs {path}: needs a header whose first column is time, then one column "
                f"per input ({', '.join(inputs) or 'this FMU has no inputs'}), and data rows"
            )
        names = [n.strip() for n in rows[0][1:]]
        unknown = [n for n in names if n not in inputs]
        if unknown or not names:
            raise ValueError(
                f"--inputs {path}: {', '.join(unknown) or 'no input column'}: not an input of "
                f"the FMU (its inputs: {', '.join(inputs) or 'none'})"
            )
        try:
            data = np.array([[float(x) for x in r] for r in rows[1:] if r], dtype=float)
        except ValueError as e:
            raise ValueError(f"--inputs {path}: {e}") from e
        if data.shape[1] != len(names) + 1 or not np.isfinite(data).all():
            raise ValueError(f"--inputs {path}: every row needs {len(names) + 1} finite numbers")
        if np.any(np.diff(data[:, 0]) <= 0):
            raise ValueError(f"--inputs {path}: the times must increase")
        return cls(data[:, 0], {n: data[:, j + 1] for j, n in enumerate(names)})

    def at(self, t: float) -> dict[str, float]:
        return {n: float(np.interp(t, self.times, v)) for n, v in self.values.items()}


@dataclass
class Motion:
    """Shape samples over time: ``x[k, i]``, ``y[k, i]`` at ``times[k]``, `pieces` pieces (the rod,
    or a frame's members) of equally many samples one after the other."""

    name: str
    guid: str
    times: np.ndarray
    x: np.ndarray
    y: np.ndarray
    #: The scene's items, each with its station in every frame (supports first).
    marks: list[Mark]
    unit: str = "m"
    #: A field along the rod (``shape_<name>[i]``, e.g. the bending moment) that colours it.
    field: np.ndarray | None = None
    field_name: str = ""
    field_unit: str = ""
    pieces: int = 1


def field_outputs(model: object, name: str, points: int) -> list[str]:
    """The outputs ``shape_<name>[1..points]`` of `model`; ValueError saying how to add them."""
    names = [f"shape_{name}[{i}]" for i in range(1, points + 1)]
    missing = [n for n in names if n not in model.variables]  # type: ignore[attr-defined]
    if missing:
        raise ValueError(
            f"--field {name}: {model.identifier} has no {missing[0]} "  # type: ignore[attr-defined]
            f'(add "{name}" to the scene\'s [shape] fields)'
        )
    return names


def record(
    fmu: Path,
    start_values: dict[str, float],
    stop: float | None,
    step: float | None,
    frames: int,
    inputs: Path | None = None,
    field: str | None = None,
) -> Motion:
    """Simulates `fmu` and samples its shape outputs at `frames` + 1 times from 0 to `stop`, the
    inputs following the CSV table `inputs` when given (:class:`InputTable`), and the shape field
    `field` (``shape_<field>[i]``) with them when given."""
    from tqdm import tqdm

    from georod_tools.fmu import FmuModel, lend

    model = FmuModel.load(fmu)
    shape: dict[str, dict[int, str]] = {"x": {}, "y": {}}
    for name in model.outputs:
        m = SHAPE.match(name)
        if m:
            shape[m.group(1)][int(m.group(2))] = name
    if not shape["x"] or sorted(shape["x"]) != sorted(shape["y"]):
        raise ValueError(f"{fmu}: no shape_x[i] / shape_y[i] outputs (give the scene a [shape])")
    order = sorted(shape["x"])
    names = [shape["x"][i] for i in order] + [shape["y"][i] for i in order]
    points = len(order)
    if field is not None:
        names += field_outputs(model, field, points)
    experiment = model.md.defaultExperiment
    stop = stop if stop is not None else float(experiment.stopTime)
    step = step if step is not None else float(experiment.stepSize)
    steps = max(1, round(stop / step))
    sampled = set(np.linspace(0, steps, min(frames, steps) + 1).round().astype(int).tolist())
    for name in start_values:
        if name not in model.variables:
            raise ValueError(f"--start-values {name}: not a variable of {model.identifier}")
    table = InputTable.read(inputs, model.names("input")) if inputs is not None else None
    initial = {**start_values, **(table.at(0.0) if table else {})}
    times, xs, ys, fs = [], [], [], []
    with lend(model, "animate") as inst:
        inst.initialize(initial)
        read = inst.reader(names)
        for k in tqdm(
            range(steps + 1), desc=f"simulating {model.identifier}", unit="step", leave=False
        ):
            if k in sampled:
                got = read()
                times.append(k * step)
                xs.append(got[:points])
                ys.append(got[points : 2 * points])
                fs.append(got[2 * points :])
            if k < steps:
                for name, value in (table.at((k + 1) * step) if table else {}).items():
                    inst.set(name, value)
                inst.step(k * step, step)
    scene = tomllib.loads((model.unzipdir / "resources" / "scene.toml").read_text("utf-8"))
    params = {n: float(v.start) for n, v in model.variables.items() if v.causality == "parameter"}
    items = marks(scene, np.array(times), resolver({**params, **start_values}))
    unit = model.variables[names[0]].unit or "m"
    motion = Motion(
        model.identifier, model.guid, np.array(times), np.array(xs), np.array(ys), items, unit
    )
    motion.pieces = max(1, len(scene.get("member", [])))
    if field is not None:
        motion.field = np.array(fs)
        motion.field_name = field
        motion.field_unit = model.variables[f"shape_{field}[1]"].unit or ""
    return motion


def figure(motion: Motion) -> tuple[Any, Callable[[int], tuple]]:
    """The animation's figure and the function that draws frame k into it (returning what it
    changed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    motion, magnification = magnified(motion)
    x, y = motion.x, motion.y
    width, height = max(np.ptp(x), 1e-12), max(np.ptp(y), 1e-12)
    fig, ax = plt.subplots(figsize=(8, 4.4), dpi=80)
    # Room below the axes for the legend: inside them it could cover a support's label.
    fig.subplots_adjust(bottom=0.3)
    ax.set_xlim(x.min() - 0.05 * width, x.max() + 0.05 * width)
    ax.set_ylim(y.min() - 0.1 * height, y.max() + 0.1 * height)
    # True proportions unless the motion would be a flat line in them (a beam deflecting by a
    # few percent of its length): then the y axis is stretched, by a factor the label gives.
    stretch = stretch_factor(fig, ax) if height < FLAT * width else 1.0
    if stretch == 1.0:
        ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(
        f"x [{motion.unit}]"
        + (f"; motion magnified x{magnification:g}" if magnification != 1.0 else "")
    )
    ax.set_ylabel(f"y [{motion.unit}]" + (f", stretched x{stretch:.3g}" if stretch != 1.0 else ""))
    ax.grid(alpha=0.3)
    # Each piece its own line: NaN between pieces breaks the line where one member ends.
    bx, by = broken(x, motion.pieces), broken(y, motion.pieces)
    ax.plot(bx[0], by[0], color="0.75", lw=1.5, label="initial state")
    (line,) = ax.plot(bx[0], by[0], color="C0", lw=2.5, label=shape_name(motion))
    colours = field_colours(fig, ax, motion)
    if colours is not None:
        line.set_visible(False)
    drawn_marks = MarkArtists(ax, motion)
    label = ax.set_title("")
    # At the figure's foot: below an axes box shrunk to true proportions it stays clear of the
    # x label.
    ax.legend(
        loc="lower center",
        bbox_to_anchor=(0.5, 0.01),
        bbox_transform=fig.transFigure,
        ncol=3,
        fontsize="small",
    )

    def frame(k: int) -> tuple:
        line.set_data(bx[k], by[k])
        if colours is not None:
            colours.set_segments(segments(x[k], y[k], motion.pieces))
            colours.set_array(midpoints(motion.field[k], motion.pieces))  # type: ignore[index]
        label.set_text(f"{motion.name}: t = {motion.times[k]:.5f} s")
        drawn = (colours,) if colours is not None else ()
        return line, label, *drawn_marks.show(k), *drawn

    return fig, frame


def magnified(motion: Motion) -> tuple[Motion, float]:
    """A frame whose motion would not be seen at its true size (under :data:`VISIBLE` of the
    frame's size) with its motion from the initial state magnified, by the factor (1, 2 or 5
    times a power of ten) that brings it to about that size, and the factor. A rod keeps its
    true motion (a flat one is drawn with its y axis stretched instead)."""
    if motion.pieces == 1:
        return motion, 1.0
    dx, dy = motion.x - motion.x[:1], motion.y - motion.y[:1]
    amplitude = float(np.max(np.hypot(dx, dy)))
    size = max(float(np.ptp(motion.x[0])), float(np.ptp(motion.y[0])))
    if amplitude == 0.0 or amplitude >= VISIBLE * size:
        return motion, 1.0
    wanted = VISIBLE * size / amplitude
    decade = 10.0 ** math.floor(math.log10(wanted))
    factor = max(f * decade for f in (1.0, 2.0, 5.0) if f * decade <= wanted)
    shown = replace(motion, x=motion.x[:1] + factor * dx, y=motion.y[:1] + factor * dy)
    shown.marks = [magnified_anchor(m, motion, factor) for m in motion.marks]
    return shown, factor


def magnified_anchor(mark: Mark, motion: Motion, factor: float) -> Mark:
    """A point fixed in space (a stop) moved so that its distance from its node's initial
    position is magnified with the motion."""
    if mark.anchor is None:
        return mark
    first = replace(mark, stations=mark.stations[:1], pieces=mark.pieces[:1])
    start = on_shape(first, motion.x[:1], motion.y[:1], motion.pieces)[0]
    anchor = start + factor * (np.array(mark.anchor) - start)
    return replace(mark, anchor=(float(anchor[0]), float(anchor[1])))


def render(motion: Motion, out: Path, fps: int) -> Path:
    """Writes the animation of `motion` to `out` (GIF)."""
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter
    from tqdm import tqdm

    fig, frame = figure(motion)
    anim = FuncAnimation(fig, frame, frames=len(motion.times), blit=True)
    bar = tqdm(total=len(motion.times), desc=f"rendering {out.name}", unit="frame", leave=False)
    out.parent.mkdir(parents=True, exist_ok=True)
    anim.save(str(out), writer=PillowWriter(fps=fps), progress_callback=lambda i, n: bar.update(1))
    bar.close()
    plt.close(fig)
    return out


class MarkArtists:
    """The scene's items on the axes: one marker line per kind (one legend entry each) and each
    item's name beside it, moved to where the items are in each frame."""

    def __init__(self, ax: Any, motion: Motion) -> None:
        self.at = {id(m): positions(m, motion.x, motion.y, motion.pieces) for m in motion.marks}
        self.kinds: dict[str, list[Mark]] = {}
        for m in motion.marks:
            self.kinds.setdefault(m.kind, []).append(m)
        self.lines = {}
        for kind in self.kinds:
            style = STYLES[kind]
            (self.lines[kind],) = ax.plot(
                [],
                [],
                style.marker,
                color=style.colour,
                mfc=style.colour if style.filled else "white",
                ms=8,
                ls="--" if style.paired else "none",
                label=style.legend,
            )
        named: dict[tuple[str, str], Mark] = {}
        for m in motion.marks:
            # A link's name once, at its first end.
            if STYLES[m.kind].named:
                named.setdefault((m.kind, m.name), m)
        self.names = [
            (m, ax.annotate(m.name, (0.0, 0.0), textcoords="offset points", xytext=(4, -14)))
            for m in named.values()
        ]
        self.show(0)

    def show(self, k: int) -> list[Any]:
        """Moves every item to frame k; returns the artists it changed."""
        for kind, items in self.kinds.items():
            points = np.array([self.at[id(m)][k] for m in items])
            if STYLES[kind].paired:
                # Pairs of ends, each pair a segment, NaN between pairs.
                pairs = points.reshape(-1, 2, 2)
                gaps = np.full((len(pairs), 1, 2), np.nan)
                points = np.concatenate([pairs, gaps], axis=1).reshape(-1, 2)
            self.lines[kind].set_data(points[:, 0], points[:, 1])
        for m, name in self.names:
            xy = self.at[id(m)][k]
            name.set_visible(not np.isnan(xy[0]))
            if not np.isnan(xy[0]):
                name.xy = tuple(xy)
        return [*self.lines.values(), *(name for _, name in self.names)]


def support_positions(motion: Motion) -> np.ndarray:
    """Where each support is in each frame, ``(frames, supports, 2)``."""
    found = [
        positions(m, motion.x, motion.y, motion.pieces) for m in motion.marks if m.kind == "support"
    ]
    return np.stack(found, axis=1) if found else np.zeros((len(motion.times), 0, 2))


def stretch_factor(fig: object, ax: object) -> float:
    """How much the y axis of `ax` magnifies against the x axis: display length per unit of y
    over display length per unit of x, from the axes' box and limits."""
    box = ax.get_position()  # type: ignore[attr-defined]
    fig_w, fig_h = fig.get_size_inches()  # type: ignore[attr-defined]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()  # type: ignore[attr-defined]
    return float((box.height * fig_h / (y1 - y0)) / (box.width * fig_w / (x1 - x0)))


def shape_name(motion: Motion) -> str:
    return "deformed frame" if motion.pieces > 1 else "deformed rod"


def broken(values: np.ndarray, pieces: int) -> np.ndarray:
    """``(frames, samples)`` of `pieces` pieces with a NaN column between consecutive pieces."""
    if pieces == 1:
        return values
    frames, samples = values.shape
    split = values.reshape(frames, pieces, samples // pieces)
    gaps = np.full((frames, pieces, 1), np.nan)
    return np.concatenate([split, gaps], axis=2).reshape(frames, -1)[:, :-1]


def segments(x: np.ndarray, y: np.ndarray, pieces: int = 1) -> np.ndarray:
    """The shape as segments between consecutive samples of each piece,
    ``(pieces (points - 1), 2, 2)``: no segment joins two pieces."""
    p = np.column_stack([x, y]).reshape(pieces, -1, 2)
    return np.stack([p[:, :-1], p[:, 1:]], axis=2).reshape(-1, 2, 2)


def midpoints(values: np.ndarray, pieces: int = 1) -> np.ndarray:
    """A segment's colour value: the mean of its two samples (within each piece)."""
    v = values.reshape(pieces, -1)
    return (0.5 * (v[:, :-1] + v[:, 1:])).reshape(-1)


def field_colours(fig: object, ax: object, motion: Motion) -> object:
    """The rod coloured by `motion.field` (a diverging colour map centred on zero, over every
    frame's range) with a colour bar naming the field and its unit; None without a field."""
    if motion.field is None:
        return None
    from matplotlib.collections import LineCollection
    from matplotlib.colors import Normalize

    bound = max(float(np.max(np.abs(motion.field))), 1e-300)
    colours = LineCollection(
        segments(motion.x[0], motion.y[0], motion.pieces),
        cmap="coolwarm",
        norm=Normalize(-bound, bound),
        linewidths=3.0,
        label=f"{shape_name(motion)}, coloured by {motion.field_name}",
    )
    colours.set_array(midpoints(motion.field[0], motion.pieces))
    ax.add_collection(colours)  # type: ignore[attr-defined]
    unit = f" [{motion.field_unit}]" if motion.field_unit else ""
    fig.colorbar(colours, ax=ax, label=f"{motion.field_name}{unit}")  # type: ignore[attr-defined]
    return colours
