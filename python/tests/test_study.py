"""Smoke tests of the section 6.1 study (georod_tools.study) and of the demo (georod_tools.demo):
the pure helpers exactly, the study and the demo end to end with tiny runs (about 15 s)."""

from __future__ import annotations

import csv
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from georod_tools.classify import classify
from georod_tools.demo import summarize
from georod_tools.runner import CaseConfig, CaseResult
from georod_tools.study import (
    PAPER_CASES,
    PaperCase,
    StudySettings,
    agreement,
    lines,
    markdown,
    wells,
)

REPO = Path(__file__).resolve().parents[2]
BEAM_FMU = REPO / "target" / "fmu" / "BuckledBeam.fmu"
needs_fmu = pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale


def _result(samples: np.ndarray, exponent: float) -> CaseResult:
    """A CaseResult without running anything (classified from `samples`)."""
    cfg = CaseConfig(fmu="none.fmu", transient_periods=0, sample_periods=len(samples))
    return CaseResult(
        config=cfg,
        samples=samples,
        sample_times=np.arange(len(samples)) * cfg.period,
        size=np.ptp(samples, axis=0) + 1.0,
        dense=None,
        lyapunov=None,
        classification=classify(samples, exponent, size=np.ptp(samples, axis=0) + 1.0),
        wall_time=0.0,
    )


def test_paper_cases_cover_figures_2_to_5() -> None:
    counts = {f: sum(c.figure == f for c in PAPER_CASES) for f in (2, 3, 4, 5)}
    assert counts == {2: 6, 3: 6, 4: 8, 5: 6}
    fig4d = next(c for c in PAPER_CASES if c.name == "fig4d")
    assert (fig4d.F, fig4d.Omega, fig4d.period) == (0.7, 3460.0, 24)


def test_lines_groups_cases_into_sweeps() -> None:
    st = StudySettings(fmu="x.fmu")
    cfgs = [st.config(0.7, om) for om in (3400.0, 3500.0)] + [st.config(f, 3500.0) for f in (0.4,)]
    cfgs.append(replace(st.config(0.7, 3400.0), dt_max=5e-6))
    groups = lines(cfgs)
    got = sorted((p, tuple(v)) for _, p, v in groups)
    assert got == [("F", (0.4,)), ("F", (0.7,)), ("Omega", (3400.0, 3500.0))]
    for base, param, values in groups:
        for v in values:
            assert base.with_value(param, v) in cfgs


def test_agreement_and_wells() -> None:
    period3 = np.array([[0.3, 1.0], [-0.2, 2.0], [0.1, -1.0]] * 10)
    r = _result(period3, -0.01)
    assert r.classification.label == "period-3"
    assert wells(r) == "both"
    p3 = PaperCase(2, "c", 0.7, 3500.0, "three-period", "periodic", 3, "both")
    chaotic = PaperCase(2, "b", 0.6, 3500.0, "chaotic", "chaotic", None, "both")
    p6 = replace(p3, period=6)
    long = PaperCase(4, "e", 0.7, 3450.0, "long", "long-period")
    assert agreement(p3, r) == "yes"
    assert agreement(p6, r) == "partly"
    assert agreement(chaotic, r) == "no"
    assert agreement(long, r) == "partly"
    one_well = _result(np.abs(period3) + 0.1, -0.01)
    assert wells(one_well) == "one (+)"
    assert agreement(p3, one_well) == "partly"


def test_markdown_table() -> None:
    text = markdown([{"a": 1, "b": "x"}], ("a", "b"))
    assert text.splitlines() == ["| a | b |", "|---|---|", "| 1 | x |"]


def test_demo_summary() -> None:
    t = np.linspace(0.0, 0.1, 101)
    res = np.zeros(101, dtype=[("time", float), ("w_mid", float), ("v_mid", float)])
    res["time"], res["w_mid"], res["v_mid"] = t, 0.33 + 0.5 * np.sin(200 * t), 100 * np.cos(t)
    s = summarize(res)
    assert s.static_w_mid == pytest.approx(0.33)
    assert s.w_max == pytest.approx(0.83, abs=1e-3) and s.w_min == pytest.approx(-0.17, abs=1e-3)
    assert s.crosses_zero and s.t_end == pytest.approx(0.1)
    assert "visits both wells" in s.text()
    with pytest.raises(ValueError):
        summarize(res[:0])


@needs_fmu
def test_study_quick_smoke(tmp_path: Path) -> None:
    """Two cases (one agrees, one -- very likely at these short runs -- does not, so the checks
    run too), a 2-value bifurcation diagram, elements 2 and 6."""
    from georod_tools.study import run_study

    st = StudySettings(
        fmu=str(BEAM_FMU),
        elements=6,
        dt_max=2e-5,
        n_per_period=10,
        transient=10,
        periods=25,
        dense_periods=5,
        bif_count=2,
        bif_transient=5,
        bif_periods=15,
        element_counts=(2, 6),
        cases=(PAPER_CASES[0], PAPER_CASES[2]),
    )
    rep = run_study(st, tmp_path, workers=2, progress=False)
    assert [c.name for c, _ in rep.cases] == ["fig2a", "fig2c"]
    assert abs(rep.statics[0]) < 1e-6 < abs(rep.statics[1])  # 2 elements: no buckling
    for name in ("overview_fig2.png", "bifurcation_F.png", "bifurcation_Omega.png",
                 "elements.png", "cases/fig2a.png", "cases/fig2c.png"):  # fmt: skip
        size = (tmp_path / name).stat().st_size
        assert 1000 < size < 200_000, name
    with (tmp_path / "classifications.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert [r["case"] for r in rows] == ["fig2a", "fig2c"]
    assert all(int(r["samples"]) == 25 for r in rows)
    differing = sum(r["agrees"] != "yes" for r in rows)
    if differing:  # base + 5 variants per differing case
        conv = (tmp_path / "convergence.csv").read_text().splitlines()
        assert len(conv) == 1 + 6 * differing
    assert "## Number of elements" in (tmp_path / "study.md").read_text()


@needs_fmu
def test_study_command_line_refuses_bad_workers(capsys: pytest.CaptureFixture[str]) -> None:
    from georod_tools.cli import main

    with pytest.raises(SystemExit) as e:
        main(["study", "--workers", "0"])
    assert e.value.code == 2
    assert "--workers" in capsys.readouterr().err


@needs_fmu
def test_demo_fast_smoke(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from georod_tools.demo import main

    assert main(["--out", str(tmp_path), "--transient", "5", "--periods", "15"]) == 0
    out = capsys.readouterr().out
    assert "static w_mid = 0.3" in out and "largest Lyapunov exponent" in out
    for name in ("demo_buckled_beam.png", "demo_poincare_F1.5.png", "demo_poincare_F0.4.png"):
        assert (tmp_path / name).stat().st_size > 1000
