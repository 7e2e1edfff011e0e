"""Arches (docs/arches.md): short arch cases through the FMUs, classified by the chaos tools, and
the start in the inverted equilibrium z3 through FMU variables only.

The thresholds on w_mid below (wells at 0 and -3.99, the ring's position and width) are
regression guards drawn from this code's own runs (docs/arches.md), not independent references;
the independent statements are the classifications, the torus exponent 0 and the static z3 of
the core's ``georod modes``.

- PinnedArch (defaults, 10 elements), F = 20, Omega = 1000 rad/s (~0.8 of the lowest natural
  frequency about z1, 1228 rad/s): the global chaotic attractor of docs/figures/
  arches_chaos_pinned.png; a short run (100 + 100 periods) already measures an exponent of
  ~0.8 per period.
- Z3_PRELUDE pushes the crown through with the f_ctrl input and releases it: the arch rests in
  z3; at small forcing it stays there.
- ClampedArch, d = 1e-4, Omega = 2000 rad/s, F = 112: the modulated (quasi-periodic) snap-through
  motion of docs/figures/arches_clamped_ring.png (a ring in the Poincaré section).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from georod_tools.studies.arches import Z3_PRELUDE
from georod_tools.studies.arches_study import arch_case, clamped_ring_case

pytestmark = pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale


def test_pinned_arch_chaotic() -> None:
    from georod_tools.analysis.case import run_case

    r = run_case(arch_case("PinnedArch", F=20.0, transient_periods=100, sample_periods=100))
    assert r.classification.kind == "chaotic", r.classification.note
    assert r.exponent_per_period > 0.3
    # Global: the motion visits both wells (z1 at 0, z3 at -3.99).
    assert r.samples[:, 0].max() > -0.5 and r.samples[:, 0].min() < -2.7


def test_prelude_reaches_the_static_z3() -> None:
    """After the push and release (150 periods at Omega = 1000) the arch rests in z3: w_mid equals
    the core's static z3 (``georod modes``) to 1e-6 m (measured 5e-9; the residual motion's
    amplitude v / omega ~ 1e-5 / 1000), and the kinetic energy is below 1e-10 of the strain
    energy (measured 1e-16): a start at rest, like the static state the FMU starts from in z1."""
    from georod_tools.analysis.case import start_forcing
    from georod_tools.fmu import FmuModel, core_command, lend

    z3 = next(m for m in core_command.modes("PinnedArch", count=1) if m.equilibrium == "z3")
    cfg = arch_case("PinnedArch", F=2.0, prelude=Z3_PRELUDE)
    with lend(FmuModel.load(cfg.fmu)) as inst:
        inst.initialize(cfg.fmu_parameters())
        assert inst.get(["w_mid"])[0] == pytest.approx(0.0, abs=1e-12)  # z1
        assert start_forcing(inst, cfg) == Z3_PRELUDE.periods
        w, v, e_kin, e_strain, f = inst.get(["w_mid", "v_mid", "E_kin", "E_strain", "F"])
    print(f"after the prelude: w_mid {w:.9f} (z3 {z3.w_mid:.9f}), v_mid {v:.2e}, E_kin {e_kin:.2e}")
    assert w == pytest.approx(z3.w_mid, abs=1e-6)
    assert e_kin < 1e-10 * e_strain and abs(v) < 1e-3
    assert f == 2.0  # the forcing is on


def test_pinned_arch_from_z3_stays_in_z3() -> None:
    from georod_tools.analysis.case import run_case

    cfg = arch_case(
        "PinnedArch",
        F=2.0,
        transient_periods=30,
        sample_periods=20,
        lyapunov=False,
        prelude=Z3_PRELUDE,
    )
    r = run_case(cfg)
    assert r.classification.label == "period-1"
    assert np.all(r.samples[:, 0] < -3.5)
    first = (Z3_PRELUDE.periods + 31) * cfg.period  # samples at the end of each period
    assert r.sample_times[0] == pytest.approx(first, rel=1e-12)


def test_clamped_arch_quasi_periodic() -> None:
    """Figure 11 analogue (docs/arches.md section 4), short: 400 + 300 periods. On an invariant
    torus the largest exponent is 0 (known value); the core's tangent measures a few 1e-3 per
    period over 290 periods; bound 0.02, a tenth of the chaotic cases' exponents."""
    from georod_tools.analysis.case import run_case

    r = run_case(clamped_ring_case(transient_periods=400, sample_periods=300, dense_periods=0))
    assert r.classification.kind == "quasi-periodic", r.classification.note
    assert abs(r.exponent_per_period) < 0.02
    # A ring of finite size: the section moves over a few percent of the swing of w_mid.
    w = r.samples[:, 0]
    assert 0.05 < np.ptp(w) < 0.5 and np.all(w < -5.5)


def test_arch_path_command_writes_diagram(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`georod-tools study arch-path`: CSV and PNG of the PinnedArch path, with its three
    zero-load equilibria (z2 unstable) and its limit points reported."""
    from georod_tools.cli import main

    out = tmp_path / "path"
    assert main(["study", "arch-path", "--scene", "PinnedArch", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert (out / "static_PinnedArch.csv").stat().st_size > 0
    assert (out / "static_PinnedArch.png").stat().st_size > 0
    assert (out / "run.json").is_file()
    assert "z2: w_mid" in text and "(unstable)" in text and text.count("LimitPoint") == 2


def test_earlier_substeps() -> None:
    """T/20 cut into pieces of at most 1e-5 s: 32 per twentieth at Omega = 1000 (T = 6.28 ms)."""
    from georod_tools.studies.arches_study import earlier_substeps

    assert earlier_substeps(1000.0) == 640 and earlier_substeps(2000.0) == 320
    assert earlier_substeps(2 * math.pi / 2e-4) == 20  # exactly 1e-5 per twentieth: no round-up


def test_quick_study_writes_a_run_folder_not_docs(tmp_path: Path) -> None:
    """`georod-tools study arches --quick` (about 15 s): every figure of docs/arches.md into the
    run folder with its run.json, nothing into docs/; the z3 cascade starts in the inverted
    well (w_mid near -4) and the ClampedArch ring is quasi-periodic, as the page says."""
    import json

    from georod_tools.cli import main

    docs = Path(__file__).resolve().parents[2] / "docs"
    before = {p: p.stat().st_mtime_ns for p in docs.rglob("*") if p.is_file()}
    out = tmp_path / "arches"
    assert main(["study", "arches", "--quick", "--out", str(out)]) == 0
    names = {p.name for p in out.iterdir()}
    for fig in (
        "static_pinned",
        "static_clamped",
        "chaos_pinned",
        "cascades",
        "clamped",
        "clamped_ring",
        "clamped_doubling",
        "onset_elements",
    ):
        assert f"arches_{fig}.png" in names
    record = json.loads((out / "run.json").read_text())
    assert record["status"] == "complete" and set(record["fmu"]) == {"PinnedArch", "ClampedArch"}
    log = (out / "study_log.txt").read_text()
    assert "cascade from z3: F = 2: period-1" in log and "w_mid in [-4.1" in log
    assert "Figure 11 analogue" in log and "quasi-periodic" in log
    assert {p: p.stat().st_mtime_ns for p in docs.rglob("*") if p.is_file()} == before
