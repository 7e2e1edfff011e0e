"""A case of a sweep that produced no result, and why (:class:`CaseFailure`)."""

from __future__ import annotations

from dataclasses import dataclass

#: Kinds of failed case: the FMU refused (fmi2Discard / fmi2Error), a Python exception in the
#: case, or the worker (lost, or unable to load the FMU). Only ``worker`` failures are retried by
#: ``--resume``; the others are deterministic.
FAIL_FMU, FAIL_EXCEPTION, FAIL_WORKER = "fmu", "exception", "worker"
KINDS = (FAIL_FMU, FAIL_EXCEPTION, FAIL_WORKER)


@dataclass(frozen=True)
class CaseFailure:
    """The swept value, the kind of failure (:data:`KINDS`), the reason in words (the FMU's
    status and log message, the exception, or what happened to the worker) and the worker."""

    value: float
    kind: str
    reason: str
    worker: str | None = None
