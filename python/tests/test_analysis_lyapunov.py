"""Benettin's algorithm (georod_tools.lyapunov) against exponents known exactly, with
renormalization every k > 1 steps, on maps and through the FMU.

Known values:
- a linear map ``x -> A x`` has the exponent ln of the spectral radius of ``A`` (the norm of a
  vector grows like ``rho(A)^n`` once it has turned into the leading eigendirection); for ``A =
  exp(-0.3) R(phi)`` every vector shrinks by exactly ``exp(-0.3)`` per step;
- a rigid rotation of a torus (quasi-periodic) has exponent 0;
- the damped axial vibration of the straight rod (BuckledBeam FMU with ``pre_shortening = 0``, no
  load, at rest at u = 0): the separation of the perturbed instance is a free axial vibration,
  which stays axial and, with the damping matrix ``d / (rho A)`` times the mass matrix on the
  translations, decays like ``exp(-d t / (2 rho A))`` in every axial mode: the exponent is
  ``-d / (2 rho A)`` (-250 1/s for the defaults), and 0 without damping. The separation is put in
  the first axial mode (exact discrete eigenvector ``sin(pi i / n)`` on u1, frequency
  ``omega_h``) and the time unit chosen as ``2 pi / omega_h``, so that the separation norm
  ``|(u, v / Omega)|`` is the mode's energy norm (conserved by the midpoint rule when undamped).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from georod_tools.lyapunov import LyapunovSettings, benettin, map_exponent


def rotation(phi: float) -> np.ndarray:
    return np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])


@pytest.mark.parametrize("every", [1, 4])
def test_contracting_rotation_has_exponent_minus_0_3(every: int) -> None:
    """Every vector shrinks by exp(-0.3) per step: each interval of `every` steps measures
    exactly -0.3 every (round-off), whatever the renormalization interval."""
    a = math.exp(-0.3) * rotation(1.0)
    lyap = map_exponent(
        lambda x: a @ x, [0.3, -0.2], LyapunovSettings(every=every, renormalizations=50)
    )
    assert lyap.per_step == pytest.approx(-0.3, abs=1e-12)
    assert np.allclose(lyap.log_growth, -0.3 * every, rtol=0, atol=1e-12)
    assert np.allclose(lyap.running, -0.3, rtol=0, atol=1e-12)


def test_linear_map_converges_to_its_spectral_radius_every_3() -> None:
    """Eigenvalues exp(-0.1) and exp(-0.7) in a skewed basis: the separation turns into the
    slow direction during the discarded intervals, then each interval of 3 steps measures
    -0.3 up to exp(-1.8 k) of the fast one (k intervals in): -0.1 per step to 1e-12."""
    basis = np.array([[1.0, 0.8], [0.3, 1.0]])
    a = basis @ np.diag([math.exp(-0.1), math.exp(-0.7)]) @ np.linalg.inv(basis)
    lyap = map_exponent(
        lambda x: a @ x, [1.0, 1.0], LyapunovSettings(every=3, renormalizations=40, discard=20)
    )
    assert lyap.per_step == pytest.approx(-0.1, abs=1e-12)


def test_torus_rotation_exponent_is_zero_every_3() -> None:
    """Quasi-periodic: (x, y) -> (x + a, y + b) mod 1 with a, b, 1 rationally independent.
    Separations are carried unchanged: exponent 0 up to round-off (the separation d0 = 1e-8 sits
    on coordinates of size 1, so each step rounds it by ~1e-8 relative; the mean measured
    1.6e-9, bound 1e-7)."""
    a, b = (math.sqrt(5.0) - 1.0) / 2.0, math.sqrt(2.0) - 1.0

    def wrap(d: np.ndarray) -> np.ndarray:
        return (d + 0.5) % 1.0 - 0.5

    lyap = map_exponent(
        lambda x: (x + np.array([a, b])) % 1.0,
        [0.1, 0.7],
        LyapunovSettings(every=3, renormalizations=200),
        difference=lambda p, q: wrap(p - q),
    )
    assert abs(lyap.per_step) < 1e-7


def test_logistic_map_exponent_is_ln2_every_3() -> None:
    """Logistic map at r = 4 (exponent ln 2) renormalized every 3 iterations: d0 = 1e-10 grows
    by 8 on average per interval, still linear. Statistical error: the spread of ln(d/d0) per
    interval over 5000 intervals (stderr ~0.003); bound 0.02."""
    lyap = map_exponent(
        lambda x: 4.0 * x * (1.0 - x),
        0.3,
        LyapunovSettings(d0=1e-10, every=3, renormalizations=5000),
    )
    assert lyap.per_step == pytest.approx(math.log(2.0), abs=0.02)
    assert lyap.stderr < 0.01


E, RHO, L, N = 1.2e4, 1.0e-6, 10.0, 10  # FMU defaults (b = h = 1: rho A = 1e-6), 10 elements


@pytest.mark.parametrize("damping", [5e-4, 0.0])
def test_axial_vibration_exponent_is_minus_d_over_2_rho_a(
    fmu_paths: dict[str, object], damping: float
) -> None:
    from georod_tools.runner import FmuModel, FmuPair, Instance, Recorder

    theta, length = math.pi / N, L / N
    w2 = 6.0 * E / (RHO * length**2) * (1.0 - math.cos(theta)) / (2.0 + math.cos(theta))
    omega = math.sqrt(w2)  # the time unit: one period of the mode
    model = FmuModel.load(fmu_paths["BuckledBeam"])
    params = {
        "pre_shortening": 0.0,
        "F": 0.0,
        "Omega": omega,
        "elements": N,
        "dt_max": 1e-6,
        "d": damping,
    }
    n_per_period = 20  # communication steps of T/20, each 10 sub-steps of T/200
    ref = Instance(model, params, omega, n_per_period, name="reference")
    pert = Instance(model, params, omega, n_per_period, name="perturbed")
    try:
        pair = FmuPair(ref, pert, omega, Recorder(dense=False))
        direction = np.zeros(pair.mask.size)
        direction[0 : 3 * (N + 1) : 3] = np.sin(theta * np.arange(N + 1))  # u1, first axial mode
        settings = LyapunovSettings(d0=1e-6, every=3, renormalizations=20, discard=1)
        lyap = benettin(pair, settings, np.where(pair.mask, direction, 0.0), ref.period)
    finally:
        ref.close()
        pert.close()
    c = damping / RHO
    dt = ref.period / 200
    s = 0.5 * dt
    step_rate = math.log((1 + s * c + s * s * w2) / (1 - s * c + s * s * w2)) / (2 * dt)
    print(
        f"d = {damping}: exponent {lyap.per_second:.6f} 1/s, -d/(2 rho A) = {-c / 2}, "
        f"the midpoint map's own decay rate {-step_rate:.6f}"
    )
    if damping == 0.0:
        # The midpoint rule conserves the mode's energy norm, which the separation norm is
        # (Omega = omega_h): zero to round-off, measured 7e-8 1/s (1e-11 per period).
        assert abs(lyap.per_second) < 1e-5
        return
    # Two small departures from -c/2: the midpoint rule damps the mode at (c/2) / (1 + (omega
    # dt/2)^2) (2.5e-4 relative here) and the separation norm oscillates by ~c / omega within
    # a cycle of a damped mode, which averaged over 60 periods shifts the mean by ~1e-4;
    # measured 1.4e-4 in all. 1e-3 bounds both; a 20 % error in d is 200x that.
    assert lyap.per_second / (-0.5 * c) - 1.0 == pytest.approx(0.0, abs=1e-3)
