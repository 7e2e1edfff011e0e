"""The benchmark's BuckledBeam (F = 0.7, Omega = 4500) through the FMU and through the core
alone: one initialized instance integrating a horizon repeatedly from its initial state, the
step loop of the core (``georod bench-steps``), its static state and natural frequencies (from
the FMU and ``georod modes``), and the error measures of :mod:`.benchmark`.
"""

from __future__ import annotations

import contextlib
import math
import os
import statistics
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from georod_tools.fmu import FmuModel, core_command, lend


@dataclass(frozen=True)
class BeamScene:
    """The BuckledBeam scene of model.md (defaults = the FMU's) at one excitation."""

    E: float = 1.2e4
    nu: float = 0.2
    rho: float = 1.0e-6
    d: float = 5.0e-4
    b: float = 1.0
    h: float = 1.0
    L: float = 10.0
    pre_shortening: float = 0.11
    well: int = 1
    F: float = 0.7
    Omega: float = 4500.0

    @property
    def period(self) -> float:
        return 2.0 * math.pi / self.Omega

    def fmu_parameters(self) -> dict[str, float]:
        return {
            "E": self.E,
            "nu": self.nu,
            "rho": self.rho,
            "d": self.d,
            "b": self.b,
            "h": self.h,
            "L": self.L,
            "pre_shortening": self.pre_shortening,
            "well": self.well,
            "F": self.F,
            "Omega": self.Omega,
        }


@dataclass
class Run:
    """One integration over a horizon: ``w`` at the communication points ``k h`` (``w[0]`` is the
    static state), the median wall time of the integration loop and every repetition's time."""

    w: np.ndarray
    seconds: float
    times: list[float]
    extra: dict[str, float] = field(default_factory=dict)


def default_fmu() -> Path:
    from georod_tools import fmu_path

    return fmu_path("BuckledBeam")


def machine_load() -> str:
    """The 1/5/15-minute load averages and the CPU count, for the record."""
    try:
        a, b, c = os.getloadavg()
        return f"load average {a:.2f} {b:.2f} {c:.2f} on {os.cpu_count()} CPUs"
    except OSError:
        return f"load average unknown, {os.cpu_count()} CPUs"


class FmuBeam:
    """One initialized BuckledBeam FMU instance (static solve done in the constructor) that
    integrates the horizon repeatedly from its initial FMU state (kept as an FMU state handle,
    never read)."""

    def __init__(
        self, scene: BeamScene, elements: int, dt_max: float, n_comm: int, fmu: Path | None = None
    ) -> None:
        self.model = FmuModel.load(fmu or default_fmu())
        params = scene.fmu_parameters()
        params.update({"elements": elements, "dt_max": dt_max})
        self._lend = lend(self.model, "benchmark")
        self.inst = self._lend.__enter__()
        try:
            self.inst.initialize(params)
        except BaseException:
            self._lend.__exit__(None, None, None)
            raise
        self.slave = self.inst.slave
        self.h = scene.period / n_comm
        self.vr_w = [self.model.variable("w_mid").vr]
        self.vr_newton = [self.model.variable("newton_iterations").vr]
        self.state0 = self.slave.getFMUstate()

    def w_static(self) -> float:
        self.slave.setFMUstate(self.state0)
        return float(self.slave.getReal(self.vr_w)[0])

    def integrate(self, steps: int, count_newton: bool = False) -> tuple[np.ndarray, float, int]:
        """`steps` communication steps from the initial state; returns w_mid at every
        communication point, the loop's wall time and (with `count_newton`, which adds one
        `fmi2GetInteger` per step to the loop) the total Newton corrections."""
        slave, h, vr, vrn = self.slave, self.h, self.vr_w, self.vr_newton
        slave.setFMUstate(self.state0)
        w = np.empty(steps + 1)
        w[0] = slave.getReal(vr)[0]
        newton = 0
        do_step, get_real, get_integer = slave.doStep, slave.getReal, slave.getInteger
        t0 = time.perf_counter()
        if count_newton:
            for k in range(steps):
                do_step(k * h, h)
                w[k + 1] = get_real(vr)[0]
                newton += get_integer(vrn)[0]
        else:
            for k in range(steps):
                do_step(k * h, h)
                w[k + 1] = get_real(vr)[0]
        seconds = time.perf_counter() - t0
        return w, seconds, newton

    def run(self, steps: int, repeats: int) -> Run:
        """One untimed run that counts the Newton corrections (instrumentation, like Exudyn's
        sensor run), then `repeats` timed runs of `fmi2DoStep` + `fmi2GetReal(w_mid)`."""
        _, _, newton = self.integrate(steps, count_newton=True)
        times: list[float] = []
        w = np.empty(0)
        for _ in range(max(1, repeats)):
            w, s, _ = self.integrate(steps)
            times.append(s)
        return Run(w, statistics.median(times), times, {"newton": float(newton)})

    def close(self) -> None:
        with contextlib.suppress(Exception):
            self.slave.freeFMUstate(self.state0)
        self._lend.__exit__(None, None, None)


@contextlib.contextmanager
def fmu_beam(
    scene: BeamScene, elements: int, dt_max: float, n_comm: int, fmu: Path | None = None
) -> Iterator[FmuBeam]:
    beam = FmuBeam(scene, elements, dt_max, n_comm, fmu)
    try:
        yield beam
    finally:
        beam.close()


def fmu_run(
    scene: BeamScene,
    n: int,
    periods: int,
    repeats: int,
    elements: int = 10,
    comm_per_period: int | None = None,
    fmu: Path | None = None,
) -> Run:
    """`periods` forcing periods with ``dt_max = T / n`` and communication step ``T / c``
    (``c = comm_per_period`` or `n`; `n` must be a multiple of c)."""
    c = comm_per_period or n
    if n % c:
        raise ValueError(f"{n} steps per period is not a multiple of {c} communication steps")
    # dt_max = T/n: the FMU cuts T/c into n/c sub-steps (it allows for round-off)
    with fmu_beam(scene, elements, scene.period / n, c, fmu) as beam:
        return beam.run(periods * c, repeats)


def core_seconds(scene: BeamScene, n: int, periods: int, elements: int = 10) -> float:
    """Wall time of the Rust core alone (``georod bench-steps``, no FMI, no Python) for the same
    integration: the median of 3 (the machine is shared)."""
    dt = scene.period / n
    sets = {**scene.fmu_parameters(), "elements": elements, "dt_max": dt}
    times = [core_command.bench_steps("BuckledBeam", sets, periods * n, dt) for _ in range(3)]
    return statistics.median(times)


@dataclass(frozen=True)
class ModelQuantities:
    """The FMU's static w_mid and, from ``georod modes`` about the same equilibrium, its w_mid
    and lowest natural frequencies (rad/s)."""

    elements: int
    w_static_fmu: float
    w_static_core: float
    omegas: tuple[float, ...]


def model_quantities(
    scene: BeamScene, elements: int, count: int = 3, fmu: Path | None = None
) -> ModelQuantities:
    """Static state and frequencies from the core (nothing recomputed here): the FMU's initial
    w_mid, and ``georod modes`` on the FMU's own scene file about the equilibrium in its well."""
    model = FmuModel.load(fmu or default_fmu())
    params = {**scene.fmu_parameters(), "elements": elements}
    with lend(model, "static") as inst:
        inst.initialize(params)
        w_fmu = float(inst.get(["w_mid"])[0])
    scene_file = str(model.unzipdir / "resources" / "scene.toml")
    overrides = {k: v for k, v in params.items() if k not in ("F", "Omega")}
    modes = core_command.modes(scene_file, overrides, count=count)
    near = min({m.equilibrium: m.w_mid for m in modes}.items(), key=lambda e: abs(e[1] - w_fmu))
    omegas = tuple(m.omega for m in modes if m.equilibrium == near[0])
    return ModelQuantities(elements, w_fmu, near[1], omegas)


def errors(w: np.ndarray, ref: np.ndarray) -> tuple[float, float]:
    """(|error| at the final time, max |error| over the grid of `w`); `ref` is on a grid that
    refines it by an integer factor."""
    n, m = len(w) - 1, len(ref) - 1
    if m % n:
        raise ValueError(f"reference grid {m} does not refine {n}")
    r = ref[:: m // n]
    e = np.abs(w - r)
    return float(e[-1]), float(e.max())


def convergence_rows(name: str, runs: dict[int, np.ndarray]) -> list[dict[str, object]]:
    """Differences between successive refinements of a reference (on the coarsest grid)."""
    ns = sorted(runs)
    rows = []
    for a, b in zip(ns, ns[1:], strict=False):
        step = (len(runs[b]) - 1) // (len(runs[ns[0]]) - 1)
        step_a = (len(runs[a]) - 1) // (len(runs[ns[0]]) - 1)
        wa, wb = runs[a][::step_a], runs[b][::step]
        d = np.abs(wa - wb)
        rows.append(
            {
                "method": name,
                "n_coarse": a,
                "n_fine": b,
                "diff_final": float(d[-1]),
                "diff_max": float(d.max()),
            }
        )
    return rows


def equal_error_ratio(
    fmu: Sequence[tuple[float, float]], other: Sequence[tuple[float, float]]
) -> list[tuple[float, float, float, float]]:
    """For every (error, seconds) point of `fmu` inside the error range of `other`, the other's
    seconds interpolated in log-log at that error: rows (error, t_fmu, t_other, ratio). Uses the
    part of `other` where the error falls monotonically with time."""
    pts = sorted((t, e) for e, t in other if e > 0)
    mono: list[tuple[float, float]] = []
    for t, e in pts:
        if not mono or e < mono[-1][1]:
            mono.append((t, e))
    if len(mono) < 2:
        return []
    le = np.log([e for _, e in mono])[::-1]
    lt = np.log([t for t, _ in mono])[::-1]
    rows = []
    for e, t in fmu:
        if e <= 0 or not (le[0] <= math.log(e) <= le[-1]):
            continue
        t_other = float(np.exp(np.interp(math.log(e), le, lt)))
        rows.append((e, t, t_other, t_other / t))
    return rows
