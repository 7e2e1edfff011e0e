"""The classifier and the Lyapunov algorithm on signals with known answers (no FMU needed)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from georod_tools.analysis.classify import (
    CHAOTIC,
    PERIODIC,
    QUASI_PERIODIC,
    UNRESOLVED,
    ClassifySettings,
    classify,
    correlation_dimension,
    detect_period,
    period_mismatch,
)
from map_twin import map_exponent

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0  # an irrational rotation number, badly approximable


def circle_map(omega: float, k: float = 0.0):  # noqa: ANN201
    """theta -> theta + omega - k / (2 pi) sin(2 pi theta) (mod 1)."""
    return lambda th: (th + omega - k / (2 * math.pi) * np.sin(2 * math.pi * th)) % 1.0


def circle_difference(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a - b on the circle of circumference 1."""
    return (a - b + 0.5) % 1.0 - 0.5


def ring(theta: np.ndarray) -> np.ndarray:
    """A closed, non-circular curve in a (w, v)-like plane with very different axis scales."""
    return np.c_[
        0.4 * np.cos(2 * np.pi * theta) * (1 + 0.3 * np.cos(4 * np.pi * theta)),
        600.0 * np.sin(2 * np.pi * theta),
    ]


def logistic(x: np.ndarray) -> np.ndarray:
    return 4.0 * x * (1.0 - x)


def test_period_three_sequence() -> None:
    rng = np.random.default_rng(1)
    base = np.array([[0.1, 100.0], [0.5, -300.0], [-0.4, 250.0]])
    x = np.tile(base, (30, 1))
    x += 1e-6 * np.ptp(base, axis=0) * rng.standard_normal(x.shape)  # residue far below tol
    assert detect_period(x) == 3  # smallest period: 6, 9, ... also repeat
    c = classify(x, exponent=-0.01)
    assert (c.kind, c.period, c.label) == (PERIODIC, 3, "period-3")
    assert c.mismatch[0] > 0.5 and c.mismatch[2] < 1e-3


def test_period_one_needs_the_attractor_size() -> None:
    """A period-1 orbit samples one point: the tolerance is relative to the size of the orbit
    (the continuous trajectory's range), not to the samples' own spread."""
    x = np.array([0.3, -12.0]) + 1e-9 * np.random.default_rng(2).standard_normal((50, 2))
    assert detect_period(x, size=np.array([0.2, 500.0])) == 1
    assert detect_period(np.zeros((10, 2))) == 1  # not moving at all


def test_period_needs_two_repeats() -> None:
    x = np.tile([[0.0], [1.0], [2.0], [3.0], [4.0]], (2, 1))  # period 5, only 10 samples
    assert np.isnan(period_mismatch(x, 8)[4])
    assert detect_period(x, k_max=8) is None


def test_circle_map_rotation_is_quasi_periodic() -> None:
    """Circle map with K = 0 and an irrational rotation: exponent exactly 0, samples on a ring."""
    f = circle_map(GOLDEN)
    lyap = map_exponent(f, 0.1, 500, difference=circle_difference)
    assert abs(lyap.per_period) < 1e-6
    theta = (0.1 + GOLDEN * np.arange(300)) % 1.0
    x = ring(theta)
    assert 0.9 < correlation_dimension(x) < 1.15
    c = classify(x, lyap.per_period)
    assert c.kind == QUASI_PERIODIC, c.note
    assert c.period is None and np.nanmin(c.mismatch) > 1e-3


def test_logistic_map_exponent_is_ln2() -> None:
    """r = 4: lambda = ln 2. 20000 iterations give a standard error ~0.01; the tolerance 0.04 is
    ~4 standard errors."""
    lyap = map_exponent(logistic, 0.3, 20000)
    assert abs(lyap.per_period - math.log(2.0)) < 0.04
    assert lyap.stderr < 0.01
    xs = [0.3]
    for _ in range(499):
        xs.append(float(logistic(np.array(xs[-1]))))
    c = classify(np.array(xs), lyap.per_period)
    assert c.kind == CHAOTIC


def test_henon_exponent() -> None:
    """Henon map (a = 1.4, b = 0.3): largest exponent 0.419 (literature), here within 0.02."""

    def henon(x: np.ndarray) -> np.ndarray:
        return np.array([1.0 - 1.4 * x[0] ** 2 + x[1], 0.3 * x[0]])

    lyap = map_exponent(henon, [0.1, 0.1], 10000)
    assert abs(lyap.per_period - 0.419) < 0.02


def test_area_filling_samples_are_unresolved() -> None:
    """Exponent ~0 but the samples cover an area (dimension ~2): neither a ring nor a period."""
    x = np.random.default_rng(3).random((300, 2))
    assert correlation_dimension(x) > 1.6
    assert classify(x, 0.0).kind == UNRESOLVED


def test_threshold_not_sign() -> None:
    """A small positive exponent (almost undamped modes, estimator noise) is not chaos."""
    theta = (0.1 + GOLDEN * np.arange(300)) % 1.0
    st = ClassifySettings()
    assert classify(ring(theta), 0.5 * st.chaos_threshold).kind == QUASI_PERIODIC
    assert classify(ring(theta), 2.0 * st.chaos_threshold).kind == CHAOTIC


@pytest.mark.parametrize(
    "kwargs", [{"k_max": 0}, {"period_tol": 0.0}, {"period_tol": 1.5}, {"chaos_threshold": 0.0}]
)
def test_settings_are_checked(kwargs: dict[str, float]) -> None:
    with pytest.raises(ValueError):
        ClassifySettings(**kwargs)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    "kwargs", [{"d0": 0.0}, {"d0": 1e-2}, {"max_separation": math.inf}, {"align_periods": 0}]
)
def test_twin_settings_are_checked(kwargs: dict[str, float]) -> None:
    from georod_tools.analysis.twin import TwinSettings

    with pytest.raises(ValueError):
        TwinSettings(**kwargs)  # type: ignore[arg-type]


def test_bad_samples_are_refused() -> None:
    with pytest.raises(ValueError, match="non-finite"):
        classify(np.array([[0.0, np.nan]] * 5), 0.0)


def test_no_exponent_decides_only_periods() -> None:
    """Without an exponent a ring is not enough: chaotic sections can measure dimension ~1."""
    theta = (0.1 + GOLDEN * np.arange(300)) % 1.0
    c = classify(ring(theta), None)
    assert c.kind == UNRESOLVED and "no Lyapunov exponent" in c.note
    assert classify(np.tile([[0.0, 1.0], [1.0, 0.0]], (10, 1)), None).label == "period-2"


@pytest.mark.parametrize("where", [0, 40, 89])
def test_one_sample_off_breaks_the_period(where: int) -> None:
    """A period-3 orbit whose samples repeat to 1e-6 except one (first, middle or last), which
    is off by 5 tolerances in one coordinate: every sample must repeat, so it is not period-3
    (nor period-6, 9, ...: the sample has no partner anywhere), while the same sample off by
    half a tolerance still is. Guards the test against a mean, median or sub-range of the
    differences, which one sample does not move past the tolerance."""
    rng = np.random.default_rng(4)
    base = np.array([[0.1, 100.0], [0.5, -300.0], [-0.4, 250.0]])
    size = np.ptp(base, axis=0)
    x = np.tile(base, (30, 1)) + 1e-6 * size * rng.standard_normal((90, 2))
    st = ClassifySettings()
    for factor, periodic in [(5.0, False), (0.5, True)]:
        y = x.copy()
        y[where, 1] += factor * st.period_tol * size[1]
        mismatch = period_mismatch(y, st.k_max)
        # one sample off by a in a set of size ~size: the difference to its partners is ~a
        assert mismatch[2] == pytest.approx(factor * st.period_tol, rel=0.05)
        c = classify(y, exponent=-0.01)
        if periodic:
            assert c.label == "period-3", c.note
        else:
            assert c.kind != PERIODIC, c.note
            assert detect_period(y) is None
