"""Shared helpers for the FMU tests: paths, instances driven through fmpy.fmi2.FMU2Slave, log
capture.

Variables are addressed by NAME (docs/scenes.md, "What every FMU has"); value references are
looked up in each FMU's own modelDescription.xml, never hard-coded.
"""

from __future__ import annotations

import math
import os
import subprocess
import weakref
from collections.abc import Mapping, Sequence
from ctypes import byref, c_void_p
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from fmpy import calloc, free
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)
from fmpy.model_description import ModelDescription

REPO = Path(__file__).resolve().parents[2]
FMU_DIR = REPO / "target" / "fmu"
#: The FMI 3.0 FMUs of the same scene files (scripts/build_fmus writes both versions).
FMU3_DIR = REPO / "target" / "fmu3"
#: What scripts/build_libs builds (scripts/build_fmus runs it): the georod command and the
#: linux64 (glibc 2.17) and win64 libraries.
LIBS_DIR = REPO / "target" / "libs"
GEOROD_CLI = LIBS_DIR / "georod"
GEOROD_LIB = LIBS_DIR / "libgeorod.so"
#: The paper's scenes, whose FMUs these tests exercise (scene files in scenes/).
SCENES: tuple[str, ...] = tuple(sorted(p.stem for p in (REPO / "scenes").glob("*.toml")))
#: Every scene file that scripts/build_fmus packages into FMU_DIR/<stem>.fmu: the paper's scenes
#: and the examples.
SCENE_FILES: tuple[Path, ...] = tuple(
    sorted((REPO / "scenes").glob("*.toml")) + sorted((REPO / "examples").glob("*.toml"))
)

#: C math functions the FMU libraries must not import: they take them from the libm crate, the
#: same bits on every platform (test_fmu_platforms.py, test_fmu_win64.py).
C_MATH = {
    *"sin cos tan asin acos atan atan2 sinh cosh tanh asinh acosh atanh exp exp2 expm1".split(),
    *"log log2 log10 log1p pow hypot cbrt sincos fmod remainder erf erfc lgamma tgamma".split(),
}

# FMI 2.0 status codes (fmi2Status)
OK, WARNING, DISCARD, ERROR, FATAL = 0, 1, 2, 3, 4
STATUS_LABEL = ["OK", "Warning", "Discard", "Error", "Fatal", "Pending"]
# fmi2StatusKind
LAST_SUCCESSFUL_TIME = 2

Value = float | int


@dataclass
class FmuInfo:
    """One packaged FMU, extracted once per test session."""

    scene: str
    path: Path
    unzipdir: Path
    md: ModelDescription
    vr: dict[str, int] = field(default_factory=dict)
    types: dict[str, str] = field(default_factory=dict)
    start: dict[str, str] = field(default_factory=dict)

    @classmethod
    def from_model_description(
        cls, scene: str, path: Path, unzipdir: Path, md: ModelDescription
    ) -> FmuInfo:
        info = cls(scene=scene, path=path, unzipdir=unzipdir, md=md)
        for v in md.modelVariables:
            info.vr[v.name] = v.valueReference
            info.types[v.name] = v.type
            if v.start is not None:
                info.start[v.name] = v.start
        return info

    @property
    def library(self) -> Path:
        ident = self.md.coSimulation.modelIdentifier
        return self.unzipdir / "binaries" / "linux64" / f"{ident}.so"


@dataclass
class LogRecord:
    instance: str
    status: int
    category: str
    message: str


class LogCapture:
    """An fmi2CallbackFunctions whose logger appends the FMU's messages to `records`.

    fmpy formats the variadic printf arguments in a native proxy (fmpy.logging.addLoggerProxy)
    that keeps ONE process-wide Python target: registering a per-capture callback there would
    leave a dangling function pointer once the capture is garbage collected (a segfault in a
    later, unrelated instance). So every capture registers the same immortal dispatcher, which
    routes each message by the componentEnvironment the FMU hands back (FMI 2.0: the first
    logger argument is `callbacks->componentEnvironment`)."""

    _next_id = 1

    def __init__(self, echo: bool = False) -> None:
        self.records: list[LogRecord] = []
        self.echo = echo
        self.id = LogCapture._next_id
        LogCapture._next_id += 1
        _CAPTURES[self.id] = self
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = _DISPATCHER
        self.callbacks.allocateMemory = _CALLOC
        self.callbacks.freeMemory = _FREE
        self.callbacks.componentEnvironment = c_void_p(self.id)
        _add_proxy(self.callbacks)

    def append(self, rec: LogRecord) -> None:
        self.records.append(rec)
        if self.echo:
            print(f"[{STATUS_LABEL[rec.status] if rec.status < 6 else rec.status}] {rec.message}")

    def clear(self) -> None:
        self.records.clear()

    def messages(self) -> list[str]:
        return [r.message for r in self.records]

    def text(self) -> str:
        return "\n".join(self.messages())


_CAPTURES: weakref.WeakValueDictionary[int, LogCapture] = weakref.WeakValueDictionary()
UNROUTED: list[LogRecord] = []  # messages of instances without a capture (or a foreign env)


def _text(b: object) -> str:
    return b.decode("utf-8", "replace") if isinstance(b, bytes) else str(b or "")


def _dispatch(
    env: int | None, instance: bytes, status: int, category: bytes, message: bytes
) -> None:
    rec = LogRecord(_text(instance), int(status), _text(category), _text(message))
    capture = _CAPTURES.get(env) if env else None
    if capture is not None:
        capture.append(rec)
    else:
        UNROUTED.append(rec)
        print(f"[{rec.instance} status {rec.status}] {rec.message}")


# Module-level, hence alive for the whole process (the native proxy keeps a raw pointer to it).
_DISPATCHER = fmi2CallbackLoggerTYPE(_dispatch)
_CALLOC = fmi2CallbackAllocateMemoryTYPE(calloc)
_FREE = fmi2CallbackFreeMemoryTYPE(free)


def _add_proxy(callbacks: fmi2CallbackFunctions) -> None:
    from fmpy.logging import addLoggerProxy

    addLoggerProxy(byref(callbacks))


def new_slave(info: FmuInfo, instance_name: str | None = None) -> FMU2Slave:
    """Loads the FMU's library (not yet instantiated)."""
    return FMU2Slave(
        guid=info.md.guid,
        unzipDirectory=str(info.unzipdir),
        modelIdentifier=info.md.coSimulation.modelIdentifier,
        instanceName=instance_name or info.scene,
    )


def set_values(slave: FMU2Slave, info: FmuInfo, values: Mapping[str, Value]) -> None:
    """Sets variables by name, Real or Integer according to the model description."""
    for name, value in values.items():
        vr = info.vr[name]
        if info.types[name] in ("Integer", "Enumeration"):
            slave.setInteger([vr], [int(value)])
        else:
            slave.setReal([vr], [float(value)])


def get_reals(slave: FMU2Slave, info: FmuInfo, names: Sequence[str]) -> list[float]:
    return slave.getReal([info.vr[n] for n in names])


def instantiate(
    info: FmuInfo,
    params: Mapping[str, Value] | None = None,
    instance_name: str | None = None,
    log: LogCapture | None = None,
    initialize: bool = True,
    start_time: float = 0.0,
) -> FMU2Slave:
    """A slave instantiated, parameters set and (by default) initialized at `start_time`."""
    slave = new_slave(info, instance_name)
    slave.instantiate(
        callbacks=log.callbacks if log is not None else None, loggingOn=log is not None
    )
    slave.setupExperiment(startTime=start_time)
    if params:
        set_values(slave, info, params)
    if initialize:
        slave.enterInitializationMode()
        slave.exitInitializationMode()
    return slave


def release(slave: FMU2Slave) -> None:
    """Terminate (if possible) and free; never raises."""
    try:
        slave.terminate()
    except Exception:  # noqa: BLE001 - terminate may be refused in the error state
        pass
    slave.freeInstance()


OUTPUTS: tuple[str, ...] = ("w_mid", "v_mid", "E_kin", "E_strain")


def run_steps(
    slave: FMU2Slave,
    info: FmuInfo,
    h: float,
    n: int,
    k0: int = 0,
    names: Sequence[str] = OUTPUTS,
) -> np.ndarray:
    """Steps n communication steps of length h from t = k0*h (time from a step counter) and
    returns the outputs `names` at t = k0*h .. (k0+n)*h, shape (n + 1, len(names))."""
    vrs = [info.vr[x] for x in names]
    rows = [slave.getReal(vrs)]
    for k in range(k0, k0 + n):
        slave.doStep(k * h, h)
        rows.append(slave.getReal(vrs))
    return np.asarray(rows, dtype=float)


def trajectory(
    info: FmuInfo,
    params: Mapping[str, Value] | None,
    h: float,
    n: int,
    names: Sequence[str] = OUTPUTS,
    instance_name: str | None = None,
) -> np.ndarray:
    """A fresh instance run for n steps of h; outputs at every communication point."""
    slave = instantiate(info, params, instance_name=instance_name)
    try:
        return run_steps(slave, info, h, n, names=names)
    finally:
        release(slave)


def max_rel_diff(a: np.ndarray, b: np.ndarray) -> float:
    """max |a - b| / max |a| (0 when both vanish)."""
    scale = float(np.max(np.abs(a)))
    diff = float(np.max(np.abs(a - b)))
    return diff / scale if scale > 0 else diff


def period(omega: float) -> float:
    return 2.0 * math.pi / omega


def run_cmd(
    cmd: Sequence[str | os.PathLike[str]],
    timeout: float = 900.0,
    env: Mapping[str, str] | None = None,
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(c) for c in cmd],
        cwd=REPO,
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


def stale_fmus(scene_files: Sequence[Path], fmu_dir: Path, library: Path) -> list[str]:
    """Why the FMUs of `scene_files` (fmu_dir/<stem>.fmu) must be packaged again: each one that is
    missing, older than `library` (when it exists) or older than its scene file. Empty when every
    FMU is up to date."""
    reasons = []
    lib_time = library.stat().st_mtime if library.exists() else None
    for scene in scene_files:
        fmu = fmu_dir / f"{scene.stem}.fmu"
        if not fmu.exists():
            reasons.append(f"{fmu.name} is missing")
            continue
        fmu_time = fmu.stat().st_mtime
        if lib_time is not None and fmu_time < lib_time:
            reasons.append(f"{fmu.name} is older than {library.name}")
        if fmu_time < scene.stat().st_mtime:
            reasons.append(f"{fmu.name} is older than its scene file {scene.name}")
    return reasons
