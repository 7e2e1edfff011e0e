"""The one command line (``georod-tools`` / ``python -m georod_tools``): every subcommand answers
--help, and a zero, negative or non-finite step, count, time, period count, worker count or
frequency is refused with exit status 2 and a message that names the option and the allowed
range (no traceback)."""

from __future__ import annotations

import ast
import runpy
import subprocess
import sys
from pathlib import Path

import pytest

import georod_tools
from georod_tools.cli import build_parser

PACKAGE = Path(georod_tools.__file__).parent


def _subcommands(parser: object = None, prefix: tuple[str, ...] = ()) -> list[tuple[str, ...]]:
    """Every (sub)subcommand path of the parser, e.g. ("study", "paper")."""
    parser = parser or build_parser()
    out: list[tuple[str, ...]] = []
    for action in parser._actions:  # type: ignore[attr-defined]
        if action.__class__.__name__ == "_SubParsersAction":
            for name, sub in sorted(action.choices.items()):
                out.append((*prefix, name))
                out += _subcommands(sub, (*prefix, name))
    return out


#: (module run with ``python -m``, arguments before --help)
COMMANDS: list[tuple[str, list[str]]] = [
    ("georod_tools", []),
    *[("georod_tools", list(path)) for path in _subcommands()],
]


def _run_module(module: str, args: list[str]) -> int:
    """``python -m module args`` in this process; returns the exit status."""
    argv = sys.argv
    sys.argv = [module, *args]
    imported = sys.modules.pop(module, None)  # as in a fresh interpreter (no runpy warning)
    try:
        runpy.run_module(module, run_name="__main__", alter_sys=True)
    except SystemExit as e:
        return int(e.code or 0) if not isinstance(e.code, str) else 1
    finally:
        sys.argv = argv
        if imported is not None:
            sys.modules[module] = imported
    return 0


def test_one_command_line() -> None:
    """Only the command line defines main() (no module is a command of its own), and the
    subcommands the issue asks for are all there."""
    mains = []
    for path in sorted(PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text())
        if any(isinstance(n, ast.FunctionDef) and n.name == "main" for n in tree.body):
            mains.append(str(path.relative_to(PACKAGE)))
    assert mains == ["cli/__init__.py"]
    paths = set(_subcommands())
    for want in [
        ("case",),
        ("sweep",),
        ("study", "paper"),
        ("study", "arches"),
        ("study", "stability"),
        ("benchmark", "precision"),
        ("benchmark", "lyapunov"),
        ("animate",),
        ("demo",),
    ]:
        assert want in paths


def test_console_scripts() -> None:
    """``georod-tools`` and its former name ``georod-chaos`` are installed and answer --help."""
    bindir = Path(sys.executable).parent
    for name in ("georod-tools", "georod-chaos"):
        r = subprocess.run(
            [str(bindir / name), "case", "--help"],
            capture_output=True,
            text=True,
            timeout=120,
            check=False,
        )
        assert r.returncode == 0 and "--substeps" in r.stdout, r.stderr


@pytest.mark.parametrize(("module", "args"), COMMANDS, ids=[" ".join([m, *a]) for m, a in COMMANDS])
def test_help(module: str, args: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert _run_module(module, [*args, "--help"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: ") and "--help" in out


EXIT_NOW = """
import atexit, sys, threading, time
from georod_tools.cli import exit_now
atexit.register(lambda: print("handler ran", flush=True))
if sys.argv[1] == "thread":
    threading.Thread(target=lambda: (time.sleep(0.2), print("thread done"))).start()
print("buffered output", end="")
exit_now(3)
"""


@pytest.mark.parametrize("mode", ["plain", "thread"])
def test_exit_now_keeps_handlers_output_and_threads(mode: str) -> None:
    """The entry point's quick exit keeps the status, runs the exit handlers, flushes what is
    buffered, and waits for a running (non-daemon) thread instead of cutting it off."""
    r = subprocess.run(
        [sys.executable, "-c", EXIT_NOW, mode],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert r.returncode == 3, r.stderr
    assert "buffered output" in r.stdout and "handler ran" in r.stdout
    assert ("thread done" in r.stdout) == (mode == "thread")


def test_help_through_python_m() -> None:
    r = subprocess.run(
        [sys.executable, "-m", "georod_tools", "sweep", "--help"],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert r.returncode == 0, r.stderr
    for option in ("--resume", "--overwrite", "--scheduler ADDR", "--count", "--workers"):
        assert option in r.stdout


POSITIVE_FLOAT = "must be > 0 and finite"
BAD_VALUES: list[tuple[str, list[str], str, str]] = [
    # module, arguments, the option named, the allowed range stated
    ("georod_tools", ["case", "--substeps", "0"], "--substeps", "must be an integer >= 1"),
    ("georod_tools", ["sweep", "--substeps", "-2"], "--substeps", "must be an integer >= 1"),
    ("georod_tools", ["case", "--substeps", "1.5"], "--substeps", "expected an integer"),
    ("georod_tools", ["case", "--Omega", "0"], "--Omega", POSITIVE_FLOAT + " (rad/s)"),
    ("georod_tools", ["sweep", "--Omega=-inf"], "--Omega", POSITIVE_FLOAT),
    ("georod_tools", ["sweep", "--Omega", "-3500"], "--Omega", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--F", "nan"], "--F", "must be a finite number"),
    ("georod_tools", ["case", "--elements", "1"], "--elements", "allowed range 2..100000"),
    ("georod_tools", ["case", "--elements", "1e3"], "--elements", "expected an integer"),
    ("georod_tools", ["case", "--transient", "-1"], "--transient", "must be an integer >= 0"),
    ("georod_tools", ["case", "--periods", "0"], "--periods", "must be an integer >= 1"),
    ("georod_tools", ["sweep", "--periods", "-3"], "--periods", "must be an integer >= 1"),
    ("georod_tools", ["case", "--dense-steps", "0"], "--dense-steps", "must be an integer >= 1"),
    ("georod_tools", ["case", "--dense-periods", "-1"], "--dense-periods", ">= 0"),
    ("georod_tools", ["case", "--align", "-1"], "--align", "must be an integer >= 0"),
    ("georod_tools", ["case", "--period-tol", "1"], "--period-tol", "allowed range (0, 1)"),
    ("georod_tools", ["case", "--chaos-threshold", "-0.1"], "--chaos-threshold", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--set", "E=inf"], "--set", "must be a finite number"),
    ("georod_tools", ["sweep", "--count", "0"], "--count", "allowed range 1..100000"),
    ("georod_tools", ["sweep", "--count", "-4"], "--count", "allowed range 1..100000"),
    ("georod_tools", ["sweep", "--count", "2.5"], "--count", "expected an integer"),
    ("georod_tools", ["sweep", "--workers", "0"], "--workers", "must be an integer >= 1"),
    ("georod_tools", ["sweep", "--start", "nan"], "--start", "must be a finite number"),
    ("georod_tools", ["sweep", "--stop", "inf"], "--stop", "must be a finite number"),
    ("georod_tools", ["study", "paper", "--workers", "-1"], "--workers", "must be an integer >= 1"),
    ("georod_tools", ["study", "arch-path", "--max-load", "0"], "--max-load", POSITIVE_FLOAT),
    ("georod_tools", ["study", "arch-path", "--max-load", "nan"], "--max-load", POSITIVE_FLOAT),
    ("georod_tools", ["study", "stability", "--steps", "0"], "--steps", "must be an integer >= 1"),
    ("georod_tools", ["study", "stability", "--every", "-2"], "--every", "must be an integer >= 1"),
    ("georod_tools", ["benchmark", "lyapunov", "--count", "0"], "--count", "an integer >= 1"),
    ("georod_tools", ["benchmark", "lyapunov", "--workers", "0,2"], "--workers", ">= 1"),
    ("georod_tools", ["animate", "x.fmu", "--stop", "-1"], "--stop", POSITIVE_FLOAT),
    ("georod_tools", ["animate", "x.fmu", "--frames", "0"], "--frames", "an integer >= 1"),
    ("georod_tools", ["demo", "--periods", "1"], "--periods", "must be an integer >= 2"),
    ("georod_tools", ["demo", "--transient", "-5"], "--transient", "must be an integer >= 0"),
]


@pytest.mark.parametrize(
    ("module", "args", "option", "allowed"),
    BAD_VALUES,
    ids=[" ".join([m, *a]) for m, a, _, _ in BAD_VALUES],
)
def test_bad_values_refused(
    module: str, args: list[str], option: str, allowed: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert _run_module(module, args) == 2
    err = capsys.readouterr().err
    assert f"argument {option}: " in err and allowed in err, err
    assert f"got '{args[-1].split('=', 1)[-1]}'" in err or option == "--set"
    assert "Traceback" not in err
