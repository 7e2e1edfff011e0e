"""Tables: CSV rows, markdown tables and the files that hold them (one writer for every study)."""

from __future__ import annotations

import csv
from collections.abc import Mapping, Sequence
from pathlib import Path


def write_csv(rows: Sequence[Mapping[str, object]], path: str | Path) -> Path:
    """`rows` (dicts with the same keys, in order) as a CSV file with a header."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as f:
        if rows:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    return path


def cell(v: object) -> str:
    """A number as a table shows it: 4 significant digits, exponent form when tiny or huge."""
    if isinstance(v, float):
        if v == 0 or (1e-3 <= abs(v) < 1e5):
            return f"{v:.4g}"
        return f"{v:.3e}"
    return str(v)


def markdown(rows: Sequence[Mapping[str, object]], columns: Sequence[str] | None = None) -> str:
    """A markdown table of `columns` (default: every key of the first row) of `rows`."""
    columns = list(columns if columns is not None else (rows[0] if rows else []))
    out = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    out += ["| " + " | ".join(cell(r[c]) for c in columns) + " |" for r in rows]
    return "\n".join(out)


def grid(header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A markdown table from a header and rows of values."""
    return markdown([dict(zip(header, r, strict=True)) for r in rows], header)


def write_text(text: str, path: str | Path) -> Path:
    """`text` (a markdown fragment, a log) as a file, with a final newline."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text.rstrip("\n") + "\n")
    return path
