"""A Dask sweep gives identical results with 1 and 2 workers (tiny sweep: 3 values, short runs),
sorted by the parameter, and writes its CSV and PNG."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from georod_tools.analysis.sweep import sweep_values

REPO = Path(__file__).resolve().parents[2]
BEAM_FMU = REPO / "target" / "fmu" / "BuckledBeam.fmu"


def test_sweep_values() -> None:
    assert sweep_values(0.4, 2.0, 5) == pytest.approx([0.4, 0.8, 1.2, 1.6, 2.0])
    assert sweep_values(1.0, 3.0, 1) == [1.0]
    with pytest.raises(ValueError):
        sweep_values(0.0, 1.0, 0)


@pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale
def test_sweep_independent_of_workers(tmp_path: Path) -> None:
    from georod_tools.analysis.case import CaseConfig
    from georod_tools.analysis.sweep import run_sweep
    from georod_tools.report.case_files import write_sweep_csv
    from georod_tools.report.figures import plot_sweep

    base = CaseConfig(
        fmu=str(BEAM_FMU), elements=6, substeps=16, transient_periods=10, sample_periods=25
    )
    values = [2.0, 0.4, 0.9]  # unsorted on purpose
    one = run_sweep(base, "F", values, workers=1, progress=False)
    two = run_sweep(base, "F", values, workers=2, progress=False)
    assert [r.config.F for r in one] == [0.4, 0.9, 2.0]
    assert [r.config.F for r in two] == [0.4, 0.9, 2.0]
    for a, b in zip(one, two, strict=True):
        assert np.array_equal(a.samples, b.samples)
        assert a.exponent_per_period == b.exponent_per_period
        assert a.classification.label == b.classification.label
    summary, samples = write_sweep_csv("F", two, tmp_path / "sweep.csv")
    assert len(summary.read_text().splitlines()) == 4
    assert len(samples.read_text().splitlines()) == 1 + 3 * 25
    png = plot_sweep("F", two, tmp_path / "sweep.png", chaos_threshold=0.05)
    assert png.stat().st_size > 1000


@pytest.mark.usefixtures("fmu_paths")
def test_command_line_sweep_leaves_no_extracted_fmu(tmp_path: Path) -> None:
    """A sweep on a local cluster of two workers, as its own process with its own temporary
    folder: afterwards no extracted FMU is left there (the client's is removed by its exit
    handler, each worker's with its plugin's folder: worker processes end without exit
    handlers)."""
    from sweep_cases import tiny_cli_options

    temp = tmp_path / "temp"
    temp.mkdir()
    out = tmp_path / "sweep"
    args = ["sweep", "--param", "F", "--start", "0.4", "--stop", "2", "--count", "3"]
    r = subprocess.run(
        [sys.executable, "-m", "georod_tools", *args, *tiny_cli_options(BEAM_FMU)]
        + ["--workers", "2", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
        env={**os.environ, "TMPDIR": str(temp)},
    )
    assert r.returncode == 0, r.stderr
    assert (out / "results.jsonl").is_file()
    left = [p.relative_to(temp) for p in temp.rglob("georod_*")]
    assert left == [], f"left behind in the temporary folder: {left}"


@pytest.mark.usefixtures("fmu_paths")
def test_sweep_on_given_scheduler() -> None:
    """--scheduler ADDR: the cases run on an existing cluster, same results as locally."""
    import logging

    from dask.distributed import LocalCluster

    from georod_tools.analysis.case import CaseConfig, run_case
    from georod_tools.analysis.sweep import run_sweep

    base = CaseConfig(
        fmu=str(BEAM_FMU), elements=4, substeps=16, transient_periods=5, sample_periods=15
    )
    with LocalCluster(
        n_workers=1, threads_per_worker=1, dashboard_address=None, silence_logs=logging.WARNING
    ) as cluster:
        got = run_sweep(
            base, "Omega", [3600.0, 3400.0], scheduler=cluster.scheduler_address, progress=False
        )
    assert [r.config.Omega for r in got] == [3400.0, 3600.0]
    direct = run_case(base.with_value("Omega", 3400.0))
    assert np.array_equal(got[0].samples, direct.samples)
