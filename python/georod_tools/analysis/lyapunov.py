"""The largest Lyapunov exponent of a case, as the analyses report it (:class:`LyapunovResult`),
from the core's running estimate or from the two-instance cross-check
(:mod:`georod_tools.analysis.twin`).

The core advances a tangent vector with the exact tangent map of every midpoint sub-step and
renormalizes it after each sub-step (FMU outputs ``lyapunov[1]`` in 1/s, ``lyapunov_per_period[1]``
and ``lyapunov_time``, the time averaged over). Its accumulated growth is ``G(t) =
lyapunov[1] * lyapunov_time``; read once per forcing period, the differences of G are the growth
of each period, whose spread gives the error bar.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

FloatArray = np.ndarray

#: How the exponent was obtained.
TANGENT, TWIN = "tangent", "twin"


@dataclass
class LyapunovResult:
    """The largest exponent, per forcing period and per second.

    stderr: standard error of the mean per period, from the spread of `log_growth` (treats the
        intervals as independent; a rough but honest error bar, inf with a single interval).
    log_growth: ``ln`` of the growth of each averaged interval (one forcing period for the core's
        exponent, one restart segment for the twin).
    interval_periods: the length of each interval in forcing periods.
    method: :data:`TANGENT` (the core) or :data:`TWIN` (the cross-check).
    """

    per_period: float
    per_second: float
    stderr: float
    log_growth: FloatArray = field(repr=False)
    interval_periods: FloatArray = field(repr=False)
    method: str = TANGENT

    @property
    def periods(self) -> float:
        """Forcing periods averaged over."""
        return float(np.sum(self.interval_periods))

    @property
    def running(self) -> FloatArray:
        """Running mean per period after each interval (a convergence check)."""
        return np.cumsum(self.log_growth) / np.cumsum(self.interval_periods)


def interval_stderr(log_growth: FloatArray, periods: FloatArray) -> float:
    """Standard error of the mean growth per period from intervals of `periods` periods each
    (their rates weighted by length)."""
    g, n = np.asarray(log_growth, float), np.asarray(periods, float)
    if g.size < 2:
        return math.inf
    rates = g / n
    mean = g.sum() / n.sum()
    var = float(np.sum(n * (rates - mean) ** 2) / n.sum()) * g.size / (g.size - 1)
    return math.sqrt(var / g.size)


def from_core(
    growth: FloatArray, counted_time: FloatArray, per_period: float, period: float
) -> LyapunovResult:
    """The core's exponent from `growth` (``G``) and ``lyapunov_time`` read at the end of each
    sampled period, and the final ``lyapunov_per_period[1]``; periods in which the tangent
    vector only aligned (no counted time) are left out."""
    g = np.diff(np.concatenate([[0.0], np.asarray(growth, float)]))
    n = np.diff(np.concatenate([[0.0], np.asarray(counted_time, float)])) / period
    counted = n > 0.5  # a whole period counted (the core counts sub-steps, never parts of one)
    return LyapunovResult(
        per_period=float(per_period),
        per_second=float(per_period) / period,
        stderr=interval_stderr(g[counted], n[counted]),
        log_growth=g[counted],
        interval_periods=n[counted],
        method=TANGENT,
    )
