"""Starting and finishing a run of a study or benchmark command: its folder and run.json, and
``--update-docs`` (the only way a run writes into docs/)."""

from __future__ import annotations

import argparse
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from georod_tools.report.records import (
    OutputRefusedError,
    RunRecord,
    fmu_infos,
    new_run,
    publish,
)


def start_run(
    parser: argparse.ArgumentParser,
    args: argparse.Namespace,
    argv: Sequence[str],
    parent: Path,
    command: str,
    settings: Mapping[str, Any],
    fmus: Sequence[Path],
) -> RunRecord:
    """A new folder ``parent/<last word of command>_<timestamp>`` (or ``--out``) with its
    run.json; exits with status 2 on a refused folder, a missing FMU, or --update-docs with
    --quick."""
    if getattr(args, "update_docs", False) and getattr(args, "quick", False):
        parser.error("--update-docs with --quick: quick runs never replace the docs' figures")
    missing = [str(f) for f in fmus if not Path(f).is_file()]
    if missing:
        parser.error(f"FMU {', '.join(missing)} not found: build it with scripts/build_fmus")
    name = command.split()[-1]
    try:
        return new_run(
            parent, name, command, settings, fmu_infos(fmus), argv, args, args.out, args.overwrite
        )
    except OutputRefusedError as e:
        parser.error(str(e))
        raise AssertionError from e  # unreachable


def finish_run(
    record: RunRecord,
    files: Sequence[Path],
    args: argparse.Namespace,
    docs: Path,
    pattern: str = "*",
) -> int:
    """Completes run.json with the files written; with ``--update-docs`` copies those that
    match `pattern` into `docs`. Returns the exit status (0)."""
    published: list[Path] = []
    if getattr(args, "update_docs", False):
        published = publish([f for f in files if f.match(pattern)], docs, record.folder)
    record.finish(
        "complete",
        outputs=[str(f.relative_to(record.folder)) for f in files],
        published=[str(p) for p in published],
    )
    where = f"; {len(published)} copied to {docs}" if published else ""
    print(f"{len(files)} files in {record.folder}{where}")
    return 0
