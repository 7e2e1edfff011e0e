"""A sweep with failing cases finishes, records each failure's reason, lists it and marks it.

Failures: the FMU's own fmi2Discard (F = 1000: Newton fails even after the halvings), a Python
exception and a worker process that dies (injected by :func:`sweep_cases.flaky_case`).
"""

from __future__ import annotations

import csv
import hashlib
import json
from pathlib import Path

import fmpy
import numpy as np
import pytest

from georod_tools.analysis.failure import FAIL_EXCEPTION, FAIL_FMU, FAIL_WORKER, CaseFailure
from sweep_cases import EXITS_AT, RAISES_AT, flaky_case, tiny_cli_options, tiny_config

DISCARD_F = 1000.0  # the FMU returns fmi2Discard (BuckledBeam, 4 elements, T/16 steps)


@pytest.fixture
def beam_fmu(fmu_paths: dict[str, Path]) -> Path:
    return fmu_paths["BuckledBeam"]


def test_sweep_records_fmu_exception_and_lost_worker(beam_fmu: Path) -> None:
    import dask
    import distributed  # noqa: F401 - registers the distributed config

    from georod_tools.analysis.case import run_case
    from georod_tools.analysis.sweep import chunk_sizes, sweep
    from georod_tools.report.figures import sweep_figure

    base = tiny_config(beam_fmu)
    # The first chunk holds the case that kills its worker and 0.4, which must still succeed:
    # the lost chunk runs again case by case.
    values = [EXITS_AT, 0.4, RAISES_AT, DISCARD_F, 1.5]
    assert chunk_sizes(len(values), 1)[0] == 2
    seen: list[float] = []
    # A lost task fails after one retry (default: 3; fewer worker restarts).
    with dask.config.set({"distributed.scheduler.allowed-failures": 1}):
        out = sweep(
            base,
            "F",
            values,
            workers=1,
            progress=False,
            case_fn=flaky_case,
            on_done=lambda got: seen.append(
                got.value if isinstance(got, CaseFailure) else got.config.F
            ),
        )
    assert sorted(seen) == sorted(values)  # every case reported as it finished
    assert [r.config.F for r in out.results] == [0.4, 1.5]
    direct = run_case(base.with_value("F", 1.5))
    assert np.array_equal(out.results[1].samples, direct.samples)
    by_value = {f.value: f for f in out.failures}
    assert sorted(by_value) == [RAISES_AT, EXITS_AT, DISCARD_F]
    fmu, exc, lost = by_value[DISCARD_F], by_value[RAISES_AT], by_value[EXITS_AT]
    assert fmu.kind == FAIL_FMU and "fmi2DoStep" in fmu.reason and "fmi2Discard" in fmu.reason
    assert "did not converge" in fmu.reason  # the FMU's own log message
    assert exc.kind == FAIL_EXCEPTION and "ValueError: injected failure at F = 0.9" in exc.reason
    assert lost.kind == FAIL_WORKER and "KilledWorker" in lost.reason

    fig = sweep_figure("F", out.results, 0.05, out.failures)
    ax_b, ax_l = fig.axes
    labels = [t.get_text() for t in ax_b.get_legend().get_texts()]
    assert labels == ["failed case"]
    assert "3 failed cases" in ax_b.get_title()
    for ax in (ax_b, ax_l):  # one red band centred on each failed value, none elsewhere
        centres = sorted(round(p.get_x() + p.get_width() / 2, 9) for p in ax.patches)
        assert centres == sorted(by_value)


def _run_cli(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    from georod_tools.cli import main

    try:
        rc = main(argv)
    except SystemExit as e:
        rc = int(e.code or 0)
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def test_cli_sweep_failure_table_record_and_refusals(
    beam_fmu: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "run"
    argv = ["sweep", "--param", "F", "--start", "0.4", "--stop", "1000", "--count", "2"]
    argv += [*tiny_cli_options(beam_fmu), "--workers", "1", "--out", str(out)]
    rc, stdout, stderr = _run_cli(argv, capsys)
    assert rc == 0, stderr
    # the summary lists the failed case with its reason
    assert "2 cases (2 computed now" in stdout and "1 failed" in stdout
    assert "failed cases (1):" in stdout
    assert "F = 1000.0: fmu: fmi2DoStep at t = " in stdout and "fmi2Discard" in stdout
    stem = "BuckledBeam_sweep_F_0.4_1000_2"
    with (out / f"{stem}.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert [(r["F"], r["class"]) for r in rows] == [("0.4", "unresolved"), ("1000.0", "failed")]
    assert rows[0]["failure"] == "" and rows[0]["lyapunov_per_period"] != ""
    assert rows[1]["failure"].startswith("fmu: fmi2DoStep at t = ")
    assert "returned fmi2Discard" in rows[1]["failure"]
    assert "wall_time_s" not in rows[0]  # the table is deterministic
    assert (out / f"{stem}.png").stat().st_size > 1000
    lines = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    assert sorted((r["value"], r["status"]) for r in lines) == [(0.4, "ok"), (1000.0, "failed")]

    # run.json: settings, FMU identity, versions, times, host, command line
    rec = json.loads((out / "run.json").read_text())
    md = fmpy.read_model_description(str(beam_fmu))
    assert rec["command"] == "sweep" and rec["status"] == "complete"
    assert rec["fmu"]["path"] == str(beam_fmu.resolve())
    assert rec["fmu"]["sha256"] == hashlib.sha256(beam_fmu.read_bytes()).hexdigest()
    assert rec["fmu"]["guid"] == md.guid
    assert rec["settings"]["param"] == "F" and rec["settings"]["count"] == 2
    assert rec["settings"]["values"] == [0.4, 1000.0]
    assert rec["settings"]["case"]["elements"] == 4
    assert rec["settings"]["case"]["transient_periods"] == 5
    assert rec["cases"] == {"total": 2, "ok": 1, "failed": 1, "failed_values": [1000.0]}
    assert rec["start_time"] <= rec["end_time"]
    (s,) = rec["sessions"]
    assert s["argv"] == argv and s["command_line"].startswith("python -m georod_tools sweep")
    assert s["host"] and s["cwd"] and s["computed"] == 2 and s["status"] == "complete"
    for pkg in ("georod_tools", "python", "numpy", "fmpy", "dask", "distributed"):
        assert s["versions"][pkg]
    assert s["options"]["workers"] == 1 and s["options"]["scheduler"] is None
    assert all(w["fmu_loaded"] for w in s["workers"].values())

    # the same folder again: refused (exit 2) with what to do
    rc, _, stderr = _run_cli(argv, capsys)
    assert rc == 2
    assert f"--out {out}: the folder is not empty" in stderr and "--resume" in stderr
    assert "Traceback" not in stderr
    # --resume with other settings: refused, naming the setting
    other = [a if a != "2" else "3" for a in argv]
    rc, _, stderr = _run_cli([*other, "--resume"], capsys)
    assert rc == 2 and "count: 2 recorded, 3 now" in stderr
    # --resume with the same settings: nothing to compute (the FMU's failures are final)
    rc, stdout, _ = _run_cli([*argv, "--resume"], capsys)
    assert rc == 0 and "2 of 2 cases already done, 0 to run" in stdout
    assert len((out / "results.jsonl").read_text().splitlines()) == 2
    assert len(json.loads((out / "run.json").read_text())["sessions"]) == 2
    # --overwrite: a fresh run in the same folder
    rc, stdout, _ = _run_cli([*argv, "--overwrite"], capsys)
    assert rc == 0 and "2 computed now" in stdout
    assert len(json.loads((out / "run.json").read_text())["sessions"]) == 1


def test_case_command_refuses_non_empty_folder(
    beam_fmu: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "notes.txt").write_text("an earlier run's file")
    rc, _, stderr = _run_cli(["case", "--fmu", str(beam_fmu), "--out", str(tmp_path)], capsys)
    assert rc == 2 and "the folder is not empty (notes.txt)" in stderr
    # --overwrite does not empty a folder that georod_tools did not write
    argv = ["case", "--fmu", str(beam_fmu), "--out", str(tmp_path), "--overwrite"]
    rc, _, stderr = _run_cli(argv, capsys)
    assert rc == 2 and "holds no run.json" in stderr
    assert (tmp_path / "notes.txt").is_file()


def test_resume_reruns_exactly_the_lost_cases_and_keeps_the_refusals(
    beam_fmu: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``--resume`` computes again the values whose worker was lost and those never finished,
    and no other: a finished result and the FMU's refusals (deterministic) stay as recorded."""
    from georod_tools.report.case_files import failure_record

    out = tmp_path / "run"
    argv = ["sweep", "--param", "F", "--start", "0.4", "--stop", "1000", "--count", "4"]
    argv += [*tiny_cli_options(beam_fmu), "--workers", "1", "--out", str(out)]
    rc, _, stderr = _run_cli(argv, capsys)
    assert rc == 0, stderr
    log = out / "results.jsonl"
    first = {r["value"]: r for r in map(json.loads, log.read_text().splitlines())}
    values = [0.4, 333.6, 666.8, 1000.0]
    assert sorted(first) == values
    assert first[0.4]["status"] == "ok"
    assert all(first[v]["kind"] == FAIL_FMU for v in values[1:])  # F far beyond the beam's
    # As if the run had stopped early: 666.8 was lost with its worker, 1000 never finished.
    lost = CaseFailure(666.8, FAIL_WORKER, "KilledWorker: lost with its worker", "tcp://x:1")
    kept = [first[0.4], first[333.6], failure_record(lost)]
    log.write_text("".join(json.dumps(r) + "\n" for r in kept))

    rc, stdout, stderr = _run_cli([*argv, "--resume"], capsys)
    assert rc == 0, stderr
    assert "resuming: 2 of 4 cases already done, 2 to run" in stdout
    assert "4 cases (2 computed now" in stdout
    lines = [json.loads(x) for x in log.read_text().splitlines()]
    assert lines[:3] == kept  # nothing finished is rewritten
    assert sorted(r["value"] for r in lines[3:]) == [666.8, 1000.0]  # exactly these again
    assert all(r["kind"] == FAIL_FMU for r in lines[3:])
    rec = json.loads((out / "run.json").read_text())
    assert rec["cases"] == {
        "total": 4,
        "ok": 1,
        "failed": 3,
        "failed_values": [333.6, 666.8, 1000.0],
    }
    assert rec["sessions"][-1]["computed"] == 2
