"""Command line of the chaos analyses (``georod-chaos`` / ``python -m georod_tools``).

    python -m georod_tools case --fmu target/fmu/BuckledBeam.fmu --F 0.7 --Omega 3500
    python -m georod_tools sweep --param F --start 0.4 --stop 2 --count 100 --workers 2

`case` writes a three-panel PNG (Poincaré section, phase portrait, displacement-time diagram) and
the samples as CSV and prints the classification; `sweep` writes the bifurcation diagram with the
Lyapunov exponent beneath (PNG) and two CSV files. Bad arguments are refused with their allowed
range (exit status 2); a failing simulation exits with status 1 and the FMU's message.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from georod_tools.classify import ClassifySettings

if TYPE_CHECKING:
    from georod_tools.runner import CaseConfig

DEFAULT_OUT = Path("out") / "chaos"


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
        return name.strip(), float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{name}: {value!r} is not a number") from None


def _add_case_options(p: argparse.ArgumentParser, sweep: bool) -> None:
    g = p.add_argument_group("model")
    g.add_argument("--fmu", type=Path, help="FMU file (default: target/fmu/<scene>.fmu)")
    g.add_argument(
        "--scene", default="BuckledBeam", help="scene of scenes/ when no --fmu (BuckledBeam)"
    )
    g.add_argument("--F", type=float, help="forcing amplitude (default: the FMU's start value)")
    g.add_argument("--Omega", type=float, help="forcing frequency in rad/s, > 0 (default: FMU's)")
    g.add_argument("--elements", type=int, default=10, help="finite elements, >= 2 (10)")
    g.add_argument("--dt-max", type=float, default=1e-5, help="largest internal step, > 0 (1e-5)")
    g.add_argument(
        "--set",
        type=_name_value,
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="any other FMU parameter (repeatable), e.g. --set well=-1",
    )
    g = p.add_argument_group("run")
    g.add_argument("--transient", type=int, default=200, help="periods discarded, >= 0 (200)")
    g.add_argument("--periods", type=int, default=200, help="periods sampled, >= 1 (200)")
    g.add_argument(
        "--per-period",
        type=int,
        default=20 if sweep else 40,
        help=f"communication steps per forcing period, >= 1 ({20 if sweep else 40})",
    )
    if not sweep:
        g.add_argument(
            "--dense-periods",
            type=int,
            default=20,
            help="last sampled periods kept for the phase portrait and time plot (20)",
        )
    g = p.add_argument_group("analysis")
    g.add_argument("--no-lyapunov", action="store_true", help="skip the Lyapunov exponent")
    g.add_argument("--renorm-every", type=int, default=1, help="periods between renormalizations")
    g.add_argument("--d0", type=float, default=1e-7, help="Lyapunov separation, > 0 (1e-7)")
    g.add_argument("--discard", type=int, default=10, help="Lyapunov intervals not averaged (10)")
    d = ClassifySettings()
    g.add_argument("--k-max", type=int, default=d.k_max, help=f"largest period ({d.k_max})")
    g.add_argument(
        "--period-tol",
        type=float,
        default=d.period_tol,
        help=f"period tolerance relative to the attractor size, in (0, 1) ({d.period_tol})",
    )
    g.add_argument(
        "--chaos-threshold",
        type=float,
        default=d.chaos_threshold,
        help=f"exponent per period above which a motion is chaotic, > 0 ({d.chaos_threshold})",
    )
    p.add_argument("--out", type=Path, default=DEFAULT_OUT, help=f"output folder ({DEFAULT_OUT})")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="georod-chaos",
        description="Chaos analyses of the georod FMUs: Poincaré sections, phase portraits, "
        "bifurcation diagrams, Lyapunov exponents.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    pc = sub.add_parser("case", help="one run: section, phase portrait, time plot, exponent")
    _add_case_options(pc, sweep=False)
    ps = sub.add_parser("sweep", help="bifurcation diagram over F or Omega (Dask)")
    ps.add_argument("--param", default="F", help="parameter swept: F, Omega or any FMU Real (F)")
    ps.add_argument("--start", type=float, required=True, help="first value")
    ps.add_argument("--stop", type=float, required=True, help="last value")
    ps.add_argument("--count", type=int, default=50, help="number of values, 1..100000 (50)")
    ps.add_argument("--workers", type=int, default=2, help="local worker processes, >= 1 (2)")
    ps.add_argument("--scheduler", help="address of a running Dask scheduler (no local cluster)")
    ps.add_argument("--no-progress", action="store_true", help="no progress bar")
    _add_case_options(ps, sweep=True)
    from georod_tools.study import add_study_parser

    add_study_parser(sub)
    from georod_tools.benchmark import add_benchmark_parser

    add_benchmark_parser(sub)
    return parser


def _check(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Range checks that argparse types cannot express; exits with status 2 and the range."""

    def need(ok: bool, msg: str) -> None:
        if not ok:
            parser.error(msg)

    def finite(x: float | None) -> bool:
        return x is None or math.isfinite(x)

    need(finite(args.F), f"--F {args.F}: must be a finite number")
    need(
        args.Omega is None or (finite(args.Omega) and args.Omega > 0),
        f"--Omega {args.Omega}: must be > 0 (rad/s)",
    )
    need(2 <= args.elements <= 100000, f"--elements {args.elements}: allowed range 2..100000")
    need(finite(args.dt_max) and args.dt_max > 0, f"--dt-max {args.dt_max}: must be > 0")
    need(args.transient >= 0, f"--transient {args.transient}: must be >= 0")
    need(args.periods >= 1, f"--periods {args.periods}: must be >= 1")
    need(args.per_period >= 1, f"--per-period {args.per_period}: must be >= 1")
    need(args.renorm_every >= 1, f"--renorm-every {args.renorm_every}: must be >= 1")
    need(finite(args.d0) and args.d0 > 0, f"--d0 {args.d0}: must be > 0")
    need(args.discard >= 0, f"--discard {args.discard}: must be >= 0")
    if not args.no_lyapunov:
        need(
            args.periods // args.renorm_every > args.discard,
            f"--periods {args.periods} must exceed --discard {args.discard} times "
            f"--renorm-every {args.renorm_every} (at least one averaged Lyapunov interval)",
        )
    need(args.k_max >= 1, f"--k-max {args.k_max}: must be >= 1")
    need(0 < args.period_tol < 1, f"--period-tol {args.period_tol}: allowed range (0, 1)")
    need(args.chaos_threshold > 0, f"--chaos-threshold {args.chaos_threshold}: must be > 0")
    for name, value in args.set:
        need(math.isfinite(value), f"--set {name}={value}: must be finite")
        need(
            name not in ("F", "Omega", "elements", "dt_max"),
            f"--set {name}: use --{name.replace('_', '-')} instead",
        )
    if args.command == "case":
        need(
            0 <= args.dense_periods <= args.periods,
            f"--dense-periods {args.dense_periods}: allowed range 0..--periods ({args.periods})",
        )
    else:
        need(1 <= args.count <= 100000, f"--count {args.count}: allowed range 1..100000")
        need(args.workers >= 1, f"--workers {args.workers}: must be >= 1")
        need(finite(args.start) and finite(args.stop), "--start/--stop must be finite")
        need(args.param not in ("elements",), "--param elements: sweep a Real parameter")
        if args.param == "Omega":
            need(
                args.start > 0 and args.stop > 0,
                f"--param Omega: --start {args.start} and --stop {args.stop} must be > 0",
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


def run_case_command(parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
    from georod_tools.plots import plot_case, write_case_csv, write_dense_csv
    from georod_tools.runner import run_case

    cfg = _base_config(parser, args)
    result = run_case(cfg)
    stem = f"{Path(cfg.fmu).stem}_F{_fmt(cfg.F)}_Omega{_fmt(cfg.Omega)}"
    png = plot_case(result, args.out / f"{stem}.png")
    csv_path = write_case_csv(result, args.out / f"{stem}_samples.csv")
    dense = write_dense_csv(result, args.out / f"{stem}_dense.csv")
    c = result.classification
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
    for p in (png, csv_path, dense):
        if p is not None:
            print(f"wrote {p}")
    return 0


def run_sweep_command(parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
    from georod_tools.plots import plot_sweep, write_sweep_csv
    from georod_tools.sweep import run_sweep, sweep_values

    base = _base_config(parser, args)
    values = sweep_values(args.start, args.stop, args.count)
    t0 = time.perf_counter()
    results = run_sweep(
        base,
        args.param,
        values,
        workers=args.workers,
        scheduler=args.scheduler,
        progress=not args.no_progress,
    )
    wall = time.perf_counter() - t0
    stem = (
        f"{Path(base.fmu).stem}_sweep_{args.param}_{_fmt(args.start)}_{_fmt(args.stop)}"
        f"_{args.count}"
    )
    png = plot_sweep(
        args.param,
        results,
        args.out / f"{stem}.png",
        chaos_threshold=None if args.no_lyapunov else args.chaos_threshold,
    )
    summary, samples = write_sweep_csv(args.param, results, args.out / f"{stem}.csv")
    kinds: dict[str, int] = {}
    for r in results:
        kinds[r.classification.label] = kinds.get(r.classification.label, 0) + 1
    print(
        f"{len(results)} cases in {wall:.1f} s: "
        + ", ".join(f"{k}: {n}" for k, n in sorted(kinds.items()))
    )
    for p in (png, summary, samples):
        print(f"wrote {p}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command == "study":
        from georod_tools.study import run_study_command

        return run_study_command(parser, args)
    if args.command == "benchmark":
        from georod_tools.benchmark import run_benchmark_command

        return run_benchmark_command(parser, args)
    _check(parser, args)
    try:
        if args.command == "case":
            return run_case_command(parser, args)
        return run_sweep_command(parser, args)
    except (RuntimeError, ValueError, OSError) as e:
        print(f"georod-chaos: error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
