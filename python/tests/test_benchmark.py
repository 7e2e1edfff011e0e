"""Smoke tests of the work-precision benchmark (georod_tools.benchmark): the pure helpers exactly,
the numpy twin of model.md's element against the FMU's static state, Exudyn's model against the
FMU's (when exudyn is installed), and the whole benchmark end to end with tiny sizes (< 30 s)."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from georod_tools.benchmark import (
    BeamScene,
    ExudynBeam,
    equal_error_ratio,
    errors,
    exudyn_status,
    fmu_run,
    generalized_frequencies,
    georod_frequencies,
    run_benchmark,
)

REPO = Path(__file__).resolve().parents[2]
BEAM_FMU = REPO / "target" / "fmu" / "BuckledBeam.fmu"
needs_fmu = pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale
# Regression guard, not an independent reference: the static buckled w_mid of the default
# BuckledBeam (10 elements) as this code computes it (tests/physics_scenes.rs prints it).
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
def test_numpy_twin_matches_fmu_static_state() -> None:
    freq, w_mid, residual = georod_frequencies(BeamScene(), 10, 2, fmu=BEAM_FMU)
    assert residual < 1e-10  # the FMU's static state is an equilibrium of model.md's element
    assert w_mid == pytest.approx(REGRESSION_W_STATIC, abs=1e-6)  # regression guard
    assert 2000 < freq[0] < 3000 and 9000 < freq[1] < 12000


@needs_fmu
def test_exudyn_model_agrees_with_fmu() -> None:
    installed, why = exudyn_status()
    assert installed, f"exudyn is pinned in python/requirements.txt but cannot be imported: {why}"
    sc = BeamScene()
    fg, wg, _ = georod_frequencies(sc, 20, 2, fmu=BEAM_FMU)
    ex = ExudynBeam(sc, 20)
    try:
        fe = ex.frequencies(2)
        assert ex.w_static == pytest.approx(wg, rel=5e-3)
        assert fe == pytest.approx(fg, rel=1e-2)
        r = ex.run(16, 1, 1, record=True)
        assert len(r.w) == 17 and r.w[0] == pytest.approx(ex.w_static)
        assert r.seconds > 0
    finally:
        ex.close()


@needs_fmu
def test_quick_benchmark_end_to_end(tmp_path: Path) -> None:
    rep = run_benchmark(
        tmp_path / "out",
        tmp_path / "fig",
        quick=True,
        use_exudyn=exudyn_status()[0],
        fmu=BEAM_FMU,
        parts=("time", "space", "scaling"),
        log=lambda _: None,
    )
    names = {p.name for p in rep.files}
    assert {"work_precision.csv", "space.csv", "scaling.csv", "benchmark.md"} <= names
    assert "benchmark_quick_work_precision_final.png" in names
    with (tmp_path / "out" / "work_precision.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    fmu = [r for r in rows if r["method"] == "fmu"]
    assert [int(r["steps_per_period"]) for r in fmu] == [8, 16, 32]
    errs = [float(r["err_final"]) for r in fmu]
    assert errs[0] > errs[1] > errs[2] > 0
    assert all(float(r["seconds"]) > 0 for r in rows)
