"""A sweep killed mid-run and resumed gives the same final table as an uninterrupted run, bit for
bit, and recomputes none of the cases it had finished."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from georod_tools.report.records import ResultLog

# Enough cases that the kill lands mid-sweep even when the client, starved of CPU on a busy
# machine, writes several finished cases at once (with 8 cases a loaded CI machine once saw all
# 8 written before the kill).
COUNT = 24
KILL_AFTER = 3  # finished cases


def _argv(fmu: Path, out: Path, workers: int) -> list[str]:
    # about 0.2 s per case on one core: the kill lands between cases, not after the last
    return [
        sys.executable,
        "-m",
        "georod_tools",
        "sweep",
        "--fmu",
        str(fmu),
        "--param",
        "F",
        "--start",
        "0.4",
        "--stop",
        "2",
        "--count",
        str(COUNT),
        "--elements",
        "6",
        "--substeps",
        "16",
        "--transient",
        "300",
        "--periods",
        "100",
        "--no-progress",
        "--workers",
        str(workers),
        "--out",
        str(out),
    ]


def _lines(path: Path) -> int:
    return path.read_bytes().count(b"\n") if path.exists() else 0


def _tables(out: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(out.glob("*.csv"))}


def test_killed_sweep_resumes_to_the_same_table(fmu_paths: dict[str, Path], tmp_path: Path) -> None:
    fmu = fmu_paths["BuckledBeam"]
    whole, cut = tmp_path / "whole", tmp_path / "cut"
    r = subprocess.run(_argv(fmu, whole, 2), capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert f"{COUNT} cases ({COUNT} computed now" in r.stdout

    # the same sweep on one worker, killed (with its worker processes) after KILL_AFTER cases
    proc = subprocess.Popen(
        _argv(fmu, cut, 1),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        deadline = time.monotonic() + 120
        while _lines(cut / "results.jsonl") < KILL_AFTER:
            assert proc.poll() is None, "the sweep ended before it was killed"
            assert time.monotonic() < deadline, "no cases finished in 120 s"
            time.sleep(0.02)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)
    finished = len(ResultLog(cut).read())
    assert KILL_AFTER <= finished < COUNT, f"{finished} cases finished before the kill"
    assert not list(cut.glob("*.csv"))  # the final table comes only at the end
    assert json.loads((cut / "run.json").read_text())["status"] == "running"

    r = subprocess.run(
        [*_argv(fmu, cut, 1), "--resume"], capture_output=True, text=True, timeout=300
    )
    assert r.returncode == 0, r.stderr
    todo = COUNT - finished
    assert f"resuming: {finished} of {COUNT} cases already done, {todo} to run" in r.stdout
    assert f"{COUNT} cases ({todo} computed now" in r.stdout
    records = ResultLog(cut).read()
    assert len(records) == COUNT  # no finished case was computed again
    assert len({rec["value"] for rec in records}) == COUNT
    rec = json.loads((cut / "run.json").read_text())
    assert rec["status"] == "complete"
    assert [s["status"] for s in rec["sessions"]] == ["interrupted", "complete"]
    assert rec["sessions"][1]["computed"] == todo

    # the final tables are the uninterrupted run's, byte for byte
    tables = _tables(cut)
    assert len(tables) == 2
    assert tables == _tables(whole)


def test_result_log_drops_a_line_cut_by_a_kill(tmp_path: Path) -> None:
    log = ResultLog(tmp_path)
    log.append({"value": 0.5, "status": "ok", "x": [1.0, float("nan")]})
    with log.path.open("a") as f:
        f.write('{"value": 0.7, "sta')  # killed while writing
    got = log.read()
    assert [r["value"] for r in got] == [0.5]
    assert log.path.read_text().endswith("]}\n")  # truncated to the last whole line
    log.append({"value": 0.7, "status": "ok"})
    assert [r["value"] for r in log.read()] == [0.5, 0.7]
    log.path.write_text('{"value": 1}\nnot json\n')
    with pytest.raises(ValueError, match="line 2: not a JSON record"):
        log.read()
