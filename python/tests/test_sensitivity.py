"""The sensitivity study of section 6.1 (georod_tools.studies.sensitivity*): the scene variants
exactly, the bracket logic on made-up scans, and the quick command end to end with checks of
its physics (each with the reason for its tolerance)."""

from __future__ import annotations

import csv
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from georod_tools.analysis.case import CaseConfig, CaseResult
from georod_tools.analysis.classify import classify
from georod_tools.studies.sensitivity_scenes import SceneSpec, scene_text
from georod_tools.studies.sensitivity_statics import prony_omega
from georod_tools.studies.sensitivity_windows import FEATURES, initial_bracket

REPO = Path(__file__).resolve().parents[2]
needs_fmu = pytest.mark.usefixtures("fmu_paths")


def test_scene_variants_change_only_what_they_say() -> None:
    base = tomllib.loads(scene_text(SceneSpec(), "BB_ref"))
    assert "model" not in base and base["name"] == "BB_ref"
    lumped = tomllib.loads(
        scene_text(SceneSpec(mass="lumped", shear_factor=5 / 6, rotational_damping=1e-5), "X")
    )
    assert lumped["model"] == {"mass": "lumped", "shear_factor": 5 / 6, "rotational_damping": 1e-5}
    assert lumped["support"] == base["support"] and lumped["load"] == base["load"]
    dead = tomllib.loads(scene_text(SceneSpec(loading="dead", axial_load=100.5), "D"))
    right = next(s for s in dead["support"] if s["name"] == "right")
    assert right["fix"] == ["u2"] and "displace" not in right
    assert {p["name"]: p["start"] for p in dead["parameter"]}["P_axial"] == 100.5
    assert [x["name"] for x in dead["load"]] == ["q", "f_ctrl", "axial"]
    short = tomllib.loads(scene_text(SceneSpec(pre_shortening=0.1025), "S"))
    assert {p["name"]: p["start"] for p in short["parameter"]}["pre_shortening"] == 0.1025
    with pytest.raises(ValueError):
        SceneSpec(loading="dead")  # no calibrated load
    with pytest.raises(ValueError):
        SceneSpec(mass="diagonal")


def test_prony_recovers_a_damped_frequency() -> None:
    dt = 1e-5
    t = np.arange(2000) * dt
    x = np.exp(-250 * t) * np.cos(2500 * t) + 0.01 * np.exp(-250 * t) * np.cos(26000 * t)
    # |s| of the slow pair = sqrt(250^2 + 2500^2); the fit is exact for a sum of two modes
    assert prony_omega(x, dt) == pytest.approx(math.hypot(250, 2500), rel=1e-8)


def _fake(omega: float, samples: np.ndarray, exponent: float) -> CaseResult:
    cfg = CaseConfig(fmu="x.fmu", Omega=omega, transient_periods=0, sample_periods=len(samples))
    size = np.ptp(samples, axis=0) + 1.0
    cls = classify(samples, exponent, size=size)
    return CaseResult(cfg, samples, np.arange(len(samples)), size, None, None, cls, 0.0)


def test_brackets_from_a_scan() -> None:
    """Scan (low to high Omega): chaos, P6, P3, P3, chaos, P4 (one well), P2, P2."""
    rng = np.random.default_rng(1)
    p = {k: np.array([[0.3 + 0.1 * j, j] for j in range(k)] * (60 // k)) for k in (2, 3, 4, 6)}
    chaos = rng.normal(size=(60, 2))
    res = [
        _fake(3400, chaos, 0.5),
        _fake(3450, p[6] - 0.5, -0.01),
        _fake(3500, p[3] - 0.4, -0.01),
        _fake(3550, p[3] - 0.4, -0.01),
        _fake(3600, chaos, 0.5),
        _fake(3650, p[4], -0.01),
        _fake(3700, p[2], -0.01),
        _fake(3750, p[2], -0.01),
    ]
    omegas = [r.config.Omega for r in res]
    got = {f.name: initial_bracket(f, omegas, res) for f in FEATURES}
    assert (got["p3_top"].lo, got["p3_top"].hi) == (3550, 3600)
    assert (got["p3_doubling"].lo, got["p3_doubling"].hi) == (3450, 3500)
    assert (got["p3_chaos"].lo, got["p3_chaos"].hi) == (3400, 3450)
    assert (got["p2_doubling"].lo, got["p2_doubling"].hi) == (3650, 3700)
    assert (got["p2_chaos"].lo, got["p2_chaos"].hi) == (3600, 3650)
    assert (got["merge"].lo, got["merge"].hi) == (3600, 3650)
    no_p2 = initial_bracket(FEATURES[3], omegas[:5], res[:5])
    assert math.isnan(no_p2.lo) and "not found" in no_p2.note


def _docs_snapshot() -> dict[str, float]:
    return {str(p): p.stat().st_mtime_ns for p in (REPO / "docs").rglob("*") if p.is_file()}


@needs_fmu
def test_sensitivity_quick_command(tmp_path: Path) -> None:
    """``study sensitivity --quick``: every question asked once, files and run.json written,
    docs/ untouched; the statics obey the mechanics they must."""
    from georod_tools.cli import main

    before = _docs_snapshot()
    out = tmp_path / "sens"
    assert main(["study", "sensitivity", "--quick", "--no-progress", "--out", str(out)]) == 0
    record = json.loads((out / "run.json").read_text())
    assert record["status"] == "complete" and record["published"] == []
    assert _docs_snapshot() == before
    for q in ("shortening", "elements", "mass", "shear", "rotational_damping", "loading"):
        assert (out / f"sensitivity_{q}.png").stat().st_size > 5000, q
    with (out / "sensitivity_variants.csv").open() as f:
        rows = {(r["question"], r["variant"]): r for r in csv.DictReader(f)}
    ref = rows[("reference", "reference")]
    w0, om_modes, om_free = (float(ref[k]) for k in ("w_mid", "omega_modes", "omega_free"))
    # the repository's documented static state (10 elements, shortening 0.11)
    assert w0 == pytest.approx(0.3305, abs=1e-4)
    # eigenproblem and free vibration at T/128: both the same frequency; they differ by the
    # midpoint rule's error (omega dt)^2 / 12 ~ 1e-4 and the pulse's small nonlinearity (~3e-4)
    assert om_free == pytest.approx(om_modes, rel=2e-3)
    # a dead load equal to the prescribed state's axial force gives the very same equilibrium
    dead = rows[("loading", "dead load")]
    assert float(dead["w_mid"]) == pytest.approx(w0, rel=1e-9)
    # ... but a far softer beam: the axial force cannot grow as it swings
    assert float(dead["omega_free"]) < 0.1 * om_free
    # 0.11 as the buckling part only: the strain part N L / EA ~ 100 * 10 / 1.2e4 ~ 0.083 added
    buckling = rows[("loading", "buckling part")]
    assert float(buckling["pre_shortening"]) - 0.11 == pytest.approx(0.0834, abs=1e-3)
    assert float(buckling["w_mid"]) > 1.8 * w0
    # less shortening: less buckling, a shallower well and a lower frequency
    short = rows[("shortening", "0.105")]
    assert float(short["w_mid"]) < w0 and float(short["omega_free"]) < 0.95 * om_free
    # lumped mass lowers the linear elements' frequency; the statics do not see the mass
    lumped = rows[("mass", "lumped")]
    assert float(lumped["w_mid"]) == pytest.approx(w0, rel=1e-12)
    assert float(lumped["omega_free"]) < om_free
    assert "slope per +0.001" in (out / "table_sensitivity_derivatives.md").read_text()
