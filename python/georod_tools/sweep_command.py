"""The ``sweep`` command: a bifurcation diagram written case by case, resumable.

Output folder (``--out``, default ``out/chaos/sweep_<param>_<timestamp>``):

- ``run.json``: the settings, the FMU (path, GUID, sha256), versions, times, one entry per
  invocation (:mod:`georod_tools.records`);
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
from pathlib import Path
from typing import Any

import numpy as np

from georod_tools.classify import Classification
from georod_tools.failure import FAIL_WORKER, CaseFailure
from georod_tools.lyapunov import LyapunovResult
from georod_tools.records import (
    OutputRefusedError,
    ResultLog,
    RunRecord,
    fmu_info,
    fresh_folder,
    jsonable,
    now,
    options,
    prepare_output,
)
from georod_tools.runner import CaseConfig, CaseResult, FmuModel

DEFAULT_PARENT = Path("out") / "chaos"


# --------------------------------------------------------------------------- case records


def result_record(value: float, r: CaseResult) -> dict[str, Any]:
    """One line of results.jsonl for a finished case (every number exact)."""
    c, ly = r.classification, r.lyapunov
    return {
        "value": value,
        "status": "ok",
        "finished": now(),
        "wall_time_s": r.wall_time,
        "class": c.label,
        "classification": {
            "kind": c.kind,
            "period": c.period,
            "exponent": c.exponent,
            "dimension": c.dimension,
            "mismatch": c.mismatch,
            "note": c.note,
        },
        "lyapunov": None
        if ly is None
        else {
            "per_step": ly.per_step,
            "stderr": ly.stderr,
            "log_growth": ly.log_growth,
            "running": ly.running,
            "every": ly.every,
            "period": ly.period,
        },
        "size": r.size,
        "sample_times": r.sample_times,
        "samples": r.samples,
    }


def failure_record(f: CaseFailure) -> dict[str, Any]:
    return {
        "value": f.value,
        "status": "failed",
        "finished": now(),
        "kind": f.kind,
        "reason": f.reason,
        "worker": f.worker,
    }


def from_record(rec: dict[str, Any], cfg: CaseConfig) -> CaseResult | CaseFailure:
    """The result or failure of a results.jsonl line; `cfg` is the case's configuration."""
    if rec["status"] != "ok":
        return CaseFailure(float(rec["value"]), rec["kind"], rec["reason"], rec.get("worker"))
    c, ly = rec["classification"], rec["lyapunov"]
    lyap = None
    if ly is not None:
        lyap = LyapunovResult(
            per_step=ly["per_step"],
            stderr=ly["stderr"],
            log_growth=np.asarray(ly["log_growth"], dtype=float),
            running=np.asarray(ly["running"], dtype=float),
            every=ly["every"],
            period=ly["period"],
        )
    return CaseResult(
        config=cfg,
        samples=np.asarray(rec["samples"], dtype=float).reshape(-1, 2),
        sample_times=np.asarray(rec["sample_times"], dtype=float),
        size=np.asarray(rec["size"], dtype=float),
        dense=None,
        lyapunov=lyap,
        classification=Classification(
            kind=c["kind"],
            period=c["period"],
            exponent=c["exponent"],
            dimension=c["dimension"],
            mismatch=np.asarray(c["mismatch"], dtype=float),
            note=c["note"],
        ),
        wall_time=rec["wall_time_s"],
    )


def latest(records: Sequence[dict[str, Any]], values: Sequence[float]) -> dict[float, dict]:
    """The last record of each of `values` (a resumed worker failure is appended again)."""
    wanted = set(values)
    out: dict[float, dict[str, Any]] = {}
    for rec in records:
        v = float(rec["value"])
        if v in wanted:
            out[v] = rec
    return out


def settled(rec: dict[str, Any]) -> bool:
    """Whether a record is final (a result, or a deterministic failure)."""
    return rec["status"] == "ok" or rec.get("kind") != FAIL_WORKER


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


def run_sweep_command(
    parser: argparse.ArgumentParser,
    args: argparse.Namespace,
    base: CaseConfig,
    argv: Sequence[str],
) -> int:
    """Runs (or resumes) the sweep of the command line; returns the exit status."""
    from georod_tools.plots import plot_sweep, write_sweep_csv
    from georod_tools.sweep import case_value, sweep, sweep_values

    values = sweep_values(args.start, args.stop, args.count)
    model = FmuModel.load(base.fmu)
    fmu = fmu_info(base.fmu, model.md.guid, model.identifier)
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
            log.append(result_record(case_value(got.config, args.param), got))

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
    return 0


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
