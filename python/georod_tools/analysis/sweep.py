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

Cases travel in chunks (:func:`chunk_sizes`): Dask costs 5-10 ms of scheduler, client and worker
time per task, 5-10 % of a 0.1 s case, and on a machine with as many workers as cores that time
comes out of the cases'. Chunks shrink as the sweep goes (guided scheduling: the first ones are
large, the last cases go one by one), so the workers still finish together.

A case that fails (the FMU returns fmi2Discard or fmi2Error, a Python exception, a lost worker or
one that cannot load the FMU) becomes a :class:`~georod_tools.analysis.failure.CaseFailure` with
its reason (a chunk lost with its worker runs again case by case, so that only a case that kills
its worker fails); :func:`sweep` always finishes and returns results and failures, :func:`run_sweep`
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
from georod_tools.analysis.worker_start import start_worker_server
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
    "chunk_sizes",
    "run_chunk_on_worker",
    "run_on_worker",
    "run_sweep",
    "sweep",
    "sweep_configs",
    "sweep_values",
]

#: Parameters a sweep may vary by default (any other FMU Real parameter works too).
SWEEPABLE = ("F", "Omega")

CaseFn = Callable[[CaseConfig], CaseResult]

#: Most cases in one Dask task: what a worker lost mid-chunk takes with it before the chunk runs
#: again case by case, and how far apart the progress bar's updates may be.
MAX_CHUNK = 8
#: Guided scheduling: a chunk holds at most 1 / (GUIDE x slots) of the cases left when it is
#: cut, so that while a slot runs it the others have work queued, and the chunks shrink to
#: single cases at the end, where the slots then finish within about one case of each other.
GUIDE = 2


def chunk_sizes(count: int, slots: int) -> list[int]:
    """How `count` cases are cut into Dask tasks for `slots` parallel workers: each chunk
    ``remaining // (GUIDE * slots)`` cases, between 1 and :data:`MAX_CHUNK`, largest first.
    (100 cases, 2 workers: 9 chunks of 8, then 7, 5, 4, 3, 2 and 7 single cases: 21 tasks.)"""
    if count < 0 or slots < 1:
        raise ValueError(f"count = {count} must be >= 0 and slots = {slots} >= 1")
    sizes: list[int] = []
    left = count
    while left > 0:
        size = min(MAX_CHUNK, max(1, left // (GUIDE * slots)))
        sizes.append(size)
        left -= size
    return sizes


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


def run_chunk_on_worker(
    cfgs: Sequence[CaseConfig],
    values: Sequence[float],
    sha256: str,
    name: str,
    case_fn: CaseFn,
) -> list[CaseResult | CaseFailure]:
    """:func:`run_on_worker` for each case of a chunk, in order."""
    return [run_on_worker(c, v, sha256, name, case_fn) for c, v in zip(cfgs, values, strict=True)]


@dataclass
class SweepOutcome:
    """Results sorted by value, failures sorted by value, and each worker's state (address ->
    :func:`georod_tools.fmu.worker.worker_fmu_status`) when the sweep started."""

    results: list[CaseResult] = field(default_factory=list)
    failures: list[CaseFailure] = field(default_factory=list)
    workers: dict[str, dict[str, Any]] = field(default_factory=dict)


def local_cluster(workers: int) -> Any:
    """`workers` single-threaded processes (started by :func:`worker_start_method`), each
    holding only the chunk it runs (worker saturation 1; Dask's default 1.1 gives a
    single-threaded worker a second task to hold). A worker that dies then takes only its
    running chunk with it: a task held behind it would also count the death as one of its
    allowed failures, so that a case that kills its worker again and again could make an
    innocent case fail. The round trip to the scheduler for the next chunk (3 ms) is what the
    chunks make rare."""
    import dask
    from dask.distributed import LocalCluster

    method = start_worker_server()
    config = {
        "distributed.scheduler.worker-saturation": 1.0,
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
        slots = sum(client.nthreads().get(a, 1) for a in good) or 1
        sizes = chunk_sizes(len(configs), slots)

        def submit(cases: list[int], priority: int) -> Any:
            return client.submit(
                run_chunk_on_worker,
                [configs[i] for i in cases],
                [vals[i] for i in cases],
                sha256=payload.sha256,
                name=payload.name,
                case_fn=case_fn,
                pure=False,
                # Dask runs the highest priority first: the chunks in order, largest first.
                priority=priority,
                **restrict,
            )

        chunks: dict[str, list[int]] = {}
        futures = []
        start = 0
        for k, size in enumerate(sizes):
            cases = list(range(start, start + size))
            start += size
            fut = submit(cases, len(sizes) - k)
            chunks[fut.key] = cases
            futures.append(fut)
        bar = None
        if progress:
            from tqdm import tqdm

            total = progress_total or len(configs)
            bar = stack.enter_context(
                tqdm(total=total, initial=total - len(configs), desc=f"sweep {param}", unit="case")
            )
        finished = as_completed(futures)
        for fut in finished:
            cases = chunks.pop(fut.key)
            lost = None
            try:
                got_all = fut.result()
            except Exception as e:  # noqa: BLE001 - worker lost (KilledWorker), cancelled, ...
                lost = f"{type(e).__name__}: {e}"
            fut.release()
            if lost is not None:
                if len(cases) > 1:
                    # Lost with its worker: each case runs again on its own, so that only a
                    # case that kills its worker fails, not the others of its chunk.
                    for i in cases:
                        again = submit([i], len(sizes) + 1)
                        chunks[again.key] = [i]
                        finished.add(again)
                    continue
                got_all = [CaseFailure(vals[cases[0]], FAIL_WORKER, lost)]
            for got in got_all:
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
