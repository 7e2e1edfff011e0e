"""Requirement 1: fmpy validates each FMU and simulates it with its default experiment and with a
harmonic excitation given as start values."""

from __future__ import annotations

from pathlib import Path

import fmpy
import numpy as np
import pytest
from fmpy.validation import validate_fmu

from helpers import FMU_DIR, FmuInfo, period

# Excitations used with simulate_fmu for the paper's scenes. The beam's F is per unit length
# (paper: F = 0.9 is in the chaotic band at Omega = 3.5e3); the arches take a crown point load
# (units N), F = 50 gives a visible crown motion on a 32-long arch without snapping through in a
# few periods. Another scene of scenes/ is excited with its own start values of F and Omega.
HARMONIC = {
    "BuckledBeam": {"F": 0.9, "Omega": 3.5e3},
    "PinnedArch": {"F": 50.0, "Omega": 1.0e3},
    "ClampedArch": {"F": 50.0, "Omega": 1.0e3},
}


def excitation(fmu: FmuInfo) -> dict[str, float]:
    """F and Omega for the harmonic test: tuned for the paper's scenes, else the scene's own."""
    if fmu.scene in HARMONIC:
        return HARMONIC[fmu.scene]
    sv = {name: float(fmu.start[name]) for name in ("F", "Omega") if name in fmu.start}
    assert len(sv) == 2 and sv["F"] != 0.0 and sv["Omega"] > 0.0, (
        f"{fmu.scene}: no harmonic excitation to test (F, Omega = {sv}): give the scene a harmonic "
        f"load with non-zero start values of F and Omega in [defaults], or an entry in HARMONIC"
    )
    return sv


@pytest.mark.usefixtures("fmu_paths")
def test_excitation_of_a_scene_outside_the_table(tmp_path: Path) -> None:
    """A scene that is not one of the paper's is excited with its own F and Omega (no KeyError),
    and one without a harmonic load is refused with a message that says what to add."""

    def info(name: str) -> FmuInfo:
        path = FMU_DIR / f"{name}.fmu"
        md = fmpy.read_model_description(str(path))
        return FmuInfo.from_model_description(name, path, tmp_path, md)

    assert excitation(info("ThreeSpan")) == {"F": 1000.0, "Omega": 60.0}
    with pytest.raises(AssertionError, match="Cantilever: no harmonic excitation"):
        excitation(info("Cantilever"))


def test_validate_fmu_finds_no_problem(fmu: FmuInfo) -> None:
    problems = validate_fmu(str(fmu.path))
    assert problems == [], "\n".join(problems)


def test_model_description_interface(fmu: FmuInfo) -> None:
    """The standard names (docs/scenes.md, "What every FMU has") and the shipped scenes' own
    (scenes/*.toml); scene-specific parameters only where they belong."""
    md = fmu.md
    assert md.fmiVersion == "2.0"
    assert md.coSimulation is not None and md.coSimulation.modelIdentifier == fmu.scene
    common = {"E", "nu", "rho", "d", "b", "h", "L", "elements", "dt_max", "F", "Omega", "f_ctrl"}
    common |= {"w_mid", "v_mid", "E_kin", "E_strain", "newton_iterations"}
    names = set(fmu.vr)
    assert common <= names
    beam_only, arch_only = {"pre_shortening", "well"}, {"H", "P0"}
    if fmu.scene == "BuckledBeam":
        assert beam_only <= names and not (arch_only & names)
    else:
        assert arch_only <= names and not (beam_only & names)
    cs = md.coSimulation
    assert cs.canHandleVariableCommunicationStepSize
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate
    assert md.defaultExperiment is not None


def test_simulate_default_experiment(fmu: FmuInfo) -> None:
    res = fmpy.simulate_fmu(str(fmu.path), output=["w_mid", "v_mid", "E_kin", "E_strain"])
    stop = fmu.md.defaultExperiment.stopTime
    assert res["time"][0] == 0.0
    assert abs(res["time"][-1] - float(stop)) < 1e-9
    for name in ("w_mid", "v_mid", "E_kin", "E_strain"):
        assert np.all(np.isfinite(res[name])), name
    assert np.all(res["E_kin"] >= 0.0)


def test_simulate_harmonic_excitation(fmu: FmuInfo) -> None:
    """With F != 0 the midspan moves: its velocity reaches a clearly non-zero level and the
    displacement leaves its initial value by more than round-off (1e-6 of the span)."""
    sv = excitation(fmu)
    stop = 5 * period(sv["Omega"])
    res = fmpy.simulate_fmu(
        str(fmu.path), start_values=sv, stop_time=stop, step_size=1e-4, output=["w_mid", "v_mid"]
    )
    w, v = res["w_mid"], res["v_mid"]
    assert np.all(np.isfinite(w)) and np.all(np.isfinite(v))
    span = float(fmu.start["L"])
    assert np.ptp(w) > 1e-6 * span, f"w_mid hardly moves: ptp {np.ptp(w):.3e}"
    assert np.max(np.abs(v)) > 0.0


def test_simulate_zero_excitation_stays_at_rest(fmu: FmuInfo) -> None:
    """F = 0 from a static equilibrium: nothing moves beyond solver round-off (1e-8 of the span,
    a loose bound for a Newton tolerance of about 1e-10 per step over 100 steps)."""
    res = fmpy.simulate_fmu(
        str(fmu.path), start_values={"F": 0.0}, stop_time=0.01, step_size=1e-4, output=["w_mid"]
    )
    w = res["w_mid"]
    span = float(fmu.start["L"])
    assert np.max(np.abs(w - w[0])) < 1e-8 * span
