"""The ``animate`` command: a GIF of the deformed rod from an FMU's shape outputs.

    georod-tools animate FMU [--start-values NAME=VALUE ...] [--inputs FILE.csv] [--stop T]
                             [--step H] [--frames N] [--fps N] [-o FILE.gif]

``--inputs FILE.csv``: a first column ``time`` (s, increasing) and one column per FMU input, named
like it; before each communication step each input is set to its value interpolated at the
step's end (a moving support reaches it there, a load input is held at it over the step).
Supports are drawn where they are in each frame; a y axis stretched to show a flat motion says by
how much. ``--field NAME`` colours the rod by the field ``shape_<NAME>[i]`` (``[shape] fields``
of the scene: e.g. M, the bending moment, moving with the rod).

Default output: a new ``out/animate/<name>_<timestamp>/<name>.gif`` with its run.json; with
``-o FILE.gif`` the settings go beside it as ``FILE.gif.json`` and an existing file is kept unless
``--overwrite``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Sequence
from pathlib import Path

from georod_tools.cli.args import name_value, positive_float, positive_int

DEFAULT_OUT = Path("out") / "animate"
#: The line `georod-tools --help` shows.
HELP = "Animate the deformed rod of an FMU from its shape outputs (GIF)."


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "animate",
        help=HELP,
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("fmu", type=Path, help="the FMU (its scene needs a [shape] table)")
    p.add_argument(
        "--start-values",
        "--set",
        dest="set",
        type=name_value,
        nargs="+",
        action="extend",
        default=[],
        metavar="NAME=VALUE",
        help="start values of parameters or inputs (e.g. F=1.5 f_ctrl=0.01)",
    )
    p.add_argument(
        "--inputs",
        type=Path,
        metavar="FILE.csv",
        help="inputs over time: a time column and one column per FMU input",
    )
    p.add_argument(
        "--field",
        metavar="NAME",
        help="colour the rod by the shape field shape_<NAME>[i] (e.g. M; the scene's [shape] "
        "fields)",
    )
    p.add_argument("--stop", type=positive_float, help="end time in s, > 0 (default: the FMU's)")
    p.add_argument("--step", type=positive_float, help="communication step in s, > 0 (the FMU's)")
    p.add_argument("--frames", type=positive_int, default=150, help="frames, >= 1 (150)")
    p.add_argument("--fps", type=positive_int, default=25, help="frames per second, >= 1 (25)")
    p.add_argument("-o", "--out", type=Path, help=f"GIF to write (a new folder in {DEFAULT_OUT})")
    p.add_argument("--overwrite", action="store_true", help="replace an existing -o file")
    p.set_defaults(run=run, _parser=p)


def run(parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]) -> int:
    """Records and renders; returns the exit status."""
    from georod_tools.fmu import FmuModel
    from georod_tools.report.animation import record, render
    from georod_tools.report.records import OutputRefusedError, fmu_info, new_run

    if not args.fmu.is_file():
        parser.error(f"{args.fmu}: no such FMU (build it with scripts/build_fmus)")
    settings = {
        "start_values": dict(args.set),
        "inputs": str(args.inputs) if args.inputs else None,
        "field": args.field,
        "stop": args.stop,
        "step": args.step,
        "frames": args.frames,
        "fps": args.fps,
    }
    model = FmuModel.load(args.fmu)
    if args.inputs is not None:
        from georod_tools.report.animation import InputTable

        try:  # refused before anything is written
            InputTable.read(args.inputs, model.names("input"))
        except ValueError as e:
            parser.error(str(e))
    if args.field is not None:
        from georod_tools.report.animation import field_outputs

        points = sum(1 for n in model.outputs if n.startswith("shape_x["))
        try:
            field_outputs(model, args.field, max(points, 1))
        except ValueError as e:
            parser.error(str(e))
    run_record = None
    if args.out is None:
        try:
            run_record = new_run(
                DEFAULT_OUT,
                args.fmu.stem,
                "animate",
                settings,
                fmu_info(args.fmu, model.guid, model.identifier),
                argv,
                args,
            )
        except OutputRefusedError as e:
            parser.error(str(e))
        out = run_record.folder / f"{args.fmu.stem}.gif"
    else:
        out = args.out
        if out.exists() and not args.overwrite:
            parser.error(f"-o {out}: the file exists; pass --overwrite to replace it")
    started = time.time()
    try:
        motion = record(
            args.fmu, dict(args.set), args.stop, args.step, args.frames, args.inputs, args.field
        )
    except ValueError as e:
        parser.error(str(e))
    render(motion, out, args.fps)
    done = {"stop": float(motion.times[-1]), "frames": len(motion.times)}
    if run_record is not None:
        run_record.finish("complete", result=done, outputs=[out.name])
    else:
        info = {
            "command": ["georod-tools", *argv] if argv else sys.argv,
            "fmu": str(args.fmu),
            "guid": motion.guid,
            **settings,
            **done,
            "seconds": round(time.time() - started, 2),
        }
        Path(f"{out}.json").write_text(json.dumps(info, indent=2) + "\n", encoding="utf-8")
    print(f"wrote {out} ({len(motion.times)} frames, t = 0..{motion.times[-1]:g} s)")
    return 0
