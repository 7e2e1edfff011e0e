"""One case: an FMU run past its transient, sampled stroboscopically at ``t = k T`` (``T = 2 pi /
Omega``), with the largest Lyapunov exponent from the core, and classified.

Time steps: the FMU's ``dt_max`` is ``T / N`` exactly (``N`` = ``substeps``, midpoint sub-steps
per forcing period), and a communication step is one whole period, so the FMU takes N equal
sub-steps per step and no Python runs between them. Only the dense window is stepped in ``T / m``
(``m`` dividing N): the last `dense_periods` when a phase portrait is asked for, and always the
last sampled period, whose swing gives the classifier the size of the orbit. With ``m`` a power of
two, ``(T / m) / (N / m)`` is ``T / N`` to the last bit, so the sub-steps, the trajectory, the
samples and the exponent are the same bits whatever the dense window: ``case`` and ``sweep`` give
identical numbers for the same settings. Communication points come from a period counter, never
from a running sum.

The exponent (``lyapunov_count = 1``): the core advances a tangent vector from the end of the
transient; it aligns with the most unstable direction for `align_periods` periods and is then
averaged over the rest of the sampled periods (:mod:`georod_tools.analysis.lyapunov`).

Each case is deterministic and starts from the FMU's initial state at ``t = 0`` (or from where a
:class:`Prelude` took it): a sweep does not depend on how many workers ran it.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from georod_tools.analysis.classify import Classification, ClassifySettings, classify
from georod_tools.analysis.lyapunov import LyapunovResult, from_core
from georod_tools.analysis.prelude import Prelude
from georod_tools.fmu import FmuModel, Instance, lend

#: The default sub-steps per forcing period: T / 128 (1.4e-5 s at Omega = 3500, where the former
#: default dt_max = 1e-5 s took T / 180: about twice its time-step error, still three orders below
#: the error of the 10-element mesh, docs/benchmark.md). A power of two: see the module docstring.
DEFAULT_SUBSTEPS = 128
#: The dense window's default resolution: the largest power of two dividing N, up to this.
MAX_DEFAULT_DENSE_STEPS = 64
#: The sensors sampled by default: displacement and velocity of the midspan (every scene of the
#: paper); a case names its own (`CaseConfig.sensor`, `CaseConfig.velocity`).
OUTPUTS = ("w_mid", "v_mid")
LYAPUNOV_OUTPUTS = ("lyapunov[1]", "lyapunov_time")
#: FMU parameters a case sets from its own fields (never through `params`).
MANAGED = ("F", "Omega", "elements", "dt_max", "lyapunov_count", "lyapunov_start", "lyapunov_align")


def default_dense_steps(substeps: int) -> int:
    """The dense window's steps per period: the largest power of two that divides `substeps`, up
    to 64 (a power of two keeps the sub-steps bit for bit those of whole-period steps)."""
    m = 1
    while substeps % (2 * m) == 0 and 2 * m <= MAX_DEFAULT_DENSE_STEPS:
        m *= 2
    return m


@dataclass(frozen=True)
class CaseConfig:
    """One run: FMU, excitation, mesh and time step, other parameters by name, and the analysis.

    substeps: midpoint sub-steps per forcing period N (``dt_max = T / N``).
    params: further FMU parameters as (name, value) pairs (e.g. ``(("well", -1),)``); a tuple so
        the config is hashable and cheap to send to Dask workers.
    transient_periods: forcing periods run and discarded before sampling.
    sample_periods: forcing periods sampled (one Poincaré point each).
    dense_periods: the last this many sampled periods are kept densely (phase portrait, time
        plot), `dense_steps` points per period; 0 keeps none.
    dense_steps: communication steps per period in the dense window; must divide `substeps`
        (a power of two keeps the results independent of the window); 0 takes
        :func:`default_dense_steps`.
    lyapunov: also compute the largest exponent (the core's tangent map: about 1.4x the cost of
        the sampled periods).
    align_periods: sampled periods in which the tangent vector only aligns with the most
        unstable direction; the exponent is averaged over the rest. 10 periods: the chaotic
        cases' leading exponent (0.3-1 per period) separates from the next (near 0) by e^3 or
        more; for periodic orbits the estimate only needs to stay near zero.
    prelude: what happens before the forcing starts (e.g. pushing an arch into another
        equilibrium); None starts the forcing at t = 0 from the FMU's initial state.
    sensor, velocity: the displacement sensor sampled and its velocity partner (the FMU's output
        names; :mod:`georod_tools.analysis.scene_sensors` picks them for any scene); an empty
        `velocity` samples the sensor's change over each step's last sub-step instead.
    forced: the FMU has a harmonic load (parameters F and Omega, set by the case); without one,
        `Omega` is only the sampling period's ``2 pi / T`` and F is not set.
    """

    fmu: str
    F: float = 0.7
    Omega: float = 3500.0
    elements: int = 10
    substeps: int = DEFAULT_SUBSTEPS
    params: tuple[tuple[str, float], ...] = ()
    transient_periods: int = 200
    sample_periods: int = 200
    dense_periods: int = 0
    dense_steps: int = 0
    lyapunov: bool = True
    align_periods: int = 10
    prelude: Prelude | None = None
    classify_settings: ClassifySettings = field(default_factory=ClassifySettings)
    sensor: str = OUTPUTS[0]
    velocity: str = OUTPUTS[1]
    forced: bool = True

    def __post_init__(self) -> None:
        checks = [
            (math.isfinite(self.F), f"F = {self.F} must be finite"),
            (self.Omega > 0 and math.isfinite(self.Omega), f"Omega = {self.Omega} must be > 0"),
            (self.elements >= 2, f"elements = {self.elements} must be >= 2"),
            (self.substeps >= 1, f"substeps = {self.substeps} must be >= 1"),
            (self.transient_periods >= 0, "transient_periods must be >= 0"),
            (self.sample_periods >= 1, "sample_periods must be >= 1"),
            (
                0 <= self.dense_periods <= self.sample_periods,
                f"dense_periods = {self.dense_periods} must lie in 0..sample_periods "
                f"({self.sample_periods})",
            ),
            (
                self.dense_steps == 0 or self.substeps % self.dense_steps == 0,
                f"dense_steps = {self.dense_steps} must divide substeps = {self.substeps} "
                "(the dense window takes the same sub-steps)",
            ),
            (self.align_periods >= 0, "align_periods must be >= 0"),
        ]
        for ok, msg in checks:
            if not ok:
                raise ValueError(msg)
        managed = sorted({n for n, _ in self.params} & set(MANAGED))
        if managed:
            raise ValueError(
                f"params {', '.join(managed)}: set by the case itself (F, Omega, elements, "
                "substeps, lyapunov)"
            )
        if self.lyapunov and self.sample_periods <= self.align_periods:
            raise ValueError(
                f"sample_periods = {self.sample_periods} leaves no period to average the "
                f"Lyapunov exponent over after align_periods = {self.align_periods}"
            )

    @property
    def period(self) -> float:
        """Forcing period ``T = 2 pi / Omega`` in seconds."""
        return 2.0 * math.pi / self.Omega

    @property
    def dt_max(self) -> float:
        """The sub-step ``T / N`` (the FMU's dt_max)."""
        return self.period / self.substeps

    @property
    def velocity_name(self) -> str:
        """The velocity's column name: its sensor, or ``d(<sensor>)/dt`` when sampled."""
        return self.velocity or f"d({self.sensor})/dt"

    @property
    def dense_steps_per_period(self) -> int:
        return self.dense_steps or default_dense_steps(self.substeps)

    @property
    def start_periods(self) -> int:
        """Periods before the forcing starts (the prelude's)."""
        return self.prelude.periods if self.prelude else 0

    def fmu_parameters(self) -> dict[str, float]:
        """Every parameter set on the FMU before initialization, by name."""
        T = self.period
        p: dict[str, float] = dict(self.params)
        p.update({"elements": self.elements, "dt_max": self.dt_max})
        if self.forced:
            p.update({"F": 0.0 if self.prelude else self.F, "Omega": self.Omega})
        if self.lyapunov:
            # Half a sub-step before the period boundary: round-off in the core's clock cannot
            # move the first advanced (or counted) sub-step by one.
            start = (self.start_periods + self.transient_periods) * T - 0.5 * self.dt_max
            p.update(
                {
                    "lyapunov_count": 1,
                    "lyapunov_start": start,
                    "lyapunov_align": self.align_periods * T,
                }
            )
        return p

    def with_value(self, name: str, value: float) -> CaseConfig:
        """A copy with parameter `name` (F, Omega, elements, substeps or any FMU name) set."""
        if name in ("F", "Omega"):
            return replace(self, **{name: float(value)})
        if name in ("elements", "substeps"):
            return replace(self, **{name: int(value)})
        rest = tuple((n, v) for n, v in self.params if n != name)
        return replace(self, params=(*rest, (name, value)))

    def value(self, name: str) -> float:
        """The value of `name` in this config (F, Omega, elements, substeps or a params entry)."""
        if name in ("F", "Omega", "elements", "substeps"):
            return float(getattr(self, name))
        return float(dict(self.params)[name])


@dataclass
class CaseResult:
    """Outcome of one case.

    samples: (n, 2) stroboscopic (w_mid, v_mid) at ``sample_times`` = k T.
    size: the swing of (w_mid, v_mid): their range over the samples and the last sampled period
        (the attractor size the classifier's tolerance scales with; nonzero for a period-1 orbit).
    dense: (m, 3) columns t, w_mid, v_mid over the last `dense_periods` periods, or None.
    """

    config: CaseConfig
    samples: np.ndarray
    sample_times: np.ndarray
    size: np.ndarray
    dense: np.ndarray | None
    lyapunov: LyapunovResult | None
    classification: Classification
    wall_time: float

    @property
    def exponent_per_period(self) -> float:
        return self.lyapunov.per_period if self.lyapunov else math.nan

    @property
    def exponent_per_second(self) -> float:
        return self.lyapunov.per_second if self.lyapunov else math.nan


@dataclass
class Trajectory:
    """What a run records: samples ``(t, w, v)`` at every period end, the dense points ``(t, w,
    v)`` and, with the exponent, the core's accumulated growth and counted time per sample."""

    samples: list[tuple[float, float, float]] = field(default_factory=list)
    dense: list[tuple[float, float, float]] = field(default_factory=list)
    growth: list[float] = field(default_factory=list)
    counted: list[float] = field(default_factory=list)


def start_forcing(inst: Instance, cfg: CaseConfig) -> int:
    """Runs the prelude (if any) and switches the forcing on; returns the periods it took."""
    if cfg.prelude is None:
        return 0
    cfg.prelude.run(inst, cfg.period)
    inst.set("F", cfg.F)
    return cfg.prelude.periods


def through_transient(inst: Instance, cfg: CaseConfig) -> int:
    """Runs the prelude, switches the forcing on and steps through the transient periods, one
    step per period; returns the index of the first sampled period."""
    T = cfg.period
    first = start_forcing(inst, cfg)
    for k in range(first, first + cfg.transient_periods):
        inst.step(k * T, T)
    return first + cfg.transient_periods


def sample(inst: Instance, cfg: CaseConfig, first: int, dense_from: int) -> Trajectory:
    """The sampled periods from period `first`: one step per period, ``T / m`` steps from
    period `dense_from` on (the dense window). Without a velocity sensor each step ends with its
    last sub-step taken alone, and the velocity is the sensor's change over it divided by it."""
    T, m = cfg.period, cfg.dense_steps_per_period
    derived = not cfg.velocity
    names = (cfg.sensor,) + (() if derived else (cfg.velocity,))
    read = inst.reader(names + (LYAPUNOV_OUTPUTS if cfg.lyapunov else ()))
    if derived:
        step, state = derived_stepping(inst, cfg, read)
    else:
        step = inst.step

        def state() -> tuple:
            got = read()
            return got[0], got[1], got[2:]

    rec = Trajectory()
    for k in range(first, first + cfg.sample_periods):
        if k >= dense_from:
            if not rec.dense and not (derived and k == first):
                w, v, _ = state()
                rec.dense.append((k * T, w, v))
            for j in range(m):
                step(k * T + j * (T / m), T / m)
                if j < m - 1:
                    w, v, _ = state()
                    rec.dense.append((k * T + (j + 1) * (T / m), w, v))
        else:
            step(k * T, T)
        w, v, extra = state()
        t = (k + 1) * T
        rec.samples.append((t, w, v))
        if k >= dense_from:
            rec.dense.append((t, w, v))
        if cfg.lyapunov:
            rec.growth.append(extra[0] * extra[1])
            rec.counted.append(extra[1])
    return rec


def derived_stepping(
    inst: Instance, cfg: CaseConfig, read: Callable[[], np.ndarray]
) -> tuple[Callable[[float, float], None], Callable[[], tuple]]:
    """A step that takes its last sub-step ``dt`` alone, and the state after it: the sensor and
    its change over that sub-step divided by ``dt`` (the sub-step's mean velocity: the velocity
    at its end to first order in ``dt``)."""
    dt = cfg.dt_max
    read_sensor = inst.reader((cfg.sensor,))
    before = [math.nan]

    def step(t: float, h: float) -> None:
        if h > 1.5 * dt:
            inst.step(t, h - dt)
            t, h = t + h - dt, dt
        before[0] = read_sensor()[0]
        inst.step(t, h)

    def state() -> tuple:
        got = read()
        return got[0], (got[0] - before[0]) / dt, got[1:]

    return step, state


def exponent_per_period(inst: Instance, cfg: CaseConfig) -> float:
    """The core's exponent per sampling period (an unforced FMU has no
    ``lyapunov_per_period``: its exponent per second times the period)."""
    if not cfg.lyapunov:
        return math.nan
    if cfg.forced:
        return inst.get(["lyapunov_per_period[1]"])[0]
    return inst.get(["lyapunov[1]"])[0] * cfg.period


def run_case(config: CaseConfig) -> CaseResult:
    """Runs one case (see :class:`CaseConfig`) and classifies its motion."""
    t_start = time.perf_counter()
    cfg = config
    T = cfg.period
    model = FmuModel.load(cfg.fmu)
    with lend(model, "case") as inst:
        inst.initialize(cfg.fmu_parameters())
        first = through_transient(inst, cfg)
        last = first + cfg.sample_periods
        rec = sample(inst, cfg, first, last - max(cfg.dense_periods, 1))
        per_period = exponent_per_period(inst, cfg)
    strobe = np.asarray(rec.samples, dtype=float)
    dense = np.asarray(rec.dense, dtype=float)
    samples = strobe[:, 1:]
    last_period = dense[dense[:, 0] >= (last - 1) * T - 0.5 * T / cfg.substeps, 1:]
    swing = np.vstack([samples, last_period])
    size = swing.max(axis=0) - swing.min(axis=0)
    lyap = from_core(rec.growth, rec.counted, per_period, T) if cfg.lyapunov else None
    exponent = lyap.per_period if lyap is not None else None
    cls = classify(samples, exponent, cfg.classify_settings, size=size)
    return CaseResult(
        config=cfg,
        samples=samples,
        sample_times=strobe[:, 0],
        size=size,
        dense=dense if cfg.dense_periods > 0 else None,
        lyapunov=lyap,
        classification=cls,
        wall_time=time.perf_counter() - t_start,
    )


def run_case_plain(config: CaseConfig) -> CaseResult:
    """:func:`run_case` without the exponent (the trajectory's own cost); the result keeps
    `config`."""
    result = run_case(replace(config, lyapunov=False))
    result.config = config
    return result
