"""Smoke tests of the benchmarks (georod_tools.studies.benchmark, .lyapunov_benchmark): the pure
helpers exactly, the core's model quantities (the FMU's static state, ``georod modes``) against
each other and against Exudyn's model, and both benchmarks end to end with tiny sizes."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from georod_tools.studies.bench_beam import (
    BeamScene,
    equal_error_ratio,
    errors,
    fmu_run,
    model_quantities,
)
from georod_tools.studies.exudyn_beam import ExudynBeam, exudyn_status, generalized_frequencies

REPO = Path(__file__).resolve().parents[2]
BEAM_FMU = REPO / "target" / "fmu" / "BuckledBeam.fmu"
needs_fmu = pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale
# Regression guard, not an independent reference: the static buckled w_mid of the default
# BuckledBeam (10 elements) as this code computes it (tests/suite/physics_scenes.rs prints it).
REGRESSION_W_STATIC = 0.3304747


def test_errors_on_refined_grid() -> None:
    ref = np.linspace(0.0, 1.0, 9)
    w = ref[::4] + np.array([0.0, 0.5, -0.25])
    assert errors(w, ref) == (0.25, 0.5)
    with pytest.raises(ValueError):
        errors(np.zeros(4), ref)


def test_equal_error_ratio_interpolates_log_log() -> None:
    # other: error = 1/t^2 (t = 1, 10, 100); fmu at error 1e-2 took 1 s -> other needs 10 s
    other = [(1.0, 1.0), (1e-2, 10.0), (1e-4, 100.0)]
    rows = equal_error_ratio([(1e-3, 2.0), (1e-6, 1.0)], other)
    assert len(rows) == 1  # 1e-6 is outside the other's range
    e, t, t_other, ratio = rows[0]
    assert e == 1e-3 and t == 2.0
    assert t_other == pytest.approx(10**1.5)
    assert ratio == pytest.approx(10**1.5 / 2)


def test_generalized_frequencies_of_a_chain() -> None:
    # two unit masses, springs 1 to ground and 1 between, third coordinate removed
    K = np.array([[2.0, -1.0, 5.0], [-1.0, 2.0, 5.0], [5.0, 5.0, 5.0]])
    M = np.eye(3)
    f = generalized_frequencies(K, M, [2], 2)
    assert f == pytest.approx([1.0, math.sqrt(3.0)])


@needs_fmu
def test_fmu_run_is_second_order_and_repeatable() -> None:
    sc = BeamScene()
    ref = fmu_run(sc, 1024, 2, 1, fmu=BEAM_FMU)
    e = [errors(fmu_run(sc, n, 2, 2, fmu=BEAM_FMU).w, ref.w)[1] for n in (64, 128)]
    assert 3.0 < e[0] / e[1] < 5.0  # midpoint rule: second order (max error over 2 periods)
    a = fmu_run(sc, 16, 1, 1, fmu=BEAM_FMU)
    b = fmu_run(sc, 16, 1, 1, fmu=BEAM_FMU)
    assert np.array_equal(a.w, b.w)  # restored FMU state: bit-identical repetitions
    # regression guard (this code's static buckled w_mid, 10 elements; no independent source)
    assert a.w[0] == pytest.approx(REGRESSION_W_STATIC, abs=1e-6)


@needs_fmu
def test_model_quantities_come_from_the_core() -> None:
    """The FMU's static state and ``georod modes`` about the same equilibrium agree (two paths
    through the core: the FMU's load stepping and the continuation of the static path; measured
    equal to 1e-12), and the frequencies are those of the buckled beam."""
    q = model_quantities(BeamScene(), 10, 2, fmu=BEAM_FMU)
    assert q.w_static_fmu == pytest.approx(q.w_static_core, abs=1e-9)
    assert q.w_static_fmu == pytest.approx(REGRESSION_W_STATIC, abs=1e-6)  # regression guard
    assert 2000 < q.omegas[0] < 3000 and 9000 < q.omegas[1] < 12000


@needs_fmu
def test_exudyn_model_agrees_with_the_core() -> None:
    installed, why = exudyn_status()
    assert installed, f"exudyn is pinned in python/requirements.txt but cannot be imported: {why}"
    sc = BeamScene()
    q = model_quantities(sc, 20, 2, fmu=BEAM_FMU)
    ex = ExudynBeam(sc, 20)
    try:
        fe = ex.frequencies(2)
        assert ex.w_static == pytest.approx(q.w_static_fmu, rel=5e-3)
        assert fe == pytest.approx(q.omegas, rel=1e-2)
        r = ex.run(16, 1, 1, record=True)
        assert len(r.w) == 17 and r.w[0] == pytest.approx(ex.w_static)
        assert r.seconds > 0
    finally:
        ex.close()


@needs_fmu
def test_quick_benchmark_end_to_end(tmp_path: Path) -> None:
    from georod_tools.studies.benchmark_report import run_benchmark

    rep = run_benchmark(
        tmp_path / "out",
        quick=True,
        use_exudyn=exudyn_status()[0],
        fmu=BEAM_FMU,
        parts=("time", "space", "scaling"),
        log=lambda _: None,
    )
    names = {p.name for p in rep.files}
    assert {"work_precision.csv", "space.csv", "scaling.csv", "benchmark.md"} <= names
    assert {"benchmark_work_precision_final.png", "benchmark_scaling.png"} <= names
    with (tmp_path / "out" / "work_precision.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    fmu = [r for r in rows if r["method"] == "fmu"]
    assert [int(r["steps_per_period"]) for r in fmu] == [8, 16, 32]
    errs = [float(r["err_final"]) for r in fmu]
    assert errs[0] > errs[1] > errs[2] > 0
    assert all(float(r["seconds"]) > 0 for r in rows)


@needs_fmu
def test_lyapunov_methods_benchmark_end_to_end(tmp_path: Path) -> None:
    """Three values of F, 20 + 20 periods, one worker: the table has a row per method with
    positive times and the ratios; the twin's reference runs the core's trajectory exactly."""
    from georod_tools.studies.lyapunov_benchmark import BenchSettings, run_lyapunov_benchmark

    st = BenchSettings(
        str(BEAM_FMU), count=3, transient=20, periods=20, substeps=32, workers=(1,), bench_steps=500
    )
    files = run_lyapunov_benchmark(st, tmp_path, progress=False, say=lambda _: None)
    assert {f.name for f in files} == {
        "lyapunov_methods.csv",
        "lyapunov_agreement.csv",
        "lyapunov_methods.md",
        "lyapunov_methods.png",
    }
    with (tmp_path / "lyapunov_methods.csv").open() as fh:
        rows = {r["method"]: r for r in csv.DictReader(fh)}
    assert set(rows) == {"core", "twin", "plain"}
    assert float(rows["core"]["wall_vs_core"]) == 1.0
    assert all(float(r["wall_s"]) > 0 and float(r["us_per_substep"]) > 0 for r in rows.values())
    assert int(rows["twin"]["substeps"]) == 3 * (20 + 2 * 20) * 32
    with (tmp_path / "lyapunov_agreement.csv").open() as fh:
        agree = list(csv.DictReader(fh))
    assert len(agree) == 3 and all(a["same_samples"] == "True" for a in agree)
    assert "Classification equal for" in (tmp_path / "lyapunov_methods.md").read_text()
