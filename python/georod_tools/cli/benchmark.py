"""The ``benchmark`` command, each run into a new folder under ``out/benchmark/``:

    georod-tools benchmark precision [--quick] [--no-exudyn] [--parts LIST]   # docs/benchmark.md
    georod-tools benchmark lyapunov [--quick] [--count N] [--workers 1,2]     # the two methods

``precision``: work-precision of the FMU against Exudyn, spatial error, scaling
(:mod:`georod_tools.studies.benchmark`); ``--update-docs`` copies its figures into docs/figures.
``lyapunov``: the core's exponent against the two-instance cross-check on the same bifurcation
diagram, with 1, 2, ... Dask workers (:mod:`georod_tools.studies.lyapunov_benchmark`).
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

from georod_tools.cli.args import add_output_options, nonnegative_int, positive_int
from georod_tools.cli.runs import finish_run, start_run
from georod_tools.cli.study import DOCS

DEFAULT_OUT = Path("out") / "benchmark"


def _workers(text: str) -> tuple[int, ...]:
    try:
        got = tuple(int(x) for x in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a list like 1,2,4, got {text!r}") from None
    if not got or min(got) < 1:
        raise argparse.ArgumentTypeError(f"worker counts must be integers >= 1, got {text!r}")
    return got


#: The line `georod-tools --help` shows.
HELP = "benchmarks: precision (vs Exudyn), lyapunov (methods)"


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "benchmark",
        help=HELP,
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    kinds = p.add_subparsers(dest="benchmark", required=True)
    from georod_tools.studies.benchmark import PARTS

    s = kinds.add_parser("precision", help="work-precision against Exudyn, spatial error, scaling")
    s.add_argument("--quick", action="store_true", help="smoke-test sizes (seconds)")
    s.add_argument("--no-exudyn", action="store_true", help="skip the Exudyn runs")
    s.add_argument("--fmu", type=Path, help="BuckledBeam FMU (target/fmu/BuckledBeam.fmu)")
    s.add_argument(
        "--parts", default=",".join(PARTS), help=f"comma-separated subset of {','.join(PARTS)}"
    )
    add_output_options(s, "out/benchmark/precision", "docs/figures")
    s.set_defaults(run=run_precision, _parser=s)

    from georod_tools.studies.lyapunov_benchmark import BenchSettings, default_workers

    d = BenchSettings(fmu="")
    s = kinds.add_parser("lyapunov", help="the core's exponent against the two-instance twin")
    s.add_argument("--quick", action="store_true", help="6 values, 50 + 50 periods")
    s.add_argument("--count", type=positive_int, help=f"values of F, >= 1 ({d.count})")
    s.add_argument("--transient", type=nonnegative_int, help=f"periods, >= 0 ({d.transient})")
    s.add_argument("--periods", type=positive_int, help=f"sampled periods, >= 11 ({d.periods})")
    s.add_argument("--substeps", type=positive_int, help=f"sub-steps per period ({d.substeps})")
    s.add_argument(
        "--workers",
        type=_workers,
        help=f"worker counts, e.g. 1,2 (1, 2, 4, ... up to the cores: "
        f"{','.join(map(str, default_workers()))})",
    )
    s.add_argument("--fmu", type=Path, help="BuckledBeam FMU (target/fmu/BuckledBeam.fmu)")
    s.add_argument("--no-progress", action="store_true", help="no progress bars")
    add_output_options(s, "out/benchmark/lyapunov")
    s.set_defaults(run=run_lyapunov, _parser=s)


def run_precision(
    parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]
) -> int:
    from georod_tools import fmu_path
    from georod_tools.studies.benchmark import PARTS
    from georod_tools.studies.benchmark_report import run_benchmark

    parts = [x.strip() for x in args.parts.split(",") if x.strip()]
    bad = [x for x in parts if x not in PARTS]
    if bad or not parts:
        parser.error(f"--parts: unknown {', '.join(bad)}; choose from {', '.join(PARTS)}")
    fmu = args.fmu or fmu_path("BuckledBeam")
    settings = {"quick": args.quick, "exudyn": not args.no_exudyn, "parts": parts}
    record = start_run(parser, args, argv, DEFAULT_OUT, "benchmark precision", settings, [fmu])
    rep = run_benchmark(record.folder, args.quick, not args.no_exudyn, fmu, parts)
    return finish_run(record, rep.files, args, DOCS, "benchmark_*.png")


def run_lyapunov(
    parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]
) -> int:
    from georod_tools import fmu_path
    from georod_tools.studies.lyapunov_benchmark import (
        BenchSettings,
        default_workers,
        run_lyapunov_benchmark,
    )

    fmu = str((args.fmu or fmu_path("BuckledBeam")).resolve())
    st = BenchSettings.quick(fmu) if args.quick else BenchSettings(fmu, workers=default_workers())
    for name in ("count", "transient", "periods", "substeps", "workers"):
        if getattr(args, name) is not None:
            st = replace(st, **{name: getattr(args, name)})
    if st.periods <= 10:
        parser.error(f"--periods {st.periods}: must be >= 11 (10 periods align the exponent)")
    record = start_run(
        parser, args, argv, DEFAULT_OUT, "benchmark lyapunov", {"settings": st}, [Path(fmu)]
    )
    files = run_lyapunov_benchmark(st, record.folder, progress=not args.no_progress)
    return finish_run(record, files, args, DOCS)
