"""One FMU file, extracted once per process, with its variables by name, and the instances it
keeps for reuse.

Extraction and loading happen once per path and file version (:meth:`FmuModel.load`, cached per
process: a Dask worker loads an FMU once, whatever the number of cases it runs); the extracted
folder is removed when the process exits, or with the folder given as `workdir` (a Dask worker's
processes end without running exit handlers: its FMU goes into the worker plugin's folder,
removed when the plugin is torn down). The model also keeps the instances given back after use
(:func:`georod_tools.fmu.instance.lend`).
"""

from __future__ import annotations

import atexit
import shutil
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from fmpy import extract, read_model_description


@dataclass(frozen=True)
class Variable:
    """A model variable: value reference, type (Real, Integer, ...), causality, variability,
    start value (None when the description gives none) and unit."""

    name: str
    vr: int
    type: str
    causality: str
    variability: str
    start: str | None
    unit: str | None

    @property
    def is_integer(self) -> bool:
        return self.type in ("Integer", "Enumeration")


class FmuModel:
    """An FMU extracted once, its model description and its variables by name."""

    _cache: dict[tuple[str, float], FmuModel] = {}
    lock = threading.Lock()

    def __init__(self, path: str | Path, workdir: str | Path | None = None) -> None:
        self.path = Path(path)
        if not self.path.is_file():
            raise FileNotFoundError(f"FMU {self.path} not found (build it with scripts/build_fmus)")
        self.unzipdir = Path(tempfile.mkdtemp(prefix=f"georod_{self.path.stem}_", dir=workdir))
        atexit.register(shutil.rmtree, self.unzipdir, True)
        extract(str(self.path), unzipdir=str(self.unzipdir))
        self.md = read_model_description(str(self.unzipdir))
        if self.md.coSimulation is None:
            raise ValueError(f"{self.path} is not a Co-Simulation FMU")
        self.identifier: str = self.md.coSimulation.modelIdentifier
        self.guid: str = self.md.guid
        self.variables: dict[str, Variable] = {}
        for v in self.md.modelVariables:
            unit = getattr(v, "unit", None) or getattr(
                getattr(v, "declaredType", None), "unit", None
            )
            self.variables[v.name] = Variable(
                v.name, v.valueReference, v.type, v.causality, v.variability, v.start, unit
            )
        #: Instances given back after use (:func:`georod_tools.fmu.instance.lend`).
        self.idle: list[Any] = []

    @classmethod
    def load(cls, path: str | Path, workdir: str | Path | None = None) -> FmuModel:
        """The cached model of `path` (extracted again when the file changed); a first load
        extracts into a new folder in `workdir` (default: the system's temporary folder)."""
        p = Path(path).resolve()
        key = (str(p), p.stat().st_mtime if p.exists() else 0.0)
        with cls.lock:
            if key not in cls._cache:
                cls._cache[key] = cls(p, workdir)
            return cls._cache[key]

    @classmethod
    def forget(cls, path: str | Path) -> None:
        """Drops the cached models of `path` (before their folder is removed)."""
        p = str(Path(path).resolve())
        with cls.lock:
            for key in [k for k in cls._cache if k[0] == p]:
                del cls._cache[key]

    def variable(self, name: str) -> Variable:
        """The variable `name`; KeyError naming the FMU's variables of that kind otherwise."""
        try:
            return self.variables[name]
        except KeyError:
            raise KeyError(f"{self.identifier} has no variable {name!r}") from None

    def names(self, causality: str) -> list[str]:
        """Names of the variables of one causality (``parameter``, ``input``, ``output``)."""
        return [n for n, v in self.variables.items() if v.causality == causality]

    @property
    def parameters(self) -> list[str]:
        return self.names("parameter")

    @property
    def outputs(self) -> list[str]:
        return self.names("output")

    def start(self, name: str) -> float | None:
        """The start value of `name` as a number, or None."""
        v = self.variables.get(name)
        return None if v is None or v.start is None else float(v.start)
