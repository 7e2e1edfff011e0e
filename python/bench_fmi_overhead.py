#!/usr/bin/env python3
"""Benchmark (not a test): the cost of driving the core through FMI + fmpy + ctypes.

Times N doStep calls of one internal sub-step each (communication step h == dt_max) of the
BuckledBeam (10 elements) through fmpy.fmi2.FMU2Slave, against the same N steps in the Rust core
directly (`target/release/georod bench-steps`), and prints both and their ratio.

    .venv/bin/python python/bench_fmi_overhead.py [--steps 10000] [--dt 1e-5] [--repeat 3]
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import fmpy
from fmpy.fmi2 import FMU2Slave

from georod_tools.cli.args import positive_float, positive_int

REPO = Path(__file__).resolve().parents[1]
FMU = REPO / "target" / "fmu" / "BuckledBeam.fmu"
CLI = REPO / "target" / "release" / "georod"
ELEMENTS = 10


def time_fmpy(unzipdir: str, steps: int, dt: float, with_get: bool) -> float:
    md = fmpy.read_model_description(unzipdir)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU2Slave(
        guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.coSimulation.modelIdentifier
    )
    slave.instantiate()
    slave.setupExperiment(startTime=0.0)
    slave.setReal([vr["dt_max"]], [dt])
    slave.setInteger([vr["elements"]], [ELEMENTS])
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    out = [vr["w_mid"], vr["v_mid"]]
    start = time.perf_counter()
    if with_get:
        for k in range(steps):
            slave.doStep(k * dt, dt)
            slave.getReal(out)
    else:
        for k in range(steps):
            slave.doStep(k * dt, dt)
    seconds = time.perf_counter() - start
    slave.terminate()
    slave.freeInstance()
    return seconds


def time_core(steps: int, dt: float) -> float | None:
    if not CLI.exists():
        return None
    cmd = [
        str(CLI),
        "bench-steps",
        "--scene",
        "BuckledBeam",
        "--set",
        f"elements={ELEMENTS}",
        "--set",
        f"dt_max={dt!r}",
        "--steps",
        str(steps),
        "--dt",
        repr(dt),
    ]
    r = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if r.returncode != 0:
        print(f"note: {' '.join(cmd)} failed: {r.stderr.strip()}", file=sys.stderr)
        return None
    return float(r.stdout.split()[0])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    ap.add_argument("--steps", type=positive_int, default=10_000, help="doStep calls, >= 1 (10000)")
    ap.add_argument("--dt", type=positive_float, default=1e-5, help="step in s, > 0 (1e-5)")
    ap.add_argument("--repeat", type=positive_int, default=3, help="best of N runs, >= 1 (3)")
    args = ap.parse_args()
    if not FMU.exists():
        print(f"{FMU} missing: run scripts/build_fmus", file=sys.stderr)
        return 1

    tmp = tempfile.mkdtemp(prefix="bench_fmu_")
    try:
        unzipdir = fmpy.extract(str(FMU), unzipdir=tmp)
        fmi = min(time_fmpy(unzipdir, args.steps, args.dt, False) for _ in range(args.repeat))
        fmi_get = min(time_fmpy(unzipdir, args.steps, args.dt, True) for _ in range(args.repeat))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    core_runs = [time_core(args.steps, args.dt) for _ in range(args.repeat)]
    core = min((c for c in core_runs if c is not None), default=None)

    n = args.steps
    print(
        f"BuckledBeam, {ELEMENTS} elements, {n} steps of {args.dt:g} s (one sub-step each),"
        f" best of {args.repeat}"
    )
    print(f"{'path':<34} {'total [s]':>10} {'per step [us]':>14} {'ratio':>8}")
    rows = [
        ("Rust core (georod bench-steps)", core),
        ("fmpy doStep", fmi),
        ("fmpy doStep + getReal(2)", fmi_get),
    ]
    for name, t in rows:
        if t is None:
            print(f"{name:<34} {'n/a':>10} {'n/a':>14} {'n/a':>8}")
            continue
        ratio = f"{t / core:8.2f}" if core else f"{'n/a':>8}"
        print(f"{name:<34} {t:10.4f} {1e6 * t / n:14.2f} {ratio}")
    if core is None:
        print(
            f"note: {CLI} bench-steps not available;"
            " build it with `cargo build --release --bin georod`"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
