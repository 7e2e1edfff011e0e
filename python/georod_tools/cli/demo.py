"""The ``demo`` command: the BuckledBeam FMU seen from a host (the Python half of scripts/demo):
the default experiment through fmpy, two Poincaré sections with their exponents, a summary.

    georod-tools demo [--out DIR] [--transient N] [--periods N]
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path

from georod_tools.cli.args import add_output_options, int_range, nonnegative_int

DEFAULT_OUT = Path("out") / "demo"


#: The line `georod-tools --help` shows.
HELP = "the BuckledBeam FMU end to end (plots, sections, summary)"


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "demo",
        help=HELP,
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "--transient", type=nonnegative_int, default=150, help="transient periods, >= 0 (150)"
    )
    p.add_argument("--periods", type=int_range(2), default=150, help="sampled periods, >= 2 (150)")
    p.add_argument("--fmu", type=Path, help="BuckledBeam FMU (target/fmu/BuckledBeam.fmu)")
    add_output_options(p, f"{DEFAULT_OUT}/demo")
    p.set_defaults(run=run, _parser=p)


def run(parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]) -> int:
    from georod_tools import fmu_path
    from georod_tools.report.records import OutputRefusedError, fmu_infos, new_run
    from georod_tools.studies.demo import run_demo

    fmu = args.fmu or fmu_path("BuckledBeam")
    if not fmu.is_file():
        parser.error(f"{fmu} not found; run scripts/build_fmus first")
    settings = {"transient": args.transient, "periods": args.periods}
    try:
        record = new_run(
            DEFAULT_OUT,
            "demo",
            "demo",
            settings,
            fmu_infos([fmu]),
            argv,
            args,
            args.out,
            args.overwrite,
        )
    except OutputRefusedError as e:
        parser.error(str(e))
    files = run_demo(record.folder, fmu, args.transient, args.periods)
    record.finish("complete", outputs=[f.name for f in files])
    for f in (*files, record.path):
        print(f"wrote {f}")
    return 0
