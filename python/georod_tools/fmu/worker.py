"""Ship an FMU to Dask workers as bytes.

Workers may run on other machines, in another working directory, without the client's files: the
client reads the ``.fmu`` once (:class:`FmuPayload`) and registers a :class:`FmuPlugin` holding
its bytes on the scheduler, which installs it on every worker, present and future. Each worker
writes the bytes into its own local directory, checks the sha256, extracts and loads the FMU once
(:meth:`georod_tools.fmu.FmuModel.load`, cached per process) and checks that its shared library
loads on this platform. Cases then refer to the FMU by its sha256 (:func:`worker_fmu_path`),
never by the client's path.

A worker that cannot load the FMU does not fail the registration: it remembers why, answers
:func:`worker_fmu_status` with the reason, and :func:`worker_fmu_path` raises
:class:`FmuUnavailableError` naming the worker and the reason.
"""

from __future__ import annotations

import ctypes
import hashlib
import os
import shutil
import socket
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from distributed import WorkerPlugin

from georod_tools.fmu.model import FmuModel

if TYPE_CHECKING:
    from distributed import Client


@dataclass(frozen=True)
class FmuPayload:
    """An FMU file's bytes, its name and sha256 (what travels to the workers)."""

    name: str
    data: bytes
    sha256: str

    @classmethod
    def read(cls, path: str | Path) -> FmuPayload:
        p = Path(path)
        data = p.read_bytes()
        return cls(p.name, data, hashlib.sha256(data).hexdigest())

    @property
    def plugin_name(self) -> str:
        return f"georod-fmu-{self.sha256[:20]}"


# Worker-side state (one worker process): sha256 -> local .fmu path, or the reason it failed.
_LOADED: dict[str, str] = {}
_ERRORS: dict[str, str] = {}
#: How many times this process extracted and loaded an FMU (checked by the tests: once per
#: worker, not once per case).
LOAD_COUNT = 0


class FmuUnavailableError(RuntimeError):
    """No usable FMU on this worker (or on any worker)."""


def worker_address() -> str:
    """The address of the Dask worker this runs on (host:pid outside a worker)."""
    try:
        from distributed import get_worker

        return str(get_worker().address)
    except ValueError:  # not inside a worker
        return f"{socket.gethostname()}:{os.getpid()}"


def _check_library(model: FmuModel) -> None:
    """Raises with a clear reason when the FMU has no binary for this platform or it won't load."""
    import fmpy

    folder = Path(model.unzipdir) / "binaries" / fmpy.platform
    lib = folder / f"{model.identifier}{fmpy.sharedLibraryExtension}"
    if not lib.is_file():
        have = sorted(p.name for p in (Path(model.unzipdir) / "binaries").glob("*"))
        raise FmuUnavailableError(
            f"the FMU has no binary for platform {fmpy.platform} (it has: {', '.join(have)})"
        )
    ctypes.CDLL(str(lib))


class FmuPlugin(WorkerPlugin):
    """Installs one FMU (as bytes) on each worker it is registered with."""

    idempotent = True

    def __init__(self, payload: FmuPayload) -> None:
        self.payload = payload
        self.folder: str | None = None

    def setup(self, worker: Any) -> None:
        global LOAD_COUNT
        p = self.payload
        try:
            base = getattr(worker, "local_directory", None) or tempfile.gettempdir()
            self.folder = tempfile.mkdtemp(prefix="georod_fmu_", dir=base)
            path = Path(self.folder) / p.name
            path.write_bytes(p.data)
            got = hashlib.sha256(path.read_bytes()).hexdigest()
            if got != p.sha256:
                raise FmuUnavailableError(f"sha256 {got} of the written file != {p.sha256}")
            # Extracted inside the plugin's folder: a worker process ends without exit
            # handlers, so only teardown's removal of the folder cleans up after it.
            model = FmuModel.load(path, workdir=self.folder)
            _check_library(model)
            LOAD_COUNT += 1
            _LOADED[p.sha256] = str(path)
            _ERRORS.pop(p.sha256, None)
        except Exception as e:  # noqa: BLE001 - remembered, reported per worker and per case
            _LOADED.pop(p.sha256, None)
            _ERRORS[p.sha256] = f"{type(e).__name__}: {e}"

    def teardown(self, worker: Any) -> None:
        _LOADED.pop(self.payload.sha256, None)
        if self.folder:
            FmuModel.forget(Path(self.folder) / self.payload.name)
            shutil.rmtree(self.folder, ignore_errors=True)


def worker_fmu_path(sha256: str, name: str = "the FMU") -> str:
    """The local path of the FMU `sha256` on this worker; FmuUnavailableError naming the worker
    and the reason otherwise."""
    if sha256 in _LOADED:
        return _LOADED[sha256]
    why = _ERRORS.get(sha256, "it was never installed here (FmuPlugin not registered)")
    raise FmuUnavailableError(f"worker {worker_address()} cannot load {name}: {why}")


def worker_fmu_status(sha256: str) -> dict[str, Any]:
    """Run on each worker (``client.run``): whether the FMU is loaded, why not, and the worker's
    host and georod_tools version (recorded in run.json)."""
    from georod_tools import __version__

    return {
        "host": socket.gethostname(),
        "pid": os.getpid(),
        "cwd": os.getcwd(),
        "georod_tools": __version__,
        "fmu_loaded": sha256 in _LOADED,
        "error": None if sha256 in _LOADED else _ERRORS.get(sha256, "not installed"),
        "loads": LOAD_COUNT,
    }


def install(client: Client, payload: FmuPayload) -> dict[str, dict[str, Any]]:
    """Registers the FMU on every worker of `client`'s cluster and returns each worker's
    :func:`worker_fmu_status`. Raises FmuUnavailableError naming every worker and its reason
    when none can load it."""
    try:
        client.register_plugin(FmuPlugin(payload), name=payload.plugin_name)
    except Exception as e:  # noqa: BLE001 - e.g. georod_tools missing on a worker
        raise FmuUnavailableError(
            f"could not install {payload.name} on the workers ({type(e).__name__}: {e}); "
            "every worker needs georod_tools installed"
        ) from e
    status: dict[str, dict[str, Any]] = client.run(worker_fmu_status, payload.sha256)
    if status and not any(s["fmu_loaded"] for s in status.values()):
        lines = "\n".join(f"  worker {a}: {s['error']}" for a, s in sorted(status.items()))
        raise FmuUnavailableError(f"no worker could load {payload.name}:\n{lines}")
    return status
