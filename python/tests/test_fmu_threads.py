"""Requirement 4: two instances stepped concurrently from two Python threads give exactly (==)
what each gives alone. fmpy calls the FMU through ctypes, which releases the GIL during each
call, so the two doStep computations really overlap; any shared mutable state in the library
would show up as a difference."""

from __future__ import annotations

import threading

import numpy as np

from helpers import FmuInfo, instantiate, release, run_steps

H, N = 1e-4, 150


def _run(
    info: FmuInfo, params: dict[str, float], name: str, barrier: threading.Barrier | None
) -> np.ndarray:
    slave = instantiate(info, params, instance_name=name)
    try:
        if barrier is not None:
            barrier.wait(timeout=60)
        return run_steps(slave, info, H, N)
    finally:
        release(slave)


def test_two_threads_equal_one_alone(fmus: dict[str, FmuInfo]) -> None:
    # Different scenes and parameters at once: no cross-talk either way.
    jobs = [
        (fmus["BuckledBeam"], {"F": 0.9, "elements": 10}, "beam_a"),
        (fmus["BuckledBeam"], {"F": 1.5, "elements": 12}, "beam_b"),
        (fmus["PinnedArch"], {"F": 50.0, "elements": 10}, "arch"),
    ]
    alone = [_run(info, p, name, None) for info, p, name in jobs]

    results: list[np.ndarray | None] = [None] * len(jobs)
    errors: list[BaseException] = []
    barrier = threading.Barrier(len(jobs))

    def work(i: int) -> None:
        info, p, name = jobs[i]
        try:
            results[i] = _run(info, p, name + "_thread", barrier)
        except BaseException as e:  # noqa: BLE001 - reported in the main thread
            errors.append(e)
            barrier.abort()

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(jobs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
    assert not errors, errors
    for i, (ref, got) in enumerate(zip(alone, results, strict=True)):
        assert got is not None
        assert np.array_equal(ref, got), f"job {jobs[i][2]} differs when run concurrently"
    assert not np.array_equal(alone[0], alone[1])


def test_two_identical_instances_in_threads(beam: FmuInfo) -> None:
    params = {"F": 0.9, "elements": 10}
    ref = _run(beam, params, "alone", None)
    out: dict[int, np.ndarray] = {}
    barrier = threading.Barrier(2)

    def work(i: int) -> None:
        out[i] = _run(beam, params, f"twin{i}", barrier)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
    assert set(out) == {0, 1}
    assert np.array_equal(out[0], ref) and np.array_equal(out[1], ref)
