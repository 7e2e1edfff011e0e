"""The deformed rod over time, from an FMU's shape outputs (``shape_x[i]``, ``shape_y[i]``).

:func:`record` runs the FMU from its initial state (communication step `step`, default: the FMU's
default experiment) and samples the shape at `frames` equally spaced times; :func:`render` writes
a GIF (matplotlib + Pillow) with the initial shape in grey, the supports marked, and the time
shown. The command is ``georod-tools animate`` (:mod:`georod_tools.cli.animate`).
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

SHAPE = re.compile(r"shape_([xy])\[(\d+)\]$")


@dataclass
class Motion:
    """Shape samples over time: ``x[k, i]``, ``y[k, i]`` at ``times[k]``."""

    name: str
    guid: str
    times: np.ndarray
    x: np.ndarray
    y: np.ndarray
    supports: list[tuple[str, float]]
    unit: str = "m"


def record(
    fmu: Path, start_values: dict[str, float], stop: float | None, step: float | None, frames: int
) -> Motion:
    """Simulates `fmu` and samples its shape outputs at `frames` + 1 times from 0 to `stop`."""
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
    experiment = model.md.defaultExperiment
    stop = stop if stop is not None else float(experiment.stopTime)
    step = step if step is not None else float(experiment.stepSize)
    steps = max(1, round(stop / step))
    sampled = set(np.linspace(0, steps, min(frames, steps) + 1).round().astype(int).tolist())
    for name in start_values:
        if name not in model.variables:
            raise ValueError(f"--start-values {name}: not a variable of {model.identifier}")
    times, xs, ys = [], [], []
    with lend(model, "animate") as inst:
        inst.initialize(start_values)
        read = inst.reader(names)
        for k in tqdm(
            range(steps + 1), desc=f"simulating {model.identifier}", unit="step", leave=False
        ):
            if k in sampled:
                got = read()
                times.append(k * step)
                xs.append(got[: len(order)])
                ys.append(got[len(order) :])
            if k < steps:
                inst.step(k * step, step)
    scene = tomllib.loads((model.unzipdir / "resources" / "scene.toml").read_text("utf-8"))
    supports = [(s["name"], float(s["at"])) for s in scene.get("support", [])]
    unit = model.variables[names[0]].unit or "m"
    return Motion(
        model.identifier, model.guid, np.array(times), np.array(xs), np.array(ys), supports, unit
    )


def render(motion: Motion, out: Path, fps: int) -> Path:
    """Writes the animation of `motion` to `out` (GIF)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter
    from tqdm import tqdm

    x, y = motion.x, motion.y
    width, height = max(np.ptp(x), 1e-12), max(np.ptp(y), 1e-12)
    fig, ax = plt.subplots(figsize=(8, 4), dpi=80)
    ax.set_xlim(x.min() - 0.05 * width, x.max() + 0.05 * width)
    ax.set_ylim(y.min() - 0.1 * height, y.max() + 0.1 * height)
    # True proportions unless the motion would be a flat line in them (a beam deflecting by a
    # few percent of its length): then the y axis is stretched, and says so.
    stretched = height < 0.15 * width
    if not stretched:
        ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(f"x [{motion.unit}]")
    ax.set_ylabel(f"y [{motion.unit}]" + (", stretched" if stretched else ""))
    ax.grid(alpha=0.3)
    ax.plot(x[0], y[0], color="0.75", lw=1.5, label="initial state")
    points = x.shape[1]
    for name, at in motion.supports:
        i = round(at * (points - 1))
        ax.plot([x[0, i]], [y[0, i]], "k^", ms=8)
        ax.annotate(name, (x[0, i], y[0, i]), textcoords="offset points", xytext=(4, -14))
    (line,) = ax.plot(x[0], y[0], color="C0", lw=2.5, label="deformed rod")
    label = ax.set_title("")
    ax.legend(loc="upper right")

    def frame(k: int) -> tuple:
        line.set_data(x[k], y[k])
        label.set_text(f"{motion.name}: t = {motion.times[k]:.5f} s")
        return line, label

    anim = FuncAnimation(fig, frame, frames=len(motion.times), blit=True)
    bar = tqdm(total=len(motion.times), desc=f"rendering {out.name}", unit="frame", leave=False)
    out.parent.mkdir(parents=True, exist_ok=True)
    anim.save(str(out), writer=PillowWriter(fps=fps), progress_callback=lambda i, n: bar.update(1))
    bar.close()
    plt.close(fig)
    return out
