"""The largest Lyapunov exponent: the core's (tangent map of the midpoint rule, read through the
FMU) against exact values, and the two-instance cross-check (georod_tools.analysis.twin) against
exact values on maps and against the core on the paper's buckled beam.

Exact values:
- a linear map ``x -> A x`` separates nearby states by ``A`` itself: once the separation has
  turned into the leading eigendirection, every further segment grows by the leading eigenvalue,
  whatever part of the state is observed;
- a bar whose only free dof is the axial (or shear) displacement of its midpoint
  (python/tests/scenes/AxialBar.toml, ShearBar.toml) is one exact linear mode ``q'' + c q' +
  omega^2 q = 0``: the midpoint rule maps ``(q, q')`` by ``S = (I - s A)^-1 (I + s A)``, ``s =
  dt / 2``, whose determinant is ``(1 - s c + s^2 omega^2) / (1 + s c + s^2 omega^2)``. Its two
  exponents are both ``ln(det S) / (2 dt)`` (a complex pair), close to the continuous
  ``-c / 2 = -d / (2 rho A)``; their sum is exactly ``ln(det S) / dt`` (the growth of an area).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from georod_tools.analysis.twin import TwinSettings, restart_segments
from scene_fmus import package_scene

BEAM_FMU = Path(__file__).resolve().parents[2] / "target" / "fmu" / "BuckledBeam.fmu"


class LinearMapTwin:
    """The twin backend of a linear map: the separation itself evolves by `a`; the restart puts
    it at `d0` along `direction`; `observe` picks what the separation is measured in."""

    def __init__(self, a: np.ndarray, direction: np.ndarray, observe: np.ndarray) -> None:
        self.a, self.direction, self.observe = a, direction / np.linalg.norm(direction), observe
        self.delta = np.zeros(len(direction))
        self.restarts = 0

    def restart(self, d0: float) -> None:
        self.delta = d0 * self.direction
        self.restarts += 1

    def advance(self) -> None:
        self.delta = self.a @ self.delta

    def separation(self) -> float:
        return float(np.linalg.norm(self.observe @ self.delta))


def _estimate(backend: LinearMapTwin, periods: int, st: TwinSettings) -> float:
    segs = restart_segments(backend, periods, st)
    return sum(s.growth for s in segs) / sum(s.periods for s in segs)


@pytest.mark.parametrize("rate", [0.7, -0.1])
def test_twin_on_a_linear_map_measures_the_leading_eigenvalue(rate: float) -> None:
    """Eigenvalues exp(rate) and exp(rate - 0.6) in a skewed basis, only the first coordinate
    observed. After 5 aligning periods the slow direction is left at e^-3 of the fast one; it
    fades further within each counted segment, so the estimate is rate to within about
    e^-3 / 10 (measured 1e-3 for the growing map); bound 0.01. The growing map restarts whenever
    the separation passes restart_separation, the decaying one never restarts."""
    basis = np.array([[1.0, 0.8], [0.3, 1.0]])
    a = basis @ np.diag([math.exp(rate), math.exp(rate - 0.6)]) @ np.linalg.inv(basis)
    backend = LinearMapTwin(a, np.array([0.2, 1.0]), np.array([[1.0, 0.0]]))
    got = _estimate(backend, 400, TwinSettings())
    assert got == pytest.approx(rate, abs=0.01)
    assert backend.restarts > 1 if rate > 0 else backend.restarts == 1


def test_twin_on_a_contracting_rotation_is_exact() -> None:
    """exp(-0.3) R(1 rad) shrinks every vector by exactly exp(-0.3) per period: with the whole
    separation observed every segment measures -0.3 per period to round-off."""
    c, s = math.cos(1.0), math.sin(1.0)
    a = math.exp(-0.3) * np.array([[c, -s], [s, c]])
    got = _estimate(LinearMapTwin(a, np.array([0.3, -0.2]), np.eye(2)), 200, TwinSettings())
    assert got == pytest.approx(-0.3, abs=1e-12)


# ------------------------------------------------------------------ the core, exact linear case

E, NU, RHO, D, HALF = 1.2e4, 0.2, 1.0e-6, 5.0e-4, 5.0  # the bars' defaults, element length L/2


@pytest.fixture(scope="module")
def bars(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    out = Path(tmp_path_factory.mktemp("bars"))
    return {name: package_scene(name, out).path for name in ("AxialBar", "ShearBar")}


def midpoint_rate(omega2: float, c: float, dt: float) -> float:
    """ln|z| / dt of the midpoint map of q'' + c q' + omega2 q = 0 (half of ln det S / dt)."""
    s = 0.5 * dt
    return math.log((1 - s * c + s * s * omega2) / (1 + s * c + s * s * omega2)) / (2 * dt)


@pytest.mark.parametrize("damping", [D, 0.0])
@pytest.mark.parametrize("bar", ["AxialBar", "ShearBar"])
def test_core_exponents_of_one_linear_mode(bars: dict[str, Path], bar: str, damping: float) -> None:
    """Both exponents of the bar's single mode through the FMU (Omega = omega: the tangent norm
    is the mode's energy norm), 4000 sub-steps of omega dt = 0.076 or 0.049 after 100 aligning.

    The sum is the growth of an area, which the QR bookkeeping gets exactly: equal to 2 ln|z|/dt
    to round-off (measured 1e-13 relative; bound 1e-9). Each exponent alone follows its vector
    around the mode's ellipse, which with damping is not quite a circle in the energy norm (axes
    differ by ~c / omega = 0.013 or 0.02): the running mean wobbles by that over the averaging
    time, 0.02 / (4000 dt) ~ 5 1/s at most; bound 10 1/s, 4 % of d / (2 rho A) = 250 1/s. The
    midpoint rule's own rate is within 0.15 % of -d / (2 rho A) at these steps."""
    from georod_tools.fmu import FmuModel, lend

    model = FmuModel.load(bars[bar])
    g = E / (2 * (1 + NU))
    omega2 = 3 * (E if bar == "AxialBar" else g) / (RHO * HALF**2)
    omega = math.sqrt(omega2)
    dt = 2e-6
    exact = midpoint_rate(omega2, damping / RHO, dt)
    with lend(model, "bar") as inst:
        inst.initialize(
            {
                "d": damping,
                "Omega": omega,
                "F": 1.0,
                "dt_max": dt,
                "lyapunov_count": 2,
                "lyapunov_align": 100 * dt,
            }
        )
        for k in range(41):  # the load sets the mode going; the tangent map ignores it anyway
            inst.step(k * 100 * dt, 100 * dt)
        lam1, lam2, counted = inst.get(["lyapunov[1]", "lyapunov[2]", "lyapunov_time"])
    assert counted == pytest.approx(4000 * dt, rel=1e-9)
    print(f"{bar} d = {damping}: {lam1:.6f} + {lam2:.6f} 1/s; exact {exact:.6f} each")
    assert lam1 + lam2 == pytest.approx(2 * exact, rel=1e-9, abs=1e-9)
    assert lam1 == pytest.approx(exact, abs=10.0) and lam2 == pytest.approx(exact, abs=10.0)
    if damping:
        assert exact == pytest.approx(-0.5 * damping / RHO, rel=2e-3)


# ------------------------------------------------------------------ core against the twin


@pytest.mark.usefixtures("fmu_paths")
@pytest.mark.parametrize("F", [1.2, 2.0])
def test_core_exponent_agrees_with_the_two_instance_twin(F: float) -> None:
    """The paper's BuckledBeam at Omega = 3500 (10 elements, T/64 sub-steps, 50 transient + 400
    sampled periods): F = 1.2 chaotic, F = 2.0 a period-1 orbit. The twin's reference computes the
    core's exponent too, so both are compared over exactly the periods the twin counted. The
    chaotic window must be clearly chaotic, exponent > 0.2 per period (4x the chaos threshold):
    not tighter, because where the chaos is intermittent or transient, round-off decides how long
    the near-periodic phases last, and they lower the average (F = 1.0: 0.28 or 0.64 per period,
    F = 1.5: 0.22 or 0.58, under two solver variants that differ at round-off; F = 1.2: 0.75 and
    0.86).

    Chaotic: the twin's segments grow like the tangent vector up to the change of the observed
    fraction of the separation at their two ends, an O(1) term per segment of ~10 periods that
    averages out over ~30 segments; over F = 0.7..1.5 and two transients the two differed by at
    most 0.05 per period. Bound 0.1 (a sixth of the exponent; a time-unit or factor-2 error is far
    outside). Periodic: the leading exponents are a cluster near zero (the almost undamped
    rotations, -0.005..-0.001 per period); measured |twin - core| <= 0.005, bound 0.01 (a fifth
    of the chaos threshold). Both classify alike."""
    from georod_tools.analysis.case import CaseConfig, run_case
    from georod_tools.analysis.twin import run_twin

    cfg = CaseConfig(fmu=str(BEAM_FMU), F=F, substeps=64, transient_periods=50, sample_periods=400)
    twin = run_twin(cfg)
    core = run_case(cfg)
    assert np.array_equal(twin.result.samples, core.samples)  # the same trajectory
    assert twin.core is not None and twin.core.per_period == core.exponent_per_period
    t, c = twin.result.exponent_per_period, twin.core_on_segments
    whole = core.exponent_per_period
    print(f"F = {F}: twin {t:.4f}, core on the same periods {c:.4f}, core {whole:.4f}")
    if F == 1.2:
        assert c > 0.2 and abs(t - c) < 0.1
        assert core.classification.kind == twin.result.classification.kind == "chaotic"
    else:
        assert abs(c) < 0.05 and abs(t - c) < 0.01
        assert core.classification.label == twin.result.classification.label == "period-1"
