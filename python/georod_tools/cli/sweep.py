"""The ``sweep`` command: a bifurcation diagram written case by case, resumable, on Dask.

    georod-tools sweep --param F --start 0.4 --stop 2 --count 100 --workers 2

The cases take the ``case`` command's options and defaults (:mod:`georod_tools.cli.case`), so a
sweep's case at F and ``georod-tools case --F F`` give the same numbers.

Output folder (``--out``, default ``out/sweep/sweep_<param>_<timestamp>``):

- ``run.json``: the settings, the FMU (path, GUID, sha256), versions, times, one entry per
  invocation (:mod:`georod_tools.report.records`);
- ``results.jsonl``: one line per finished case, appended as it finishes: the value and either
  the stroboscopic samples, exponent and class, or the failure's kind and reason;
- at the end, from ``results.jsonl`` alone: ``<stem>.csv`` (one row per value, failures with
  their reason; no wall times, so an interrupted and resumed sweep gives the same bytes as an
  uninterrupted one), ``<stem>_samples.csv`` and ``<stem>.png`` (failed values as red bands).

``--resume`` reruns no finished case: only the values without a line, and those whose worker
was lost or could not load the FMU (the FMU's refusals and Python exceptions are deterministic
and stay recorded).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from importlib import import_module
from pathlib import Path
from threading import Thread

from georod_tools.analysis.case import CaseConfig, CaseResult
from georod_tools.analysis.failure import CaseFailure
from georod_tools.cli.args import finite_float, int_range, positive_int
from georod_tools.cli.case import OWN_FLAGS, add_case_options, base_config, check_case_options
from georod_tools.fmu import FmuModel
from georod_tools.report.case_files import (
    failure_record,
    from_record,
    latest,
    result_record,
    settled,
)
from georod_tools.report.records import (
    OutputRefusedError,
    ResultLog,
    RunRecord,
    fmu_info,
    fresh_folder,
    jsonable,
    options,
    prepare_output,
)

DEFAULT_PARENT = Path("out") / "sweep"
#: Largest sweep accepted on the command line.
MAX_COUNT = 100_000


# --------------------------------------------------------------------------- the command


def sweep_settings(args: argparse.Namespace, base: CaseConfig, values: Sequence[float]) -> dict:
    """What makes the results (compared on --resume): not the workers, scheduler or folder."""
    case = jsonable(base)
    case.pop("fmu")
    return {
        "param": args.param,
        "start": args.start,
        "stop": args.stop,
        "count": args.count,
        "values": list(values),
        "case": case,
        "fmu_sha256": None,  # filled in by run_sweep_command
    }


def _stem(base: CaseConfig, args: argparse.Namespace) -> str:
    def fmt(x: float) -> str:
        return f"{x:g}".replace("+", "")

    return (
        f"{Path(base.fmu).stem}_sweep_{args.param}_{fmt(args.start)}_{fmt(args.stop)}_{args.count}"
    )


#: The line `georod-tools --help` shows.
HELP = "bifurcation diagram over F, Omega or any FMU Real parameter (Dask, resumable); exits 1 "
"when every case failed"


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "sweep",
        help=HELP,
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("--param", default="F", help="parameter swept: F, Omega or any FMU Real (F)")
    p.add_argument("--start", type=finite_float, required=True, help="first value, finite")
    p.add_argument("--stop", type=finite_float, required=True, help="last value, finite")
    p.add_argument(
        "--count",
        type=int_range(1, MAX_COUNT),
        default=50,
        help=f"number of values, 1..{MAX_COUNT} (50)",
    )
    p.add_argument(
        "--workers", type=positive_int, default=2, help="local worker processes, >= 1 (2)"
    )
    p.add_argument(
        "--scheduler",
        metavar="ADDR",
        help="address of a running Dask scheduler, e.g. tcp://host:8786 (no local cluster); "
        "its workers need georod_tools, not the FMU file: the FMU is sent to them",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_case_options(p, sweep=True)
    g = p.add_argument_group("output")
    g.add_argument(
        "--out",
        type=Path,
        help=f"output folder (default: a new {DEFAULT_PARENT}/sweep_<param>_<timestamp>); an "
        "existing non-empty folder is refused unless --resume or --overwrite",
    )
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
    p.set_defaults(run=run, _parser=p)


def run(parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]) -> int:
    """Runs (or resumes) the sweep of the command line; returns the exit status."""
    from georod_tools.analysis.sweep import sweep, sweep_values
    from georod_tools.report.case_files import write_sweep_csv

    check_case_options(parser, args)
    if args.param in ("elements", "substeps"):
        parser.error(f"--param {args.param}: sweep a Real parameter")
    if args.param in OWN_FLAGS and args.param not in ("F", "Omega"):
        parser.error(f"--param {args.param}: set by georod_tools from the time-step options")
    if args.param == "Omega" and not (args.start > 0 and args.stop > 0):
        parser.error(f"--param Omega: --start {args.start} and --stop {args.stop} must be > 0")
    base = base_config(parser, args)
    values = sweep_values(args.start, args.stop, args.count)
    model = FmuModel.load(base.fmu)
    fmu = fmu_info(base.fmu, model.guid, model.identifier)
    settings = sweep_settings(args, base, values)
    settings["fmu_sha256"] = fmu["sha256"]
    if args.out is None and args.resume:
        parser.error("--resume needs --out DIR, the folder of the run to continue")
    out = args.out if args.out is not None else fresh_folder(DEFAULT_PARENT, f"sweep_{args.param}")
    try:
        prepare_output(out, resume=args.resume, overwrite=args.overwrite)
        if args.resume:
            record = RunRecord.load(out)
            record.check_resumable("sweep", settings)
            record.data["fmu"] = fmu  # the same bytes, maybe at another path
        else:
            record = RunRecord.create(out, "sweep", settings, fmu)
    except OutputRefusedError as e:
        parser.error(str(e))
    log = ResultLog(out)
    done = {v: r for v, r in latest(log.read(), values).items() if settled(r)}
    todo = [v for v in values if v not in done]
    session = record.start_session(argv, options(args))
    print(f"output folder: {out}")
    if done:
        print(f"resuming: {len(done)} of {len(values)} cases already done, {len(todo)} to run")
    computed = 0

    def on_done(got: CaseResult | CaseFailure) -> None:
        nonlocal computed
        computed += 1
        if isinstance(got, CaseFailure):
            log.append(failure_record(got))
        else:
            log.append(result_record(got.config.value(args.param), got))

    t0 = time.perf_counter()
    session["scheduler"] = args.scheduler or f"local cluster of {args.workers} processes"
    try:
        if todo:
            outcome = sweep(
                base,
                args.param,
                todo,
                workers=args.workers,
                scheduler=args.scheduler,
                progress=not args.no_progress,
                on_done=on_done,
                progress_total=len(values),
                on_started=load_figures,
            )
            session["workers"] = outcome.workers
    except KeyboardInterrupt:
        session["computed"] = computed
        record.finish("interrupted")
        print(f"\ninterrupted after {computed} new cases; continue with --resume --out {out}")
        return 130
    except Exception as e:
        session["computed"] = computed
        record.finish("failed", error=f"{type(e).__name__}: {e}")
        raise
    wall = time.perf_counter() - t0
    session["computed"] = computed
    session["wall_time_s"] = round(wall, 3)

    final = latest(log.read(), values)
    got = [from_record(final[v], base.with_value(args.param, v)) for v in values if v in final]
    results = [g for g in got if isinstance(g, CaseResult)]
    failures = [g for g in got if isinstance(g, CaseFailure)]
    stem = _stem(base, args)
    threshold = None if args.no_lyapunov else args.chaos_threshold
    from georod_tools.report.figures import plot_sweep

    png = plot_sweep(args.param, results, out / f"{stem}.png", threshold, failures)
    summary, samples = write_sweep_csv(
        args.param, results, out / f"{stem}.csv", failures, wall_time=False
    )
    cases = {
        "total": len(values),
        "ok": len(results),
        "failed": len(failures),
        "failed_values": [f.value for f in failures],
    }
    record.finish("complete", cases=cases, outputs=[p.name for p in (summary, samples, png)])
    _print_summary(args.param, results, failures, computed, wall)
    for p in (png, summary, samples, record.path, log.path):
        print(f"wrote {p}")
    if failures and not results:
        print(f"every case failed ({len(failures)}): nothing to analyse", file=sys.stderr)
        return 1
    return 0


def load_figures() -> None:
    """Loads the figure's modules (matplotlib: half a second) in a thread while the cases run,
    when this process only waits; importing is thread-safe, the plot waits for it if need be.
    Started once the workers are up, so as not to slow their start."""
    Thread(target=import_module, args=("georod_tools.report.figures",), daemon=True).start()


def _print_summary(
    param: str,
    results: Sequence[CaseResult],
    failures: Sequence[CaseFailure],
    computed: int,
    wall: float,
) -> None:
    kinds: dict[str, int] = {}
    for r in results:
        kinds[r.classification.label] = kinds.get(r.classification.label, 0) + 1
    n = len(results) + len(failures)
    print(
        f"{n} cases ({computed} computed now in {wall:.1f} s, {len(failures)} failed): "
        + ", ".join(f"{k}: {c}" for k, c in sorted(kinds.items()))
    )
    if failures:
        print(f"failed cases ({len(failures)}):")
        for f in failures:
            where = f" [{f.worker}]" if f.worker else ""
            print(f"  {param} = {f.value!r}: {f.kind}: {f.reason}{where}")
    sys.stdout.flush()
