"""The deformed rod over time, from an FMU's shape outputs (``shape_x[i]``, ``shape_y[i]``).

    python -m georod_tools animate FMU [--start-values NAME=VALUE ...] [--stop T] [--step H]
                                       [--frames N] [--fps N] [-o out/animate/NAME.gif]

Runs the FMU through fmpy from its initial state (communication step ``--step``, default: the
FMU's default experiment), samples the shape at ``--frames`` equally spaced times, and writes a
GIF (matplotlib + Pillow) with the reference shape in grey, the supports marked, and the time
shown. The settings that made it are written beside it (``NAME.gif.json``); an existing file is
kept unless ``--overwrite`` is given.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import time
import tomllib
from collections.abc import Sequence
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


def _positive(kind: type) -> object:
    def parse(text: str) -> float | int:
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
        if not (np.isfinite(value) and value > 0):
            raise argparse.ArgumentTypeError(f"must be finite and > 0, got {text!r}")
        return value

    return parse


def _name_value(text: str) -> tuple[str, float]:
    name, sep, value = text.partition("=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    try:
        return name.strip(), float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{name}: {value!r} is not a number") from None


def record(
    fmu: Path, start_values: dict[str, float], stop: float | None, step: float | None, frames: int
) -> Motion:
    """Simulates `fmu` and samples its shape outputs at `frames` + 1 times from 0 to `stop`."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    from tqdm import tqdm

    md = read_model_description(str(fmu))
    shape: dict[str, dict[int, int]] = {"x": {}, "y": {}}
    variables = {v.name: v for v in md.modelVariables}
    for v in md.modelVariables:
        m = SHAPE.match(v.name)
        if m:
            shape[m.group(1)][int(m.group(2))] = v.valueReference
    if not shape["x"] or sorted(shape["x"]) != sorted(shape["y"]):
        raise ValueError(f"{fmu}: no shape_x[i] / shape_y[i] outputs (give the scene a [shape])")
    order = sorted(shape["x"])
    vr_x, vr_y = [shape["x"][i] for i in order], [shape["y"][i] for i in order]
    experiment = md.defaultExperiment
    stop = stop if stop is not None else float(experiment.stopTime)
    step = step if step is not None else float(experiment.stepSize)
    steps = max(1, round(stop / step))
    sampled = set(np.linspace(0, steps, min(frames, steps) + 1).round().astype(int).tolist())
    unzipped = extract(str(fmu))
    ident = md.coSimulation.modelIdentifier
    slave = FMU2Slave(
        guid=md.guid, unzipDirectory=unzipped, modelIdentifier=ident, instanceName="animate"
    )
    slave.instantiate()
    times, xs, ys = [], [], []
    try:
        slave.setupExperiment(startTime=0.0)
        for name, value in start_values.items():
            if name not in variables:
                raise ValueError(f"--set {name}: not a variable of {ident}")
            vr = variables[name].valueReference
            if variables[name].type == "Real":
                slave.setReal([vr], [value])
            else:
                slave.setInteger([vr], [int(value)])
        slave.enterInitializationMode()
        slave.exitInitializationMode()
        for k in tqdm(range(steps + 1), desc=f"simulating {ident}", unit="step", leave=False):
            if k in sampled:
                times.append(k * step)
                xs.append(slave.getReal(vr_x))
                ys.append(slave.getReal(vr_y))
            if k < steps:
                slave.doStep(k * step, step)
        slave.terminate()
    finally:
        slave.freeInstance()
    scene = tomllib.loads((Path(unzipped) / "resources" / "scene.toml").read_text("utf-8"))
    supports = [(s["name"], float(s["at"])) for s in scene.get("support", [])]
    return Motion(ident, md.guid, np.array(times), np.array(xs), np.array(ys), supports)


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
    ax.set_xlabel("x (length units)")
    ax.set_ylabel("y (length units)" + (", stretched" if stretched else ""))
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


DESCRIPTION = "Animate the deformed rod of an FMU from its shape outputs (GIF)."


def add_options(p: argparse.ArgumentParser) -> None:
    """The options of the animate command (also a subcommand of ``python -m georod_tools``)."""
    p.add_argument("fmu", type=Path, help="the FMU (its scene needs a [shape] table)")
    p.add_argument(
        "--start-values", "--set", dest="set", type=_name_value, nargs="+", action="extend",
        default=[], metavar="NAME=VALUE",
        help="start values of parameters or inputs (e.g. F=1.5 f_ctrl=0.01)",
    )
    p.add_argument("--stop", type=_positive(float), help="end time (default: the FMU's)")
    p.add_argument("--step", type=_positive(float), help="communication step (default: the FMU's)")
    p.add_argument("--frames", type=_positive(int), default=150, help="frames (150)")
    p.add_argument("--fps", type=_positive(int), default=25, help="frames per second (25)")
    p.add_argument("-o", "--out", type=Path, help="GIF to write (out/animate/<name>.gif)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing file")


def add_animate_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("animate", help=DESCRIPTION, description=DESCRIPTION)
    add_options(p)


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m georod_tools animate", description=DESCRIPTION)
    add_options(p)
    return run(p.parse_args(argv), argv)


def run(args: argparse.Namespace, argv: Sequence[str] | None = None) -> int:
    """Runs the command for parsed arguments; returns the exit status."""
    if not args.fmu.is_file():
        print(f"animate: {args.fmu} not found (build it with scripts/build_fmus)", file=sys.stderr)
        return 2
    out = args.out or Path("out") / "animate" / f"{args.fmu.stem}.gif"
    if out.exists() and not args.overwrite:
        print(f"animate: {out} exists; pass --overwrite to replace it", file=sys.stderr)
        return 2
    started = time.time()
    try:
        motion = record(args.fmu, dict(args.set), args.stop, args.step, args.frames)
    except ValueError as e:
        print(f"animate: {e}", file=sys.stderr)
        return 2
    render(motion, out, args.fps)
    settings = {
        "command": sys.argv if argv is None else ["animate", *argv],
        "fmu": str(args.fmu),
        "guid": motion.guid,
        "start_values": dict(args.set),
        "stop": float(motion.times[-1]),
        "frames": len(motion.times),
        "fps": args.fps,
        "seconds": round(time.time() - started, 2),
    }
    Path(f"{out}.json").write_text(json.dumps(settings, indent=2) + "\n", encoding="utf-8")
    print(f"wrote {out} ({len(motion.times)} frames, t = 0..{motion.times[-1]:g} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
