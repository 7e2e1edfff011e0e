"""The two-trajectory estimate of georod_tools.analysis.twin on maps ``x_{n+1} = f(x_n)``: the
estimator the FMU cross-check uses (restart along a fixed direction, count aligned segments),
with one map iteration as the period. The classifier's tests take their exponents from it."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from georod_tools.analysis.lyapunov import LyapunovResult
from georod_tools.analysis.twin import TwinSettings, estimate, restart_segments

Map = Callable[[np.ndarray], np.ndarray]
Difference = Callable[[np.ndarray, np.ndarray], np.ndarray]


class MapTwin:
    """A reference orbit and a twin of the map `f`; `difference(a, b)` is ``a - b`` (override
    for angles on a circle)."""

    def __init__(self, f: Map, x0: np.ndarray, difference: Difference | None = None) -> None:
        self.f = f
        self.x = np.atleast_1d(np.asarray(x0, dtype=float))
        self.y = self.x.copy()
        self.difference = difference or (lambda a, b: a - b)
        rng = np.random.default_rng(12345)
        d = rng.standard_normal(self.x.size)
        self.direction = d / np.linalg.norm(d)

    def advance(self) -> None:
        self.x = np.atleast_1d(np.asarray(self.f(self.x), dtype=float))
        self.y = np.atleast_1d(np.asarray(self.f(self.y), dtype=float))

    def restart(self, d0: float) -> None:
        self.y = self.x + d0 * self.direction

    def separation(self) -> float:
        return float(np.linalg.norm(self.difference(self.y, self.x)))


def map_exponent(
    f: Map,
    x0: np.ndarray | float,
    iterations: int,
    difference: Difference | None = None,
    transient: int = 100,
    settings: TwinSettings | None = None,
) -> LyapunovResult:
    """The largest exponent per iteration of `f` from `x0` after `transient` iterations (d0 =
    1e-9: far above the rounding of coordinates of size 1)."""
    twin = MapTwin(f, np.asarray(x0, dtype=float), difference)
    for _ in range(transient):
        twin.x = np.atleast_1d(np.asarray(f(twin.x), dtype=float))
    st = settings or TwinSettings(d0=1e-9, max_separation=1e-3, restart_separation=1e-6)
    return estimate(restart_segments(twin, iterations, st), 1.0)
