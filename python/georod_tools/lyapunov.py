"""Largest Lyapunov exponent by Benettin's two-trajectory method.

The algorithm is written once, against the small :class:`PairBackend` protocol (advance a
reference and a perturbed trajectory, read and reset their separation). Two backends exist:

- :class:`MapPair` here: a pure-Python map ``x_{n+1} = f(x_n)`` (unit tests, e.g. the logistic
  map at ``r = 4`` whose exponent is ``ln 2``);
- :class:`georod_tools.runner.FmuPair`: two FMU instances of the rod; the perturbed one is reset
  by writing a serialized FMU state with patched displacement and velocity vectors.

Why two nearby trajectories rather than a tangent (variational) equation: the FMU exposes no
Jacobian of its period map, but it exposes its state, so a finite but tiny separation ``d0``,
renormalized back to ``d0`` every ``m`` periods before nonlinearity sets in, measures the same
exponent (Benettin et al. 1980). One map iteration or one forcing period is the time unit; the FMU
backend converts to 1/s with the period ``T = 2 pi / Omega``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

FloatArray = np.ndarray


class PairBackend(Protocol):
    """A reference trajectory and a perturbed one, advanced together.

    ``separation`` is perturbed minus reference in the coordinates in which the Euclidean norm is
    taken (the backend chooses its scaling; any norm gives the same exponent in the limit).
    """

    def advance(self, steps: int) -> None:
        """Advances both trajectories by `steps` time units (map iterations, forcing periods)."""
        ...

    def separation(self) -> FloatArray:
        """The current separation vector (perturbed - reference)."""
        ...

    def set_separation(self, delta: FloatArray) -> None:
        """Puts the perturbed trajectory at reference + `delta`."""
        ...


@dataclass(frozen=True)
class LyapunovSettings:
    """Parameters of the Benettin algorithm.

    d0: separation norm after each renormalization (small enough to stay linear over `every`
        steps, large enough to stay far above round-off and solver tolerance).
    every: renormalize every `every` time units (``m``).
    renormalizations: how many renormalizations are averaged.
    discard: renormalizations run first and not averaged, so that the separation has turned into
        the most unstable direction before it is measured.
    seed: seed of the initial direction (deterministic results).
    """

    d0: float = 1e-8
    every: int = 1
    renormalizations: int = 200
    discard: int = 10
    seed: int = 12345

    def __post_init__(self) -> None:
        if not (self.d0 > 0.0 and math.isfinite(self.d0)):
            raise ValueError(f"d0 = {self.d0} must be finite and > 0")
        if self.every < 1:
            raise ValueError(f"every = {self.every} must be >= 1")
        if self.renormalizations < 1:
            raise ValueError(f"renormalizations = {self.renormalizations} must be >= 1")
        if self.discard < 0:
            raise ValueError(f"discard = {self.discard} must be >= 0")


@dataclass
class LyapunovResult:
    """The exponent per time unit of the backend (per map iteration or per forcing period).

    log_growth: ``ln(d / d0)`` of each averaged renormalization interval.
    running: running mean per time unit after each averaged interval (convergence check).
    stderr: standard error of the mean per time unit, from the spread of `log_growth` (treats the
        intervals as independent; a rough but honest error bar).
    period: length of one time unit in seconds when known (forcing period ``T``), else None.
    """

    per_step: float
    stderr: float
    log_growth: FloatArray = field(repr=False)
    running: FloatArray = field(repr=False)
    every: int = 1
    period: float | None = None

    @property
    def per_period(self) -> float:
        """Exponent per forcing period (same as `per_step` for the FMU backend)."""
        return self.per_step

    @property
    def per_second(self) -> float:
        """Exponent in 1/s (``per_period / T``); NaN when the period is unknown."""
        return self.per_step / self.period if self.period else math.nan


def initial_direction(n: int, seed: int, mask: FloatArray | None = None) -> FloatArray:
    """A deterministic unit vector of length `n` (zero where `mask` is False)."""
    rng = np.random.default_rng(seed)
    v = rng.standard_normal(n)
    if mask is not None:
        v = np.where(mask, v, 0.0)
    norm = float(np.linalg.norm(v))
    if norm == 0.0:
        raise ValueError("no free coordinate to perturb")
    return v / norm


def benettin(
    pair: PairBackend,
    settings: LyapunovSettings,
    direction: FloatArray,
    period: float | None = None,
    on_interval: Callable[[int], None] | None = None,
) -> LyapunovResult:
    """Largest Lyapunov exponent of `pair` (Benettin's algorithm).

    Starts the perturbed trajectory at reference + ``d0 * direction`` (`direction` is normalized
    here), then repeats: advance ``every`` steps, measure ``d = |separation|``, add ``ln(d/d0)``,
    rescale the separation back to ``d0``. The first ``discard`` intervals are not averaged.
    `on_interval(i)` is called after each interval (e.g. to record samples or show progress).
    """
    s = settings
    direction = np.asarray(direction, dtype=float)
    norm = float(np.linalg.norm(direction))
    if not (norm > 0.0 and math.isfinite(norm)):
        raise ValueError("the initial direction must be finite and nonzero")
    pair.set_separation(direction * (s.d0 / norm))
    logs: list[float] = []
    for i in range(s.discard + s.renormalizations):
        pair.advance(s.every)
        delta = pair.separation()
        d = float(np.linalg.norm(delta))
        if not (d > 0.0 and math.isfinite(d)):
            raise FloatingPointError(
                f"separation became {d} after interval {i}: d0 = {s.d0} too small (collapsed onto "
                "the reference) or the perturbed trajectory diverged"
            )
        if i >= s.discard:
            logs.append(math.log(d / s.d0))
        pair.set_separation(delta * (s.d0 / d))
        if on_interval is not None:
            on_interval(i)
    growth = np.asarray(logs)
    running = np.cumsum(growth) / (s.every * np.arange(1, growth.size + 1))
    per_step = float(growth.mean()) / s.every
    stderr = (
        float(growth.std(ddof=1)) / math.sqrt(growth.size) / s.every
        if growth.size > 1
        else math.inf
    )
    return LyapunovResult(per_step, stderr, growth, running, s.every, period)


class MapPair:
    """Reference and perturbed orbits of a map ``x_{n+1} = f(x_n)`` (a :class:`PairBackend`).

    `difference(a, b)` gives ``a - b`` (override for angles on a circle, e.g. ``(a - b + 0.5) % 1
    - 0.5``).
    """

    def __init__(
        self,
        f: Callable[[FloatArray], FloatArray],
        x0: FloatArray | float,
        difference: Callable[[FloatArray, FloatArray], FloatArray] | None = None,
    ) -> None:
        self.f = f
        self.x = np.atleast_1d(np.asarray(x0, dtype=float)).copy()
        self.y = self.x.copy()
        self.difference = difference or (lambda a, b: a - b)

    def advance(self, steps: int) -> None:
        for _ in range(steps):
            self.x = np.atleast_1d(np.asarray(self.f(self.x), dtype=float))
            self.y = np.atleast_1d(np.asarray(self.f(self.y), dtype=float))

    def separation(self) -> FloatArray:
        return np.asarray(self.difference(self.y, self.x), dtype=float)

    def set_separation(self, delta: FloatArray) -> None:
        self.y = self.x + delta


def map_exponent(
    f: Callable[[FloatArray], FloatArray],
    x0: FloatArray | float,
    settings: LyapunovSettings | None = None,
    transient: int = 100,
    difference: Callable[[FloatArray, FloatArray], FloatArray] | None = None,
) -> LyapunovResult:
    """Largest Lyapunov exponent (per iteration) of the map `f` from `x0`, after `transient`
    iterations of the reference orbit."""
    settings = settings or LyapunovSettings()
    pair = MapPair(f, x0, difference)
    for _ in range(transient):
        pair.x = np.atleast_1d(np.asarray(f(pair.x), dtype=float))
    pair.y = pair.x.copy()
    return benettin(pair, settings, initial_direction(pair.x.size, settings.seed))
