"""The FMU's log messages, routed to the instance that logged them.

fmpy formats the variadic printf arguments of the logger in a native proxy that keeps one
process-wide Python target; a callback per instance registered there would leave a dangling
function pointer once the instance is gone. So every instance registers the same immortal
dispatcher, which routes each message by the ``componentEnvironment`` the FMU hands back (FMI 2.0:
the first argument of the logger).
"""

from __future__ import annotations

import itertools
import weakref
from ctypes import byref, c_void_p

from fmpy import calloc, free
from fmpy.fmi2 import (
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)

#: How many messages each instance keeps (errors quote the last one).
KEEP = 20


class MessageLog:
    """The last :data:`KEEP` messages of one instance, and the callbacks to instantiate it with."""

    _ids = itertools.count(1)

    def __init__(self) -> None:
        self.messages: list[str] = []
        self.id = next(MessageLog._ids)
        _LOGS[self.id] = self
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = _DISPATCHER
        self.callbacks.allocateMemory = _CALLOC
        self.callbacks.freeMemory = _FREE
        self.callbacks.componentEnvironment = c_void_p(self.id)
        try:
            from fmpy.logging import addLoggerProxy

            addLoggerProxy(byref(self.callbacks))
        except Exception:  # noqa: BLE001 - without the proxy the raw format string is logged
            pass

    def append(self, text: str) -> None:
        self.messages.append(text)
        del self.messages[:-KEEP]

    def last(self) -> str:
        return self.messages[-1] if self.messages else "(no message logged)"


_LOGS: weakref.WeakValueDictionary[int, MessageLog] = weakref.WeakValueDictionary()


def _text(b: object) -> str:
    return b.decode("utf-8", "replace") if isinstance(b, bytes) else str(b or "")


def _dispatch(
    env: int | None, instance: bytes, status: int, category: bytes, message: bytes
) -> None:
    log = _LOGS.get(env) if env else None
    if log is not None:
        log.append(_text(message))


# Module-level, hence alive for the whole process (the native proxy keeps a raw pointer to it).
_DISPATCHER = fmi2CallbackLoggerTYPE(_dispatch)
_CALLOC = fmi2CallbackAllocateMemoryTYPE(calloc)
_FREE = fmi2CallbackFreeMemoryTYPE(free)
