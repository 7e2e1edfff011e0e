"""Drive one georod FMU through fmpy's FMU2Slave: run past the transient, then sample the
midspan displacement and velocity stroboscopically at ``t = k T`` (``T = 2 pi / Omega``), keep the
dense trajectory for phase portraits if asked, and estimate the largest Lyapunov exponent with a
second instance that follows a perturbed trajectory.

Time stepping: a period is cut into ``n_per_period`` equal communication steps ``h = T /
n_per_period`` and the FMU cuts each into the fewest equal sub-steps no longer than ``dt_max``, so
every sub-step has the same length and the samples land exactly on ``k T``. Communication points
are ``k h`` from a step counter (no running sum).

Each case is self-contained (a fresh instance started from the static state at ``t = 0``) and
deterministic, which makes a sweep independent of how many workers run it.
"""

from __future__ import annotations

import atexit
import math
import shutil
import tempfile
import time
from collections.abc import Callable, Mapping
from ctypes import byref, c_char_p, c_int, c_void_p
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TypeVar

import numpy as np
from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)

from georod_tools.classify import Classification, ClassifySettings, classify
from georod_tools.fmu_state import decode_state, encode_state, free_mask
from georod_tools.lyapunov import LyapunovResult, LyapunovSettings, benettin, initial_direction

OUTPUT_NAMES = ("w_mid", "v_mid")
T = TypeVar("T")


#: fmi2Status names by value.
FMI2_STATUS = ("fmi2OK", "fmi2Warning", "fmi2Discard", "fmi2Error", "fmi2Fatal", "fmi2Pending")


class FmuError(RuntimeError):
    """An FMI call failed; the message carries the returned status and what the FMU logged.

    status: the fmi2Status the call returned (2 = fmi2Discard, 3 = fmi2Error, ...), or None when
    the failure was not a status (e.g. the library could not be loaded).
    """

    def __init__(self, message: str, status: int | None = None) -> None:
        super().__init__(message)
        self.status = status


class FmuModel:
    """One FMU file extracted once per process, with its name -> (value reference, type) table.

    Extraction happens once per path (cached by :meth:`load`); the directory is removed when the
    process exits.
    """

    _cache: dict[tuple[str, float], FmuModel] = {}

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        if not self.path.is_file():
            raise FileNotFoundError(f"FMU {self.path} not found (build it with scripts/build_fmus)")
        self.unzipdir = Path(tempfile.mkdtemp(prefix=f"georod_{self.path.stem}_"))
        atexit.register(shutil.rmtree, self.unzipdir, True)
        extract(str(self.path), unzipdir=str(self.unzipdir))
        self.md = read_model_description(str(self.unzipdir))
        if self.md.coSimulation is None:
            raise ValueError(f"{self.path} is not a Co-Simulation FMU")
        self.identifier: str = self.md.coSimulation.modelIdentifier
        self.vr: dict[str, int] = {}
        self.types: dict[str, str] = {}
        self.causality: dict[str, str] = {}
        for v in self.md.modelVariables:
            self.vr[v.name] = v.valueReference
            self.types[v.name] = v.type
            self.causality[v.name] = v.causality

    @classmethod
    def load(cls, path: str | Path) -> FmuModel:
        """The cached model of `path` (re-extracted when the file changed)."""
        p = Path(path).resolve()
        key = (str(p), p.stat().st_mtime if p.exists() else 0.0)
        if key not in cls._cache:
            cls._cache[key] = cls(p)
        return cls._cache[key]

    @property
    def parameters(self) -> list[str]:
        return [n for n, c in self.causality.items() if c == "parameter"]


class _Log:
    """Collects the FMU's log messages (shown in errors)."""

    def __init__(self) -> None:
        self.messages: list[str] = []
        self._logger = fmi2CallbackLoggerTYPE(self._log)
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = self._logger
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        try:
            from fmpy.logging import addLoggerProxy

            addLoggerProxy(byref(self.callbacks))
        except Exception:  # noqa: BLE001 - without the proxy the raw format string is logged
            pass

    def _log(
        self,
        env: c_void_p,
        instance: c_char_p,
        status: c_int,
        category: c_char_p,
        message: c_char_p,
    ) -> None:
        text = message.decode("utf-8", "replace") if isinstance(message, bytes) else str(message)
        self.messages.append(text)
        del self.messages[:-20]

    def last(self) -> str:
        return self.messages[-1] if self.messages else "(no message logged)"


class Instance:
    """One instantiated and initialized FMU, stepped in whole periods of the forcing.

    `params` are set by name before initialization (Integer or Real as the model description
    says). `k` counts communication steps; the time is ``k * h``.
    """

    def __init__(
        self,
        model: FmuModel,
        params: Mapping[str, float],
        omega: float,
        n_per_period: int,
        name: str = "georod",
    ) -> None:
        self.model = model
        self.period = 2.0 * math.pi / omega
        self.n_per_period = n_per_period
        self.h = self.period / n_per_period
        self.k = 0
        self.log = _Log()
        self.slave = FMU2Slave(
            guid=model.md.guid,
            unzipDirectory=str(model.unzipdir),
            modelIdentifier=model.identifier,
            instanceName=name,
        )
        self._vr_out = [model.vr[n] for n in OUTPUT_NAMES]
        self._alive = False
        self._call(lambda: self.slave.instantiate(callbacks=self.log.callbacks, loggingOn=False))
        self._alive = True
        try:
            self._call(lambda: self.slave.setupExperiment(startTime=0.0))
            for name_, value in params.items():
                self._set(name_, value)
            self._call(self.slave.enterInitializationMode)
            self._call(self.slave.exitInitializationMode)
        except BaseException:
            self.close()
            raise

    def _call(self, fn: Callable[[], T], what: str = "") -> T:
        """Calls `fn`, turning fmpy's exception for a non-OK status into FmuError with the
        FMU's last log message (which says why)."""
        try:
            return fn()
        except Exception as e:  # fmpy raises a plain Exception / FMICallException on status > OK
            status = getattr(e, "status", None)
            returned = ""
            if what and isinstance(status, int) and 0 <= status < len(FMI2_STATUS):
                returned = f" returned {FMI2_STATUS[status]}"
            raise FmuError(f"{what or e}{returned}: {self.log.last()}", status) from e

    def _set(self, name: str, value: float) -> None:
        m = self.model
        if name not in m.vr or m.causality[name] != "parameter":
            raise ValueError(
                f"{m.identifier} has no parameter {name!r}; its parameters are "
                f"{', '.join(m.parameters)}"
            )
        vr = m.vr[name]
        if m.types[name] in ("Integer", "Enumeration"):
            if float(value) != int(value):
                raise ValueError(f"parameter {name} is an Integer, got {value}")
            self._call(lambda: self.slave.setInteger([vr], [int(value)]), f"setting {name}={value}")
        else:
            self._call(lambda: self.slave.setReal([vr], [float(value)]), f"setting {name}={value}")

    @property
    def time(self) -> float:
        return self.k * self.h

    def outputs(self) -> tuple[float, float]:
        """(w_mid, v_mid) now."""
        w, v = self.slave.getReal(self._vr_out)
        return float(w), float(v)

    def step(self) -> None:
        """One communication step of length h."""
        t = self.k * self.h
        self._call(lambda: self.slave.doStep(t, self.h), f"fmi2DoStep at t = {t:.6g}")
        self.k += 1

    def serialize(self) -> bytes:
        """The instance's state as bytes (fmi2SerializeFMUstate)."""
        state = self._call(self.slave.getFMUstate, "fmi2GetFMUstate")
        try:
            return bytes(self._call(lambda: self.slave.serializeFMUstate(state)))
        finally:
            self.slave.freeFMUstate(state)

    def restore(self, blob: bytes, k: int) -> None:
        """Puts the instance in the serialized state `blob`, at communication step `k`."""
        state = self._call(lambda: self.slave.deSerializeFMUstate(blob), "fmi2DeSerializeFMUstate")
        try:
            self._call(lambda: self.slave.setFMUstate(state), "fmi2SetFMUstate")
        finally:
            self.slave.freeFMUstate(state)
        self.k = k

    def close(self) -> None:
        """Terminates and frees the instance (never raises)."""
        if not self._alive:
            return
        self._alive = False
        try:
            self.slave.terminate()
        except Exception:  # noqa: BLE001 - terminate is refused in some states; free anyway
            pass
        try:
            self.slave.freeInstance()
        except Exception:  # noqa: BLE001
            pass


@dataclass
class Recorder:
    """What the reference instance records while sampling: stroboscopic samples every period,
    the range of (w, v) at every communication point, and optionally the dense trajectory."""

    dense: bool
    dense_from_step: int = 0
    samples: list[tuple[float, float, float]] = field(default_factory=list)
    trajectory: list[tuple[float, float, float]] = field(default_factory=list)
    lo: np.ndarray = field(default_factory=lambda: np.full(2, np.inf))
    hi: np.ndarray = field(default_factory=lambda: np.full(2, -np.inf))

    def point(self, inst: Instance) -> None:
        w, v = inst.outputs()
        self.lo = np.minimum(self.lo, (w, v))
        self.hi = np.maximum(self.hi, (w, v))
        if self.dense and inst.k >= self.dense_from_step:
            self.trajectory.append((inst.time, w, v))
        if inst.k % inst.n_per_period == 0:
            self.samples.append((inst.time, w, v))


def advance_periods(inst: Instance, periods: int, recorder: Recorder | None = None) -> None:
    """`periods` forcing periods of `inst`, recording every communication point if asked."""
    for _ in range(periods * inst.n_per_period):
        inst.step()
        if recorder is not None:
            recorder.point(inst)


class FmuPair:
    """Reference and perturbed FMU instances for :func:`georod_tools.lyapunov.benettin`.

    Separation coordinates: the free degrees of freedom of ``(u, v / Omega)`` (velocities scaled
    by the forcing frequency so both halves are displacements of comparable size; any norm gives
    the same exponent). The perturbed instance is reset by patching the reference's serialized
    state (:mod:`georod_tools.fmu_state`) and deserializing it.
    """

    def __init__(self, ref: Instance, pert: Instance, omega: float, recorder: Recorder) -> None:
        self.ref, self.pert, self.omega, self.recorder = ref, pert, omega, recorder
        st = decode_state(ref.serialize())
        scene_file = ref.model.unzipdir / "resources" / "scene.toml"
        self.mask = np.concatenate([free_mask(scene_file, st.elements)] * 2)

    def _vector(self, blob: bytes) -> np.ndarray:
        st = decode_state(blob)
        return np.concatenate([st.displacements, st.velocities / self.omega])

    def advance(self, steps: int) -> None:
        advance_periods(self.ref, steps, self.recorder)
        advance_periods(self.pert, steps)

    def separation(self) -> np.ndarray:
        d = self._vector(self.pert.serialize()) - self._vector(self.ref.serialize())
        return np.where(self.mask, d, 0.0)

    def set_separation(self, delta: np.ndarray) -> None:
        blob = self.ref.serialize()
        st = decode_state(blob)
        n = st.dofs
        delta = np.where(self.mask, delta, 0.0)
        u = st.displacements + delta[:n]
        v = st.velocities + delta[n:] * self.omega
        self.pert.restore(encode_state(blob, u, v), self.ref.k)


@dataclass(frozen=True)
class CaseConfig:
    """One run: FMU, excitation, mesh and time step, other parameters by name, and the analysis.

    params: further FMU parameters as (name, value) pairs (e.g. ``(("well", -1),)``); a tuple so
        the config is hashable and cheap to send to Dask workers.
    transient_periods: forcing periods run and discarded before sampling.
    sample_periods: forcing periods sampled (one Poincaré point each).
    n_per_period: communication steps per forcing period.
    dense_periods: the last this many sampled periods are kept densely (phase portrait, time
        plot); 0 keeps none.
    lyapunov: also estimate the largest exponent over the sampled periods (doubles the cost).
    lyapunov_every / lyapunov_d0 / lyapunov_discard: Benettin settings (renormalize every
        `every` periods to separation `d0` in the scaled state norm; the first `discard`
        intervals are not averaged). The defaults (1 period, 1e-7) sit in the linear regime:
        on the BuckledBeam (F = 0.9 chaotic, F = 0.4 period-1) d0 = 1e-9, 1e-7, 1e-5 give the same
        exponent to 4 digits, and renormalizing every 3 periods changes it by < 0.001.
    """

    fmu: str
    F: float = 0.7
    Omega: float = 3500.0
    elements: int = 10
    dt_max: float = 1e-5
    params: tuple[tuple[str, float], ...] = ()
    transient_periods: int = 200
    sample_periods: int = 200
    n_per_period: int = 20
    dense_periods: int = 0
    lyapunov: bool = True
    lyapunov_every: int = 1
    lyapunov_d0: float = 1e-7
    lyapunov_discard: int = 10
    seed: int = 12345
    classify_settings: ClassifySettings = field(default_factory=ClassifySettings)

    def __post_init__(self) -> None:
        checks = [
            (math.isfinite(self.F), f"F = {self.F} must be finite"),
            (self.Omega > 0 and math.isfinite(self.Omega), f"Omega = {self.Omega} must be > 0"),
            (self.elements >= 2, f"elements = {self.elements} must be >= 2"),
            (self.dt_max > 0 and math.isfinite(self.dt_max), f"dt_max = {self.dt_max} must be > 0"),
            (self.transient_periods >= 0, "transient_periods must be >= 0"),
            (self.sample_periods >= 1, "sample_periods must be >= 1"),
            (self.n_per_period >= 1, "n_per_period must be >= 1"),
            (
                0 <= self.dense_periods <= self.sample_periods,
                "0 <= dense_periods <= sample_periods",
            ),
            (self.lyapunov_every >= 1, "lyapunov_every must be >= 1"),
            (self.lyapunov_d0 > 0, "lyapunov_d0 must be > 0"),
            (self.lyapunov_discard >= 0, "lyapunov_discard must be >= 0"),
        ]
        for ok, msg in checks:
            if not ok:
                raise ValueError(msg)
        if self.lyapunov and (
            self.sample_periods // self.lyapunov_every - self.lyapunov_discard < 1
        ):
            raise ValueError(
                f"sample_periods = {self.sample_periods} leaves no Lyapunov interval after "
                f"{self.lyapunov_discard} discarded intervals of {self.lyapunov_every} periods"
            )

    @property
    def period(self) -> float:
        """Forcing period ``T = 2 pi / Omega`` in seconds."""
        return 2.0 * math.pi / self.Omega

    def fmu_parameters(self) -> dict[str, float]:
        """Every parameter set on the FMU, by name."""
        p: dict[str, float] = {"elements": self.elements, "dt_max": self.dt_max}
        p.update(dict(self.params))
        p.update({"F": self.F, "Omega": self.Omega})
        return p

    def with_value(self, name: str, value: float) -> CaseConfig:
        """A copy with parameter `name` (F, Omega, elements, dt_max or any FMU name) set."""
        if name in ("F", "Omega", "dt_max"):
            return replace(self, **{name: float(value)})
        if name == "elements":
            return replace(self, elements=int(value))
        rest = tuple((n, v) for n, v in self.params if n != name)
        return replace(self, params=(*rest, (name, value)))


@dataclass
class CaseResult:
    """Outcome of one case.

    samples: (n, 2) stroboscopic (w_mid, v_mid) at ``sample_times`` = k T.
    size: range of (w_mid, v_mid) over every communication point of the sampled periods (the
        attractor size used by the classifier; nonzero even for a period-1 orbit).
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


def run_case(config: CaseConfig, u0: np.ndarray | None = None) -> CaseResult:
    """Runs one case (see :class:`CaseConfig`) and classifies its motion. With `u0`, both
    instances start from these displacements at rest (written into a serialized FMU state)
    instead of the FMU's own initial state, e.g. from another static equilibrium."""
    t_start = time.perf_counter()
    cfg = config
    model = FmuModel.load(cfg.fmu)
    params = cfg.fmu_parameters()

    def make(name: str) -> Instance:
        inst = Instance(model, params, cfg.Omega, cfg.n_per_period, name=name)
        if u0 is not None:
            blob = inst.serialize()
            n = decode_state(blob).dofs
            if u0.size != n:
                raise ValueError(f"state has {u0.size} dofs, the FMU {n}")
            inst.restore(encode_state(blob, u0, np.zeros(n)), 0)
        return inst

    ref = make("reference")
    pert: Instance | None = None
    try:
        advance_periods(ref, cfg.transient_periods)
        first_dense = cfg.transient_periods + cfg.sample_periods - cfg.dense_periods
        rec = Recorder(dense=cfg.dense_periods > 0, dense_from_step=first_dense * cfg.n_per_period)
        if cfg.dense_periods > 0 and cfg.dense_periods == cfg.sample_periods:
            w, v = ref.outputs()  # include the start of the dense window
            rec.trajectory.append((ref.time, w, v))
        lyap: LyapunovResult | None = None
        if cfg.lyapunov:
            pert = make("perturbed")
            pair = FmuPair(ref, pert, cfg.Omega, rec)
            intervals = cfg.sample_periods // cfg.lyapunov_every
            settings = LyapunovSettings(
                d0=cfg.lyapunov_d0,
                every=cfg.lyapunov_every,
                renormalizations=intervals - cfg.lyapunov_discard,
                discard=cfg.lyapunov_discard,
                seed=cfg.seed,
            )
            direction = initial_direction(pair.mask.size, cfg.seed, pair.mask)
            lyap = benettin(pair, settings, direction, period=cfg.period)
            advance_periods(ref, cfg.sample_periods - intervals * cfg.lyapunov_every, rec)
        else:
            advance_periods(ref, cfg.sample_periods, rec)
    finally:
        ref.close()
        if pert is not None:
            pert.close()
    strobe = np.asarray(rec.samples, dtype=float).reshape(-1, 3)
    samples = strobe[:, 1:]
    size = rec.hi - rec.lo
    dense = np.asarray(rec.trajectory, dtype=float).reshape(-1, 3) if rec.dense else None
    exponent = lyap.per_period if lyap is not None else None
    cls = classify(samples, exponent, cfg.classify_settings, size=size)
    return CaseResult(
        config=cfg,
        samples=samples,
        sample_times=strobe[:, 0],
        size=size,
        dense=dense,
        lyapunov=lyap,
        classification=cls,
        wall_time=time.perf_counter() - t_start,
    )
