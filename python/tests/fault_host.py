"""A hostile FMI 2.0 host for test_fmu_fault_injection.py (its scenarios are in
fault_scenarios.py, which runs as its own process: a crash of the FMU then fails one test
instead of killing the test run).

Raw ctypes calls (every status is returned, nothing raises); variables by name from the FMU's
modelDescription.xml. Before each hostile call a `try ...` line goes to stderr, so a crash names
its cause.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from ctypes import (
    CDLL,
    POINTER,
    addressof,
    byref,
    c_char_p,
    c_double,
    c_int,
    c_size_t,
    c_uint,
    c_void_p,
    create_string_buffer,
)
from pathlib import Path

import fmpy

from helpers import ERROR, LAST_SUCCESSFUL_TIME, OK, OUTPUTS, LogCapture

P = POINTER
C = c_void_p  # fmi2Component, fmi2FMUstate
PROTOTYPES: dict[str, tuple[object, list[object]]] = {
    "fmi2Instantiate": (C, [c_char_p, c_int, c_char_p, c_char_p, C, c_int, c_int]),
    "fmi2FreeInstance": (None, [C]),
    "fmi2SetupExperiment": (c_int, [C, c_int, c_double, c_double, c_int, c_double]),
    "fmi2EnterInitializationMode": (c_int, [C]),
    "fmi2ExitInitializationMode": (c_int, [C]),
    "fmi2DoStep": (c_int, [C, c_double, c_double, c_int]),
    "fmi2GetReal": (c_int, [C, P(c_uint), c_size_t, P(c_double)]),
    "fmi2SetReal": (c_int, [C, P(c_uint), c_size_t, P(c_double)]),
    "fmi2SetInteger": (c_int, [C, P(c_uint), c_size_t, P(c_int)]),
    "fmi2GetRealStatus": (c_int, [C, c_int, P(c_double)]),
    "fmi2GetFMUstate": (c_int, [C, P(C)]),
    "fmi2SetFMUstate": (c_int, [C, C]),
    "fmi2FreeFMUstate": (c_int, [C, P(C)]),
    "fmi2SerializedFMUstateSize": (c_int, [C, C, P(c_size_t)]),
    "fmi2SerializeFMUstate": (c_int, [C, C, C, c_size_t]),
    "fmi2DeSerializeFMUstate": (c_int, [C, C, c_size_t, P(C)]),
}
H = 1e-5  # one internal sub-step at the default dt_max
NOT_LIVE = "not a live FMU state of this instance"
#: Every byte of this many at the start of a serialized state is flipped, whatever the sample:
#: the versioned header, the GUID and the scene name lie there (their layout is not read here).
HEAD_BYTES = 256


class Fmu:
    """The extracted FMU: its library with typed entry points, and its variables by name."""

    def __init__(self, unzipdir: Path) -> None:
        md = fmpy.read_model_description(str(unzipdir))
        ident = md.coSimulation.modelIdentifier
        self.lib = CDLL(str(unzipdir / "binaries" / "linux64" / f"{ident}.so"))
        self.f: dict[str, Callable[..., int]] = {}
        for name, (restype, argtypes) in PROTOTYPES.items():
            fn = self.lib[name]  # a fresh function object: fmpy's typed ones stay untouched
            fn.restype, fn.argtypes = restype, argtypes
            self.f[name] = fn
        self.guid = md.guid.encode()
        self.resources = (unzipdir / "resources").as_uri().encode()
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.types = {v.name: v.type for v in md.modelVariables}


class Host:
    """One instance; every call returns the FMI status."""

    def __init__(self, fmu: Fmu, name: str, params: dict[str, float], stop: float | None = None):
        self.fmu, self.f, self.log = fmu, fmu.f, LogCapture()
        self.c = self.f["fmi2Instantiate"](
            name.encode(), 1, fmu.guid, fmu.resources, addressof(self.log.callbacks), 0, 0
        )
        assert self.c, f"fmi2Instantiate failed: {self.log.text()}"
        status = self.f["fmi2SetupExperiment"](self.c, 0, 0.0, 0.0, stop is not None, stop or 0.0)
        assert status == OK
        for k, v in params.items():
            vr = (c_uint * 1)(fmu.vr[k])
            if fmu.types[k] in ("Integer", "Enumeration"):
                assert self.f["fmi2SetInteger"](self.c, vr, 1, (c_int * 1)(int(v))) == OK
            else:
                assert self.f["fmi2SetReal"](self.c, vr, 1, (c_double * 1)(v)) == OK
        assert self.f["fmi2EnterInitializationMode"](self.c) == OK
        assert self.f["fmi2ExitInitializationMode"](self.c) == OK, self.log.text()

    def time(self) -> float:
        t = c_double(math.nan)
        assert self.f["fmi2GetRealStatus"](self.c, LAST_SUCCESSFUL_TIME, byref(t)) == OK
        return t.value

    def step(self, h: float = H) -> int:
        return int(self.f["fmi2DoStep"](self.c, self.time(), h, 1))

    def outputs(self) -> list[float]:
        vrs = (c_uint * len(OUTPUTS))(*(self.fmu.vr[n] for n in OUTPUTS))
        out = (c_double * len(OUTPUTS))()
        assert self.f["fmi2GetReal"](self.c, vrs, len(OUTPUTS), out) == OK
        return list(out)

    def get_state(self, slot: int | None = None) -> tuple[int, int | None]:
        s = c_void_p(slot)
        return int(self.f["fmi2GetFMUstate"](self.c, byref(s))), s.value

    def set_state(self, h: int | None) -> int:
        return int(self.f["fmi2SetFMUstate"](self.c, h))

    def free_state(self, h: int | None) -> tuple[int, int | None]:
        s = c_void_p(h)
        return int(self.f["fmi2FreeFMUstate"](self.c, byref(s))), s.value

    def size(self, h: int | None) -> tuple[int, int]:
        n = c_size_t(987654321)
        return int(self.f["fmi2SerializedFMUstateSize"](self.c, h, byref(n))), n.value

    def serialize(self, h: int | None, size: int | None = None) -> tuple[int, bytes]:
        if size is None:
            _, size = self.size(h)
        buf = create_string_buffer(b"\xa5" * size, size)
        return int(self.f["fmi2SerializeFMUstate"](self.c, h, buf, size)), buf.raw

    def deserialize(self, blob: bytes, slot: int | None = None) -> tuple[int, int | None]:
        buf = create_string_buffer(blob, len(blob))
        s = c_void_p(slot)
        return int(self.f["fmi2DeSerializeFMUstate"](self.c, buf, len(blob), byref(s))), s.value

    def last_message(self) -> str:
        return self.log.records[-1].message if self.log.records else ""


class Checker:
    """Counts the checks and keeps the first failures."""

    def __init__(self) -> None:
        self.checked = 0
        self.failures: list[str] = []

    def __call__(self, ok: bool, what: str) -> None:
        self.checked += 1
        if not ok and len(self.failures) < 20:
            self.failures.append(what)

    def refused(self, host: Host, status: int, func: str, part: str, what: str) -> None:
        """`status` is fmi2Error with a logged message of `func` that contains `part`."""
        msg = host.last_message()
        ok = status == ERROR and msg.startswith(f"{func}: ") and part in msg
        self(ok, f"{what}: status {status}, message {msg!r}")
        host.log.clear()

    def like_twin(self, host: Host, twin: Host, what: str) -> None:
        """The instance still steps, exactly like its untouched twin."""
        ok = host.step() == OK and twin.step() == OK
        a, b = host.outputs(), twin.outputs()
        self(ok and a == b and all(map(math.isfinite, a)), f"{what}: not like the twin {a} {b}")


def attempt(what: str) -> str:
    print(f"try {what}", file=sys.stderr, flush=True)
    return what


def pair(fmu: Fmu, elements: int) -> tuple[Host, Host]:
    """An instance and its twin, 3 steps into a loaded run."""
    params = {"F": 0.9, "elements": elements}
    a, b = Host(fmu, "subject", params), Host(fmu, "twin", params)
    for _ in range(3):
        assert a.step() == OK and b.step() == OK
    return a, b


def good_state(host: Host) -> tuple[int, bytes]:
    status, s = host.get_state()
    assert status == OK and s
    status, blob = host.serialize(s)
    assert status == OK
    return s, blob
