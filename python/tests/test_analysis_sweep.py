"""A Dask sweep gives identical results with 1 and 2 workers (tiny sweep: 5 values, short runs),
sorted by the parameter, whether cases travel in chunks or one by one, and writes its CSV and
PNG; how cases are cut into chunks."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

from georod_tools.analysis.sweep import MAX_CHUNK, chunk_sizes, sweep_values

REPO = Path(__file__).resolve().parents[2]
BEAM_FMU = REPO / "target" / "fmu" / "BuckledBeam.fmu"


def test_sweep_values() -> None:
    assert sweep_values(0.4, 2.0, 5) == pytest.approx([0.4, 0.8, 1.2, 1.6, 2.0])
    assert sweep_values(1.0, 3.0, 1) == [1.0]
    with pytest.raises(ValueError):
        sweep_values(0.0, 1.0, 0)


@pytest.mark.parametrize("count", [0, 1, 2, 5, 17, 100, 1000])
@pytest.mark.parametrize("slots", [1, 2, 3, 16])
def test_chunk_sizes_cover_every_case_and_shrink_to_single_cases(count: int, slots: int) -> None:
    sizes = chunk_sizes(count, slots)
    assert sum(sizes) == count
    assert all(1 <= s <= MAX_CHUNK for s in sizes)
    assert sizes == sorted(sizes, reverse=True)  # largest first
    # guided: no chunk holds more than 1 / (2 slots) of the cases left when it is cut, so the
    # work after it keeps the other slots busy; the last 2 slots cases go one by one
    left = count
    for s in sizes:
        assert s == 1 or s <= left / (2 * slots)
        left -= s
    assert sizes[-min(count, 2 * slots) :] == [1] * min(count, 2 * slots)


def test_chunk_sizes_of_the_bifurcation_diagram() -> None:
    # 100 cases on 2 workers: 21 tasks instead of 100
    assert chunk_sizes(100, 2) == [8] * 9 + [7, 5, 4, 3, 2] + [1] * 7
    with pytest.raises(ValueError, match="slots = 0"):
        chunk_sizes(10, 0)
    with pytest.raises(ValueError, match="count = -1"):
        chunk_sizes(-1, 2)


@pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale
def test_sweep_independent_of_workers(tmp_path: Path) -> None:
    from georod_tools.analysis.case import CaseConfig
    from georod_tools.analysis.sweep import run_sweep
    from georod_tools.report.case_files import write_sweep_csv
    from georod_tools.report.figures import plot_sweep

    base = CaseConfig(
        fmu=str(BEAM_FMU), elements=6, substeps=16, transient_periods=10, sample_periods=25
    )
    values = [2.0, 0.4, 0.9, 1.3, 0.6]  # unsorted on purpose
    # one worker runs the first two cases as one task, two workers run each on its own
    assert chunk_sizes(len(values), 1) == [2, 1, 1, 1]
    assert chunk_sizes(len(values), 2) == [1, 1, 1, 1, 1]
    one = run_sweep(base, "F", values, workers=1, progress=False)
    two = run_sweep(base, "F", values, workers=2, progress=False)
    assert [r.config.F for r in one] == sorted(values)
    assert [r.config.F for r in two] == sorted(values)
    for a, b in zip(one, two, strict=True):
        assert np.array_equal(a.samples, b.samples)
        assert a.exponent_per_period == b.exponent_per_period
        assert a.classification.label == b.classification.label
    summary, samples = write_sweep_csv("F", two, tmp_path / "sweep.csv")
    assert len(summary.read_text().splitlines()) == 1 + len(values)
    assert len(samples.read_text().splitlines()) == 1 + len(values) * 25
    png = plot_sweep("F", two, tmp_path / "sweep.png", chaos_threshold=0.05)
    assert png.stat().st_size > 1000


@pytest.mark.usefixtures("fmu_paths")
def test_command_line_sweep_leaves_no_extracted_fmu(
    tmp_path: Path, request: pytest.FixtureRequest
) -> None:
    """A sweep on a local cluster of two workers, as its own process with its own temporary
    folder: afterwards no extracted FMU is left there (the client's is removed by its exit
    handler, each worker's with its plugin's folder: worker processes end without exit
    handlers)."""
    from sweep_cases import tiny_cli_options

    # A short temporary folder: multiprocessing's fork server puts its socket there, and a
    # socket's path is limited to 107 bytes (pytest-xdist's tmp_path alone comes near it).
    temp = Path(tempfile.mkdtemp(prefix="sweep", dir="/tmp"))
    request.addfinalizer(lambda: shutil.rmtree(temp, ignore_errors=True))
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
        n_workers=1, threads_per_worker=1, dashboard_address=":0", silence_logs=logging.WARNING
    ) as cluster:
        got = run_sweep(
            base, "Omega", [3600.0, 3400.0], scheduler=cluster.scheduler_address, progress=False
        )
    assert [r.config.Omega for r in got] == [3400.0, 3600.0]
    direct = run_case(base.with_value("Omega", 3400.0))
    assert np.array_equal(got[0].samples, direct.samples)
