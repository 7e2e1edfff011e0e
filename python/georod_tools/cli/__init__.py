"""The command line: ``georod-tools`` (also ``georod-chaos``, and ``python -m georod_tools``).

    georod-tools case --F 1.5 --Omega 3500                       # one case
    georod-tools sweep --param F --start 0.4 --stop 2 --count 100  # a bifurcation diagram (Dask)
    georod-tools study paper|arches|arch-path|stability ...      # the long studies
    georod-tools benchmark precision|lyapunov ...                # the benchmarks
    georod-tools animate FMU ...                                 # a GIF of the deformed rod
    georod-tools demo                                            # the Python half of scripts/demo

Every run writes into a new folder under ``out/<command>/`` (or ``--out``) with a ``run.json``
(settings, FMU GUID and sha256, versions, command line); nothing in ``docs/`` is written unless
``--update-docs`` is given. Every subcommand answers ``--help``; a bad value is refused with the
option and its allowed range (exit status 2); a failing simulation exits with status 1 and the
FMU's message.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

PROG = "georod-tools"
#: The subcommands, in the order `--help` lists them (modules of this package).
COMMANDS = ("case", "sweep", "study", "benchmark", "animate", "demo")


def build_parser(argv: Sequence[str] = ()) -> argparse.ArgumentParser:
    """The parser. Only the subcommand named in `argv` gets its options (all of them when
    `argv` names none): the studies' and benchmarks' options import their studies, with
    matplotlib and Dask, which would add a second to every command; the others are listed
    with their help line."""
    command = next((a for a in argv if not a.startswith("-")), None)
    full = command not in COMMANDS
    parser = argparse.ArgumentParser(
        prog=PROG,
        description="Analyses of the georod FMUs: Poincaré sections, phase portraits, "
        "bifurcation diagrams, Lyapunov exponents, studies, benchmarks, animations.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    for name in COMMANDS:
        module = importlib.import_module(f"georod_tools.cli.{name}")
        if full or name == command:
            module.add_parser(sub)
        else:
            sub.add_parser(name, help=module.HELP)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(argv)
    args = parser.parse_args(argv)
    try:
        return int(args.run(args._parser, args, argv))
    except (RuntimeError, ValueError, OSError) as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 1
