"""`georod fmu --binary` refuses a library of the wrong architecture for its platform, not only a
file that is no library: a 32-bit Windows DLL offered as win64 and an aarch64 ELF offered as
linux64. Both are real shared libraries exporting every FMI 2.0 and 3.0 function (built here by
zig, which scripts/bootstrap installs for the linux64 build), so only the architecture check
stands between them and an FMU that no win64 or linux64 host could load."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from helpers import REPO, run_cmd

ZIG = REPO / ".venv" / "bin" / "python-zig"
BINARIES_RS = REPO / "src" / "packaging" / "binaries.rs"

#: (platform, zig target, file name, what the message must say was found)
WRONG = [
    ("win64", "x86-windows-gnu", "fmi32.dll", "found Pe for I386"),
    ("linux64", "aarch64-linux-gnu", "libfmi_arm.so", "found Elf for Aarch64"),
]


def fmi_function_names() -> list[str]:
    """Every FMI 2.0 and 3.0 function that `georod fmu` requires, read from its own lists."""
    names = re.findall(r'"(fmi[23]\w+)"', BINARIES_RS.read_text())
    assert len(names) > 34, f"{BINARIES_RS}: the FMI function lists were not found"
    return sorted(set(names))


def build_library(target: str, out: Path) -> Path:
    """A shared library for `target` exporting every FMI function (each returns 0); no C
    library (-nostdlib), so zig needs no libc of the target."""
    if not ZIG.exists():
        pytest.fail(f"{ZIG} missing: scripts/bootstrap installs ziglang")
    export = "__declspec(dllexport)" if "windows" in target else ""
    source = out.with_suffix(".c")
    lines = [f"{export} int {name}(void) {{ return 0; }}" for name in fmi_function_names()]
    if "windows" in target:
        lines.append("int __stdcall DllMainCRTStartup(void *h, unsigned r, void *p) { return 1; }")
    source.write_text("\n".join(lines) + "\n")
    cmd = [ZIG, "cc", "-target", target, "-shared", "-nostdlib", "-o", out, source]
    r = run_cmd(cmd, timeout=300)
    assert r.returncode == 0 and out.is_file(), f"zig cc -target {target}: {r.stderr}"
    return out


@pytest.mark.parametrize(("platform", "target", "name", "found"), WRONG, ids=["win32", "arm64"])
@pytest.mark.parametrize("fmi", ["2", "3"])
def test_binary_refuses_a_library_of_another_architecture(
    georod_cli: Path, tmp_path: Path, platform: str, target: str, name: str, found: str, fmi: str
) -> None:
    library = build_library(target, tmp_path / name)
    out = tmp_path / "Beam.fmu"
    scene = REPO / "scenes" / "BuckledBeam.toml"
    cmd = [georod_cli, "fmu", scene, "--fmi", fmi, "-o", out, "--binary", f"{platform}={library}"]
    r = run_cmd(cmd)
    assert r.returncode != 0, f"{platform}: a {target} library was packed:\n{r.stdout}"
    assert f"not a {platform} library: expected" in r.stderr, r.stderr
    assert found in r.stderr, r.stderr
    assert str(library) in r.stderr, f"the message does not name the file:\n{r.stderr}"
    assert not out.exists()
