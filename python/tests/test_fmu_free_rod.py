"""The damping `d` and the load magnitude `F` against closed forms, through the FreeRod FMU.

`python/tests/scenes/FreeRod.toml`: a straight rod, no supports, from the undeformed reference
state at rest; a uniform load `F cos(Omega t)` per unit length along -e2 (harmonic), uniform
input loads `push1` (along e1) and `push2` (along e2); sensors `v2_i` at every node of the
10-element mesh, `v1` and `w` at the ends. Paper material, `b = h = 1`: `rho A = 1e-6`,
`c = d / (rho A) = 500/s` for `d = 5e-4`.

Momentum balance (any motion). Summing the e2 rows of the semi-discrete equations
`M a + C v + f_int = f_ext` over all nodes: the element internal forces have zero resultant, the
consistent damping matrix is `c` times the consistent mass matrix (both `integral N^T N ds`, on
the translations), and the summed nodal forces of the uniform load are `-F L cos(Omega t)`. So
the linear momentum `p = sum (M v)_2 = rho A L v_cm` obeys, with `m = rho A L`:

    m dv_cm/dt = -d L v_cm - F L cos(Omega t),   i.e.   v_cm' + c v_cm = -a cos(Omega t),
    a = F / (rho A),   c = d / (rho A).

From rest, `v_cm = A cos(Omega t) + B sin(Omega t) + K exp(-c t)`: inserting gives
`-A Omega + c B = 0`, `B Omega + c A = -a`, so `A = -a c / (c^2 + Omega^2)`,
`B = -a Omega / (c^2 + Omega^2)`, and `v_cm(0) = 0` gives `K = -A`:

    v_cm(t) = -a (c cos(Omega t) + Omega sin(Omega t) - c exp(-c t)) / (c^2 + Omega^2),

which for `d = 0` is `-F / (rho A Omega) sin(Omega t)`. With the consistent mass, `sum (M v)_2`
is `rho A` times the trapezoidal sum of the nodal `v2` over the nodes, which the sensors read.
The midpoint rule applies the same balance per step with the load at the step's midpoint, so the
FMU's momentum must follow that stepped scalar equation to round-off, and the closed form to the
step's O(dt^2). (The load's nodal forces are also `a` times the mass matrix applied to a uniform
vector, so the rod translates rigidly: every node has the same velocity and none rotates.)

Rigid translation. With no load, `v' = -c v`: `v(t) = v0 exp(-d t / (rho A))`. The midpoint rule
on it (`f_int = 0`): `M (2 du/dt^2 - 2 v_n/dt) + c M du/dt = 0`, `v_(n+1) = 2 du/dt - v_n`, gives
exactly `v_(n+1) = (1 - c dt/2) / (1 + c dt/2) v_n`; under a constant load `a rho A` per length
it gives `v_(n+1) = ((1 - c dt/2) v_n + a dt) / (1 + c dt/2)`, i.e. `v_n = (a/c) (1 - r^n)` from
rest, `r` the factor above. Per step `ln r = -c dt - (c dt)^3/12 - ...`, so after `t = n dt` the
discrete decay is `exp(-c t)` times `1 - c t (c dt)^2 / 12` to leading order.

The same closed forms through the Rust core: tests/suite/closed_form_damping_load.rs.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from fmpy.fmi2 import FMU2Slave

from helpers import FmuInfo, instantiate, release, run_steps, set_values
from scene_fmus import package_scene

RHO, B, H, L = 1.0e-6, 1.0, 1.0, 10.0
RHO_A = RHO * B * H
ELEMENTS = 10
DT = 1e-6
BASE: dict[str, float] = {
    "E": 1.2e4,
    "nu": 0.2,
    "rho": RHO,
    "b": B,
    "h": H,
    "L": L,
    "elements": ELEMENTS,
    "dt_max": DT,
}
V2 = [f"v2_{i}" for i in range(ELEMENTS + 1)]


@pytest.fixture(scope="session")
def free_rod(tmp_path_factory: pytest.TempPathFactory) -> FmuInfo:
    return package_scene("FreeRod", Path(tmp_path_factory.mktemp("free_rod")))


def centre_of_mass_velocity(v2: np.ndarray) -> np.ndarray:
    """`sum (M v)_2 / (rho A L)`: the trapezoidal mean of the nodal velocities (rows: times)."""
    return (v2.sum(axis=1) - 0.5 * (v2[:, 0] + v2[:, -1])) / ELEMENTS


@pytest.mark.parametrize("d", [0.0, 5.0e-4])
def test_uniform_harmonic_load_moves_the_centre_of_mass_at_f_over_rho_a_omega(
    free_rod: FmuInfo, d: float
) -> None:
    f, omega, h, steps = 0.9, 3500.0, 1e-5, 1000  # 0.01 s, 5.6 forcing periods
    substeps = round(h / DT)
    slave = instantiate(free_rod, {**BASE, "d": d, "F": f, "Omega": omega})
    try:
        rows = run_steps(slave, free_rod, h, steps, names=[*V2, "v1_0", "v1_10", "w_0", "w_10"])
    finally:
        release(slave)
    v2, rest = rows[:, : len(V2)], rows[:, len(V2) :]
    a, c = f / RHO_A, d / RHO_A
    scale = a / omega  # F / (rho A Omega) = 257 m/s
    t = h * np.arange(steps + 1)
    exact = -a * (c * np.cos(omega * t) + omega * np.sin(omega * t) - c * np.exp(-c * t))
    exact /= c * c + omega * omega
    # The stepped scalar equation, sub-step by sub-step (t_mid as the FMU's step counter has it).
    dt, x = h / substeps, 0.5 * c * h / substeps
    stepped, v = [0.0], 0.0
    for j in range(steps * substeps):
        v = ((1.0 - x) * v - dt * a * math.cos(omega * (j * dt + 0.5 * dt))) / (1.0 + x)
        if (j + 1) % substeps == 0:
            stepped.append(v)
    stepped_v = np.array(stepped)
    v_cm = centre_of_mass_velocity(v2)
    err_exact = float(np.max(np.abs(v_cm - exact))) / scale
    err_stepped = float(np.max(np.abs(v2 - stepped_v[:, None]))) / scale
    rigid = float(np.max(np.abs(rest[:, :2]))) / scale
    rotation = float(np.max(np.abs(rest[:, 2:])))
    # For d = 0 the stepped sum is exact: v_n = -(a/Omega) sin(Omega t_n) g,
    # g = (Omega dt/2) / sin(Omega dt/2) = 1 + (Omega dt)^2/24 + ...
    g = 0.5 * omega * dt / math.sin(0.5 * omega * dt)
    predicted = (g - 1.0) * float(np.max(np.abs(np.sin(omega * t))))
    print(
        f"\nfree rod, d = {d:.0e}, uniform load {f} cos({omega} t), dt = {dt:.0e}: errors of "
        f"F/(rho A Omega) = {scale:.1f} m/s\n"
        f"  momentum velocity vs closed form: {err_exact:.3e}"
        + (f" (midpoint sampling predicts (g - 1) = {predicted:.3e})" if d == 0.0 else "")
        + f"\n  every node vs the stepped scalar equation: {err_stepped:.2e}; "
        f"v1 {rigid:.1e}, w at the ends {rotation:.1e} rad"
    )
    # Every node follows the midpoint rule applied to the momentum balance: round-off of 1e4
    # linear sub-steps (measured 6e-13, 2e-13); 1e-11 bounds it, 1e4 below a 1e-7 error in F.
    assert err_stepped < 1e-11, f"nodes off the stepped momentum balance: {err_stepped:e}"
    # The translation stays rigid and transverse: v1 and w stay at round-off (measured 4e-26 of
    # the scale and 2e-15 rad).
    assert rigid < 1e-12 and rotation < 1e-12
    # Against the continuous closed form: the midpoint rule samples the load at mid-steps
    # ((Omega dt)^2 / 24 = 5.1e-7) and, with damping, O((c dt)^2) = 2.5e-7 terms; measured
    # 5.10e-7 and 5.96e-7. 5e-6 bounds that 10x over and is 2e4 below a 10 % error in F.
    assert err_exact < 5e-6, f"d = {d}: momentum off the closed form by {err_exact:e}"
    if d == 0.0:
        # Undamped, the gap is exactly the sampling factor: identify it (round-off ~1e-11 of
        # a 5e-7 gap), which a wrong F, Omega or time base would not reproduce.
        assert abs(err_exact / predicted - 1.0) < 1e-3, f"{err_exact:e} vs {predicted:e}"


def step_and_read(
    slave: FMU2Slave, info: FmuInfo, t0: float, h: float, n: int, names: list[str]
) -> np.ndarray:
    """n communication steps of h from t0; the outputs `names` at t0 and after each step."""
    vrs = [info.vr[x] for x in names]
    rows = [slave.getReal(vrs)]
    for k in range(n):
        slave.doStep(t0 + k * h, h)
        rows.append(slave.getReal(vrs))
    return np.asarray(rows, dtype=float)


def test_rigid_translation_loses_velocity_as_exp_minus_d_t_over_rho_a(free_rod: FmuInfo) -> None:
    d = 5.0e-4
    c = d / RHO_A
    accel = np.array([3.0e4, -2.0e4])  # push1, push2 per unit length divided by rho A
    names = ["v1_0", "v1_5", "v1_10", "v2_0", "v2_5", "v2_10"]
    slave = instantiate(free_rod, {**BASE, "d": d, "F": 0.0})
    try:
        # Speed up: the input loads held for 10 communication steps of 1e-4 s (1000 sub-steps).
        set_values(slave, free_rod, {"push1": accel[0] * RHO_A, "push2": accel[1] * RHO_A})
        h_push, n_push = 1e-4, 10
        push = step_and_read(slave, free_rod, 0.0, h_push, n_push, names)
        t_push = h_push * n_push
        # Then no load: 1e4 communication steps of one sub-step each (0.01 s, c t = 5).
        set_values(slave, free_rod, {"push1": 0.0, "push2": 0.0})
        steps = 10_000
        decay = step_and_read(slave, free_rod, t_push, DT, steps, names)
    finally:
        release(slave)

    # Speeding up from rest: v_n = (a/c) (1 - r^n) exactly, (a/c) (1 - exp(-c t)) to O(dt^2).
    dt_push = h_push / round(h_push / DT)
    r_push = (1.0 - 0.5 * c * dt_push) / (1.0 + 0.5 * c * dt_push)
    n_sub = round(t_push / dt_push)
    v_push = np.repeat(accel / c * (1.0 - r_push**n_sub), 3)
    err_push = float(np.max(np.abs(push[-1] - v_push) / np.abs(v_push)))
    continuous = accel / c * (1.0 - math.exp(-c * t_push))
    gap_push = float(np.max(np.abs(v_push[::3] / continuous - 1.0)))
    e = math.exp(-c * t_push)
    predicted_push = c * t_push * (c * dt_push) ** 2 / 12.0 * e / (1.0 - e)

    # The decay, step by step and against exp(-c t).
    r = (1.0 - 0.5 * c * DT) / (1.0 + 0.5 * c * DT)
    per_step = float(np.max(np.abs(decay[1:] - r * decay[:-1]) / np.abs(decay[:-1])))
    spread = float(np.max(np.ptp(decay[:, :3], axis=1)) + np.max(np.ptp(decay[:, 3:], axis=1)))
    t = steps * DT
    ratio = decay[-1] / decay[0]
    gap = float(np.max(np.abs(ratio / math.exp(-c * t) - 1.0)))
    predicted = c * t * (c * DT) ** 2 / 12.0
    print(
        f"\nfree rod, rigid translation, d = {d:.0e} (c = {c:.0f}/s), dt = {DT:.0e}\n"
        f"  push {t_push} s: v = {push[-1][[0, 3]]} vs (a/c)(1 - r^n): {err_push:.2e}; "
        f"(a/c)(1 - r^n) vs (a/c)(1 - exp(-ct)): {gap_push:.3e} (predicted {predicted_push:.3e})\n"
        f"  decay, per step: max |v_(n+1) - r v_n| / |v_n| = {per_step:.2e} "
        f"(r = (1 - c dt/2)/(1 + c dt/2)); nodes differ by {spread:.1e} m/s\n"
        f"  after {t} s: v/v0 = {ratio[0]:.12e}, exp(-d t/(rho A)) = {math.exp(-c * t):.12e}, "
        f"rel. gap {gap:.4e} (predicted c t (c dt)^2 / 12 = {predicted:.4e})"
    )
    # The input load's speed-up is the exact discrete solution: round-off (measured 8e-14);
    # 1e-12 bounds it, far below a 1e-6 error in the input or d. Its gap to the continuous
    # solution is the predicted O(dt^2) c t (c dt)^2 e^-ct / (12 (1 - e^-ct)) = 1.6e-8, within
    # 1 % (measured 1.606e-8 for 1.606e-8).
    assert err_push < 1e-12, f"speed-up off the exact discrete solution: {err_push:e}"
    assert abs(gap_push - predicted_push) < 1e-2 * predicted_push
    # Per step: the exact factor up to round-off. Positions carry ulps (~1e-16 strains) whose
    # elastic forces walk the nodal velocities apart by ~1e-12 m/s per step (measured
    # 4.4e-11 of |v|, nodes 4e-11 m/s apart). 1e-9 bounds both; a 1 % error in d shows as 5e-6.
    assert per_step < 1e-9, f"per-step factor off by {per_step:e}"
    assert spread < 1e-9, "the translation is not rigid"
    # Against exp(-c t): the predicted O(dt^2) gap within 1 % (measured 2e-4 of it, the next
    # order and round-off); a 0.1 % error in d would move it by 5e-3, 5e4 times the gap.
    assert abs(gap - predicted) < 1e-2 * predicted, f"gap {gap:e} vs predicted {predicted:e}"
