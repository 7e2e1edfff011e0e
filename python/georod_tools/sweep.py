"""Parameter sweeps (bifurcation diagrams) distributed with Dask.

Each value of the swept parameter is one :func:`georod_tools.runner.run_case`: a fresh FMU
instance from the static state at ``t = 0``, deterministic (fixed seed of the Lyapunov
perturbation), so the results do not depend on which worker ran which case or how many workers
there were. Results come back sorted by the parameter value.

Runs on a local cluster of `workers` single-threaded worker processes by default (one FMU case
per process at a time: the FMU is single-threaded and the processes keep the cases apart), or on
any running scheduler when its address is given (its workers need this package installed).
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from contextlib import ExitStack

import numpy as np

from georod_tools.runner import CaseConfig, CaseResult, run_case

#: Parameters a sweep may vary by default (any other FMU Real parameter works too).
SWEEPABLE = ("F", "Omega")


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


def _value(cfg: CaseConfig, param: str) -> float:
    if param in ("F", "Omega", "dt_max", "elements"):
        return float(getattr(cfg, param))
    return float(dict(cfg.params)[param])


def run_sweep(
    base: CaseConfig,
    param: str,
    values: Sequence[float],
    workers: int = 1,
    scheduler: str | None = None,
    progress: bool = True,
    on_result: Callable[[CaseResult], None] | None = None,
) -> list[CaseResult]:
    """Runs `base` for every value of `param` on Dask and returns the results sorted by value.

    workers: number of local worker processes (ignored when `scheduler` is given).
    scheduler: address of a running Dask scheduler (``tcp://host:8786``); None starts a local
        cluster that is shut down afterwards.
    progress: show a tqdm bar over the completed cases.
    A failing case cancels the rest and raises RuntimeError naming its parameter value.
    """
    from dask.distributed import Client, LocalCluster, as_completed

    if workers < 1:
        raise ValueError(f"workers = {workers} must be >= 1")
    configs = sweep_configs(base, param, values)
    if not configs:
        return []
    results: list[CaseResult] = []
    with ExitStack() as stack:
        if scheduler:
            client = stack.enter_context(Client(scheduler))
        else:
            cluster = stack.enter_context(
                LocalCluster(
                    n_workers=workers,
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=":0",
                    silence_logs=logging.WARNING,
                )
            )
            client = stack.enter_context(Client(cluster))
        futures = client.map(run_case, configs, pure=True)
        index = {f.key: i for i, f in enumerate(futures)}
        bar = None
        if progress:
            from tqdm import tqdm

            bar = stack.enter_context(tqdm(total=len(futures), desc=f"sweep {param}", unit="case"))
        for fut in as_completed(futures):
            cfg = configs[index[fut.key]]
            try:
                res = fut.result()
            except Exception as e:
                client.cancel(futures)
                raise RuntimeError(f"case {param} = {_value(cfg, param):g} failed: {e}") from e
            results.append(res)
            if on_result is not None:
                on_result(res)
            if bar is not None:
                bar.update(1)
    results.sort(key=lambda r: _value(r.config, param))
    return results
