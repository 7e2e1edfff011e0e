"""Run records: what every output folder of the command line keeps beside its data.

- :func:`prepare_output`: a run never overwrites an earlier run's output silently. An existing
  non-empty folder is refused unless it is resumed (its ``run.json`` is kept) or overwritten
  (only a folder that holds a ``run.json``, i.e. one of ours, is emptied); a default folder gets
  a fresh timestamped name.
- :class:`RunRecord`: ``run.json``, the settings of the run (compared on ``--resume``), the FMU
  (path, GUID, sha256), the state and times, and one entry per invocation (command line, host,
  working directory, options, Python / numpy / fmpy / dask versions, start and end time).
- :class:`ResultLog`: ``results.jsonl``, one JSON line per finished case, flushed and synced as
  each case finishes, so a killed run keeps every case it finished.

JSON numbers are Python's ``repr`` of the float, which reads back bit for bit (NaN is written as
``NaN``, as Python's json module does).
"""

from __future__ import annotations

import datetime as dt
import hashlib
import json
import os
import platform
import shlex
import shutil
import socket
import sys
from collections.abc import Iterable, Mapping
from dataclasses import asdict
from pathlib import Path
from typing import Any

RUN_JSON = "run.json"
RESULTS = "results.jsonl"
FORMAT = "georod_tools run record 1"


class OutputRefusedError(ValueError):
    """The output folder cannot be used as asked (message says why and what to pass)."""


def now() -> str:
    """Local time with its UTC offset, to the second (ISO 8601)."""
    return dt.datetime.now().astimezone().isoformat(timespec="seconds")


def fresh_folder(parent: Path, name: str) -> Path:
    """``parent/<name>_<YYYYmmdd-HHMMSS>``, with ``-2``, ``-3``, ... if that exists already."""
    stamp = dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    base = parent / f"{name}_{stamp}"
    path, n = base, 1
    while path.exists():
        n += 1
        path = base.with_name(f"{base.name}-{n}")
    return path


def prepare_output(
    out: Path, resume: bool = False, overwrite: bool = False, resumable: bool = True
) -> Path:
    """Checks (and creates) the output folder `out` for a new run, a resumed one or an overwrite
    (`resumable`: the command has ``--resume``, which the refusal then offers).

    Refuses (OutputRefusedError): a non-empty folder without `resume` or `overwrite`; `resume`
    of a folder without run.json; `overwrite` of a non-empty folder without run.json (not
    written by this tool: remove it yourself); both flags; a path that is a file.
    """
    if resume and overwrite:
        raise OutputRefusedError("--resume and --overwrite exclude each other")
    if out.exists() and not out.is_dir():
        raise OutputRefusedError(f"--out {out}: is a file, not a folder")
    entries = sorted(p.name for p in out.iterdir()) if out.is_dir() else []
    has_record = RUN_JSON in entries
    if resume:
        if not has_record:
            raise OutputRefusedError(
                f"--resume: {out} holds no {RUN_JSON} of an earlier run; nothing to resume"
            )
        return out
    if entries and not overwrite:
        shown = ", ".join(entries[:5]) + (", ..." if len(entries) > 5 else "")
        resume_hint = "--resume to continue the run recorded there, " if resumable else ""
        raise OutputRefusedError(
            f"--out {out}: the folder is not empty ({shown}); pass {resume_hint}--overwrite to "
            "replace it, or choose another --out"
        )
    if entries:  # overwrite
        if not has_record:
            raise OutputRefusedError(
                f"--overwrite: {out} holds no {RUN_JSON}, so it was not written by georod_tools; "
                "refusing to delete its contents (remove them yourself or choose another --out)"
            )
        for p in out.iterdir():
            if p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
            else:
                p.unlink()
    out.mkdir(parents=True, exist_ok=True)
    return out


def sha256_file(path: str | Path) -> str:
    h = hashlib.sha256()
    with Path(path).open("rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def fmu_info(path: str | Path, guid: str, identifier: str) -> dict[str, Any]:
    p = Path(path).resolve()
    return {
        "path": str(p),
        "sha256": sha256_file(p),
        "guid": guid,
        "model_identifier": identifier,
        "bytes": p.stat().st_size,
    }


def versions() -> dict[str, str]:
    """Versions of Python, the platform and the packages the results depend on."""
    from importlib.metadata import PackageNotFoundError, version

    from georod_tools import __version__

    out = {"georod_tools": __version__, "python": sys.version.split()[0]}
    out["platform"] = platform.platform()
    for pkg in ("numpy", "fmpy", "dask", "distributed", "matplotlib"):
        try:
            out[pkg] = version(pkg)
        except PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def jsonable(x: Any) -> Any:
    """`x` as plain JSON data (dataclasses, paths, tuples, numpy scalars and arrays)."""
    if hasattr(x, "__dataclass_fields__"):
        return jsonable(asdict(x))
    if isinstance(x, Mapping):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, Path):
        return str(x)
    if hasattr(x, "tolist"):  # numpy
        return x.tolist()
    return x


def options(args: Any) -> dict[str, Any]:
    """The parsed options of an argparse Namespace (private ``_`` entries and the function that
    runs the command left out)."""
    return {k: v for k, v in vars(args).items() if not k.startswith("_") and not callable(v)}


def normalized(x: Any) -> Any:
    """`x` as it reads back from JSON (tuples become lists), for comparisons with a record."""
    return json.loads(json.dumps(jsonable(x)))


def differences(
    recorded: Mapping[str, Any], now_: Mapping[str, Any], prefix: str = ""
) -> list[str]:
    """``key: recorded -> now`` for every setting that differs (nested dicts by dotted key)."""
    out = []
    for k in sorted(set(recorded) | set(now_)):
        a, b = recorded.get(k, "(absent)"), now_.get(k, "(absent)")
        if isinstance(a, dict) and isinstance(b, dict):
            out += differences(a, b, f"{prefix}{k}.")
        elif a != b:
            out.append(f"{prefix}{k}: {a!r} recorded, {b!r} now")
    return out


class RunRecord:
    """``run.json`` of one output folder (written atomically: temporary file, then rename)."""

    def __init__(self, folder: Path, data: dict[str, Any]) -> None:
        self.folder, self.data = folder, data

    @property
    def path(self) -> Path:
        return self.folder / RUN_JSON

    @classmethod
    def create(
        cls, folder: Path, command: str, settings: Mapping[str, Any], fmu: Mapping[str, Any]
    ) -> RunRecord:
        """A new record (not yet saved). `fmu`: :func:`fmu_info` of the FMU, or such infos by
        name when a run uses several FMUs."""
        data = {
            "format": FORMAT,
            "command": command,
            "status": "running",
            "start_time": now(),
            "end_time": None,
            "fmu": dict(fmu),
            "settings": normalized(settings),
            "sessions": [],
        }
        return cls(folder, data)

    @classmethod
    def load(cls, folder: Path) -> RunRecord:
        path = folder / RUN_JSON
        try:
            data = json.loads(path.read_text())
        except (OSError, ValueError) as e:
            raise OutputRefusedError(f"--resume: cannot read {path}: {e}") from e
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise OutputRefusedError(f"--resume: {path} is not a georod_tools run record")
        return cls(folder, data)

    def check_resumable(self, command: str, settings: Mapping[str, Any]) -> None:
        """Refuses to resume a run of another command or with other settings (lists them)."""
        if self.data.get("command") != command:
            raise OutputRefusedError(
                f"--resume: {self.folder} holds a {self.data.get('command')!r} run, "
                f"not a {command!r} run"
            )
        diff = differences(self.data.get("settings", {}), normalized(settings))
        if diff:
            raise OutputRefusedError(
                f"--resume: the settings differ from those recorded in {self.path}:\n  "
                + "\n  ".join(diff)
                + "\nrerun with the recorded settings, or choose another --out"
            )

    def start_session(self, argv: Iterable[str], options: Mapping[str, Any]) -> dict[str, Any]:
        """Appends this invocation (marking earlier ones that never ended as interrupted)."""
        for s in self.data["sessions"]:
            if s.get("status") == "running":
                s["status"] = "interrupted"
        argv = list(argv)
        session = {
            "command_line": shlex.join(["python", "-m", "georod_tools", *argv]),
            "argv": argv,
            "cwd": os.getcwd(),
            "host": socket.gethostname(),
            "pid": os.getpid(),
            "start_time": now(),
            "end_time": None,
            "status": "running",
            "versions": versions(),
            "options": normalized(options),
        }
        self.data["sessions"].append(session)
        self.data["status"] = "running"
        self.data["end_time"] = None
        self.save()
        return session

    def finish(self, status: str = "complete", **fields: Any) -> None:
        """Ends the current session (and the run when `status` is complete) with `fields`."""
        t = now()
        session = self.data["sessions"][-1]
        session.update(status=status, end_time=t)
        self.data["status"] = status
        if status == "complete":
            self.data["end_time"] = t
        self.data.update(normalized(fields))
        self.save()

    def save(self) -> None:
        self.folder.mkdir(parents=True, exist_ok=True)
        tmp = self.path.with_suffix(".json.tmp")
        tmp.write_text(json.dumps(self.data, indent=1) + "\n")
        os.replace(tmp, self.path)


class ResultLog:
    """``results.jsonl``: append-only, one JSON object per line, synced per line."""

    def __init__(self, folder: Path) -> None:
        self.path = folder / RESULTS

    def read(self) -> list[dict[str, Any]]:
        """Every complete line. A last line cut short by a kill is dropped and truncated away,
        so that the next append starts on a fresh line."""
        if not self.path.exists():
            return []
        raw = self.path.read_bytes()
        keep = raw.rfind(b"\n") + 1
        if keep < len(raw):
            with self.path.open("r+b") as f:
                f.truncate(keep)
        out = []
        for n, line in enumerate(raw[:keep].decode().splitlines(), 1):
            if line.strip():
                try:
                    out.append(json.loads(line))
                except ValueError as e:
                    raise ValueError(f"{self.path}, line {n}: not a JSON record ({e})") from e
        return out

    def append(self, record: Mapping[str, Any]) -> None:
        line = json.dumps(jsonable(record), separators=(",", ":")) + "\n"
        with self.path.open("a") as f:
            f.write(line)
            f.flush()
            os.fsync(f.fileno())


def fmu_infos(paths: Iterable[str | Path]) -> dict[str, Any]:
    """:func:`fmu_info` of each FMU by file stem (for runs that use several)."""
    from georod_tools.fmu import FmuModel

    out = {}
    for p in paths:
        m = FmuModel.load(p)
        out[Path(p).stem] = fmu_info(p, m.guid, m.identifier)
    return out


def new_run(
    parent: Path,
    name: str,
    command: str,
    settings: Mapping[str, Any],
    fmus: Mapping[str, Any],
    argv: Iterable[str],
    args: Any,
    out: Path | None = None,
    overwrite: bool = False,
) -> RunRecord:
    """The output folder of a new run (`out`, or a fresh ``parent/<name>_<timestamp>``), checked
    by :func:`prepare_output`, with its run.json started. Raises OutputRefusedError."""
    folder = out if out is not None else fresh_folder(parent, name)
    prepare_output(folder, overwrite=overwrite, resumable=False)
    record = RunRecord.create(folder, command, settings, fmus)
    record.start_session(argv, options(args))
    return record


def publish(files: Iterable[Path], docs_dir: Path, root: Path | None = None) -> list[Path]:
    """Copies `files` (figures and tables of a finished run) into `docs_dir` (``--update-docs``),
    at their paths relative to `root` (the run folder; default: flat). The only way a run writes
    into the repository's docs."""
    copied = []
    for f in files:
        target = docs_dir / (f.relative_to(root) if root is not None else f.name)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(f, target)
        copied.append(target)
    return copied
