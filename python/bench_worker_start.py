"""The start of a sweep's local Dask workers: forked from the fork server (what georod-tools
does) against forked straight from the command's process (what it did before; unsafe when the
process has other threads), in interleaved pairs, each run a fresh interpreter.

    .venv/bin/python python/bench_worker_start.py [--pairs 3] [--workers 2]

Prints, per start method, the command's imports, the cluster coming up, the first task and the
whole, then the ratio of the totals (docs/benchmark.md, "Local Dask workers from a fork server").
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time

METHODS = ("fork", "forkserver")


def one_run(method: str, workers: int) -> dict[str, float]:
    """In this (fresh) process: what a sweep command does before its first case."""
    t0 = time.perf_counter()
    if method == "forkserver":
        from georod_tools.analysis.worker_start import start_worker_server

        start_worker_server()
    from dask.distributed import Client

    from georod_tools.analysis import sweep

    if method == "fork":
        sweep.start_worker_server = lambda: "fork"  # the former start, for comparison only
    t1 = time.perf_counter()
    with sweep.local_cluster(workers) as cluster, Client(cluster) as client:
        t2 = time.perf_counter()
        client.run(lambda: None)
        t3 = time.perf_counter()
    return {"imports": t1 - t0, "cluster up": t2 - t1, "first task": t3 - t2, "total": t3 - t0}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pairs", type=int, default=3)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--one", choices=METHODS, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one:
        print(json.dumps(one_run(args.one, args.workers)))
        return 0
    runs: dict[str, list[dict[str, float]]] = {m: [] for m in METHODS}
    for _ in range(args.pairs):
        for method in METHODS:
            cmd = [sys.executable, __file__, "--one", method, "--workers", str(args.workers)]
            out = subprocess.run(cmd, capture_output=True, text=True, check=True, timeout=300)
            runs[method].append(json.loads(out.stdout.strip().splitlines()[-1]))
    keys = ("imports", "cluster up", "first task", "total")
    print(f"| start | {' | '.join(keys)} |")
    print(f"|---|{'---|' * len(keys)}")
    for method, got in runs.items():
        cells = [f"{min(r[k] for r in got):.2f}-{max(r[k] for r in got):.2f} s" for k in keys]
        print(f"| {method} | {' | '.join(cells)} |")
    ratios = [
        s["total"] / f["total"] for f, s in zip(runs["fork"], runs["forkserver"], strict=True)
    ]
    print("total, fork server / fork, per pair: " + ", ".join(f"{r:.2f}" for r in ratios))
    return 0


if __name__ == "__main__":
    sys.exit(main())
