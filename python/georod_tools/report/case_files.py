"""The numbers of cases and sweeps as files: CSV tables of samples and classifications, and the
JSON lines of ``results.jsonl`` (one per finished case, read back bit for bit on ``--resume``)."""

from __future__ import annotations

import csv
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from georod_tools.analysis.case import CaseConfig, CaseResult
from georod_tools.analysis.classify import Classification
from georod_tools.analysis.failure import FAIL_WORKER, CaseFailure
from georod_tools.analysis.lyapunov import LyapunovResult
from georod_tools.report.records import now


def write_case_csv(result: CaseResult, path: str | Path) -> Path:
    """The stroboscopic samples: columns k (period index), t [s], then the sampled sensor and its
    velocity (``w_mid``, ``v_mid`` for the paper's scenes)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    period = result.config.period
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["k", "t", result.config.sensor, result.config.velocity_name])
        for t, (wm, vm) in zip(result.sample_times, result.samples, strict=True):
            w.writerow([round(t / period), repr(float(t)), repr(float(wm)), repr(float(vm))])
    return path


def write_dense_csv(result: CaseResult, path: str | Path) -> Path | None:
    """The dense trajectory (t, sensor, velocity), if recorded."""
    if result.dense is None:
        return None
    path = Path(path)
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t", result.config.sensor, result.config.velocity_name])
        for row in result.dense:
            w.writerow([repr(float(x)) for x in row])
    return path


def write_sweep_csv(
    param: str,
    results: Sequence[CaseResult],
    path: str | Path,
    failures: Sequence[CaseFailure] = (),
    wall_time: bool = True,
) -> tuple[Path, Path]:
    """Two files: `path` with one row per case sorted by value (value, class, period, exponents,
    wall time unless `wall_time` is False, and the reason of a failed case, whose class is
    ``failed``) and `<stem>_samples.csv` with every stroboscopic sample (value, k, w_mid, v_mid).
    Without the wall time the table depends only on the cases (deterministic)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    samples_path = path.with_name(path.stem + "_samples.csv")
    header = [
        param,
        "class",
        "period",
        "lyapunov_per_period",
        "lyapunov_per_second",
        "lyapunov_stderr",
        "correlation_dimension",
    ]
    rows: list[tuple[float, list[object]]] = []
    for r in results:
        c = r.classification
        x = r.config.value(param)
        row: list[object] = [
            repr(x),
            c.kind,
            c.period or "",
            repr(r.exponent_per_period),
            repr(r.exponent_per_second),
            repr(r.lyapunov.stderr if r.lyapunov else math.nan),
            repr(c.dimension),
        ]
        rows.append((x, [*row, *([f"{r.wall_time:.3f}"] if wall_time else []), ""]))
    for fl in failures:
        row = [repr(fl.value), "failed", "", "", "", "", ""]
        rows.append((fl.value, [*row, *([""] if wall_time else []), f"{fl.kind}: {fl.reason}"]))
    rows.sort(key=lambda t: t[0])
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow([*header, *(["wall_time_s"] if wall_time else []), "failure"])
        w.writerows(row for _, row in rows)
    with samples_path.open("w", newline="") as f:
        w = csv.writer(f)
        names = [results[0].config.sensor, results[0].config.velocity_name] if results else []
        w.writerow([param, "k", *(names or ["w_mid", "v_mid"])])
        for r in results:
            x = repr(r.config.value(param))
            for t, (wm, vm) in zip(r.sample_times, r.samples, strict=True):
                w.writerow([x, round(t / r.config.period), repr(float(wm)), repr(float(vm))])
    return path, samples_path


# --------------------------------------------------------------------------- results.jsonl


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
            "per_period": ly.per_period,
            "per_second": ly.per_second,
            "stderr": ly.stderr,
            "log_growth": ly.log_growth,
            "interval_periods": ly.interval_periods,
            "method": ly.method,
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
            per_period=ly["per_period"],
            per_second=ly["per_second"],
            stderr=ly["stderr"],
            log_growth=np.asarray(ly["log_growth"], dtype=float),
            interval_periods=np.asarray(ly["interval_periods"], dtype=float),
            method=ly["method"],
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
