"""georod from Python (georod_tools.api, docs/python.md) in the source checkout, and where the
`georod` command is found (georod_tools.command): a scene packaged (FMI 2.0 and 3.0), checked,
simulated and its modes found, the results as numpy arrays against closed forms; a refusal
raises GeorodError with georod's own message and status; a command that is not where the
installation keeps it is named with how to get it. The same API from an installed wheel:
test_wheel_smoke.py."""

from __future__ import annotations

import math
import zipfile
from pathlib import Path

import numpy as np
import pytest

import georod_tools as georod
from georod_tools import command
from helpers import GEOROD_CLI, REPO

pytestmark = pytest.mark.timeout(120)

CANTILEVER = REPO / "examples" / "Cantilever.toml"
# The example's steel flat bar: EI = 875 N.m2, rho A = 3.925 kg/m.
L, EI, RHO_A = 2.0, 210e9 * 0.05 * 0.01**3 / 12, 7850.0 * 0.05 * 0.01


def test_the_checkout_runs_its_own_build() -> None:
    assert command.is_checkout() and not command.is_installed()
    assert command.executable() == GEOROD_CLI


def test_package_writes_the_fmu_it_names(tmp_path: Path) -> None:
    fmu = georod.package(CANTILEVER, tmp_path / "c.fmu")
    fmu3 = georod.package(CANTILEVER, tmp_path / "c3.fmu", fmi=3)
    assert (fmu, fmu3) == (tmp_path / "c.fmu", tmp_path / "c3.fmu")
    with zipfile.ZipFile(fmu3) as z:
        assert 'fmiVersion="3.0"' in z.read("modelDescription.xml").decode()
    with pytest.raises(georod.GeorodError) as e:
        georod.package(CANTILEVER, tmp_path / "c.zip")
    assert (
        e.value.status == 1
        and str(e.value) == f"-o {tmp_path / 'c.zip'}: the output must be a .fmu file"
    )


def test_check_reads_the_initial_state(tmp_path: Path) -> None:
    report = georod.check(CANTILEVER)
    assert "scene Cantilever is valid" in report.text
    # Default P = 218.75 N: P L^2 / EI = 1, a large deflection; the root carries P and P x_tip.
    rx, ry, m = report.reactions["root"]
    assert ry == pytest.approx(218.75, rel=1e-6)
    x_tip = L + report.sensors["u_tip"]
    assert m == pytest.approx(218.75 * x_tip, rel=1e-5)
    bad = tmp_path / "bad.toml"
    bad.write_text(CANTILEVER.read_text().replace("L = 2.0", "L = -2.0"))
    with pytest.raises(georod.GeorodError) as e:
        georod.check(bad)
    assert e.value.status == 1 and str(e.value).startswith(f"{bad}: ")


def test_simulate_returns_the_outputs_as_arrays() -> None:
    run = georod.simulate(
        CANTILEVER, step=1e-3, stop=0.01, outputs=["w_tip", "root_M"], parameters={"P": 0.5}
    )
    assert run.dtype.names == ("time", "w_tip", "root_M")
    np.testing.assert_allclose(run["time"], np.arange(11) * 1e-3, atol=1e-15)
    # At rest under its static deflection: P L^3 / (3 EI) (shear and the mesh within 1e-3).
    assert run["w_tip"] == pytest.approx(-0.5 * L**3 / (3 * EI), rel=1e-3)
    pushed = georod.simulate(CANTILEVER, step=1e-3, stop=0.01, inputs={"f_tip": 5.0})
    assert pushed["w_tip"][-1] < pushed["w_tip"][0], "the input pushes the tip down"
    with pytest.raises(georod.GeorodError) as e:
        georod.simulate(CANTILEVER, step=1e-3, stop=0.01, outputs=["nope"])
    assert e.value.status == 1 and "`nope` is not an output of Cantilever" in str(e.value)
    with pytest.raises(georod.GeorodError) as e:
        georod.simulate(CANTILEVER, step=-1.0, stop=0.01)
    assert e.value.status == 2 and str(e.value).startswith("--step -1.0: must be")


def test_modes_give_the_cantilevers_first_frequency() -> None:
    """(1.8751^2 / 2 pi) sqrt(EI / (rho A L^4)) without the tip load (Euler-Bernoulli; shear and
    rotary inertia of this slender bar and the mesh: within 1e-3)."""
    modes = georod.modes(CANTILEVER, count=2, parameters={"P": 0.0})
    f1 = 1.875104068711961**2 / (2 * math.pi) * math.sqrt(EI / (RHO_A * L**4))
    assert modes.frequencies[0] == pytest.approx(f1, rel=1e-3)
    assert len(modes.frequencies) == 2 and modes.frequencies[1] > 6 * f1
    assert modes.shapes["node"][-1] == 20 and abs(modes.shapes["u2_1"][-1]) > 0


def test_a_missing_command_is_named_with_how_to_get_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # An installation whose bundle lost its command.
    monkeypatch.setattr(command, "BUNDLE_DIR", tmp_path)
    monkeypatch.setattr(command, "MANIFEST", tmp_path / "bundle.toml")
    (tmp_path / "bundle.toml").write_text('version = "0.1.0"\n')
    with pytest.raises(command.NotFound, match="pip install --force-reinstall georod"):
        command.executable()
    # A checkout that has not built the command yet.
    (tmp_path / "bundle.toml").unlink()
    monkeypatch.setattr(command, "REPO_ROOT", tmp_path)
    (tmp_path / "Cargo.toml").write_text("")
    (tmp_path / "src" / "bin" / "georod").mkdir(parents=True)
    with pytest.raises(command.NotFound, match="cargo build --release --bin georod"):
        command.executable()
    # Neither.
    (tmp_path / "Cargo.toml").unlink()
    with pytest.raises(command.NotFound, match="install the georod wheel"):
        command.executable()


def test_an_installation_without_scenes_asks_for_an_fmu(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """georod-tools --scene NAME needs the checkout's scenes/; an installed wheel has none."""
    monkeypatch.setattr(georod, "SCENE_DIR", tmp_path / "scenes")
    monkeypatch.setattr(georod, "FMU_DIR", tmp_path / "fmu")
    with pytest.raises(ValueError, match=r"no scenes/ folder .*; pass --fmu FILE\.fmu"):
        georod.fmu_path("BuckledBeam")
