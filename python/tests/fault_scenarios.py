"""The hostile scenarios of test_fmu_fault_injection.py, each run in its own process:

    python fault_scenarios.py SCENARIO UNZIPDIR [--elements N] [--sample K] [--masks 0x01,0xff|all]

SCENARIO: corrupt (single-byte flips), truncate, handles (stale, double-freed, foreign, garbage,
NULL), stoptime. Prints the JSON summary of fault_host.Checker as the last stdout line.

Serialized states are opaque bytes here: corrupted and cut, never decoded. States with a valid
checksum but bad fields (what a buggy tool would write) are crafted by the Rust test
tests/fmi_hardening.rs, which owns the layout.
"""

from __future__ import annotations

import argparse
import json
import random
from collections.abc import Callable
from ctypes import addressof, create_string_buffer
from pathlib import Path

from fault_host import HEAD_BYTES, NOT_LIVE, Checker, Fmu, H, Host, attempt, good_state, pair
from helpers import ERROR, OK, WARNING

DESER = "fmi2DeSerializeFMUstate"


def corrupt(fmu: Fmu, check: Checker, elements: int, sample: int, masks: list[int]) -> None:
    """Every one of the first HEAD_BYTES bytes and `sample` other positions (all when 0 or more
    than there are), each XORed with each mask (masks 1..255: every one of the 255 other values of
    the byte): refused, the output slot untouched, the instance like its twin."""
    host, twin = pair(fmu, elements)
    keep, blob = good_state(host)
    head = min(HEAD_BYTES, len(blob))
    rest = range(head, len(blob))
    picked = rest if sample <= 0 or sample >= len(rest) else random.Random(7).sample(rest, sample)
    for at in [*range(head), *sorted(picked)]:
        for mask in masks:
            what = attempt(f"byte {at} ^ {mask:#04x} of {len(blob)}")
            bad = bytearray(blob)
            bad[at] ^= mask
            status, slot = host.deserialize(bytes(bad), keep)
            check.refused(host, status, DESER, "", what)
            check(slot == keep, f"{what}: output slot changed to {slot}")
            check.like_twin(host, twin, what)
    status, again = host.serialize(keep)
    check(status == OK and again == blob, "the kept state changed")


def truncate(fmu: Fmu, check: Checker) -> None:
    """Every shorter buffer, and longer ones: refused."""
    host, twin = pair(fmu, 10)
    keep, blob = good_state(host)
    longer = [blob + b"\x00", blob + bytes(range(8)), blob + b"\x5a" * 4096, blob + blob]
    for bad in [blob[:n] for n in range(len(blob))] + longer:
        what = attempt(f"{len(bad)} of {len(blob)} bytes")
        status, slot = host.deserialize(bad, keep)
        msg = host.last_message()
        says = "too short" in msg or "does not match the length" in msg
        check(status == ERROR and says, f"{what}: status {status}, message {msg!r}")
        check.refused(host, status, DESER, "", what)
        check(slot == keep, f"{what}: output slot changed")
    check.like_twin(host, twin, "after the truncated buffers")


def handles(fmu: Fmu, check: Checker) -> None:
    """Handles that are not live states of the instance are refused by every function without
    touching their memory; NULL is refused or ignored as FMI 2.0 says."""
    host, twin = pair(fmu, 10)
    other, _ = pair(fmu, 10)
    theirs, theirs_blob = good_state(other)
    s, _ = good_state(host)
    status, cleared = host.free_state(s)
    check(status == OK and cleared is None, "freeing a live state")
    # Handles are never reused: many states got and freed after `s` leave it stale for good.
    for _ in range(200):
        status, t = host.get_state()
        check(status == OK and t != s, "a freed handle was given out again")
        check(host.free_state(t)[0] == OK, "freeing a live state")
    junk = create_string_buffer(bytes(range(256)) * 2, 512)
    bad = {
        "stale": s,
        "foreign": theirs,
        "garbage": addressof(junk),
        "misaligned": addressof(junk) + 3,
        "unmapped": 0x10,
        "kernel": 0xFFFF_8000_0000_1000,
    }
    for label, h in bad.items():
        attempt(label)
        check.refused(host, host.set_state(h), "fmi2SetFMUstate", NOT_LIVE, f"set {label}")
        status, slot = host.free_state(h)
        check.refused(host, status, "fmi2FreeFMUstate", NOT_LIVE, f"free {label}")
        check(slot == h, f"free {label}: the handle was changed")
        status, size = host.size(h)
        check.refused(host, status, "fmi2SerializedFMUstateSize", NOT_LIVE, f"size {label}")
        check(size == 987654321, f"size {label}: output written")
        status, out = host.serialize(h, 64)
        check.refused(host, status, "fmi2SerializeFMUstate", NOT_LIVE, f"serialize {label}")
        check(out == b"\xa5" * 64, f"serialize {label}: output written")
        check.like_twin(host, twin, label)
    check(junk.raw == bytes(range(256)) * 2, "the garbage handle's memory was changed")
    # Double free through a copy of the handle (the host's own variable is NULL after a free).
    s2, _ = good_state(host)
    check(host.free_state(s2)[0] == OK, "free")
    check.refused(host, host.free_state(s2)[0], "fmi2FreeFMUstate", NOT_LIVE, "double free")
    # NULL: refused where a state is required, ignored by fmi2FreeFMUstate.
    check.refused(host, host.set_state(None), "fmi2SetFMUstate", "FMUstate is NULL", "set NULL")
    check.refused(host, host.size(None)[0], "fmi2SerializedFMUstateSize", "NULL", "size NULL")
    check(host.free_state(None) == (OK, None), "free NULL")
    # The foreign state is untouched and still works in its own instance.
    check(other.serialize(theirs)[1] == theirs_blob, "the foreign state changed")
    check(other.set_state(theirs) == OK, "the foreign state no longer works in its instance")
    deserialize_slots(host, check, theirs)
    check.like_twin(host, twin, "after the hostile handles")


def deserialize_slots(host: Host, check: Checker, foreign: int) -> None:
    """`*FMUstate` of fmi2DeSerializeFMUstate is output only; fmi2GetFMUstate reuses only its own
    states and answers anything else with a new state and fmi2Warning."""
    held, blob = good_state(host)
    for label, slot in [("unmapped", 0x10), ("held", held), ("foreign", foreign)]:
        attempt(f"deserialize into a {label} slot")
        status, new = host.deserialize(blob, slot)
        check(status == OK and new not in (None, slot), f"deserialize into {label}: {status}")
        check(host.serialize(new)[1] == blob, f"deserialize into {label}: wrong state")
    check(host.serialize(held)[1] == blob, "the held state changed")
    status, same = host.get_state(held)
    check(status == OK and same == held, "fmi2GetFMUstate does not update its own state")
    for label, slot in [("unmapped", 0x10), ("foreign", foreign)]:
        attempt(f"get into a {label} slot")
        status, new = host.get_state(slot)
        msg = host.last_message()
        ok = status == WARNING and new not in (None, slot) and "neither NULL" in msg
        check(ok, f"get into {label}: {status} {msg!r}")
        host.log.clear()


def stoptime(fmu: Fmu, check: Checker) -> None:
    """A step past stopTime is refused and changes nothing; shorter steps go on."""
    stop = 1e-4  # 10 steps of H
    host = Host(fmu, "subject", {"F": 0.9}, stop=stop)
    twin = Host(fmu, "twin", {"F": 0.9})
    for _ in range(8):
        check(host.step() == OK and twin.step() == OK, "steps before stopTime")
    t, before = host.time(), host.outputs()
    for h in (3 * H, 2 * H * (1 + 1e-7), 1.0):
        attempt(f"a step of {h} from {t}")
        status = host.step(h)
        check.refused(host, status, "fmi2DoStep", "past stopTime = 1e-4", f"step {h}")
        check(host.time() == t and host.outputs() == before, f"step {h} changed the state")
    check.like_twin(host, twin, "a shorter step")
    check(host.step(H * (1 + 1e-12)) == OK, "a step to stopTime up to round-off is refused")
    check.refused(host, host.step(), "fmi2DoStep", "would end at t = 1.1", "a step after stop")


SCENARIOS: dict[str, Callable[..., None]] = {
    "truncate": truncate,
    "handles": handles,
    "stoptime": stoptime,
}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("scenario", choices=["corrupt", *SCENARIOS])
    p.add_argument("unzipdir", type=Path)
    p.add_argument("--elements", type=int, default=10)
    p.add_argument("--sample", type=int, default=0, help="positions after the header; 0: all")
    p.add_argument("--masks", default="0x01,0xff", help="XOR masks in hex, or all: 0x01 to 0xff")
    a = p.parse_args()
    fmu, check = Fmu(a.unzipdir), Checker()
    if a.scenario == "corrupt":
        every = a.masks == "all"
        masks = list(range(1, 256)) if every else [int(m, 16) for m in a.masks.split(",")]
        corrupt(fmu, check, a.elements, a.sample, masks)
    else:
        SCENARIOS[a.scenario](fmu, check)
    print(json.dumps({"checked": check.checked, "failures": check.failures}))


if __name__ == "__main__":
    main()
