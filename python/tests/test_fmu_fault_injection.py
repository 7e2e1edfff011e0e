"""The FMUs against a hostile host (issue 13): corrupt and truncated serialized states, freed /
foreign / garbage state handles, stopTime. States with a valid checksum but bad fields are
crafted by the Rust test tests/fmi_hardening.rs, which owns the layout; here serialized states
are opaque bytes. Each scenario runs in its own process (fault_scenarios.py), so that a crash of
the FMU is a failed test that names the call that crashed; after every refused call the instance
must still step exactly like an untouched twin.

The single-byte corruptions run densely by default (every byte of 10-element states, the first
256 bytes and 2000 sampled positions of a 200-element one, each XORed with 0x01 and 0xff). The
exhaustive version is marked `exhaustive`, which the default run deselects (pyproject.toml); it
runs with `-m exhaustive` (scripts/fault_injection): every single-byte corruption of a 10-element
state of every scene (each byte replaced by each of its 255 other values), and every byte of a
200-element state XORed with each single bit and 0xff.
States left unfreed at fmi2FreeInstance are checked under valgrind (test_fmu_valgrind.py).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import FmuInfo

SCENARIOS = Path(__file__).with_name("fault_scenarios.py")
BIT_MASKS = "0x01,0x02,0x04,0x08,0x10,0x20,0x40,0x80,0xff"


def run_scenario(fmu: FmuInfo, scenario: str, *args: str, timeout: float = 300) -> int:
    """Runs one scenario in a fresh process; fails on a crash or a failed check. Returns the
    number of checks made."""
    cmd = [sys.executable, str(SCENARIOS), scenario, str(fmu.unzipdir), *args]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=False)
    tries = [line for line in r.stderr.splitlines() if line.startswith("try ")]
    if r.returncode != 0:
        pytest.fail(
            f"{fmu.scene} {scenario} {args}: the host process died (exit {r.returncode}) "
            f"during {tries[-1] if tries else 'set-up'}\n{r.stderr[-3000:]}"
        )
    summary = json.loads(r.stdout.strip().splitlines()[-1])
    assert summary["failures"] == [], f"{fmu.scene} {scenario}: {summary['failures']}"
    assert summary["checked"] > 0 and tries
    return int(summary["checked"])


def state_size(elements: int) -> int:
    """A lower bound of the serialized size: two vectors of 3 (elements + 1) f64."""
    return 2 * 8 * 3 * (elements + 1)


def test_every_byte_flip_of_a_small_state_is_refused(fmu: FmuInfo) -> None:
    checked = run_scenario(fmu, "corrupt", "--elements", "10", "--masks", "0x01,0xff")
    assert checked > 3 * 2 * state_size(10)  # 3 checks per flip, every byte, 2 masks


def test_sampled_byte_flips_of_a_large_state_are_refused(beam: FmuInfo) -> None:
    checked = run_scenario(beam, "corrupt", "--elements", "200", "--sample", "2000")
    assert checked > 3 * 2 * 2000


def test_truncated_and_extended_states_are_refused(fmu: FmuInfo) -> None:
    assert run_scenario(fmu, "truncate") > state_size(10)


def test_bad_state_handles_are_refused_without_being_touched(fmu: FmuInfo) -> None:
    run_scenario(fmu, "handles")


def test_steps_past_stop_time_are_refused(fmu: FmuInfo) -> None:
    run_scenario(fmu, "stoptime")


@pytest.mark.exhaustive
def test_every_single_byte_corruption_of_a_small_state_is_refused(fmu: FmuInfo) -> None:
    checked = run_scenario(fmu, "corrupt", "--elements", "10", "--masks", "all", timeout=3600)
    assert checked > 3 * 255 * state_size(10)  # 3 checks per corruption, every byte, 255 values


@pytest.mark.exhaustive
def test_every_byte_of_a_large_state_flipped(fmu: FmuInfo) -> None:
    checked = run_scenario(fmu, "corrupt", "--elements", "200", "--masks", BIT_MASKS, timeout=1800)
    assert checked > 3 * 9 * state_size(200)
