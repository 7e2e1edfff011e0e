"""Parameter sweeps (bifurcation diagrams) distributed with Dask.

Each value of the swept parameter is one :func:`georod_tools.analysis.case.run_case` (or another
`case_fn`, e.g. the twin cross-check): the FMU's initial state at ``t = 0``, deterministic (the
core's tangent vector starts from a seeded direction), so the results do not depend on which
worker ran which case or how many workers there were. Results come back sorted by the value.

Runs on a local cluster of `workers` single-threaded worker processes by default (one FMU case
per process at a time: an FMU instance is single-threaded and the processes keep the cases
apart), or on any running scheduler when its address is given (its workers need this package
installed, not the FMU file: the FMU travels to them as bytes, see
:mod:`georod_tools.fmu.worker`). A worker loads the FMU once and reuses its instances from case
to case (:meth:`georod_tools.fmu.FmuModel.instance`).

A case that fails (the FMU returns fmi2Discard or fmi2Error, a Python exception, a lost worker or
one that cannot load the FMU) becomes a :class:`~georod_tools.analysis.failure.CaseFailure` with
its reason; :func:`sweep` always finishes and returns results and failures, :func:`run_sweep`
(the studies' entry) raises after the whole sweep when any case failed.
"""

from __future__ import annotations

import logging
import sys
from collections.abc import Callable, Sequence
from contextlib import ExitStack
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from georod_tools.analysis.case import CaseConfig, CaseResult, run_case
from georod_tools.analysis.failure import (
    FAIL_EXCEPTION,
    FAIL_FMU,
    FAIL_WORKER,
    CaseFailure,
)
from georod_tools.fmu import FmuError
from georod_tools.fmu.worker import (
    FmuPayload,
    FmuUnavailableError,
    install,
    worker_address,
    worker_fmu_path,
)

__all__ = [
    "CaseFailure",
    "SweepOutcome",
    "run_on_worker",
    "run_sweep",
    "sweep",
    "sweep_configs",
    "sweep_values",
]

#: Parameters a sweep may vary by default (any other FMU Real parameter works too).
SWEEPABLE = ("F", "Omega")

CaseFn = Callable[[CaseConfig], CaseResult]


def sweep_values(start: float, stop: float, count: int) -> list[float]:
    """`count` evenly spaced values from `start` to `stop` inclusive, rounded to 12 significant
    digits (0.6, not 0.6000000000000001, in file names and CSV)."""
    if count < 1:
        raise ValueError(f"count = {count} must be >= 1")
    if count == 1:
        return [float(start)]
    return [float(f"{x:.12g}") for x in np.linspace(start, stop, count)]


def sweep_configs(base: CaseConfig, param: str, values: Sequence[float]) -> list[CaseConfig]:
    """One config per value, `base` with `param` set."""
    return [base.with_value(param, v) for v in values]


def run_on_worker(
    cfg: CaseConfig, value: float, sha256: str, name: str, case_fn: CaseFn
) -> CaseResult | CaseFailure:
    """One case on a worker with the worker's copy of the FMU; failures come back as
    :class:`CaseFailure` (the FMU's status and log, or the exception) instead of raising."""
    worker = worker_address()
    try:
        local = replace(cfg, fmu=worker_fmu_path(sha256, name))
    except FmuUnavailableError as e:
        return CaseFailure(value, FAIL_WORKER, str(e), worker)
    try:
        result = case_fn(local)
    except FmuError as e:
        return CaseFailure(value, FAIL_FMU, str(e), worker)
    except Exception as e:  # noqa: BLE001 - recorded with its type, the sweep goes on
        return CaseFailure(value, FAIL_EXCEPTION, f"{type(e).__name__}: {e}", worker)
    result.config = cfg
    return result


@dataclass
class SweepOutcome:
    """Results sorted by value, failures sorted by value, and each worker's state (address ->
    :func:`georod_tools.fmu.worker.worker_fmu_status`) when the sweep started."""

    results: list[CaseResult] = field(default_factory=list)
    failures: list[CaseFailure] = field(default_factory=list)
    workers: dict[str, dict[str, Any]] = field(default_factory=dict)


def local_cluster(workers: int) -> Any:
    """`workers` single-threaded processes, each holding its running case and the next one
    (worker saturation 2: the next case starts without a round trip to the scheduler, which
    cost 3 ms per case, a tenth of a short case; a worker that dies takes its running case
    with it, and the one it held is run again: for Dask both were on the lost worker, and each
    counts one of its allowed failures).

    On Linux the worker processes are forked from this one, which has imported everything
    they need: a worker is up in 0.07 s instead of the 0.4 s of a fresh interpreter importing
    Dask again (elsewhere, where forking is unsafe or unavailable, they are spawned). Forking
    a process with threads is safe only while no other thread holds a lock the child needs:
    this process starts no thread of its own before the cluster is up (see `on_started` of
    :func:`sweep`), and a worker restarted later inherits at most an import under way, of a
    module it never imports."""
    import dask
    from dask.distributed import LocalCluster

    method = "fork" if sys.platform.startswith("linux") else "spawn"
    config = {
        "distributed.scheduler.worker-saturation": 2.0,
        "distributed.worker.multiprocessing-method": method,
        # Dask's sampling profiler takes the worker's GIL every 10 ms to walk the running
        # case's stack, which is in the FMU anyway: 4 % of a case's time.
        "distributed.worker.profile.enabled": False,
    }
    with dask.config.set(config):
        return LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",
            silence_logs=logging.WARNING,
        )


def sweep(
    base: CaseConfig,
    param: str,
    values: Sequence[float],
    workers: int = 1,
    scheduler: str | None = None,
    progress: bool = True,
    on_done: Callable[[CaseResult | CaseFailure], None] | None = None,
    payload: FmuPayload | None = None,
    case_fn: CaseFn = run_case,
    progress_total: int | None = None,
    on_started: Callable[[], None] | None = None,
) -> SweepOutcome:
    """Runs `base` for every value of `param` on Dask; always finishes.

    workers: number of local worker processes (ignored when `scheduler` is given).
    scheduler: address of a running Dask scheduler (``tcp://host:8786``); None starts a local
        cluster that is shut down afterwards.
    on_done: called in this process with each result or failure as it arrives (e.g. to append
        it to a file).
    payload: the FMU as bytes (default: read from ``base.fmu``); the workers never read
        ``base.fmu``, so it need not exist where they run.
    case_fn: what runs one case on a worker (default :func:`run_case`; must be importable there).
    progress_total: the progress bar's total when this sweep finishes a larger one (``--resume``).
    on_started: called in this process once the workers are up and have the FMU, while the
        cases run (e.g. to load what the results need next).
    Raises FmuUnavailableError (naming each worker and its reason) when no worker can load the
    FMU.
    """
    from dask.distributed import Client, as_completed

    if workers < 1:
        raise ValueError(f"workers = {workers} must be >= 1")
    outcome = SweepOutcome()
    configs = sweep_configs(base, param, values)
    if not configs:
        return outcome
    payload = payload or FmuPayload.read(base.fmu)
    with ExitStack() as stack:
        if scheduler:
            client = stack.enter_context(Client(scheduler))
        else:
            cluster = stack.enter_context(local_cluster(workers))
            client = stack.enter_context(Client(cluster))
        outcome.workers = install(client, payload)
        if on_started is not None:
            on_started()
        good = [a for a, s in outcome.workers.items() if s["fmu_loaded"]]
        for a, s in sorted(outcome.workers.items()):
            if not s["fmu_loaded"]:
                print(
                    f"warning: worker {a} cannot load {payload.name}: {s['error']}", file=sys.stderr
                )
        # workers that failed to load the FMU get no case while a good one is there
        restrict: dict[str, Any] = {}
        if len(good) < len(outcome.workers):
            restrict = {"workers": good, "allow_other_workers": True}
        vals = [c.value(param) for c in configs]
        futures = client.map(
            run_on_worker,
            configs,
            vals,
            sha256=payload.sha256,
            name=payload.name,
            case_fn=case_fn,
            pure=False,
            **restrict,
        )
        index = {f.key: i for i, f in enumerate(futures)}
        bar = None
        if progress:
            from tqdm import tqdm

            total = progress_total or len(futures)
            bar = stack.enter_context(
                tqdm(total=total, initial=total - len(futures), desc=f"sweep {param}", unit="case")
            )
        for fut in as_completed(futures):
            i = index[fut.key]
            try:
                got = fut.result()
            except Exception as e:  # noqa: BLE001 - worker lost (KilledWorker), cancelled, ...
                got = CaseFailure(vals[i], FAIL_WORKER, f"{type(e).__name__}: {e}")
            fut.release()
            if isinstance(got, CaseFailure):
                outcome.failures.append(got)
            else:
                outcome.results.append(got)
            if on_done is not None:
                on_done(got)
            if bar is not None:
                bar.update(1)
    outcome.results.sort(key=lambda r: r.config.value(param))
    outcome.failures.sort(key=lambda f: f.value)
    return outcome


def run_sweep(
    base: CaseConfig,
    param: str,
    values: Sequence[float],
    workers: int = 1,
    scheduler: str | None = None,
    progress: bool = True,
    on_result: Callable[[CaseResult], None] | None = None,
    case_fn: CaseFn = run_case,
) -> list[CaseResult]:
    """:func:`sweep` for callers that need every case: the results sorted by value, or, after
    the whole sweep ran, RuntimeError listing each failed value and its reason."""

    def done(got: CaseResult | CaseFailure) -> None:
        if on_result is not None and isinstance(got, CaseResult):
            on_result(got)

    out = sweep(
        base,
        param,
        values,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
        on_done=done,
        case_fn=case_fn,
    )
    if out.failures:
        lines = "; ".join(f"{param} = {f.value:g}: {f.reason}" for f in out.failures)
        raise RuntimeError(f"{len(out.failures)} of {len(values)} cases failed: {lines}")
    return out.results
