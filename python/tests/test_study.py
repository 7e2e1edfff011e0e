"""Smoke tests of the section 6.1 study (georod_tools.studies.paper, .paper_report) and of the
demo (georod_tools.studies.demo): the pure helpers exactly, the study and the demo end to end with
tiny runs, and the rule that a run writes into docs/ only with --update-docs."""

from __future__ import annotations

import csv
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from georod_tools.analysis.case import CaseConfig, CaseResult
from georod_tools.analysis.classify import classify
from georod_tools.report.tables import markdown
from georod_tools.studies.demo import summarize
from georod_tools.studies.paper import StudySettings, agreement, lines, wells
from georod_tools.studies.paper_cases import PAPER_CASES, PaperCase

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
    cfgs.append(replace(st.config(0.7, 3400.0), substeps=256))
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


def _docs_snapshot() -> dict[str, float]:
    docs = REPO / "docs"
    return {str(p): p.stat().st_mtime_ns for p in docs.rglob("*") if p.is_file()}


@needs_fmu
def test_study_quick_smoke(tmp_path: Path) -> None:
    """Two cases (one agrees, one -- very likely at these short runs -- does not, so the checks
    run too), a 2-value bifurcation diagram, elements 2 and 6; nothing in docs/ changes."""
    from georod_tools.studies.paper import run_study
    from georod_tools.studies.paper_report import write_outputs

    before = _docs_snapshot()
    st = StudySettings(
        fmu=str(BEAM_FMU),
        elements=6,
        substeps=16,
        transient=10,
        periods=25,
        dense_periods=5,
        bif_count=2,
        bif_transient=5,
        bif_periods=15,
        element_counts=(2, 6),
        cases=(PAPER_CASES[0], PAPER_CASES[2]),
    )
    rep = run_study(st, workers=2, progress=False)
    write_outputs(st, rep, tmp_path)
    assert [c.name for c, _ in rep.cases] == ["fig2a", "fig2c"]
    assert abs(rep.statics[0]) < 1e-6 < abs(rep.statics[1])  # 2 elements: no buckling
    for name in (
        "overview_fig2.png",
        "bifurcation_F.png",
        "bifurcation_Omega.png",
        "elements.png",
        "cases/fig2a.png",
        "cases/fig2c.png",
    ):
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
    assert _docs_snapshot() == before


@needs_fmu
def test_study_commands_write_runs_not_docs(tmp_path: Path) -> None:
    """``study arches --quick`` and ``benchmark precision --quick`` (the two that wrote into
    docs/figures before) leave docs/ untouched and write a run folder with run.json; a quick run
    refuses --update-docs."""
    import json

    from georod_tools.cli import main

    before = _docs_snapshot()
    out = tmp_path / "bench"
    argv = [
        "benchmark",
        "precision",
        "--quick",
        "--no-exudyn",
        "--parts",
        "time",
        "--out",
        str(out),
    ]
    assert main(argv) == 0
    record = json.loads((out / "run.json").read_text())
    assert record["status"] == "complete" and record["published"] == []
    assert "benchmark_work_precision_final.png" in record["outputs"]
    assert record["fmu"]["BuckledBeam"]["guid"]
    assert _docs_snapshot() == before
    with pytest.raises(SystemExit) as e:
        main(["study", "arches", "--quick", "--update-docs", "--out", str(tmp_path / "a")])
    assert e.value.code == 2
    assert _docs_snapshot() == before


@needs_fmu
def test_study_command_line_refuses_bad_workers(capsys: pytest.CaptureFixture[str]) -> None:
    from georod_tools.cli import main

    with pytest.raises(SystemExit) as e:
        main(["study", "paper", "--workers", "0"])
    assert e.value.code == 2
    assert "--workers" in capsys.readouterr().err


@needs_fmu
def test_demo_fast_smoke(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from georod_tools.cli import main

    out = tmp_path / "demo"
    assert main(["demo", "--out", str(out), "--transient", "5", "--periods", "15"]) == 0
    text = capsys.readouterr().out
    assert "static w_mid = 0.3" in text and "largest Lyapunov exponent" in text
    for name in ("demo_buckled_beam.png", "demo_poincare_F1.5.png", "demo_poincare_F0.4.png"):
        assert (out / name).stat().st_size > 1000
    summary = (out / "summary.txt").read_text()
    assert "static w_mid = 0.3" in summary and "F = 1.5" in summary
    assert (out / "run.json").is_file()
