"""Stops, cables and cubic springs through packaged FMUs (fmpy's FMU2Slave on python/tests/scenes/);
the core runs its closed-form checks in tests/contact_*.rs.

- RestingBeam: a pinned beam resting on a stop under its weight: the stop carries half the weight
  from the static initial state on; bounced by a harmonic force, every output of the stop stays in
  its range through the impacts and the energy-momentum FMU keeps its ledger at round-off; an FMU
  state serialized between impacts continues bit for bit in a fresh instance.
- StayedBeam: a cable stay shares a midspan load with the beam when taut and carries nothing when
  pushed.
- SofteningSpring: a push that takes a softening spring past its peak is refused (fmi2Discard, a
  logged reason naming the spring, every output as before).
- A stop with a negative gap is refused by `georod fmu` with the file and the key, and nothing is
  written; the stops' outputs have their value references.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Callable
from pathlib import Path

import pytest
from fmpy.fmi1 import FMICallException

from helpers import (
    DISCARD,
    GEOROD_CLI,
    FmuInfo,
    LogCapture,
    get_reals,
    instantiate,
    release,
    run_cmd,
    run_steps,
)
from scene_fmus import SCENE_DIR, ensure_georod, package_scene

WEIGHT = 9.81 * 7850.0 * 0.02 * 0.02  # the resting beam's weight, N


@pytest.fixture(scope="module")
def fmus(tmp_path_factory: pytest.TempPathFactory) -> Callable[[str], FmuInfo]:
    out = Path(tmp_path_factory.mktemp("contact"))
    return lambda name: package_scene(name, out)


def test_a_beam_rests_on_a_stop_and_bounces_on_it(fmus: Callable[[str], FmuInfo]) -> None:
    """Statics: the stop carries W/2 (the moment about the pin; the beam's sag changes the arms by
    1e-7), touched (`rest_contact` = 1), pressed in by W/(2k) beyond its 1 mm gap. Bounced by 18 N
    at 40 rad/s with integrator = 2: about 18 impacts in 0.5 s, the force never pulls, the contact
    fraction within [0, 1] and strictly between at the steps where the beam lands or lifts off, and
    energy_error at round-off (1e-12 of the energy, measured 7e-15 J of 0.1 J)."""
    info = fmus("RestingBeam")
    slave = instantiate(info)
    try:
        force, contact, tip = get_reals(slave, info, ["rest_force", "rest_contact", "w_tip"])
    finally:
        release(slave)
    assert abs(force - WEIGHT / 2) < 1e-5 * WEIGHT, force
    assert contact == 1.0
    assert abs(tip + 1e-3 + force / 1e6) < 1e-12, tip

    names = ["rest_force", "rest_contact", "energy_error", "E_kin", "E_strain"]
    rows = run_steps(
        slave := instantiate(info, {"F": 18.0, "integrator": 2}), info, 1e-3, 500, names=names
    )
    release(slave)
    forces, contacts, errors = rows[:, 0], rows[:, 1], rows[:, 2]
    energy = (rows[:, 3] + rows[:, 4]).max()
    assert forces.min() >= 0.0
    assert contacts.min() >= 0.0 and contacts.max() <= 1.0
    impacts = sum(1 for a, b in zip(contacts[:-1], contacts[1:], strict=True) if a == 0.0 < b)
    partial = sum(1 for c in contacts if 0.0 < c < 1.0)
    assert impacts >= 10 and partial >= 2 * impacts - 2, (impacts, partial)
    assert (forces[contacts == 0.0] == 0.0).all(), "no force in free flight"
    assert abs(errors).max() < 1e-12 * energy, abs(errors).max()


def test_a_state_between_impacts_continues_bit_for_bit(fmus: Callable[[str], FmuInfo]) -> None:
    """Serialized after 0.1 s of bouncing (the stop's averaged force and contact fraction are part
    of the state), restored in a fresh instance: the next 0.1 s give the same bits as the original
    run's, the stop's outputs included."""
    info = fmus("RestingBeam")
    params = {"F": 18.0}
    names = ["w_tip", "rest_force", "rest_contact", "E_kin", "energy_error"]
    a = instantiate(info, params, instance_name="original")
    try:
        run_steps(a, info, 1e-3, 100, names=names)
        state = a.getFMUstate()
        blob = a.serializeFMUstate(state)
        a.freeFMUstate(state)
        expected = run_steps(a, info, 1e-3, 100, k0=100, names=names)
    finally:
        release(a)
    b = instantiate(info, params, instance_name="fresh")
    try:
        restored = b.deSerializeFMUstate(blob)
        b.setFMUstate(restored)
        b.freeFMUstate(restored)
        got = run_steps(b, info, 1e-3, 100, k0=100, names=names)
    finally:
        release(b)
    assert (expected == got).all()
    assert (expected[:, 2] > 0.0).any() and (expected[:, 2] == 0.0).any(), "impacts in the window"


def test_a_cable_stay_shares_the_load_or_goes_slack(fmus: Callable[[str], FmuInfo]) -> None:
    """Pulled down by 100 N: the stay carries P k_c / (k_c + k_b), k_c = EA/L of the 5 mm cable,
    k_b the beam's midspan stiffness read from the slack case (pushed up by 100 N: the stay
    carries nothing and the beam alone deflects by P / k_b). Linear to 1e-5 of the deflections:
    1e-6 of P."""
    info = fmus("StayedBeam")
    slave = instantiate(info, {"P": -100.0})
    try:
        n_slack, w_up = get_reals(slave, info, ["stay_N_start", "w_M"])
    finally:
        release(slave)
    assert n_slack == 0.0
    k_b = 100.0 / w_up
    k_c = 2.1e11 * math.pi * 0.005**2 / 4 / 2.0
    slave = instantiate(info, {"P": 100.0})
    try:
        n_start, n_end = get_reals(slave, info, ["stay_N_start", "stay_N_end"])
    finally:
        release(slave)
    assert n_start == n_end
    assert abs(n_start - 100.0 * k_c / (k_c + k_b)) < 1e-6 * 100.0, n_start


def test_a_push_past_a_softening_peak_is_discarded(fmus: Callable[[str], FmuInfo]) -> None:
    """The push grows by 0.05 N a step (the spring's peak is 0.385 N, the strip takes the rest):
    the step that takes the softening spring past its peak answers fmi2Discard with the reason
    logged, and every output is what it was before the call, bit for bit."""
    info = fmus("SofteningSpring")
    log = LogCapture()
    slave = instantiate(info, log=log)
    outputs = [
        v.valueReference
        for v in info.md.modelVariables
        if v.causality == "output" and v.type == "Real"
    ]
    try:
        for k in range(400):
            slave.setReal([info.vr["push"]], [0.05 * (k + 1)])
            before = struct.pack(f"{len(outputs)}d", *slave.getReal(outputs))
            try:
                slave.doStep(k * 1e-3, 1e-3)
            except FMICallException as e:
                assert e.status == DISCARD
                break
        else:
            pytest.fail("the spring never passed its peak")
        assert "spring `soft` is past the peak of its force" in log.text(), log.text()
        assert struct.pack(f"{len(outputs)}d", *slave.getReal(outputs)) == before
    finally:
        release(slave)


def test_a_bad_stop_is_refused_and_nothing_is_written(tmp_path: Path) -> None:
    ensure_georod()
    bad = tmp_path / "BadStop.toml"
    bad.write_text(
        (SCENE_DIR / "RestingBeam.toml").read_text().replace("gap = 1.0e-3", "gap = -1.0e-3")
    )
    out = tmp_path / "BadStop.fmu"
    r = run_cmd([GEOROD_CLI, "fmu", bad, "-o", out], timeout=60)
    assert r.returncode != 0
    assert "BadStop.toml" in r.stderr and '[[stop]] #1 "rest", key `gap`' in r.stderr, r.stderr
    assert ">= 0" in r.stderr
    assert not out.exists()


def test_the_stop_outputs_have_their_value_references(fmus: Callable[[str], FmuInfo]) -> None:
    info = fmus("RestingBeam")
    assert info.vr["rest_force"] == 1_400_000
    assert info.vr["rest_contact"] == 1_500_000
