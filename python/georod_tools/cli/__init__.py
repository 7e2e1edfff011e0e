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
import atexit
import importlib
import os
import sys
import threading
from collections.abc import Sequence
from typing import NoReturn

from georod_tools.analysis.worker_start import start_worker_server

PROG = "georod-tools"
#: The subcommands, in the order `--help` lists them (modules of this package).
COMMANDS = ("case", "sweep", "study", "benchmark", "animate", "demo")
#: The subcommands that may start local Dask workers.
CLUSTER_COMMANDS = ("sweep", "study", "benchmark")


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
    command = next((a for a in argv if not a.startswith("-")), None)
    if command in CLUSTER_COMMANDS and "--scheduler" not in argv:
        # The workers' fork server makes its imports while this process makes its own.
        start_worker_server()
    parser = build_parser(argv)
    args = parser.parse_args(argv)
    try:
        return int(args.run(args._parser, args, argv))
    except (RuntimeError, ValueError, OSError) as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 1


def entry() -> NoReturn:
    """The console entry point (``georod-tools``, ``python -m georod_tools``): :func:`main`,
    then :func:`exit_now` with its status."""
    exit_now(main())


def exit_now(status: int) -> NoReturn:
    """Ends the process with `status` once the exit handlers have run (temporary folders,
    Dask's and logging's cleanup) and stdout and stderr are flushed, without Python's own
    teardown of every imported module: with Dask, matplotlib and numpy loaded that takes
    0.2-0.3 s, and nothing of this package needs it. While a thread other than the main one
    still runs (and is not a daemon), the normal exit waits for it instead."""
    others = [t for t in threading.enumerate() if t is not threading.main_thread()]
    run_handlers = getattr(atexit, "_run_exitfuncs", None)  # CPython
    if run_handlers is None or any(t.is_alive() and not t.daemon for t in others):
        sys.exit(status)
    run_handlers()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe (georod-tools ... | head)
            pass
    os._exit(status)
