"""The `georod` command (the Rust core's command line): where it is, and the console script
that starts it from an installed wheel.

- **Installed wheel** (``pip install georod``): the command lies in the bundle
  ``georod_tools/bin/`` beside this module, with the FMU library of every platform and
  ``bundle.toml`` listing them; the ``georod`` console script (:func:`start`) starts it.
- **Source checkout** (this package imported from ``<repo>/python``): ``<repo>/target/libs/
  georod`` where ``scripts/build_libs`` puts it, else cargo's ``<repo>/target/release/georod``
  (``cargo build --release --bin georod``, or ``scripts/build_fmus``).

Anything else is an error that names what is missing and how to get it (:class:`NotFound`).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import NoReturn

from georod_tools import REPO_ROOT

#: The bundle of an installed wheel.
BUNDLE_DIR: Path = Path(__file__).resolve().parent / "bin"
#: The bundle's manifest, which only an installed wheel has.
MANIFEST: Path = BUNDLE_DIR / "bundle.toml"
#: The executable's file name on this platform.
EXE_NAME = "georod.exe" if os.name == "nt" else "georod"


class NotFound(RuntimeError):
    """The georod command is not where this installation keeps it."""


def is_installed() -> bool:
    """Whether this georod_tools comes from a wheel (its bundle manifest is present)."""
    return MANIFEST.is_file()


def is_checkout() -> bool:
    """Whether this georod_tools is imported from a source checkout of georod."""
    return (REPO_ROOT / "Cargo.toml").is_file() and (REPO_ROOT / "src" / "bin" / "georod").is_dir()


def executable() -> Path:
    """The georod command of this installation: the wheel's, else the source checkout's."""
    if is_installed():
        exe = BUNDLE_DIR / EXE_NAME
        if not exe.is_file():
            raise NotFound(
                f"this installation's georod command {exe} is missing ({MANIFEST} is there): "
                "reinstall georod (pip install --force-reinstall georod, or the wheel file), or "
                "rebuild the wheels from a source checkout with scripts/build_wheels"
            )
        return exe
    if is_checkout():
        built = [REPO_ROOT / "target" / folder / EXE_NAME for folder in ("libs", "release")]
        exe = next((e for e in built if e.is_file()), None)
        if exe is None:
            raise NotFound(
                f"{built[-1]} is missing: this georod_tools is a source checkout's "
                f"({REPO_ROOT}); build the command with `cargo build --release --bin georod` "
                "(or scripts/build_fmus, which also builds the FMU libraries)"
            )
        return exe
    raise NotFound(
        f"georod_tools ({Path(__file__).resolve().parent}) has no georod command: no "
        f"{MANIFEST} (an installed wheel's bundle) and not in a source checkout; install the "
        "georod wheel (pip install georod), or build it with scripts/build_wheels"
    )


def start() -> NoReturn:
    """The ``georod`` console script of a wheel: runs the bundled command with this process's
    arguments and exit status (on POSIX it replaces this process)."""
    try:
        exe = executable()
    except NotFound as e:
        print(f"georod: {e}", file=sys.stderr)
        sys.exit(1)
    args = [str(exe), *sys.argv[1:]]
    if os.name == "posix":
        os.execv(exe, args)
    with subprocess.Popen(args) as child:
        while True:
            try:
                sys.exit(child.wait())
            except KeyboardInterrupt:
                # The console sent Ctrl+C to the child too: wait for it to end.
                continue
