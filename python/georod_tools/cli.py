"""Command line of the chaos analyses (``georod-chaos`` / ``python -m georod_tools``).

    python -m georod_tools case --fmu target/fmu/BuckledBeam.fmu --F 0.7 --Omega 3500
    python -m georod_tools sweep --param F --start 0.4 --stop 2 --count 100 --workers 2

`case` writes a three-panel PNG (Poincaré section, phase portrait, displacement-time diagram) and
the samples as CSV and prints the classification; `sweep` writes the bifurcation diagram with the
Lyapunov exponent beneath (PNG) and two CSV files, case by case, resumable
(:mod:`georod_tools.sweep_command`). Each output folder gets a ``run.json``
(:mod:`georod_tools.records`); an existing non-empty one is refused unless ``--resume`` (sweep)
or ``--overwrite``. Bad arguments are refused with their allowed range (exit status 2); a failing
simulation exits with status 1 and the FMU's message.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from georod_tools.argtypes import (
    finite_float,
    float_range,
    int_range,
    nonnegative_int,
    positive_float,
    positive_int,
)
from georod_tools.classify import ClassifySettings

if TYPE_CHECKING:
    from georod_tools.runner import CaseConfig

DEFAULT_OUT = Path("out") / "chaos"
#: Largest mesh and sweep size accepted on the command line.
MAX_ELEMENTS = MAX_COUNT = 100_000


def _default_fmu(scene: str) -> Path:
    try:
        from georod_tools import fmu_path

        return Path(fmu_path(scene))
    except ImportError:  # __init__ without the helper
        return Path(__file__).resolve().parents[2] / "target" / "fmu" / f"{scene}.fmu"


def _name_value(text: str) -> tuple[str, float]:
    name, sep, value = text.partition("=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    try:
        x = float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{name}: {value!r} is not a number") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"{name}={value}: must be a finite number")
    return name.strip(), x


def _add_case_options(p: argparse.ArgumentParser, sweep: bool) -> None:
    g = p.add_argument_group("model")
    g.add_argument("--fmu", type=Path, help="FMU file (default: target/fmu/<scene>.fmu)")
    g.add_argument(
        "--scene", default="BuckledBeam", help="scene of scenes/ when no --fmu (BuckledBeam)"
    )
    g.add_argument(
        "--F", type=finite_float, help="forcing amplitude, finite (default: the FMU's start value)"
    )
    g.add_argument(
        "--Omega",
        type=float_range(0.0, unit="rad/s"),
        help="forcing frequency in rad/s, > 0 (default: the FMU's start value)",
    )
    g.add_argument(
        "--elements",
        type=int_range(2, MAX_ELEMENTS),
        default=10,
        help=f"finite elements, 2..{MAX_ELEMENTS} (10)",
    )
    g.add_argument(
        "--dt-max", type=positive_float, default=1e-5, help="largest internal step in s, > 0 (1e-5)"
    )
    g.add_argument(
        "--set",
        type=_name_value,
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="any other FMU parameter (repeatable), e.g. --set well=-1",
    )
    g = p.add_argument_group("run")
    g.add_argument(
        "--transient", type=nonnegative_int, default=200, help="periods discarded, >= 0 (200)"
    )
    g.add_argument("--periods", type=positive_int, default=200, help="periods sampled, >= 1 (200)")
    g.add_argument(
        "--per-period",
        type=positive_int,
        default=20 if sweep else 40,
        help=f"communication steps per forcing period, >= 1 ({20 if sweep else 40})",
    )
    if not sweep:
        g.add_argument(
            "--dense-periods",
            type=nonnegative_int,
            default=20,
            help="last sampled periods kept for the phase portrait and time plot, "
            "0..--periods (20)",
        )
    g = p.add_argument_group("analysis")
    g.add_argument("--no-lyapunov", action="store_true", help="skip the Lyapunov exponent")
    g.add_argument(
        "--renorm-every", type=positive_int, default=1, help="periods between renormalizations (1)"
    )
    g.add_argument(
        "--d0", type=positive_float, default=1e-7, help="Lyapunov separation, > 0 (1e-7)"
    )
    g.add_argument(
        "--discard", type=nonnegative_int, default=10, help="Lyapunov intervals not averaged (10)"
    )
    d = ClassifySettings()
    g.add_argument(
        "--k-max", type=positive_int, default=d.k_max, help=f"largest period, >= 1 ({d.k_max})"
    )
    g.add_argument(
        "--period-tol",
        type=float_range(0.0, 1.0),
        default=d.period_tol,
        help=f"period tolerance relative to the attractor size, in (0, 1) ({d.period_tol})",
    )
    g.add_argument(
        "--chaos-threshold",
        type=positive_float,
        default=d.chaos_threshold,
        help=f"exponent per period above which a motion is chaotic, > 0 ({d.chaos_threshold})",
    )
    g = p.add_argument_group("output")
    g.add_argument(
        "--out",
        type=Path,
        help=f"output folder (default: a new {DEFAULT_OUT}/{'sweep_<param>' if sweep else 'case'}"
        "_<timestamp>); an existing non-empty folder is refused unless "
        + ("--resume or " if sweep else "")
        + "--overwrite",
    )
    if sweep:
        g.add_argument(
            "--resume",
            action="store_true",
            help="continue the sweep recorded in --out (same settings): finished cases are kept",
        )
    g.add_argument(
        "--overwrite",
        action="store_true",
        help="empty --out first (only a folder written by georod_tools, with a run.json)",
    )


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="georod-chaos",
        description="Analyses of the georod FMUs: Poincaré sections, phase portraits, "
        "bifurcation diagrams, Lyapunov exponents, studies, animations.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    pc = sub.add_parser("case", help="one run: section, phase portrait, time plot, exponent")
    _add_case_options(pc, sweep=False)
    pc.set_defaults(_parser=pc)  # errors show the subcommand's usage
    ps = sub.add_parser("sweep", help="bifurcation diagram over F or Omega (Dask)")
    ps.add_argument("--param", default="F", help="parameter swept: F, Omega or any FMU Real (F)")
    ps.add_argument("--start", type=finite_float, required=True, help="first value, finite")
    ps.add_argument("--stop", type=finite_float, required=True, help="last value, finite")
    ps.add_argument(
        "--count",
        type=int_range(1, MAX_COUNT),
        default=50,
        help=f"number of values, 1..{MAX_COUNT} (50)",
    )
    ps.add_argument(
        "--workers", type=positive_int, default=2, help="local worker processes, >= 1 (2)"
    )
    ps.add_argument(
        "--scheduler",
        metavar="ADDR",
        help="address of a running Dask scheduler, e.g. tcp://host:8786 (no local cluster); "
        "its workers need georod_tools, not the FMU file: the FMU is sent to them",
    )
    ps.add_argument("--no-progress", action="store_true", help="no progress bar")
    _add_case_options(ps, sweep=True)
    ps.set_defaults(_parser=ps)
    from georod_tools.study import add_study_parser

    add_study_parser(sub)
    from georod_tools.benchmark import add_benchmark_parser

    add_benchmark_parser(sub)
    from georod_tools.animate import add_animate_parser

    add_animate_parser(sub)
    return parser


def _check(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Checks across options (single values are checked by their argparse types); exits with
    status 2 and the allowed range."""

    def need(ok: bool, msg: str) -> None:
        if not ok:
            parser.error(msg)

    if not args.no_lyapunov:
        need(
            args.periods // args.renorm_every > args.discard,
            f"--periods {args.periods} must exceed --discard {args.discard} times "
            f"--renorm-every {args.renorm_every} (at least one averaged Lyapunov interval)",
        )
    for name, _ in args.set:
        need(
            name not in ("F", "Omega", "elements", "dt_max"),
            f"--set {name}: use --{name.replace('_', '-')} instead",
        )
    if args.command == "case":
        need(
            args.dense_periods <= args.periods,
            f"--dense-periods {args.dense_periods}: allowed range 0..--periods ({args.periods})",
        )
    else:
        need(args.param not in ("elements",), "--param elements: sweep a Real parameter")
        if args.param == "Omega":
            need(
                args.start > 0 and args.stop > 0,
                f"--param Omega: --start {args.start} and --stop {args.stop} must be > 0",
            )
        if args.param == "dt_max":
            need(
                args.start > 0 and args.stop > 0,
                f"--param dt_max: --start {args.start} and --stop {args.stop} must be > 0",
            )
    if args.fmu is not None:
        need(args.fmu.is_file(), f"--fmu {args.fmu}: no such file (build with scripts/build_fmus)")


def _base_config(parser: argparse.ArgumentParser, args: argparse.Namespace) -> CaseConfig:
    """The case configuration of the command line (parameter names checked against the FMU)."""
    from georod_tools.runner import CaseConfig, FmuModel

    fmu = args.fmu or _default_fmu(args.scene)
    if not Path(fmu).is_file():
        parser.error(f"FMU {fmu} not found: build it with scripts/build_fmus or pass --fmu")
    model = FmuModel.load(fmu)
    params = model.parameters
    for name, _ in args.set:
        if name not in params:
            parser.error(
                f"--set {name}: {model.identifier} has no such parameter; "
                f"its parameters are {', '.join(params)}"
            )
    if args.command == "sweep" and args.param not in params:
        parser.error(
            f"--param {args.param}: {model.identifier} has no such parameter; "
            f"its parameters are {', '.join(params)}"
        )

    def start(name: str) -> float:
        for v in model.md.modelVariables:
            if v.name == name and v.start is not None:
                return float(v.start)
        parser.error(f"{model.identifier} gives no start value for {name}; pass --{name}")
        raise AssertionError  # unreachable

    omega = args.Omega if args.Omega is not None else start("Omega")
    if not omega > 0:
        parser.error(f"Omega = {omega}: must be > 0; pass --Omega")
    classify = ClassifySettings(
        k_max=args.k_max,
        period_tol=args.period_tol,
        chaos_threshold=args.chaos_threshold,
        zero_band=args.chaos_threshold,
    )
    try:
        return CaseConfig(
            fmu=str(Path(fmu).resolve()),
            F=args.F if args.F is not None else start("F"),
            Omega=omega,
            elements=args.elements,
            dt_max=args.dt_max,
            params=tuple(args.set),
            transient_periods=args.transient,
            sample_periods=args.periods,
            n_per_period=args.per_period,
            dense_periods=getattr(args, "dense_periods", 0),
            lyapunov=not args.no_lyapunov,
            lyapunov_every=args.renorm_every,
            lyapunov_d0=args.d0,
            lyapunov_discard=args.discard,
            classify_settings=classify,
        )
    except ValueError as e:
        parser.error(str(e))
        raise AssertionError from e  # unreachable


def _fmt(x: float) -> str:
    return f"{x:g}".replace("+", "")


def run_case_command(
    parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]
) -> int:
    from georod_tools.plots import plot_case, write_case_csv, write_dense_csv
    from georod_tools.records import (
        OutputRefusedError,
        RunRecord,
        fmu_info,
        fresh_folder,
        jsonable,
        options,
        prepare_output,
    )
    from georod_tools.runner import FmuModel, run_case

    cfg = _base_config(parser, args)
    out = args.out if args.out is not None else fresh_folder(DEFAULT_OUT, "case")
    try:
        prepare_output(out, overwrite=args.overwrite)
    except OutputRefusedError as e:
        parser.error(str(e))
    model = FmuModel.load(cfg.fmu)
    settings = jsonable(cfg)
    settings.pop("fmu")
    record = RunRecord.create(
        out, "case", settings, fmu_info(cfg.fmu, model.md.guid, model.identifier)
    )
    record.start_session(argv, options(args))
    try:
        result = run_case(cfg)
    except Exception as e:
        record.finish("failed", error=f"{type(e).__name__}: {e}")
        raise
    stem = f"{Path(cfg.fmu).stem}_F{_fmt(cfg.F)}_Omega{_fmt(cfg.Omega)}"
    png = plot_case(result, out / f"{stem}.png")
    csv_path = write_case_csv(result, out / f"{stem}_samples.csv")
    dense = write_dense_csv(result, out / f"{stem}_dense.csv")
    c = result.classification
    written = [p for p in (png, csv_path, dense) if p is not None]
    record.finish(
        "complete",
        result={"class": c.label, "lyapunov_per_period": result.exponent_per_period},
        outputs=[p.name for p in written],
    )
    print(
        f"{Path(cfg.fmu).stem}: F = {cfg.F:g}, Omega = {cfg.Omega:g}, "
        f"{cfg.elements} elements, {cfg.transient_periods} + {cfg.sample_periods} periods"
    )
    print(f"class: {c.label} ({c.note})")
    if result.lyapunov is not None:
        ly = result.lyapunov
        print(
            f"largest Lyapunov exponent: {ly.per_period:.4f} +- {ly.stderr:.4f} per period "
            f"= {ly.per_second:.2f} 1/s"
        )
    print(f"run time: {result.wall_time:.2f} s")
    for p in (*written, record.path):
        print(f"wrote {p}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command == "study":
        from georod_tools.study import run_study_command

        return run_study_command(parser, args)
    if args.command == "benchmark":
        from georod_tools.benchmark import run_benchmark_command

        return run_benchmark_command(parser, args)
    if args.command == "animate":
        from georod_tools import animate

        return animate.run(args, argv)
    sub = args._parser
    _check(sub, args)
    try:
        if args.command == "case":
            return run_case_command(sub, args, argv)
        from georod_tools.sweep_command import run_sweep_command

        return run_sweep_command(sub, args, _base_config(sub, args), argv)
    except (RuntimeError, ValueError, OSError) as e:
        print(f"georod-chaos: error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
