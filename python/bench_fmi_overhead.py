#!/usr/bin/env python3
"""Benchmark (not a test): the cost of driving the core through FMI + fmpy + ctypes.

Times N doStep calls of one internal sub-step each (communication step h == dt_max) of the
BuckledBeam (10 elements) through fmpy.fmi2.FMU2Slave and fmpy.fmi3.FMU3Slave (the FMI 2.0 and
3.0 FMUs of the scene, one library), against the same N steps in the Rust core directly
(`target/libs/georod bench-steps`), and prints them and their ratio. Then the cost of reading
the whole shape after a step: the FMI 3.0 arrays (one fmi3GetFloat64 call) against 2 x points
scalar fmi2GetReal calls.

    .venv/bin/python python/bench_fmi_overhead.py [--steps 10000] [--dt 1e-5] [--repeat 3]
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from ctypes import CFUNCTYPE, POINTER, byref, c_bool, c_double, c_int, c_void_p
from pathlib import Path

import fmpy
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

from georod_tools.cli.args import positive_float, positive_int

REPO = Path(__file__).resolve().parents[1]
FMU = REPO / "target" / "fmu" / "BuckledBeam.fmu"
FMU3 = REPO / "target" / "fmu3" / "BuckledBeam.fmu"
CLI = REPO / "target" / "libs" / "georod"  # scripts/build_fmus (release by default)
ELEMENTS = 10


def timed_steps(
    do_step: Callable[..., object],
    get: Callable[[list[int]], object] | None,
    out: list[int],
    steps: int,
    dt: float,
) -> float:
    """Seconds for `steps` calls of do_step, each followed by get(out) when get is given."""
    start = time.perf_counter()
    if get is not None:
        for k in range(steps):
            do_step(k * dt, dt)
            get(out)
    else:
        for k in range(steps):
            do_step(k * dt, dt)
    return time.perf_counter() - start


def c_do_step(slave: FMU2Slave | FMU3Slave) -> Callable[[float, float], object]:
    """The library's own fmi2DoStep / fmi3DoStep through ctypes, with its out-arguments made
    once: the two versions compared without fmpy's per-call wrapping (its FMU3Slave.doStep
    makes four ctypes objects per call)."""
    if isinstance(slave, FMU3Slave):
        flag = POINTER(c_bool)
        proto = CFUNCTYPE(
            c_int, c_void_p, c_double, c_double, c_bool, flag, flag, flag, POINTER(c_double)
        )
        f3 = proto(("fmi3DoStep", slave.dll))
        outs = (byref(c_bool()), byref(c_bool()), byref(c_bool()), byref(c_double()))
        return lambda t, h: f3(slave.component, t, h, True, *outs)
    f2 = CFUNCTYPE(c_int, c_void_p, c_double, c_double, c_int)(("fmi2DoStep", slave.dll))
    return lambda t, h: f2(slave.component, t, h, 1)


def run_steps(
    slave: FMU2Slave | FMU3Slave, get: Callable, mode: str, out: list[int], steps: int, dt: float
) -> float:
    """mode: "step" (fmpy's doStep), "get" (and a read of `out` after each), "c" (c_do_step)."""
    do_step = c_do_step(slave) if mode == "c" else slave.doStep
    return timed_steps(do_step, get if mode == "get" else None, out, steps, dt)


def time_fmpy(unzipdir: str, steps: int, dt: float, mode: str) -> float:
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
    seconds = run_steps(slave, slave.getReal, mode, [vr["w_mid"], vr["v_mid"]], steps, dt)
    slave.terminate()
    slave.freeInstance()
    return seconds


def time_fmpy3(unzipdir: str, steps: int, dt: float, mode: str) -> float:
    md = fmpy.read_model_description(unzipdir)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU3Slave(
        guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.coSimulation.modelIdentifier
    )
    slave.instantiate()
    slave.setFloat64([vr["dt_max"]], [dt])
    slave.setInt32([vr["elements"]], [ELEMENTS])
    slave.enterInitializationMode(startTime=0.0)
    slave.exitInitializationMode()
    seconds = run_steps(slave, slave.getFloat64, mode, [vr["w_mid"], vr["v_mid"]], steps, dt)
    slave.terminate()
    slave.freeInstance()
    return seconds


def time_shape_reads(dir2: str, dir3: str, reads: int) -> tuple[float, float, int]:
    """Seconds for `reads` reads of the whole shape: (FMI 3.0 arrays, FMI 2.0 scalars one call
    each), and the number of points."""
    md3 = fmpy.read_model_description(dir3)
    arrays = [v for v in md3.modelVariables if v.name in ("shape_x", "shape_y")]
    points = int(arrays[0].dimensions[0].start)
    three = FMU3Slave(guid=md3.guid, unzipDirectory=dir3, modelIdentifier="BuckledBeam")
    three.instantiate()
    three.enterInitializationMode(startTime=0.0)
    three.exitInitializationMode()
    vrs3 = [v.valueReference for v in arrays]
    start = time.perf_counter()
    for _ in range(reads):
        three.getFloat64(vrs3, nValues=2 * points)
    array_s = time.perf_counter() - start
    three.terminate()
    three.freeInstance()
    md2 = fmpy.read_model_description(dir2)
    two = FMU2Slave(guid=md2.guid, unzipDirectory=dir2, modelIdentifier="BuckledBeam")
    two.instantiate()
    two.setupExperiment(startTime=0.0)
    two.enterInitializationMode()
    two.exitInitializationMode()
    vrs2 = [v.valueReference for v in md2.modelVariables if v.name.startswith("shape_")]
    start = time.perf_counter()
    for _ in range(reads):
        for vr in vrs2:
            two.getReal([vr])
    scalar_s = time.perf_counter() - start
    two.terminate()
    two.freeInstance()
    return array_s, scalar_s, points


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
    for fmu in (FMU, FMU3):
        if not fmu.exists():
            print(f"{fmu} missing: run scripts/build_fmus", file=sys.stderr)
            return 1

    tmp = tempfile.mkdtemp(prefix="bench_fmu_")
    try:
        dir2 = fmpy.extract(str(FMU), unzipdir=f"{tmp}/2")
        dir3 = fmpy.extract(str(FMU3), unzipdir=f"{tmp}/3")
        best = args.repeat
        timed = {
            (version, mode): min(time(d, args.steps, args.dt, mode) for _ in range(best))
            for version, time, d in ((2, time_fmpy, dir2), (3, time_fmpy3, dir3))
            for mode in ("c", "step", "get")
        }
        shapes = [time_shape_reads(dir2, dir3, args.steps // 10 or 1) for _ in range(best)]
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
        ("ctypes fmi2DoStep, args made once", timed[2, "c"]),
        ("ctypes fmi3DoStep, args made once", timed[3, "c"]),
        ("fmpy doStep", timed[2, "step"]),
        ("fmpy doStep + getReal(2)", timed[2, "get"]),
        ("fmpy fmi3DoStep", timed[3, "step"]),
        ("fmpy fmi3DoStep + getFloat64(2)", timed[3, "get"]),
    ]
    for name, t in rows:
        if t is None:
            print(f"{name:<34} {'n/a':>10} {'n/a':>14} {'n/a':>8}")
            continue
        ratio = f"{t / core:8.2f}" if core else f"{'n/a':>8}"
        print(f"{name:<34} {t:10.4f} {1e6 * t / n:14.2f} {ratio}")
    array_s = min(a for a, _, _ in shapes)
    scalar_s = min(b for _, b, _ in shapes)
    points, reads = shapes[0][2], args.steps // 10 or 1
    print(
        f"whole shape ({points} points), {reads} reads: one fmi3GetFloat64 of both arrays"
        f" {1e6 * array_s / reads:.2f} us, {2 * points} scalar fmi2GetReal calls"
        f" {1e6 * scalar_s / reads:.2f} us (x {scalar_s / array_s:.1f})"
    )
    if core is None:
        print(
            f"note: {CLI} bench-steps not available;"
            " build it with `cargo build --release --bin georod`"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
