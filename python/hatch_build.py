"""The wheel build hook of the `georod` distribution (hatchling; pyproject.toml at the root).

A wheel holds, beside the `georod_tools` package, the bundle ``georod_tools/bin/``: the `georod`
command of the wheel's platform, the FMU library of every platform it was given
(``linux64/libgeorod.so``, ``win64/georod.dll``) and ``bundle.toml``, which lists each library
with its size and CRC-32 (the command checks them before packing one into an FMU).

Two ways in:

- ``scripts/build_wheels`` builds everything with the project's cross toolchains, stages it in a
  folder named by ``GEOROD_WHEEL_STAGE`` (``georod`` or ``georod.exe``, and one folder per
  platform) and names the platform tag in ``GEOROD_WHEEL_TAG`` (``win_amd64``,
  ``manylinux_2_17_x86_64.manylinux2014_x86_64``);
- ``pip install`` of the source distribution (a platform without a wheel) builds the command
  and this platform's library with cargo, or stops with a message that Rust is needed.
"""

from __future__ import annotations

import os
import platform
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import zlib
from pathlib import Path
from typing import Any

from hatchling.builders.hooks.plugin.interface import BuildHookInterface

#: Where the bundle lies in the wheel.
BUNDLE = "georod_tools/bin"
#: Each platform's library file in a bundle (and in a stage), by FMI 2.0 platform folder.
LIBRARIES = {"linux64": "libgeorod.so", "win64": "georod.dll", "darwin64": "libgeorod.dylib"}
#: The platform folder of this machine's library, for a build from source.
HOST_FOLDERS = {
    ("linux", "x86_64"): "linux64",
    ("win32", "amd64"): "win64",
    ("win32", "x86_64"): "win64",
    ("darwin", "x86_64"): "darwin64",
    ("darwin", "arm64"): "darwin64",
}


class RustNeeded(RuntimeError):
    """A build from source on a machine without cargo."""


def manifest(version: str, stage: Path) -> str:
    """``bundle.toml`` for the libraries found in `stage` (read by src/bin/georod/bundle.rs)."""
    lines = [
        "# The FMU libraries this georod command packs (written by the wheel build,",
        "# python/hatch_build.py): each is checked against its size and CRC-32 before use.",
        f'version = "{version}"',
    ]
    for folder, name in sorted(LIBRARIES.items()):
        lib = stage / folder / name
        if lib.is_file():
            data = lib.read_bytes()
            lines += ["", "[[library]]", f'platform = "{folder}"', f'file = "{folder}/{name}"']
            lines += [f"bytes = {len(data)}", f"crc32 = {zlib.crc32(data)}"]
    return "\n".join(lines) + "\n"


def rust_needed_message(version: str) -> str:
    return (
        f"georod {version} has no wheel for this platform ({sysconfig.get_platform()}, Python "
        f"{sys.version_info.major}.{sys.version_info.minor}), so pip is building it from its "
        "source distribution, which needs Rust (cargo on PATH; see rust-version in Cargo.toml). "
        "Install Rust (rustup, or your system's packages), then rerun pip install. Wheels exist "
        "for Linux x86_64 (glibc 2.17 or later) and Windows x86_64."
    )


def build_from_source(root: Path, stage: Path, version: str) -> str:
    """Builds the command and this machine's library with cargo into `stage`; returns the
    platform tag of this machine."""
    cargo = shutil.which("cargo")
    if cargo is None:
        raise RustNeeded(rust_needed_message(version))
    env = {**os.environ, "CARGO_PROFILE_RELEASE_STRIP": "symbols"}
    cmd = [cargo, "build", "--release", "--locked", "--lib", "--bin", "georod"]
    r = subprocess.run(cmd, cwd=root, env=env, check=False)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}): see cargo's output above")
    target = Path(os.environ.get("CARGO_TARGET_DIR", root / "target")) / "release"
    exe = "georod.exe" if sys.platform == "win32" else "georod"
    shutil.copy2(target / exe, stage / exe)
    # cargo names the library as the bundle does; a platform no FMU folder names gets none.
    folder = HOST_FOLDERS.get((sys.platform, platform.machine().lower()))
    if folder is not None:
        (stage / folder).mkdir()
        shutil.copy2(target / LIBRARIES[folder], stage / folder / LIBRARIES[folder])
    return sysconfig.get_platform().replace("-", "_").replace(".", "_")


class CustomBuildHook(BuildHookInterface):
    """Adds the bundle to the wheel and gives the wheel its platform tag."""

    def initialize(self, version: str, build_data: dict[str, Any]) -> None:
        if self.target_name != "wheel":
            return
        if version == "editable":
            raise RuntimeError(
                "georod has no editable install: a source checkout uses `scripts/bootstrap` "
                "(georod_tools, editable) and cargo's target/release/georod"
            )
        self._tmp = tempfile.TemporaryDirectory(prefix="georod_wheel_")
        given = os.environ.get("GEOROD_WHEEL_STAGE")
        if given:
            stage = Path(given)
            tag = os.environ.get("GEOROD_WHEEL_TAG")
            if not tag:
                raise RuntimeError("GEOROD_WHEEL_STAGE is set without GEOROD_WHEEL_TAG")
        else:
            stage = Path(self._tmp.name) / "stage"
            stage.mkdir()
            try:
                tag = build_from_source(Path(self.root), stage, self.metadata.version)
            except RustNeeded as e:
                # The message alone, without a traceback around it: pip shows it as it is.
                print(f"\nerror: {e}\n", file=sys.stderr)
                raise SystemExit(1) from None
        exes = [e for e in ("georod", "georod.exe") if (stage / e).is_file()]
        if len(exes) != 1:
            raise RuntimeError(f"{stage}: expected one of georod, georod.exe; found {exes}")
        listing = Path(self._tmp.name) / "bundle.toml"
        listing.write_text(manifest(self.metadata.version, stage), encoding="utf-8")
        include = build_data["force_include"]
        include[str(stage / exes[0])] = f"{BUNDLE}/{exes[0]}"
        include[str(listing)] = f"{BUNDLE}/bundle.toml"
        for folder, name in LIBRARIES.items():
            if (stage / folder / name).is_file():
                include[str(stage / folder / name)] = f"{BUNDLE}/{folder}/{name}"
        build_data["tag"] = f"py3-none-{tag}"
        build_data["pure_python"] = False

    def finalize(self, version: str, build_data: dict[str, Any], artifact_path: str) -> None:
        tmp = getattr(self, "_tmp", None)
        if tmp is not None:
            tmp.cleanup()
