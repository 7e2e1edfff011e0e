"""How local Dask workers start: forked from a fork server, never from the calling process.

A worker forked straight from a process with threads inherits their locks as they were at the
fork: a logging lock held by the Dask client's thread (or by any thread of the program that runs
a sweep, a test runner's included) stays held forever in the child, which then hangs on its first
log line. Python's fork server is a fresh, single-threaded process that imports
:data:`WORKER_PRELOAD` once and forks each worker from there: safe by construction, and a worker
is up as fast as a plain fork once the server has made its imports. Those imports (a second or
two) are paid once per program; :func:`start_worker_server` called at the top of a command makes
them while the command imports its own modules, on the other core.

This module imports nothing heavy: it is meant to be called before Dask is imported.
"""

from __future__ import annotations

import multiprocessing

# What a worker runs: imported once by the server, inherited by every worker it forks.
WORKER_PRELOAD = ["distributed", "numpy", "fmpy", "georod_tools.analysis.sweep"]


def start_worker_server() -> str:
    """Starts the fork server if it is not running yet (it returns at once; the server makes
    its imports in the background) and returns the multiprocessing start method for Dask's
    ``distributed.worker.multiprocessing-method``: "forkserver", or "spawn" where there is no
    fork server (Windows)."""
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return "spawn"
    from multiprocessing import forkserver

    # The preload list counts only when the server starts (Dask sets its own, with
    # `distributed` in it, on its first cluster: too late to replace this one).
    forkserver.set_forkserver_preload(WORKER_PRELOAD)
    forkserver.ensure_running()
    return "forkserver"
