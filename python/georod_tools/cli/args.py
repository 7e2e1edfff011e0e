"""Shared pieces of the command line: argparse `type=` functions that refuse values outside
their allowed range, ``NAME=VALUE`` pairs, and the output-folder options every run has.

argparse prefixes the message with the option (``argument --count: allowed range 1..100000, got
'0'``) and exits with status 2, without a traceback. Every float type also refuses NaN and
infinities, which ``float()`` accepts.

    p.add_argument("--count", type=int_range(1, 100_000))
    p.add_argument("--Omega", type=positive_float)
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from pathlib import Path


def _number(text: str, kind: type, wanted: str) -> float:
    try:
        x = kind(text)
    except ValueError:
        what = "an integer" if kind is int else "a number"
        raise argparse.ArgumentTypeError(f"expected {what} ({wanted}), got {text!r}") from None
    if kind is float and not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"{wanted}, got {text!r}")
    return x


def int_range(lo: int, hi: int | None = None) -> Callable[[str], int]:
    """Integers in ``lo..hi`` (``>= lo`` when `hi` is None)."""
    wanted = f"allowed range {lo}..{hi}" if hi is not None else f"must be an integer >= {lo}"

    def parse(text: str) -> int:
        x = int(_number(text, int, wanted))
        if x < lo or (hi is not None and x > hi):
            raise argparse.ArgumentTypeError(f"{wanted}, got {text!r}")
        return x

    parse.__name__ = f"int_range_{lo}_{hi}"
    return parse


def float_range(
    lo: float | None = None,
    hi: float | None = None,
    lo_open: bool = True,
    hi_open: bool = True,
    unit: str = "",
) -> Callable[[str], float]:
    """Finite floats between `lo` and `hi` (open or closed ends; None: unbounded)."""
    if lo is not None and hi is not None:
        wanted = f"allowed range {'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"
    elif lo is not None:
        wanted = f"must be {'>' if lo_open else '>='} {lo:g}"
    elif hi is not None:
        wanted = f"must be {'<' if hi_open else '<='} {hi:g}"
    else:
        wanted = "must be a finite number"
    if lo is not None or hi is not None:
        wanted += " and finite"
    if unit:
        wanted += f" ({unit})"

    def parse(text: str) -> float:
        x = float(_number(text, float, wanted))
        below = lo is not None and (x <= lo if lo_open else x < lo)
        above = hi is not None and (x >= hi if hi_open else x > hi)
        if below or above:
            raise argparse.ArgumentTypeError(f"{wanted}, got {text!r}")
        return x

    parse.__name__ = "float_range"
    return parse


#: > 0 and finite (steps, times, tolerances, frequencies).
positive_float = float_range(0.0)
#: any finite float (loads, sweep ends).
finite_float = float_range()
#: integers >= 1 (counts, periods, workers).
positive_int = int_range(1)
#: integers >= 0 (transients, discarded intervals).
nonnegative_int = int_range(0)


def name_value(text: str) -> tuple[str, float]:
    """``NAME=VALUE`` with a finite number (``--set``, ``--start-values``)."""
    name, sep, value = text.partition("=")
    if not sep or not name.strip():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    try:
        x = float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{name}: {value!r} is not a number") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"{name}={value}: must be a finite number")
    return name.strip(), x


def add_output_options(p: argparse.ArgumentParser, default: str, docs: str | None = None) -> None:
    """``--out`` (default: a new timestamped folder `default`), ``--overwrite`` and, for a run
    whose figures the repository's docs show, ``--update-docs`` (copies them into `docs`)."""
    p.add_argument(
        "--out",
        type=Path,
        help=f"output folder (default: a new {default}_<timestamp>); an existing non-empty folder "
        "is refused unless --overwrite",
    )
    p.add_argument(
        "--overwrite",
        action="store_true",
        help="empty --out first (only a folder written by georod_tools, with a run.json)",
    )
    if docs is not None:
        p.add_argument(
            "--update-docs",
            action="store_true",
            help=f"also copy the figures (and tables) into {docs}; without it nothing in docs/ "
            "is written",
        )
