"""The damping and load magnitudes through the FMUs, against closed forms.

- Damping: python/tests/scenes/AxialBar.toml is a bar of two elements whose only free dof is the
  axial displacement q of its midpoint. With the rotations and transverse displacements held at 0
  the element is exactly linear in q, and the damping matrix is ``c = d / (rho A)`` times the
  consistent mass, so ``q'' + c q' + omega^2 q = F cos(Omega t) / m`` with ``omega^2 = 3 E / (rho
  l^2)``, ``l = L / 2``. Once the load is switched off, the outputs (q, q') must follow the
  implicit midpoint map of that scalar equation, and the area ``q_k q'_{k+1} - q_{k+1} q'_k`` of
  successive states shrinks by its determinant: the decay rate ``d / (2 rho A)`` of the continuous
  equation up to the midpoint rule's own factor ``1 / (1 + (omega dt / 2)^2)``.
- Load: with ``pre_shortening = 0`` the BuckledBeam FMU is a straight rod pinned at both ends
  (u1 = u2 = 0 at both ends, rotations free) starting straight and unloaded. A small uniform
  load ``F cos(Omega t)`` at ``Omega`` far below the first bending frequency: after the start
  transient has died out, ``w_mid(T) = -w_static Re H`` with the Timoshenko static deflection
  ``5 F L^4 / (384 EI) + F L^2 / (8 G A)`` (shear factor 1, model.md) and the first mode's
  dynamic factor ``H = 1 / (1 - r^2 + i c r / omega_1)``, ``r = Omega / omega_1``, ``omega_1``
  the Timoshenko frequency. The mesh error (second order, exactly ``C / n^2``:
  tests/suite/closed_form_static_beam.rs) is removed by Richardson extrapolation from 40 and 80
  elements.

The same checks on a free rod, closer to the core, are in tests/suite/closed_form_damping_load.rs.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from helpers import FmuInfo, get_reals, instantiate, release
from scene_fmus import package_scene

E, NU, RHO, D, L = 1.2e4, 0.2, 1.0e-6, 5.0e-4, 10.0  # defaults of the FMUs; b = h = 1
EI, GA = E / 12.0, E / (2.0 * (1.0 + NU))
C = D / RHO  # d / (rho A), 1/s
STRAIGHT = {"pre_shortening": 0.0}


def midpoint_map(w2: float, c: float, dt: float) -> np.ndarray:
    """One implicit midpoint step of ``q'' + c q' + w2 q = 0`` on ``(q, q')``."""
    a = np.array([[0.0, 1.0], [-w2, -c]])
    i = np.eye(2)
    return np.linalg.solve(i - 0.5 * dt * a, i + 0.5 * dt * a)


@pytest.fixture(scope="module")
def axial_bar(tmp_path_factory: pytest.TempPathFactory) -> FmuInfo:
    return package_scene("AxialBar", Path(tmp_path_factory.mktemp("axial_bar")))


def test_axial_mode_decays_at_d_over_2_rho_a(axial_bar: FmuInfo) -> None:
    """Driven at resonance for 50 steps, then free for 1000 steps of h = 1e-5 (10 sub-steps of
    1e-6 each): the outputs follow the step map to round-off and the area decays at the midpoint
    rule's rate."""
    dt, h, steps = 1e-6, 1e-5, 1000
    w2 = 3.0 * E / (RHO * (L / 2) ** 2)
    info = axial_bar
    slave = instantiate(info, {"F": 1.0, "Omega": math.sqrt(w2), "dt_max": dt})
    names = ["q_mid", "qdot_mid"]
    try:
        for k in range(50):
            slave.doStep(k * h, h)
        slave.setReal([info.vr["F"]], [0.0])
        y = np.array(get_reals(slave, info, names))
        amplitude = math.hypot(y[0] * math.sqrt(w2), y[1])
        assert amplitude > 1e-3, "the load should have set the mode going"
        step_map = np.linalg.matrix_power(midpoint_map(w2, C, dt), round(h / dt))
        states, worst = [y], 0.0
        for k in range(50, 50 + steps):
            slave.doStep(k * h, h)
            got = np.array(get_reals(slave, info, names))
            y = step_map @ y
            err = np.abs(got - y) * np.array([math.sqrt(w2), 1.0])
            worst = max(worst, float(err.max()) / amplitude)
            states.append(got)
    finally:
        release(slave)
    s = np.array(states)
    area = s[:-1, 0] * s[1:, 1] - s[1:, 0] * s[:-1, 1]
    rate = -math.log(area[-1] / area[0]) / (2.0 * (steps - 1) * h)
    gap = rate / (0.5 * C) - 1.0
    print(
        f"axial mode: max error vs step map {worst:.2e}; decay {rate:.6f} 1/s vs d/(2 rho A) "
        f"= {0.5 * C}: {gap:.3e} (midpoint: -(omega dt/2)^2 = {-w2 * dt * dt / 4:.3e})"
    )
    # The outputs follow the exact step map to round-off accumulated over 1e4 sub-steps
    # (measured 2e-12 of the amplitude); bound 1e-10.
    assert worst < 1e-10
    # The midpoint rule damps a mode at (c/2) / (1 + (omega dt/2)^2): a gap of -3.6e-4 here;
    # 1e-3 bounds it, 200x below a 20 % error in d.
    assert abs(gap) < 1e-3


def timoshenko_omega1() -> float:
    """First bending frequency of the simply supported Timoshenko beam (shear factor 1, rotary
    inertia): the lower root of (GA k^2 - rA x)(EI k^2 + GA - rI x) = GA^2 k^2, x = omega^2."""
    k, ra, ri = math.pi / L, RHO, RHO / 12.0
    a = ra * ri
    b = -(ra * (EI * k * k + GA) + ri * GA * k * k)
    c = GA * k * k * (EI * k * k + GA) - GA * GA * k * k
    return math.sqrt(2.0 * c / (-b + math.sqrt(b * b - 4.0 * a * c)))


def test_quasi_static_uniform_load_gives_the_timoshenko_deflection(beam: FmuInfo) -> None:
    f, omega = 1e-3, 100.0
    period = 2.0 * math.pi / omega
    steps = 100

    def w_at_period(elements: int) -> float:
        slave = instantiate(beam, {**STRAIGHT, "F": f, "Omega": omega, "elements": elements})
        try:
            for k in range(steps):
                slave.doStep(k * period / steps, period / steps)
            return get_reals(slave, beam, ["w_mid"])[0]
        finally:
            release(slave)

    w40, w80 = w_at_period(40), w_at_period(80)
    static = 5.0 * f * L**4 / (384.0 * EI) + f * L**2 / (8.0 * GA)
    omega1 = timoshenko_omega1()
    r = omega / omega1
    dynamic = (1.0 / complex(1.0 - r * r, C * r / omega1)).real
    expected = -static * dynamic
    extrapolated = (4.0 * w80 - w40) / 3.0
    err = extrapolated / expected - 1.0
    print(
        f"w_mid(T): 40 el {w40:.9e}, 80 el {w80:.9e}, extrapolated {extrapolated:.9e}; "
        f"closed form {expected:.9e} (static {static:.6e} x {dynamic:.6f}): {err:.2e}"
    )
    # Left out of the closed form: the higher modes' dynamic factors (mode 3 carries 0.4 % of
    # the static deflection at (Omega / omega_3)^2 ~ 1e-4: 4e-7), the start transient
    # (exp(-c T / 2) = 1.6e-7), the time step ((Omega dt)^2 = 1e-6) and the O(n^-4) mesh
    # remainder; measured 5e-6. 5e-5 bounds it and is 2000x below a 10 % error in F.
    assert abs(err) < 5e-5
