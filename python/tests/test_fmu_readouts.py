"""What a scene reads out, through FMUs packaged from scene files: section forces, strains and
fiber stresses of a cantilever under a tip load, the natural frequencies of its initial state,
and the accelerations along a free rod under a harmonic load.

`python/tests/scenes/ReadoutCantilever.toml`: a steel cantilever `L = 2`, `b = 0.04`,
`h = 0.02` (`EI = 5333 N m2`), 20 elements, dead tip load `P = 20 N` along -e2 (`P L^2 / EI =
0.015`). In its static initial state:

- the bending moment at every node (`shape_M[i]`, one sample per node) is `-P (x_tip - x)`, the
  load times the deformed lever arm, exactly (the nodal balance of the elements' forces); at the
  root the section forces are minus the root's reaction (`M_root = -root_M`, `N_root = -root_Rx`,
  `Q_root = -root_Ry`; the root's section frame is e1, e2); both to the static solver's tolerance
  (1e-10 of the increment, asserted at 1e-8 of `P L`);
- the strains are the resultants over `EA`, `GA` (`G = E / (2 (1 + nu))`) and `EI`, the fiber
  stresses `N/A -+ M h/(2 I)` (round-off);
- `frequency[1..3]` with `P = 0`: the Euler-Bernoulli cantilever `(beta L)^2 / (2 pi L^2)
  sqrt(EI / (rho A))`, `beta L = 1.8751, 4.6941, 7.8548`; the mesh error is second order,
  `1.2 (beta L / (pi n))^2` (tests/suite/readouts_frequencies.rs): 1e-3, 7e-3 and 2e-2 on 20
  elements, shear and rotary inertia `(h/L)^2 (beta L)^2 / 10`, below 6e-4: asserted at twice the
  sum.

`python/tests/scenes/ReadoutFreeRod.toml`: a free rod under `F cos(Omega t)` along e2. With the
consistent mass, the rod's momentum change is `rho A` times the integral of the interpolated
acceleration (the trapezoidal rule over the node samples `shape_a2[i]`, exact for the linear
interpolation), and the internal forces sum to zero: the mean acceleration is
`F cos(Omega (t - dt/2)) / (rho A L)`, the midpoint rule's load at the last sub-step's middle,
to the solver's tolerance (asserted at 1e-9 of `F / (rho A L)`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from helpers import FmuInfo, get_reals, instantiate, release, run_steps
from scene_fmus import package_scene

E, NU, RHO, B, H, L, P = 2.0e11, 0.3, 7850.0, 0.04, 0.02, 2.0, 20.0
AREA, INERTIA = B * H, B * H**3 / 12.0
NODES = 21


@pytest.fixture(scope="module")
def cantilever(tmp_path_factory: pytest.TempPathFactory) -> FmuInfo:
    return package_scene("ReadoutCantilever", Path(tmp_path_factory.mktemp("readouts")))


@pytest.fixture(scope="module")
def free_rod(tmp_path_factory: pytest.TempPathFactory) -> FmuInfo:
    return package_scene("ReadoutFreeRod", Path(tmp_path_factory.mktemp("readouts_free")))


def read(info: FmuInfo, params: dict[str, float], names: list[str]) -> dict[str, float]:
    slave = instantiate(info, params)
    try:
        return dict(zip(names, get_reals(slave, info, names), strict=True))
    finally:
        release(slave)


def test_moment_is_the_load_times_the_lever_arm_and_the_root_reads_the_reaction(
    cantilever: FmuInfo,
) -> None:
    shape = [f"shape_{q}[{i}]" for q in ("x", "M") for i in range(1, NODES + 1)]
    root = ["M_root", "N_root", "Q_root", "root_M", "root_Rx", "root_Ry"]
    v = read(cantilever, {"P": P}, shape + root)
    x_tip = v[f"shape_x[{NODES}]"]
    worst = max(
        abs(v[f"shape_M[{i}]"] + P * (x_tip - v[f"shape_x[{i}]"])) for i in range(1, NODES + 1)
    )
    print(f"\nReadoutCantilever: max |M + P (x_tip - x)| / (P L) = {worst / (P * L):.2e}")
    assert worst < 1e-8 * P * L
    for section, reaction in (("M_root", "root_M"), ("N_root", "root_Rx"), ("Q_root", "root_Ry")):
        assert abs(v[section] + v[reaction]) < 1e-8 * P * L, (section, v[section], v[reaction])
    assert v["M_root"] == pytest.approx(-P * L, rel=1e-3)  # small deflection: nearly P L


def test_strains_and_stresses_follow_from_the_resultants(cantilever: FmuInfo) -> None:
    names = ["M_root", "N_root", "Q_root", "kappa_root", "eps_root", "gamma_root"]
    names += ["stress_top", "stress_bottom"]
    v = read(cantilever, {"P": P}, names)
    g = E / (2.0 * (1.0 + NU))
    assert v["kappa_root"] * E * INERTIA == pytest.approx(v["M_root"], rel=1e-12)
    assert v["eps_root"] * E * AREA == pytest.approx(v["N_root"], rel=1e-12, abs=1e-12)
    assert v["gamma_root"] * g * AREA == pytest.approx(v["Q_root"], rel=1e-12)
    bending = v["M_root"] * H / (2.0 * INERTIA)
    axial = v["N_root"] / AREA
    assert v["stress_top"] == pytest.approx(axial - bending, rel=1e-12)
    assert v["stress_bottom"] == pytest.approx(axial + bending, rel=1e-12)
    # Hogging at the root: the top fiber in tension, P L h / (2 I) = 150 MPa.
    assert v["stress_top"] == pytest.approx(P * L * H / (2.0 * INERTIA), rel=1e-3)


def test_frequencies_of_the_initial_state(cantilever: FmuInfo) -> None:
    names = [f"frequency[{k}]" for k in (1, 2, 3)]
    slave = instantiate(cantilever, {"P": 0.0})
    try:
        at_start = get_reals(slave, cantilever, names)
        run_steps(slave, cantilever, 1e-4, 3, names=names)
        after = get_reals(slave, cantilever, names)
    finally:
        release(slave)
    assert after == at_start, "computed once, at fmi2ExitInitializationMode"
    root = math.sqrt(E * INERTIA / (RHO * AREA)) / (2.0 * math.pi * L**2)
    for f, beta in zip(at_start, (1.87510407, 4.69409113, 7.85475744), strict=True):
        exact = beta**2 * root
        mesh = 1.2 * (beta / (math.pi * 20)) ** 2
        shear = (H / L) ** 2 * beta**2 / 10.0
        print(f"frequency {f:.6f} Hz, Euler-Bernoulli {exact:.6f} Hz, rel. {f / exact - 1:.2e}")
        assert abs(f / exact - 1.0) < 2.0 * (mesh + shear)


def test_free_rod_mean_acceleration_is_the_load_over_the_mass(free_rod: FmuInfo) -> None:
    force, omega, mass, dt, h = 3.0, 20.0, 2.0 * 0.1 * 10.0, 1e-4, 1e-3
    names = [f"shape_a2[{i}]" for i in range(1, 12)]
    slave = instantiate(free_rod)
    try:
        rows = run_steps(slave, free_rod, h, 100, names=names)
    finally:
        release(slave)
    mean = (rows.sum(axis=1) - 0.5 * (rows[:, 0] + rows[:, -1])) / 10.0
    t = np.arange(101) * h
    expected = force / mass * np.cos(omega * (t - 0.5 * dt))
    expected[0] = 0.0  # before the first step: no sub-step taken, at rest
    error = np.max(np.abs(mean - expected)) / (force / mass)
    print(f"\nReadoutFreeRod: max |a_mean - F cos(Omega (t - dt/2)) / m| / (F / m) = {error:.2e}")
    assert error < 1e-9
