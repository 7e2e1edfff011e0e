"""The ``case`` command (one run: Poincaré section, phase portrait, time plot, exponent) and the
options it shares with ``sweep``: the same defaults, so the two integrate with identical sub-steps
and agree case by case.

    georod-tools case --scene BuckledBeam --F 1.5 --Omega 3500

Writes a three-panel PNG and the samples as CSV into a new ``out/case/case_<timestamp>`` (or
``--out``) with its run.json, and prints the classification and the exponent.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from pathlib import Path

from georod_tools.analysis.case import DEFAULT_SUBSTEPS, MANAGED, CaseConfig
from georod_tools.analysis.classify import ClassifySettings
from georod_tools.cli.args import (
    add_output_options,
    finite_float,
    float_range,
    int_range,
    name_value,
    nonnegative_int,
    positive_float,
    positive_int,
)

DEFAULT_OUT = Path("out") / "case"
#: Largest mesh accepted on the command line.
MAX_ELEMENTS = 100_000
#: Parameters that have their own flag (or are set by the case) instead of --set.
OWN_FLAGS = MANAGED


def add_case_options(p: argparse.ArgumentParser, sweep: bool) -> None:
    """Model, run and analysis options (``case`` and ``sweep``)."""
    g = p.add_argument_group("model")
    g.add_argument("--fmu", type=Path, help="FMU file (default: target/fmu/<scene>.fmu)")
    g.add_argument(
        "--scene", default="BuckledBeam", help="scene of scenes/ when no --fmu (BuckledBeam)"
    )
    g.add_argument("--F", type=finite_float, help="forcing amplitude (default: the FMU's start)")
    g.add_argument(
        "--Omega",
        type=float_range(0.0, unit="rad/s"),
        help="forcing frequency in rad/s, > 0 (default: the FMU's start value)",
    )
    g.add_argument(
        "--elements",
        type=int_range(2, MAX_ELEMENTS),
        help=f"finite elements, 2..{MAX_ELEMENTS} (default: the FMU's own mesh)",
    )
    g.add_argument(
        "--sensor",
        help="the displacement sensor sampled (default: the scene's first displacement sensor); "
        "its velocity partner (the velocity at the same station) must be a sensor too",
    )
    g.add_argument(
        "--period",
        type=positive_float,
        help="sampling period T in s, > 0, for a scene without a harmonic load (with one, "
        "T = 2 pi / Omega)",
    )
    g.add_argument(
        "--set",
        type=name_value,
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="any other FMU parameter (repeatable), e.g. --set well=-1",
    )
    g = p.add_argument_group("time steps and periods")
    g.add_argument(
        "--substeps",
        type=positive_int,
        default=DEFAULT_SUBSTEPS,
        help="midpoint sub-steps per forcing period N, >= 1: dt_max = T/N exactly, one "
        f"communication step per period ({DEFAULT_SUBSTEPS}; the former dt_max = 1e-5 s was "
        "T/180 at Omega = 3500)",
    )
    g.add_argument(
        "--transient", type=nonnegative_int, default=200, help="periods discarded, >= 0 (200)"
    )
    g.add_argument("--periods", type=positive_int, default=200, help="periods sampled, >= 1 (200)")
    if not sweep:
        g.add_argument(
            "--dense-periods",
            type=nonnegative_int,
            default=20,
            help="last sampled periods kept for the phase portrait and time plot, "
            "0..--periods (20)",
        )
    g.add_argument(
        "--dense-steps",
        type=positive_int,
        help="points per period of the dense window (and of the last period, whose swing sizes "
        "the classifier's tolerance); must divide --substeps; a power of two keeps the results "
        "bit for bit independent of the window (default: the largest power of two dividing "
        "--substeps, up to 64)",
    )
    g = p.add_argument_group("analysis")
    g.add_argument("--no-lyapunov", action="store_true", help="skip the Lyapunov exponent")
    g.add_argument(
        "--align",
        type=nonnegative_int,
        default=10,
        help="sampled periods in which the tangent vector only aligns before the exponent is "
        "averaged, 0..--periods - 1 (10)",
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


def check_case_options(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Checks across options (single values are checked by their argparse types); exits with
    status 2 and the allowed range."""

    def need(ok: bool, msg: str) -> None:
        if not ok:
            parser.error(msg)

    if not args.no_lyapunov:
        need(
            args.align < args.periods,
            f"--align {args.align}: allowed range 0..{args.periods - 1} (--periods - 1: at least "
            "one averaged Lyapunov period)",
        )
    if args.dense_steps is not None:
        need(
            args.substeps % args.dense_steps == 0,
            f"--dense-steps {args.dense_steps} must divide --substeps {args.substeps} (the dense "
            "window takes the same sub-steps)",
        )
    for name, _ in args.set:
        need(name not in OWN_FLAGS, f"--set {name}: set by georod_tools (see --help)")
    if getattr(args, "dense_periods", 0) > args.periods:
        parser.error(
            f"--dense-periods {args.dense_periods}: allowed range 0..--periods ({args.periods})"
        )
    if args.fmu is not None:
        need(args.fmu.is_file(), f"--fmu {args.fmu}: no such file (build with scripts/build_fmus)")


def base_config(parser: argparse.ArgumentParser, args: argparse.Namespace) -> CaseConfig:
    """The case configuration of the command line (parameter names checked against the FMU)."""
    from georod_tools import fmu_path
    from georod_tools.fmu import FmuModel

    try:
        fmu = args.fmu or fmu_path(args.scene)
    except ValueError as e:
        parser.error(f"--scene {args.scene}: {e}")
    if not Path(fmu).is_file():
        parser.error(f"FMU {fmu} not found: build it with scripts/build_fmus or pass --fmu")
    from georod_tools.analysis.scene_sensors import NotAnalysableError, pick

    model = FmuModel.load(fmu)
    params = model.parameters
    try:
        sampled = pick(model, args.sensor)
    except NotAnalysableError as e:
        parser.error(str(e))
    if sampled.forced and args.period is not None:
        parser.error(
            f"--period: {model.identifier} has a harmonic load, whose period 2 pi / Omega is the "
            "sampling period; set --Omega instead"
        )
    if not sampled.forced:
        for flag in ("F", "Omega"):
            if getattr(args, flag) is not None:
                parser.error(f"--{flag}: {model.identifier} has no harmonic load (no {flag})")
        if args.period is None:
            parser.error(
                f"{model.identifier} has no harmonic load: pass --period T, the sampling period "
                'in s (or add a [[load]] with time = "harmonic" to the scene)'
            )
    wanted = [n for n, _ in args.set] + ([args.param] if hasattr(args, "param") else [])
    for name in wanted:
        if name not in params:
            opt = "--param" if name == getattr(args, "param", None) else "--set"
            parser.error(
                f"{opt} {name}: {model.identifier} has no such parameter; "
                f"its parameters are {', '.join(params)}"
            )

    def start(name: str) -> float:
        value = model.start(name)
        if value is None:
            parser.error(f"{model.identifier} gives no start value for {name}; pass --{name}")
        return float(value)  # type: ignore[arg-type]

    if sampled.forced:
        omega = args.Omega if args.Omega is not None else start("Omega")
        if not omega > 0:
            parser.error(f"Omega = {omega}: must be > 0; pass --Omega")
        amplitude = args.F if args.F is not None else start("F")
    else:
        omega, amplitude = 2.0 * math.pi / args.period, 0.0
    elements = args.elements if args.elements is not None else int(start("elements"))
    classify = ClassifySettings(
        k_max=args.k_max,
        period_tol=args.period_tol,
        chaos_threshold=args.chaos_threshold,
        zero_band=args.chaos_threshold,
    )
    try:
        return CaseConfig(
            fmu=str(Path(fmu).resolve()),
            F=amplitude,
            Omega=omega,
            elements=elements,
            substeps=args.substeps,
            params=tuple(args.set),
            transient_periods=args.transient,
            sample_periods=args.periods,
            dense_periods=getattr(args, "dense_periods", 0),
            dense_steps=args.dense_steps or 0,
            lyapunov=not args.no_lyapunov,
            align_periods=args.align,
            classify_settings=classify,
            sensor=sampled.sensor,
            velocity=sampled.velocity,
            forced=sampled.forced,
        )
    except ValueError as e:
        parser.error(str(e))
        raise AssertionError from e  # unreachable


def _fmt(x: float) -> str:
    return f"{x:g}".replace("+", "")


#: The line `georod-tools --help` shows.
HELP = "one run: Poincaré section, phase portrait, time plot, Lyapunov exponent"


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "case",
        help=HELP,
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_case_options(p, sweep=False)
    add_output_options(p, f"{DEFAULT_OUT}/case")
    p.set_defaults(run=run, _parser=p)


def run(parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]) -> int:
    """The case command; returns the exit status."""
    from georod_tools.analysis.case import run_case
    from georod_tools.fmu import FmuModel
    from georod_tools.report.case_files import write_case_csv, write_dense_csv
    from georod_tools.report.figures import plot_case
    from georod_tools.report.records import OutputRefusedError, fmu_info, jsonable, new_run

    check_case_options(parser, args)
    cfg = base_config(parser, args)
    model = FmuModel.load(cfg.fmu)
    settings = jsonable(cfg)
    settings.pop("fmu")
    try:
        record = new_run(
            DEFAULT_OUT,
            "case",
            "case",
            settings,
            fmu_info(cfg.fmu, model.guid, model.identifier),
            argv,
            args,
            args.out,
            args.overwrite,
        )
    except OutputRefusedError as e:
        parser.error(str(e))
    out = record.folder
    try:
        result = run_case(cfg)
    except Exception as e:
        record.finish("failed", error=f"{type(e).__name__}: {e}")
        raise
    forcing = f"F{_fmt(cfg.F)}_Omega{_fmt(cfg.Omega)}" if cfg.forced else f"T{_fmt(cfg.period)}"
    stem = f"{Path(cfg.fmu).stem}_{forcing}"
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
    forcing = f"F = {cfg.F:g}, Omega = {cfg.Omega:g}" if cfg.forced else f"T = {cfg.period:g} s"
    print(
        f"{Path(cfg.fmu).stem}: {forcing}, {cfg.elements} elements, T/{cfg.substeps} sub-steps, "
        f"{cfg.transient_periods} + {cfg.sample_periods} periods, sampling {cfg.sensor}"
    )
    print(f"class: {c.label} ({c.note})")
    if result.lyapunov is not None:
        ly = result.lyapunov
        print(
            f"largest Lyapunov exponent: {ly.per_period:.4f} +- {ly.stderr:.4f} per period "
            f"= {ly.per_second:.2f} 1/s (core tangent map, {ly.periods:.0f} periods averaged)"
        )
    print(f"run time: {result.wall_time:.2f} s")
    for p in (*written, record.path):
        print(f"wrote {p}")
    return 0
