"""Every Python command answers --help, and refuses a zero, negative or non-finite step, count,
time, period count, worker count or frequency with exit status 2 and a message that names the
option and the allowed range (no traceback)."""

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


def _subcommands() -> list[str]:
    parser = build_parser()
    (action,) = [a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction"]
    return sorted(action.choices)  # type: ignore[arg-type]


#: (module run with ``python -m``, arguments before --help)
COMMANDS: list[tuple[str, list[str]]] = [
    ("georod_tools", []),
    *[("georod_tools", [sub]) for sub in _subcommands()],
    ("georod_tools.cli", []),
    ("georod_tools.arches", []),
    ("georod_tools.arches", ["static"]),
    ("georod_tools.arches", ["study"]),
    ("georod_tools.stability", []),
    ("georod_tools.stability", ["fmu"]),
    ("georod_tools.stability", ["plot"]),
    ("georod_tools.benchmark", []),
    ("georod_tools.demo", []),
    ("georod_tools.study", []),
    ("georod_tools.animate", []),
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


def test_every_module_with_a_main_runs_as_a_command() -> None:
    """A module that defines main() also calls it under ``python -m`` (else --help would print
    nothing and exit 0), and is in COMMANDS."""
    listed = {m for m, _ in COMMANDS}
    for path in sorted(PACKAGE.glob("*.py")):
        tree = ast.parse(path.read_text())
        has_main = any(isinstance(n, ast.FunctionDef) and n.name == "main" for n in tree.body)
        runs = '__name__ == "__main__"' in path.read_text() or path.name == "__main__.py"
        if has_main:
            assert runs, f"{path.name} defines main() but has no __main__ block"
            assert f"georod_tools.{path.stem}" in listed, f"{path.stem} missing from COMMANDS"


@pytest.mark.parametrize(("module", "args"), COMMANDS, ids=[" ".join([m, *a]) for m, a in COMMANDS])
def test_help(module: str, args: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert _run_module(module, [*args, "--help"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: ") and "--help" in out


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
    ("georod_tools", ["case", "--dt-max", "0"], "--dt-max", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--dt-max=-1e-5"], "--dt-max", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--dt-max", "-0.001"], "--dt-max", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--dt-max", "nan"], "--dt-max", POSITIVE_FLOAT),
    ("georod_tools", ["sweep", "--dt-max", "inf"], "--dt-max", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--Omega", "0"], "--Omega", POSITIVE_FLOAT + " (rad/s)"),
    ("georod_tools", ["sweep", "--Omega=-inf"], "--Omega", POSITIVE_FLOAT),
    ("georod_tools", ["sweep", "--Omega", "-3500"], "--Omega", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--F", "nan"], "--F", "must be a finite number"),
    ("georod_tools", ["case", "--elements", "1"], "--elements", "allowed range 2..100000"),
    ("georod_tools", ["case", "--elements", "1e3"], "--elements", "expected an integer"),
    ("georod_tools", ["case", "--transient", "-1"], "--transient", "must be an integer >= 0"),
    ("georod_tools", ["case", "--periods", "0"], "--periods", "must be an integer >= 1"),
    ("georod_tools", ["sweep", "--periods", "-3"], "--periods", "must be an integer >= 1"),
    ("georod_tools", ["case", "--per-period", "0"], "--per-period", "must be an integer >= 1"),
    ("georod_tools", ["case", "--dense-periods", "-1"], "--dense-periods", ">= 0"),
    ("georod_tools", ["case", "--renorm-every", "0"], "--renorm-every", ">= 1"),
    ("georod_tools", ["case", "--d0", "0"], "--d0", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--period-tol", "1"], "--period-tol", "allowed range (0, 1)"),
    ("georod_tools", ["case", "--chaos-threshold", "-0.1"], "--chaos-threshold", POSITIVE_FLOAT),
    ("georod_tools", ["case", "--set", "E=inf"], "--set", "must be a finite number"),
    ("georod_tools", ["sweep", "--count", "0"], "--count", "allowed range 1..100000"),
    ("georod_tools", ["sweep", "--count", "-4"], "--count", "allowed range 1..100000"),
    ("georod_tools", ["sweep", "--count", "2.5"], "--count", "expected an integer"),
    ("georod_tools", ["sweep", "--workers", "0"], "--workers", "must be an integer >= 1"),
    ("georod_tools", ["sweep", "--start", "nan"], "--start", "must be a finite number"),
    ("georod_tools", ["sweep", "--stop", "inf"], "--stop", "must be a finite number"),
    ("georod_tools", ["study", "--workers", "-1"], "--workers", "must be an integer >= 1"),
    ("georod_tools", ["study", "--repeats", "0"], "--repeats", "must be an integer >= 1"),
    ("georod_tools.study", ["--workers", "0"], "--workers", "must be an integer >= 1"),
    ("georod_tools.arches", ["static", "--max-load", "0"], "--max-load", POSITIVE_FLOAT),
    ("georod_tools.arches", ["static", "--max-load", "nan"], "--max-load", POSITIVE_FLOAT),
    ("georod_tools.stability", ["fmu", "--steps", "0"], "--steps", "must be an integer >= 1"),
    ("georod_tools.stability", ["fmu", "--every", "-2"], "--every", "must be an integer >= 1"),
    ("georod_tools.demo", ["--periods", "1"], "--periods", "must be an integer >= 2"),
    ("georod_tools.demo", ["--transient", "-5"], "--transient", "must be an integer >= 0"),
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
