"""`--scheduler ADDR`: workers that do not share the client's files.

The cluster's workers are separate processes started in another working directory; the sweep's
FMU is a temporary copy deleted before the sweep starts, so the workers can only run it from the
bytes the client sends them. Each worker loads it once, whatever the number of cases; a worker
that cannot load an FMU says which worker it is and why.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
import shutil
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from georod_tools.analysis.failure import FAIL_WORKER, CaseFailure
from georod_tools.fmu.worker import FmuPayload, FmuUnavailableError
from sweep_cases import tiny_cli_options, tiny_config


@pytest.fixture(scope="module")
def cluster(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[object, Path]]:
    """A LocalCluster of 2 worker processes whose working directory is an empty temp folder."""
    from dask.distributed import LocalCluster

    workdir = tmp_path_factory.mktemp("workers_cwd")
    here = os.getcwd()
    os.chdir(workdir)  # the worker processes are spawned here
    try:
        c = LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            # A free port: the scheduler serves HTTP even without a dashboard, on 8787 unless
            # told, and another test's cluster may hold that port at the same time.
            dashboard_address=":0",
            silence_logs=logging.WARNING,
        )
    finally:
        os.chdir(here)
    with c:
        yield c, workdir


def _on_workers(address: str, fn: object, *args: object) -> dict[str, object]:
    from dask.distributed import Client

    with Client(address) as client:
        return client.run(fn, *args)  # type: ignore[arg-type]


def _worker_state() -> dict[str, object]:
    from georod_tools.fmu import FmuModel, worker

    return {"cwd": os.getcwd(), "loads": worker.LOAD_COUNT, "models": len(FmuModel._cache)}


def test_remote_workers_get_the_fmu_as_bytes(
    cluster: tuple[object, Path], fmu_paths: dict[str, Path], tmp_path: Path
) -> None:
    from georod_tools.analysis.case import run_case
    from georod_tools.analysis.sweep import sweep

    c, workdir = cluster
    address = c.scheduler_address  # type: ignore[attr-defined]
    copy = tmp_path / "elsewhere" / "BuckledBeam.fmu"
    copy.parent.mkdir()
    shutil.copy(fmu_paths["BuckledBeam"], copy)
    payload = FmuPayload.read(copy)
    shutil.rmtree(copy.parent)  # gone before any worker loads it
    base = tiny_config(copy)
    values = [0.4, 0.7, 1.0, 1.5, 2.0, 2.5]
    out = sweep(base, "F", values, scheduler=address, progress=False, payload=payload)
    assert out.failures == []
    assert [r.config.F for r in out.results] == values
    assert all(r.config.fmu == str(copy) for r in out.results)  # the client's config, unchanged
    for r in out.results[:2]:
        direct = run_case(tiny_config(fmu_paths["BuckledBeam"]).with_value("F", r.config.F))
        assert np.array_equal(r.samples, direct.samples)
        assert r.exponent_per_period == direct.exponent_per_period

    state = _on_workers(address, _worker_state)
    assert len(state) == 2
    for s in state.values():
        assert s["cwd"] == str(workdir) != os.getcwd()  # type: ignore[index]
        assert s["loads"] == 1 and s["models"] == 1  # type: ignore[index]
    assert all(w["fmu_loaded"] and w["cwd"] == str(workdir) for w in out.workers.values())


def test_cli_sweep_on_a_scheduler(
    cluster: tuple[object, Path],
    fmu_paths: dict[str, Path],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    from georod_tools.cli import main

    c, workdir = cluster
    address = c.scheduler_address  # type: ignore[attr-defined]
    out = tmp_path / "out"
    argv = ["sweep", "--start", "0.4", "--stop", "2", "--count", "4", "--scheduler", address]
    argv += [*tiny_cli_options(fmu_paths["BuckledBeam"]), "--out", str(out)]
    assert main(argv) == 0, capsys.readouterr().err
    assert "4 cases (4 computed now" in capsys.readouterr().out
    session = json.loads((out / "run.json").read_text())["sessions"][0]
    assert session["scheduler"] == address
    assert len(session["workers"]) == 2
    assert all(w["fmu_loaded"] and w["cwd"] == str(workdir) for w in session["workers"].values())
    # still one load per worker after two sweeps of the same FMU
    assert {s["loads"] for s in _on_workers(address, _worker_state).values()} == {1}  # type: ignore[index]


def test_worker_that_cannot_load_names_itself_and_why(cluster: tuple[object, Path]) -> None:
    from dask.distributed import Client

    from georod_tools.analysis.case import run_case
    from georod_tools.analysis.sweep import run_on_worker
    from georod_tools.fmu.worker import install

    c, _ = cluster
    address = c.scheduler_address  # type: ignore[attr-defined]
    data = b"this is not a zip file"
    broken = FmuPayload("Broken.fmu", data, hashlib.sha256(data).hexdigest())
    with Client(address) as client:
        workers = sorted(client.scheduler_info()["workers"])
        with pytest.raises(FmuUnavailableError) as e:
            install(client, broken)
        msg = str(e.value)
        assert msg.startswith("no worker could load Broken.fmu:")
        for w in workers:
            assert f"worker {w}: " in msg
        assert "BadZipFile: File is not a zip file" in msg
        # a case sent to such a worker fails with the worker's name and the reason
        cfg = tiny_config("/nonexistent/Broken.fmu")
        fut = client.submit(
            run_on_worker, cfg, 0.7, broken.sha256, broken.name, run_case, workers=[workers[0]]
        )
        got = fut.result()
    assert isinstance(got, CaseFailure) and got.kind == FAIL_WORKER
    assert got.reason.startswith(f"worker {workers[0]} cannot load Broken.fmu: ")
