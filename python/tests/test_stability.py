"""Stability study (issue 7) through the FMUs with fmpy: very large steps and very large
excitation give either OK with finite outputs or fmi2Discard with the state intact (never NaN,
never a crash); parameters at the edges of their ranges run or are refused naming the variable;
a short smoke of georod_tools.studies.stability (energy of integrator 1 vs 2).

The long runs and the plots: scripts/study_stability (docs/stability.md)."""

from __future__ import annotations

import math

import pytest
from fmpy.fmi1 import FMICallException

from georod_tools.studies import stability
from helpers import (
    DISCARD,
    ERROR,
    FMU_DIR,
    LAST_SUCCESSFUL_TIME,
    FmuInfo,
    LogCapture,
    get_reals,
    instantiate,
    release,
)

ALL_OUTPUTS = ("w_mid", "v_mid", "E_kin", "E_strain", "W_ext", "W_ctrl", "E_damped", "energy_error")


def start(info: FmuInfo, params: dict[str, float], log: LogCapture):
    """Instantiated, parameters set (Integer and Enumeration with fmi2SetInteger: helpers.
    set_values would send an Enumeration through fmi2SetReal) and initialized."""
    slave = instantiate(info, log=log, initialize=False)
    try:
        for name, value in params.items():
            if info.types[name] in ("Integer", "Enumeration"):
                slave.setInteger([info.vr[name]], [int(value)])
            else:
                slave.setReal([info.vr[name]], [float(value)])
        slave.enterInitializationMode()
        slave.exitInitializationMode()
    except BaseException:
        release(slave)
        raise
    return slave


def drive(slave, info: FmuInfo, h: float, steps: int) -> tuple[int, bool]:
    """Steps of h from t = 0 (time from a step counter); returns (steps done, discarded).
    Checks: finite outputs after OK; after fmi2Discard the outputs and the last successful time
    are those before the call."""
    for k in range(steps):
        before = get_reals(slave, info, ALL_OUTPUTS)
        try:
            slave.doStep(k * h, h)
        except FMICallException as e:
            assert e.status == DISCARD, f"doStep returned {e.status}"
            assert get_reals(slave, info, ALL_OUTPUTS) == before
            assert slave.getRealStatus(LAST_SUCCESSFUL_TIME) == pytest.approx(k * h, abs=1e-15)
            return k, True
        values = get_reals(slave, info, ALL_OUTPUTS)
        assert all(math.isfinite(v) for v in values), dict(zip(ALL_OUTPUTS, values, strict=False))
    return steps, False


@pytest.mark.parametrize("integrator", [1, 2])
@pytest.mark.parametrize("per_period", [1.0, 1.1, 2.0, 2.2])
@pytest.mark.parametrize(
    ("scene_name", "F", "Omega"),
    [
        ("PinnedArch", 500.0, 1000.0),
        ("PinnedArch", 3000.0, 1000.0),
        ("ClampedArch", 3000.0, 1000.0),
        ("BuckledBeam", 20.0, 3500.0),
    ],
)
def test_huge_excitation_huge_steps(
    fmus: dict[str, FmuInfo],
    scene_name: str,
    F: float,
    Omega: float,
    per_period: float,
    integrator: int,
) -> None:
    info = fmus[scene_name]
    h = 2 * math.pi / Omega / per_period
    log = LogCapture()
    slave = start(info, {"F": F, "Omega": Omega, "dt_max": h, "integrator": integrator}, log)
    try:
        done, discarded = drive(slave, info, h, int(10 * per_period))
        if discarded:
            assert "did not converge" in log.text()
    finally:
        release(slave)


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("E", 1e-6),
        ("E", 1e12),
        ("nu", -0.999),
        ("nu", 0.49999999999999994),  # the declared max: the double below 0.5
        ("d", 0.0),
        ("d", 1e6),
        ("dt_max", 1e-8),
        ("dt_max", 1e3),
        ("elements", 2),
        ("elements", 3000),
        ("h", 1e-3),
        ("rho", 1e-30),
    ],
)
def test_parameter_edges_run(fmus: dict[str, FmuInfo], scene: str, name: str, value: float) -> None:
    info = fmus[scene]
    params: dict[str, float] = {name: value}
    if scene != "BuckledBeam":
        params.setdefault("F", 300.0)
    log = LogCapture()
    try:
        slave = start(info, params, log)
    except FMICallException as e:  # no initial state: an error that says why
        assert e.status == ERROR and "initial" in log.text()
        return
    try:
        drive(slave, info, 1e-4, 5)
    finally:
        release(slave)


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("E", 0.0),
        ("E", -1.0),
        ("nu", -1.0),
        ("nu", 0.5),
        ("nu", 0.51),
        ("rho", 0.0),
        ("d", -1e-9),
        ("dt_max", 0.0),
        ("elements", 1),
        ("h", math.inf),
        ("F", math.nan),
    ],
)
def test_refused_values_name_the_variable(
    fmus: dict[str, FmuInfo], name: str, value: float
) -> None:
    info = fmus["BuckledBeam"]
    log = LogCapture()
    slave = instantiate(info, log=log, initialize=False)
    try:
        vr = info.vr[name]
        with pytest.raises(FMICallException) as exc:
            if info.types[name] == "Integer":
                slave.setInteger([vr], [int(value)])
            else:
                slave.setReal([vr], [value])
        assert exc.value.status == ERROR
        assert name in log.text()
    finally:
        release(slave)


def test_energy_smoke() -> None:
    """A short FMU run of both integrators after a kick: the energy-momentum scheme keeps the
    energy to round-off, the midpoint rule stays finite."""
    case = stability.CASES[0]
    runs = {i: stability.run_energy(FMU_DIR, case, i, steps=300, every=10) for i in (1, 2)}
    for r in runs.values():
        assert r.discarded_at is None, r.message
        assert all(math.isfinite(e) for e in r.energy)
    assert runs[2].max_rel_drift() < 1e-9
    assert abs(runs[2].energy_error[-1]) < 1e-8 * runs[2].reference
