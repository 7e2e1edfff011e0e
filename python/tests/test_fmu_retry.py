"""The retry path of fmi2DoStep through fmpy: a step whose Newton fails on some sub-step restarts
from the state saved at the start of the step with half the sub-step (at most 5 times); if every
attempt fails, fmi2Discard and the state exactly as before.

Both cases fail after converged sub-steps (the core test tests/suite/step_retry.rs replays every
attempt; here the premise is checked through the FMU's debug log: the first sub-step of the
failing attempt converges on its own), so a retry or discard that went on from the partly
advanced state would differ from the expected state in the last bits at least. The number of
sub-steps and cuts of a step is read from the FMU's trace message (category logAll):
"..., N sub-steps, M Newton iterations, K cuts". States are compared through every Real output
(the shape samples carry the displacement of every node) bit for bit, and serialized states as
whole byte strings; their layout is never read.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave

from helpers import DISCARD, LAST_SUCCESSFUL_TIME, FmuInfo, LogCapture, instantiate, release

CUTS = re.compile(r"(\d+) sub-steps, \d+ Newton iterations, (\d+) cuts")


def serialized(slave: FMU2Slave) -> bytes:
    state = slave.getFMUstate()
    try:
        return bytes(slave.serializeFMUstate(state))
    finally:
        slave.freeFMUstate(state)


def step_report(slave: FMU2Slave, log: LogCapture, t: float, h: float) -> tuple[int, int]:
    """doStep(t, h) (must succeed); returns (sub-steps, cuts) from the FMU's trace message."""
    log.clear()
    slave.doStep(t, h)
    found = [CUTS.search(m) for m in log.messages()]
    reports = [(int(m.group(1)), int(m.group(2))) for m in found if m]
    assert len(reports) == 1, (
        f"expected one trace 'N sub-steps, M Newton iterations, K cuts' from fmi2DoStep "
        f"(logAll); got:\n{log.text()}"
    )
    return reports[0]


def bits(slave: FMU2Slave, info: FmuInfo) -> tuple[bytes, float]:
    """Every Real output of the FMU (sensors, energies and ledger, reactions, the shape samples)
    as bytes, and the time."""
    outputs = [
        v.valueReference
        for v in info.md.modelVariables
        if v.causality == "output" and v.type == "Real"
    ]
    assert len(outputs) > 40  # the shape samples: 2 x 21 positions
    values = np.asarray(slave.getReal(outputs))
    return values.tobytes(), slave.getRealStatus(LAST_SUCCESSFUL_TIME)


def test_step_cut_twice_equals_the_step_at_the_finer_sub_step(fmus: dict[str, FmuInfo]) -> None:
    """BuckledBeam, f_ctrl = 100 over h = 5 ms: with dt_max = 0.5 ms the step needs two cuts
    (10 and 20 sub-steps fail after 4 and 19 converged ones); with dt_max = 0.125 ms it runs the
    same 40 sub-steps directly. Same state, same outputs, bit for bit."""
    beam = fmus["BuckledBeam"]
    h, dt_max, push = 5e-3, 5e-4, 100.0
    runs = {}
    for name, dt in (("cut", dt_max), ("direct", dt_max / 4)):
        log = LogCapture()
        slave = instantiate(beam, {"dt_max": dt}, instance_name=name, log=log)
        try:
            slave.setReal([beam.vr["f_ctrl"]], [push])
            if name == "cut":
                # premise: the first sub-step of the first (failing) attempt converges
                probe = instantiate(beam, {"dt_max": dt}, instance_name="probe", log=log)
                try:
                    probe.setReal([beam.vr["f_ctrl"]], [push])
                    assert step_report(probe, log, 0.0, dt_max) == (1, 0)
                finally:
                    release(probe)
            report = step_report(slave, log, 0.0, h)
            runs[name] = (report, bits(slave, beam))
        finally:
            release(slave)
    assert runs["cut"][0] == (40, 2)
    assert runs["direct"][0] == (40, 0)
    assert runs["cut"][1] == runs["direct"][1], "the retried step differs from the direct one"


def differing_bytes(a: bytes, b: bytes) -> int:
    """How many byte positions differ between two serialized states of equal length."""
    assert len(a) == len(b), f"lengths {len(a)} and {len(b)}"
    return sum(x != y for x, y in zip(a, b, strict=True))


def moving_arch(arch: FmuInfo, log: LogCapture | None = None, name: str = "arch") -> FMU2Slave:
    """PinnedArch in its chaotic regime (F = 20, Omega = 1000), dt_max = 0.5 ms, after 10 ms."""
    slave = instantiate(
        arch, {"dt_max": 5e-4, "F": 20.0, "Omega": 1000.0}, instance_name=name, log=log
    )
    for k in range(10):
        slave.doStep(k * 1e-3, 1e-3)
    return slave


def test_discarded_step_restores_the_state_bit_for_bit(fmus: dict[str, FmuInfo]) -> None:
    """A crown force f_ctrl = 1000 over 5 ms on the moving arch: every attempt (10 ... 320
    sub-steps) fails after converged sub-steps. fmi2Discard, a logged reason, every output as
    before bit for bit, and the serialized state identical to the one before the step but for
    the FMI state (now stepFailed: one byte of a small integer) and the checksum (4 bytes);
    fmi2LastSuccessfulTime is the start of the step; a host can roll back and go on exactly like
    an instance that never tried the step."""
    arch = fmus["PinnedArch"]
    log = LogCapture()
    slave = moving_arch(arch, log)
    fresh = moving_arch(arch, name="fresh")
    try:
        t, h = 0.01, 5e-3
        slave.setReal([arch.vr["f_ctrl"]], [1000.0])
        assert abs(slave.getReal([arch.vr["v_mid"]])[0]) > 1.0, "the arch should be moving"
        before = serialized(slave)
        saved = slave.getFMUstate()
        # premise: the first sub-step of the first attempt converges on its own
        probe = instantiate(arch, {"dt_max": 5e-4}, instance_name="probe", log=log)
        try:
            state = probe.deSerializeFMUstate(before)
            probe.setFMUstate(state)
            probe.freeFMUstate(state)
            assert step_report(probe, log, t, 5e-4) == (1, 0)
        finally:
            release(probe)

        outputs_before = bits(slave, arch)
        log.clear()
        with pytest.raises(FMICallException) as exc:
            slave.doStep(t, h)
        assert exc.value.status == DISCARD
        assert "did not converge" in log.text() and "halvings" in log.text()
        after = serialized(slave)
        assert after != before  # the FMI state is stepFailed now ...
        assert differing_bytes(after, before) <= 5  # ... and nothing else moved
        assert bits(slave, arch) == outputs_before
        assert slave.getRealStatus(LAST_SUCCESSFUL_TIME) == t

        # roll back, release the push, go on: exactly the run that never tried the step
        slave.setFMUstate(saved)
        slave.freeFMUstate(saved)
        slave.setReal([arch.vr["f_ctrl"]], [0.0])
        for k in range(5):
            slave.doStep(t + k * 1e-3, 1e-3)
            fresh.doStep(t + k * 1e-3, 1e-3)
        assert bits(slave, arch) == bits(fresh, arch)
    finally:
        release(slave)
        release(fresh)
