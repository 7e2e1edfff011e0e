"""examples/control/: the BuckledBeam FMU under velocity feedback from a pythonfmu controller FMU,
coupled by an SSP archive that scripts/build_ssp writes (the zip of SystemStructure.ssd and the
FMUs it names), run by libcosim (from_ssp_file) and by Ecos (ecospy). With the SSP's gain the
midspan amplitude falls well below the uncontrolled one and the control force's work W_ctrl is
negative (the controller removes energy); with the gain 0 W_ctrl stays 0."""

from __future__ import annotations

import importlib.util
import re
import sys
import zipfile
from pathlib import Path
from types import ModuleType

import pytest

from helpers import FMU_DIR, REPO, run_cmd

SSP_GAIN = 0.003  # examples/control/SystemStructure.ssd


def load_example() -> ModuleType:
    path = REPO / "examples" / "control" / "run.py"
    spec = importlib.util.spec_from_file_location("control_example", path)
    assert spec is not None and spec.loader is not None, f"{path} cannot be loaded"
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclass looks its module up there
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def example() -> ModuleType:
    return load_example()


@pytest.fixture(scope="module")
def ssp(fmu_paths: dict[str, Path], tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The archive written by the documented command, scripts/build_ssp OUT_DIR."""
    out = tmp_path_factory.mktemp("control")
    r = run_cmd([REPO / "scripts" / "build_ssp", out], timeout=600)
    assert r.returncode == 0, f"scripts/build_ssp failed:\n{r.stdout}\n{r.stderr}"
    return out / "ControlledBeam.ssp"


def test_the_archive_holds_the_ssd_and_every_fmu_it_names(ssp: Path) -> None:
    source = REPO / "examples" / "control" / "SystemStructure.ssd"
    with zipfile.ZipFile(ssp) as z:
        names = set(z.namelist())
        assert z.read("SystemStructure.ssd") == source.read_bytes()
        components = re.findall(r'source="([^"]+)"', source.read_text())
        assert sorted(components) == [
            "resources/BuckledBeam.fmu",
            "resources/VelocityFeedback.fmu",
        ]
        assert names == {"SystemStructure.ssd", *components}, names
        assert z.read("resources/BuckledBeam.fmu") == (FMU_DIR / "BuckledBeam.fmu").read_bytes()
        with z.open("resources/VelocityFeedback.fmu") as fmu, zipfile.ZipFile(fmu) as inner:
            assert "modelDescription.xml" in inner.namelist()


@pytest.mark.parametrize("engine", ["run_libcosim", "run_ecos"])
def test_feedback_removes_energy_and_amplitude(example: ModuleType, ssp: Path, engine: str) -> None:
    run = getattr(example, engine)
    free = run(ssp, 0.0)
    controlled = run(ssp, None)  # the SSP's own parameter binding
    assert controlled.gain == SSP_GAIN, f"{free.engine} did not apply the SSP's gain"
    assert free.w_ctrl == 0.0
    assert controlled.w_ctrl < 0.0, f"{free.engine}: W_ctrl = {controlled.w_ctrl}"
    assert controlled.amplitude < 0.5 * free.amplitude, (
        f"{free.engine}: amplitude {controlled.amplitude} controlled, {free.amplitude} free"
    )
