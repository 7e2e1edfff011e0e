"""The engineer's examples of examples/ as FMUs (a tip-mass cantilever, a bridge crossed by a
moving load, a beam on a Winkler foundation, a beam on elastic bearings with shaken bases, a
settlement set in initialization mode) against closed forms and the energy ledger."""

from __future__ import annotations

import math

import numpy as np

from helpers import FmuInfo, instantiate, release


def test_tip_mass_cantilever_hangs_under_both_weights(examples: dict[str, FmuInfo]) -> None:
    """Static state under gravity: the root carries the bar's weight and the 5 kg motor's (to
    1e-9: the reaction is the residual of a converged equilibrium)."""
    info = examples["TipMassCantilever"]
    slave = instantiate(info)
    try:
        ry, w_tip = slave.getReal([info.vr[n] for n in ("root_Ry", "w_tip")])
    finally:
        release(slave)
    weight = 9.81 * (7850.0 * 0.05 * 0.01 * 2.0 + 5.0)
    assert w_tip < 0.0
    assert math.isclose(ry, weight, rel_tol=1e-9), (ry, weight)


def test_bridge_sags_under_its_weight_and_the_moving_axle(examples: dict[str, FmuInfo]) -> None:
    """Initial state: the girder's own weight, midspan sag 5 q L^4 / (384 EI) + q L^2 / (8 G A)
    (q = rho A g; 40 elements: 1e-3). The axle (entering at 0.1 s, leaving at 0.77 s) adds a
    dynamic deflection whose peak exceeds its static one, P L^3 / (48 EI), at this speed
    (0.13 of the critical speed) by a few per cent."""
    info = examples["Bridge"]
    e, g_mod, rho, b, h, length = 210e9, 210e9 / 2.6, 7850.0, 0.4, 1.0, 20.0
    ei, ga, q = e * b * h**3 / 12.0, g_mod * b * h, rho * b * h * 9.81
    sag = 5.0 * q * length**4 / (384.0 * ei) + q * length**2 / (8.0 * ga)
    slave = instantiate(info)
    try:
        w0 = slave.getReal([info.vr["w_mid"]])[0]
        extra = []
        for k in range(1000):
            slave.doStep(k * 1e-3, 1e-3)
            extra.append(w0 - slave.getReal([info.vr["w_mid"]])[0])
    finally:
        release(slave)
    assert math.isclose(-w0, sag, rel_tol=1e-3), (w0, sag)
    static = 1e5 * length**3 / (48.0 * ei)
    peak = max(extra)
    assert 1.0 < peak / static < 1.3, (peak, static)
    assert abs(extra[99]) < 1e-6 * static, "the axle acted before it entered"


def test_beam_on_foundation_settles_at_hetenyi(examples: dict[str, FmuInfo]) -> None:
    """After 0.5 s (the foundation's damping, c / (rho A) = 51 /s, has taken the ringing down by
    exp(-12) at least) the deflection under the load is Hetenyi's P lambda / (2 k) (the rod's
    shear adds 6e-4, the mesh 1e-3)."""
    info = examples["BeamOnFoundation"]
    slave = instantiate(info)
    try:
        for k in range(500):
            slave.doStep(k * 1e-3, 1e-3)
        w = slave.getReal([info.vr["w_load"]])[0]
    finally:
        release(slave)
    ei, k_soil, load = 210e9 * 0.1 * 0.05**3 / 12.0, 1e6, 1e4
    lam = (k_soil / (4.0 * ei)) ** 0.25
    assert math.isclose(-w, load * lam / (2.0 * k_soil), rel_tol=3e-3), w


def test_support_input_set_in_initialization_mode_enters_the_static_state(
    examples: dict[str, FmuInfo],
) -> None:
    """BeamOnBase with its right end lifted by 10 um during initialization mode: the initial
    state is the clamped-clamped beam with that end offset, at rest: the end is there and the
    supports hold it with the shear force delta / (L^3 / (12 EI) + L / (G A)) (Timoshenko),
    to the mesh's O(l^2) (80 elements) and the tension of the axially held ends, O((delta/L)^2)
    (1.5e-3 for 1 mm, 1.5e-7 here)."""
    info = examples["BeamOnBase"]
    delta, e, nu, b, h, length = 1e-5, 70e9, 0.33, 0.05, 0.02, 1.0
    ei, ga = e * b * h**3 / 12.0, e / (2.0 * (1.0 + nu)) * b * h
    shear = delta / (length**3 / (12.0 * ei) + length / ga)
    slave = instantiate(info, {"elements": 80}, initialize=False)
    try:
        slave.enterInitializationMode()
        slave.setReal([info.vr["right_u2"]], [delta])
        slave.exitInitializationMode()
        names = ("left_Ry", "right_Ry", "shape_y[21]", "v_mid")
        left, right, y_end, v_mid = slave.getReal([info.vr[n] for n in names])
    finally:
        release(slave)
    assert y_end == delta and v_mid == 0.0
    assert math.isclose(right, shear, rel_tol=1e-3), (right, shear)
    assert math.isclose(left, -shear, rel_tol=1e-3), (left, shear)


def test_elastic_bearings_carry_the_weight_then_the_machine(examples: dict[str, FmuInfo]) -> None:
    """Static: each bearing carries half the beam's weight (its force on the rod is up) and is
    compressed by it over its stiffness. Running, the bearings' averaged forces keep carrying
    the weight plus the shaking machine force: over whole forcing periods their mean is the
    weight again (the beam, far below its first bending frequency, rides the springs)."""
    info = examples["ElasticBearings"]
    weight = 7850.0 * 0.2 * 0.3 * 6.0 * 9.81
    slave = instantiate(info)
    try:
        left, right, w_left = slave.getReal(
            [info.vr[n] for n in ("left_force", "right_force", "w_left")]
        )
        assert math.isclose(left, weight / 2.0, rel_tol=1e-9), (left, weight)
        assert math.isclose(right, weight / 2.0, rel_tol=1e-9), (right, weight)
        assert math.isclose(-w_left, weight / 2.0 / 5e7, rel_tol=1e-9), w_left
        h, period = 1e-3, 2.0 * math.pi / 40.0
        forces = []
        for k in range(round(5 * period / h)):
            slave.doStep(k * h, h)
            forces.append(sum(slave.getReal([info.vr["left_force"], info.vr["right_force"]])))
    finally:
        release(slave)
    assert max(forces) > weight + 1e3 and min(forces) < weight - 1e3
    late = forces[len(forces) // 5 :]
    assert abs(np.mean(late) - weight) < 2e-2 * weight


def test_elastic_bearings_bases_set_before_the_start_shift_the_static_state(
    examples: dict[str, FmuInfo],
) -> None:
    """ElasticBearings with both bearings' bases raised by 5 mm during initialization mode: a
    rigid translation strains nothing, so the static state is the one with the bases at 0
    lifted by exactly 5 mm (to the static solver's tolerance, 1e-10 of the 6 m span), and each
    bearing still carries half the weight."""
    info = examples["ElasticBearings"]
    weight = 7850.0 * 0.2 * 0.3 * 6.0 * 9.81
    offset = 5e-3
    names = ("w_left", "w_mid", "left_force", "right_force", "E_strain")
    states = []
    for base in (0.0, offset):
        slave = instantiate(info, initialize=False)
        try:
            slave.enterInitializationMode()
            slave.setReal([info.vr["left_base"], info.vr["right_base"]], [base, base])
            slave.exitInitializationMode()
            states.append(slave.getReal([info.vr[n] for n in names]))
        finally:
            release(slave)
    rest, raised = states
    for j in (0, 1):
        assert abs(raised[j] - rest[j] - offset) < 1e-9, (names[j], raised[j], rest[j])
    assert math.isclose(-rest[0], weight / 2.0 / 5e7, rel_tol=1e-9), rest[0]
    for state in states:
        for j in (2, 3):
            assert math.isclose(state[j], weight / 2.0, rel_tol=1e-9), (names[j], state[j])
    # The bearings store k (u - b)^2 / 2 whatever the offset.
    assert math.isclose(raised[4], rest[4], rel_tol=1e-9), (raised[4], rest[4])


def test_elastic_bearings_shaken_bases_do_the_ledgers_work(examples: dict[str, FmuInfo]) -> None:
    """ElasticBearings with its bearings' bases shaken through left_base and right_base (2 mm at
    25 and 31 Hz, out of phase): the bases' work W_supports is the sum over the steps of each
    averaged bearing force times its base's change over the step (the base moves linearly over a
    step), it moves the beam, and the ledger closes to the midpoint rule's second-order error
    (measured: 1.3e-8 of the work at 1 ms steps; bound 1e-6)."""
    info = examples["ElasticBearings"]
    h, steps = 1e-3, 300
    slave = instantiate(info, {"F": 0.0})
    vr = info.vr
    try:
        rebuilt, worst, swing = 0.0, 0.0, 0.0
        bases = [0.0, 0.0]
        for k in range(steps):
            t = (k + 1) * h
            new = [2e-3 * math.sin(2 * math.pi * 25 * t), -2e-3 * math.sin(2 * math.pi * 31 * t)]
            slave.setReal([vr["left_base"], vr["right_base"]], new)
            slave.doStep(k * h, h)
            left, right, w_mid, error = slave.getReal(
                [vr[n] for n in ("left_force", "right_force", "w_mid", "energy_error")]
            )
            rebuilt += left * (new[0] - bases[0]) + right * (new[1] - bases[1])
            bases = new
            worst = max(worst, abs(error))
            swing = max(swing, abs(w_mid))
        work, damped = slave.getReal([vr["W_supports"], vr["E_damped"]])
    finally:
        release(slave)
    assert swing > 1e-3, swing
    assert damped > 0.0 and abs(work) > 1.0, (work, damped)
    assert math.isclose(work, rebuilt, rel_tol=1e-12), (work, rebuilt)
    assert worst < 1e-6 * abs(work), (worst, work)
