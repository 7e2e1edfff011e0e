"""Requirement 6: bad input through fmpy/ctypes. Every forbidden call order or bad argument returns
fmi2Error (fmpy raises FMICallException with that `status`), a message reaches the logger
callback, and the process survives (the test keeps running and frees the instance).
A doStep that cannot converge (fmi2Discard, state as it was): test_fmu_retry.py."""

from __future__ import annotations

import math
from collections.abc import Callable
from ctypes import byref, c_void_p

import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2FMUstate

from helpers import (
    ERROR,
    OUTPUTS,
    FmuInfo,
    LogCapture,
    get_reals,
    instantiate,
    new_slave,
    release,
    set_values,
)


def expect_error(log: LogCapture | None, call: Callable[[], object], status: int = ERROR) -> str:
    """Runs `call`, expects FMICallException with `status` and (with a logger) a new message."""
    if log is not None:
        log.clear()
    with pytest.raises(FMICallException) as exc:
        call()
    assert exc.value.status == status, (
        f"{exc.value.function} returned {exc.value.status}, expected {status}"
    )
    if log is None:
        return ""
    assert log.records, f"{exc.value.function} returned status {status} without a log message"
    return log.text()


@pytest.fixture
def log() -> LogCapture:
    return LogCapture()


# --- forbidden call orders -------------------------------------------------------------------


def test_do_step_before_initialization(beam: FmuInfo, log: LogCapture) -> None:
    slave = instantiate(beam, log=log, initialize=False)
    try:
        expect_error(log, lambda: slave.doStep(0.0, 1e-4))
        slave.enterInitializationMode()
        expect_error(log, lambda: slave.doStep(0.0, 1e-4))
    finally:
        release(slave)


def test_set_fixed_parameter_after_initialization(fmu: FmuInfo, log: LogCapture) -> None:
    slave = instantiate(fmu, log=log)
    try:
        for name, value in (("E", 2.0e4), ("elements", 4), ("dt_max", 1e-6), ("L", 11.0)):
            text = expect_error(log, lambda n=name, v=value: set_values(slave, fmu, {n: v}))
            assert text
        # tunable parameters and inputs may still change
        set_values(slave, fmu, {"F": 1.0, "Omega": 900.0, "f_ctrl": 0.1})
        slave.doStep(0.0, 1e-4)
    finally:
        release(slave)


def test_set_output_refused(beam: FmuInfo, log: LogCapture) -> None:
    slave = instantiate(beam, log=log)
    try:
        expect_error(log, lambda: slave.setReal([beam.vr["w_mid"]], [1.0]))
        expect_error(log, lambda: slave.setInteger([beam.vr["newton_iterations"]], [3]))
    finally:
        release(slave)


def test_enter_initialization_twice(beam: FmuInfo, log: LogCapture) -> None:
    slave = instantiate(beam, log=log, initialize=False)
    try:
        slave.enterInitializationMode()
        expect_error(log, slave.enterInitializationMode)
    finally:
        release(slave)


def test_calls_without_instance_return_error(beam: FmuInfo) -> None:
    """getFMUstate / doStep / getReal with a NULL component (before instantiation): fmi2Error,
    no crash. There is no logger to call without an instance."""
    slave = new_slave(beam)
    try:
        assert slave.component is None
        state = fmi2FMUstate()
        expect_error(None, lambda: slave.fmi2GetFMUstate(None, byref(state)))
        expect_error(None, lambda: slave.doStep(0.0, 1e-4))
        expect_error(None, lambda: slave.getReal([beam.vr["w_mid"]]))
        expect_error(None, lambda: slave.fmi2SetFMUstate(None, c_void_p(None)))
    finally:
        slave.freeLibrary()


def test_null_state_pointers(beam: FmuInfo, log: LogCapture) -> None:
    slave = instantiate(beam, log=log)
    try:
        expect_error(log, lambda: slave.fmi2GetFMUstate(slave.component, None))
        expect_error(log, lambda: slave.fmi2SetFMUstate(slave.component, c_void_p(None)))
    finally:
        release(slave)


# --- bad arguments ---------------------------------------------------------------------------


def test_unknown_value_reference(beam: FmuInfo, log: LogCapture) -> None:
    slave = instantiate(beam, log=log)
    try:
        unknown = max(beam.vr.values()) + 1000
        expect_error(log, lambda: slave.getReal([unknown]))
        expect_error(log, lambda: slave.setReal([unknown], [1.0]))
        expect_error(log, lambda: slave.getInteger([unknown]))
        # a Real's vr used as an Integer
        expect_error(log, lambda: slave.getInteger([beam.vr["w_mid"]]))
    finally:
        release(slave)


def test_arch_only_variable_unknown_to_beam(fmus: dict[str, FmuInfo], log: LogCapture) -> None:
    """vr of H exists in the arches, not in the BuckledBeam FMU."""
    beam = fmus["BuckledBeam"]
    vr_h = fmus["PinnedArch"].vr["H"]
    slave = instantiate(beam, log=log, initialize=False)
    try:
        expect_error(log, lambda: slave.setReal([vr_h], [1.0]))
    finally:
        release(slave)


OUT_OF_RANGE: list[tuple[str, float]] = [
    ("nu", 0.7),
    ("nu", -1.0),
    ("elements", 1),
    ("E", -1.0),
    ("E", 0.0),
    ("rho", 0.0),
    ("L", -10.0),
    ("b", 0.0),
    ("h", -1.0),
    ("dt_max", 0.0),
    ("d", -1e-3),
    ("E", math.nan),
    ("F", math.nan),
    ("Omega", math.inf),
    ("L", math.inf),
]


@pytest.mark.parametrize(("name", "value"), OUT_OF_RANGE, ids=[f"{n}={v}" for n, v in OUT_OF_RANGE])
def test_out_of_range_parameter_refused(
    beam: FmuInfo, log: LogCapture, name: str, value: float
) -> None:
    """Refused when set, with a message naming the variable (spec: ... and the allowed range)."""
    slave = instantiate(beam, log=log, initialize=False)
    try:
        text = expect_error(log, lambda: set_values(slave, beam, {name: value}))
        assert f"{name}" in text, f"message does not name `{name}`: {text!r}"
    finally:
        release(slave)


def test_nan_tunable_after_initialization(beam: FmuInfo, log: LogCapture) -> None:
    slave = instantiate(beam, log=log)
    try:
        before = get_reals(slave, beam, OUTPUTS)
        expect_error(log, lambda: slave.setReal([beam.vr["F"]], [math.nan]))
        expect_error(log, lambda: slave.setReal([beam.vr["f_ctrl"]], [math.inf]))
        assert get_reals(slave, beam, OUTPUTS) == before
    finally:
        release(slave)


def test_cross_condition_refused(fmus: dict[str, FmuInfo], log: LogCapture) -> None:
    """A shortening far beyond the beam's length (no equilibrium in the well) or H > L/2 (arch)
    is refused at the latest when the initialization ends."""
    for scene, values in (("BuckledBeam", {"pre_shortening": 1000.0}), ("PinnedArch", {"H": 20.0})):
        info = fmus[scene]
        slave = instantiate(info, log=log, initialize=False)
        log.clear()
        try:
            with pytest.raises(FMICallException) as exc:
                set_values(slave, info, values)
                slave.enterInitializationMode()
                slave.exitInitializationMode()
            assert exc.value.status == ERROR
            assert log.records, f"{scene}: {exc.value.function} failed without a log message"
        finally:
            release(slave)


def test_bad_step_arguments(beam: FmuInfo, log: LogCapture) -> None:
    slave = instantiate(beam, log=log)
    try:
        expect_error(log, lambda: slave.doStep(0.0, -1e-4))
        expect_error(log, lambda: slave.doStep(0.0, math.nan))
    finally:
        release(slave)


def test_bad_serialized_state(fmus: dict[str, FmuInfo], log: LogCapture) -> None:
    """Garbage bytes, a truncated state and a state of another scene are refused."""
    beam, arch = fmus["BuckledBeam"], fmus["PinnedArch"]
    a = instantiate(beam, {"elements": 6})
    try:
        s = a.getFMUstate()
        blob = a.serializeFMUstate(s)
        a.freeFMUstate(s)
    finally:
        release(a)

    b = instantiate(arch, {"elements": 6}, log=log)
    try:
        for bad in (b"\x00" * 7, b"not a georod state at all" * 4, blob[: len(blob) // 2]):
            expect_error(log, lambda x=bad: b.deSerializeFMUstate(x))

        def other_scene() -> None:
            st = b.deSerializeFMUstate(blob)  # may already refuse here ...
            try:
                b.setFMUstate(st)  # ... or here
            finally:
                b.freeFMUstate(st)

        expect_error(log, other_scene)
    finally:
        release(b)

    c = instantiate(beam, {"elements": 7}, log=log)  # same scene, other mesh
    try:

        def other_mesh() -> None:
            st = c.deSerializeFMUstate(blob)
            try:
                c.setFMUstate(st)
            finally:
                c.freeFMUstate(st)

        expect_error(log, other_mesh)
    finally:
        release(c)


def test_process_survives_free_after_error(beam: FmuInfo, log: LogCapture) -> None:
    """An instance that answered errors can still be terminated and freed, and a new one works."""
    slave = instantiate(beam, log=log)
    expect_error(log, lambda: slave.getReal([99999]))
    release(slave)
    again: FMU2Slave = instantiate(beam)
    try:
        again.doStep(0.0, 1e-4)
    finally:
        release(again)
