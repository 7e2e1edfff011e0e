"""The two-instance cross-check of the largest Lyapunov exponent: a twin trajectory restarted
along a fixed direction, measured through outputs. Kept to check the core's exponent
(:mod:`georod_tools.analysis.case`) and to compare costs; the analyses use the core's.

The estimator (restart along a fixed direction, finite time). A reference instance A runs the
case. At the start of a segment the twin B is put in A's state (fmi2SerializeFMUstate /
fmi2DeSerializeFMUstate: an opaque blob, never read) and kicked by `d0` along the FMU's fixed
seeded direction (a change of the ``perturbation`` parameter). Both advance period by period; the
separation is measured in outputs only: the shape samples ``shape_x[i]``, ``shape_y[i]``,
``w_mid`` and ``v_mid / Omega`` (metres). After `align_periods` the separation has turned into the
most unstable direction, and its size ``s0`` is noted; the segment ends when the separation
exceeds `max_separation` (still in the linear regime) or the run ends, and contributes ``ln(s /
s0)`` over its length. Then B restarts from A. The exponent is the summed growth over the summed
counted periods.

Expected accuracy. On a chaotic attractor the growth of a segment is that of the tangent vector
over the same periods, up to the change of the observed fraction of the separation between its
two ends (shape samples see displacements, not rotations or most velocities): an O(1) term per
segment, so ~1/L per period for segments of L periods, averaging out over many segments. Measured
on the BuckledBeam (F = 1.5, Omega = 3500, T/64): within 3 % of the core's growth over the same
periods (20 segments). On a periodic orbit the leading exponents form a cluster near zero (the
almost undamped rotations; four of them within -0.005..-0.001 per period): the twin's separation
is a mixture within the cluster, weighted by how visible each direction is in the outputs, so the
twin measures an exponent near zero, not the core's particular member (measured -0.012 against
-0.0035 per period at F = 2.0). The periods spent aligning after each restart are not counted,
so on chaotic motion the twin averages over fewer periods than the core (a finite-time estimate
over a subset of the trajectory).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Protocol

import numpy as np

from georod_tools.analysis.case import (
    OUTPUTS,
    CaseConfig,
    CaseResult,
    Trajectory,
    through_transient,
)
from georod_tools.analysis.classify import classify
from georod_tools.analysis.lyapunov import TWIN, LyapunovResult, from_core, interval_stderr
from georod_tools.fmu import FmuModel, Instance, lend


@dataclass(frozen=True)
class TwinSettings:
    """d0: the kick in the state norm ``|(u, v / Omega)|`` (m): far above the solver's noise
        (~1e-13 absolute per period), far below the motion (~0.1-1 m).
    max_separation: observed separation (m) that ends a segment: 1e-4 of an attractor of ~1 m
        is still linear (the growth's relative error is about that fraction).
    align_periods: periods after each restart that are not counted (>= 1; the kick takes effect
        in the first step after the restart)."""

    d0: float = 1e-11
    max_separation: float = 1e-3
    restart_separation: float = 1e-7
    align_periods: int = 5
    segment_periods: int = 10

    def __post_init__(self) -> None:
        if not (0 < self.d0 < self.max_separation and math.isfinite(self.max_separation)):
            raise ValueError(f"need 0 < d0 ({self.d0}) < max_separation ({self.max_separation})")
        if self.align_periods < 1:
            raise ValueError(f"align_periods = {self.align_periods} must be >= 1")


class TwinBackend(Protocol):
    """A reference trajectory and a twin, advanced one period at a time."""

    def advance(self) -> None:
        """Both trajectories one forcing period further."""
        ...

    def restart(self, d0: float) -> None:
        """The twin in the reference's state, kicked by `d0` along the fixed direction (the kick
        acts in the next period)."""
        ...

    def separation(self) -> float:
        """The observed separation of the twin from the reference."""
        ...


@dataclass(frozen=True)
class Segment:
    """A counted stretch: the period index after the alignment, its length and ``ln(s / s0)``."""

    start: int
    periods: int
    growth: float


def restart_segments(backend: TwinBackend, periods: int, st: TwinSettings) -> list[Segment]:
    """Runs `periods` periods of `backend` in counted segments of `segment_periods`; the twin is
    restarted (and aligns again, uncounted) after a segment whose separation grew past
    `restart_separation`, else the next segment goes on from where this one ended."""
    out: list[Segment] = []
    k, restart = 0, True
    s = math.nan
    while k < periods:
        if restart:
            backend.restart(st.d0)
            for _ in range(min(st.align_periods, periods - k)):
                backend.advance()
                k += 1
            if k == periods:
                break
            s = backend.separation()
        s0, start = s, k
        for _ in range(min(st.segment_periods, periods - k)):
            backend.advance()
            k += 1
            s = backend.separation()
            if not (s > 0 and math.isfinite(s)):
                raise FloatingPointError(f"twin separation {s} after period {k}")
            if s > st.max_separation:
                break  # beyond the linear regime: end early (rare with these settings)
        out.append(Segment(start, k - start, math.log(s / s0)))
        restart = s > st.restart_separation
    return out


def estimate(segments: list[Segment], period: float) -> LyapunovResult:
    """The twin's exponent: summed growth over summed counted periods."""
    g = np.array([s.growth for s in segments])
    n = np.array([float(s.periods) for s in segments])
    if n.sum() == 0:
        raise ValueError("no segment was counted: more periods than align_periods are needed")
    per_period = float(g.sum() / n.sum())
    return LyapunovResult(per_period, per_period / period, interval_stderr(g, n), g, n, method=TWIN)


def observed(model: FmuModel) -> list[str]:
    """The outputs the separation is measured in: the shape samples, then w_mid and v_mid."""
    shape = [n for n in model.outputs if n.startswith(("shape_x[", "shape_y["))]
    return [*shape, *OUTPUTS]


class FmuTwin:
    """The reference A and the twin B of one case, both one step per period; A records the
    samples (and the dense window in ``T / m`` steps) as :func:`run_case` does."""

    def __init__(self, a: Instance, b: Instance, cfg: CaseConfig, first: int, dense_from: int):
        self.a, self.b, self.cfg = a, b, cfg
        self.k, self.dense_from = first, dense_from
        names = observed(a.model)
        self.obs_a, self.obs_b = a.reader(names), b.reader(names)
        self.scale = np.ones(len(names))
        self.scale[-1] = 1.0 / cfg.Omega  # v_mid / Omega: metres like the rest
        extra = ("lyapunov[1]", "lyapunov_time") if cfg.lyapunov else ()
        self.read_a = a.reader(OUTPUTS + extra)
        self.rec = Trajectory()

    def advance(self) -> None:
        T, m, k = self.cfg.period, self.cfg.dense_steps_per_period, self.k
        if k >= self.dense_from:
            if not self.rec.dense:
                w, v = self.read_a()[:2]
                self.rec.dense.append((k * T, w, v))
            for j in range(m):
                self.a.step(k * T + j * (T / m), T / m)
                w, v = self.read_a()[:2]
                self.rec.dense.append((k * T + (j + 1) * (T / m), w, v))
        else:
            self.a.step(k * T, T)
        self.b.step(k * T, T)
        self.k += 1
        got = self.read_a()
        self.rec.samples.append((self.k * T, got[0], got[1]))
        if self.cfg.lyapunov:
            self.rec.growth.append(got[2] * got[3])
            self.rec.counted.append(got[3])

    def restart(self, d0: float) -> None:
        self.b.load_state_blob(self.a.state_blob())
        base = self.b.get(["perturbation"])[0]  # A's value, restored with its state
        self.b.set("perturbation", base + d0)

    def separation(self) -> float:
        return float(np.linalg.norm((self.obs_b() - self.obs_a()) * self.scale))


@dataclass
class TwinRun:
    """The twin's case result, its segments, and (when the reference computed it too) the core's
    growth over each segment's periods."""

    result: CaseResult
    segments: list[Segment]
    core_growth: list[float] = field(default_factory=list)
    core: LyapunovResult | None = None

    @property
    def core_on_segments(self) -> float:
        """The core's exponent per period over exactly the twin's counted periods."""
        return sum(self.core_growth) / sum(s.periods for s in self.segments)


def run_twin(config: CaseConfig, settings: TwinSettings | None = None) -> TwinRun:
    """The case of `config` with the exponent from the twin. With ``config.lyapunov`` the
    reference also runs the core's tangent map (for comparisons on the same periods); without,
    both instances run the plain step (the cost of the two-instance method)."""
    t_start = time.perf_counter()
    st = settings or TwinSettings()
    cfg, T = config, config.period
    model = FmuModel.load(cfg.fmu)
    with lend(model, "reference") as a, lend(model, "twin") as b:
        a.initialize(cfg.fmu_parameters())
        first = through_transient(a, cfg)
        last = first + cfg.sample_periods
        pair = FmuTwin(a, b, cfg, first, last - max(cfg.dense_periods, 1))
        segments = restart_segments(pair, cfg.sample_periods, st)
        per_period = a.get(["lyapunov_per_period[1]"])[0] if cfg.lyapunov else math.nan
    rec = pair.rec
    strobe, dense = np.asarray(rec.samples), np.asarray(rec.dense)
    samples = strobe[:, 1:]
    swing = np.vstack([samples, dense[dense[:, 0] >= (last - 1) * T - 0.5 * cfg.dt_max, 1:]])
    size = swing.max(axis=0) - swing.min(axis=0)
    lyap = estimate(segments, T)
    result = CaseResult(
        config=cfg,
        samples=samples,
        sample_times=strobe[:, 0],
        size=size,
        dense=dense if cfg.dense_periods > 0 else None,
        lyapunov=lyap,
        classification=classify(samples, lyap.per_period, cfg.classify_settings, size=size),
        wall_time=time.perf_counter() - t_start,
    )
    run = TwinRun(result, segments)
    if cfg.lyapunov:
        g = np.concatenate([[0.0], rec.growth])
        run.core_growth = [float(g[s.start + s.periods] - g[s.start]) for s in segments]
        run.core = from_core(rec.growth, rec.counted, per_period, T)
    return run


def twin_case(config: CaseConfig) -> CaseResult:
    """:func:`run_twin` with both instances on the plain step (a sweep's ``case_fn``)."""
    result = run_twin(replace(config, lyapunov=False)).result
    result.config = config
    return result


CaseFn = Callable[[CaseConfig], CaseResult]
