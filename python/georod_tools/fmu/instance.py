"""One FMU instance driven through fmpy's FMU2Slave: parameters by name, communication steps,
outputs by name, input ramps, and the FMU state as an opaque blob.

Errors: a call that does not return fmi2OK raises :class:`FmuError` with the returned status and
the FMU's last log message (which says why).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from typing import TYPE_CHECKING, TypeVar

import numpy as np
from fmpy.fmi2 import FMU2Slave

from georod_tools.fmu.log import MessageLog

if TYPE_CHECKING:
    from georod_tools.fmu.model import FmuModel

T = TypeVar("T")

#: fmi2Status names by value.
FMI2_STATUS = ("fmi2OK", "fmi2Warning", "fmi2Discard", "fmi2Error", "fmi2Fatal", "fmi2Pending")


class FmuError(RuntimeError):
    """An FMI call failed; the message carries the returned status and what the FMU logged.

    status: the fmi2Status the call returned (2 = fmi2Discard, 3 = fmi2Error, ...), or None when
    the failure was not a status.
    """

    def __init__(self, message: str, status: int | None = None) -> None:
        super().__init__(message)
        self.status = status


class Instance:
    """One FMU instance. ``initialize`` sets parameters by name and leaves initialization mode;
    ``step`` takes one communication step; ``reader`` makes a fast getter of several outputs."""

    def __init__(self, model: FmuModel, name: str = "georod") -> None:
        self.model = model
        self.log = MessageLog()
        self.slave = FMU2Slave(
            guid=model.guid,
            unzipDirectory=str(model.unzipdir),
            modelIdentifier=model.identifier,
            instanceName=name,
        )
        self._alive = False
        self.call(lambda: self.slave.instantiate(callbacks=self.log.callbacks, loggingOn=False))
        self._alive = True

    def call(self, fn: Callable[[], T], what: str = "") -> T:
        """Calls `fn`, turning fmpy's exception for a status above fmi2Warning into FmuError
        with the FMU's last log message."""
        try:
            return fn()
        except Exception as e:  # fmpy raises FMICallException on status > fmi2Warning
            status = getattr(e, "status", None)
            returned = ""
            if what and isinstance(status, int) and 0 <= status < len(FMI2_STATUS):
                returned = f" returned {FMI2_STATUS[status]}"
            raise FmuError(f"{what or e}{returned}: {self.log.last()}", status) from e

    def set(self, name: str, value: float) -> None:
        """Sets a parameter or input by name (Integer or Real as the model description says)."""
        m = self.model
        v = m.variables.get(name)
        if v is None or v.causality not in ("parameter", "input"):
            raise ValueError(
                f"{m.identifier} has no parameter {name!r}; its parameters are "
                f"{', '.join(m.parameters)}"
            )
        if v.is_integer:
            if float(value) != int(value):
                raise ValueError(f"parameter {name} is an Integer, got {value}")
            self.call(
                lambda: self.slave.setInteger([v.vr], [int(value)]), f"setting {name}={value}"
            )
        else:
            self.call(lambda: self.slave.setReal([v.vr], [float(value)]), f"setting {name}={value}")

    def initialize(self, params: Mapping[str, float], start_time: float = 0.0) -> None:
        """setupExperiment at `start_time`, the parameters, and initialization (the FMU's static
        initial state)."""
        self.call(lambda: self.slave.setupExperiment(startTime=start_time), "fmi2SetupExperiment")
        for name, value in params.items():
            self.set(name, value)
        self.call(self.slave.enterInitializationMode, "fmi2EnterInitializationMode")
        self.call(self.slave.exitInitializationMode, "fmi2ExitInitializationMode")

    def ramp(self, name: str, value: float, slope: float) -> None:
        """Input `name` at `value` now, changing at `slope` per second over the next step (the
        FMU follows the first derivative of an input over a communication step)."""
        vr = self.model.variable(name).vr
        self.call(lambda: self.slave.setReal([vr], [float(value)]), f"setting {name}={value}")
        self.call(
            lambda: self.slave.setRealInputDerivatives([vr], [1], [float(slope)]),
            f"fmi2SetRealInputDerivatives of {name}",
        )

    def step(self, t: float, h: float) -> None:
        """One communication step from `t` of length `h`."""
        self.call(lambda: self.slave.doStep(t, h), f"fmi2DoStep at t = {t:.6g}")

    def reader(self, names: Sequence[str]) -> Callable[[], np.ndarray]:
        """A function returning the outputs `names` now, in one fmi2GetReal."""
        vrs = [self.model.variable(n).vr for n in names]
        get = self.slave.getReal
        return lambda: np.asarray(get(vrs), dtype=float)

    def get(self, names: Sequence[str]) -> np.ndarray:
        return self.reader(names)()

    def state_blob(self) -> bytes:
        """The instance's FMU state serialized (fmi2SerializeFMUstate): an opaque blob, never
        read here, for :meth:`load_state_blob` of an instance of the same FMU."""
        state = self.call(self.slave.getFMUstate, "fmi2GetFMUstate")
        try:
            return bytes(self.call(lambda: self.slave.serializeFMUstate(state), "serialize"))
        finally:
            self.slave.freeFMUstate(state)

    def load_state_blob(self, blob: bytes) -> None:
        """Puts the instance in the state `blob` (fmi2DeSerializeFMUstate, fmi2SetFMUstate):
        parameters, time and motion as they were in the instance that serialized it."""
        state = self.call(lambda: self.slave.deSerializeFMUstate(blob), "fmi2DeSerializeFMUstate")
        try:
            self.call(lambda: self.slave.setFMUstate(state), "fmi2SetFMUstate")
        finally:
            self.slave.freeFMUstate(state)

    def reset_quietly(self) -> bool:
        """fmi2Reset (back to instantiated, default parameters); False when that fails."""
        if not self._alive:
            return False
        try:
            self.call(self.slave.reset, "fmi2Reset")
            return True
        except FmuError:
            return False

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


@contextmanager
def lend(model: FmuModel, name: str = "georod") -> Iterator[Instance]:
    """An instantiated (not yet initialized) instance of `model`, reused when one is idle: a
    worker keeps its instances, and the core its meshed rod and static initial state, from case to
    case (the FMU reuses them after ``fmi2Reset`` when the fixed parameters agree). Given back
    after ``fmi2Reset``, also after a failure (the FMU recovers from any state but a fatal one);
    an instance that cannot be reset is freed instead."""
    with model.lock:
        inst = model.idle.pop() if model.idle else None
    if inst is None:
        inst = Instance(model, name)
    inst.log.messages.clear()  # errors must not quote an earlier case's message
    try:
        yield inst
    finally:
        if inst.reset_quietly():
            with model.lock:
                model.idle.append(inst)
        else:
            inst.close()
