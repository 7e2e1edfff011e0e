#!/usr/bin/env python3
"""Runs every Rust test in a process of its own under a time limit (what scripts/test calls).

    scripts/rust_tests.py [--profile quick] [--limit SECONDS] [--jobs N] [FILTER ...]

`cargo test` has no time limit: a test that hangs holds the whole run. This runner builds the
test binaries once (`cargo test --no-run`), lists each binary's tests (`--list`), and runs each
test alone (`BINARY --exact NAME`), `--jobs` at a time. A test that passes its limit is stopped,
reported with its name, the output it wrote and, where gdb is installed, every thread's stack at
the moment it was stopped; it counts as failed and the run goes on. Ignored tests are not run
(libtest's own `--ignored` rule). A test's own time limit is the default unless its name appears
in LIMITS. FILTER words keep only tests whose `binary::name` contains one of them.

The last line is `rust tests: N passed, N failed` (and the exit status is 1 when any failed or
none ran). Only the Python standard library: it runs before the project's environment exists.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
DEFAULT_LIMIT_S = 300.0
# Tests that take minutes by design get their own, longer limit (none today).
LIMITS: dict[str, float] = {}


@dataclass(frozen=True)
class Binary:
    name: str  # "lib" for the unit tests, "suite" for tests/suite/, "no_allocation" for tests/no_allocation.rs
    path: str


@dataclass
class Outcome:
    test: str
    passed: bool
    seconds: float
    detail: str = ""


def build(profile: str) -> list[Binary]:
    """Builds the test binaries; their names and paths from cargo's JSON messages."""
    cmd = ["cargo", "test", "--profile", profile, "--no-run", "--message-format=json"]
    proc = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit(f"rust tests: {' '.join(cmd)} failed ({proc.returncode})")
    binaries = []
    for line in proc.stdout.splitlines():
        msg = json.loads(line) if line.startswith("{") else {}
        if msg.get("reason") == "compiler-artifact" and msg.get("profile", {}).get("test"):
            target = msg["target"]
            name = "lib" if "lib" in target["kind"] else target["name"]
            if msg.get("executable"):
                binaries.append(Binary(name, msg["executable"]))
    return binaries


def list_tests(binary: Binary) -> list[str]:
    """The binary's tests that a plain `cargo test` runs (all listed minus the ignored)."""

    def names(*extra: str) -> set[str]:
        out = subprocess.run(
            [binary.path, "--list", "--format", "terse", *extra],
            cwd=REPO,
            stdout=subprocess.PIPE,
            text=True,
            check=True,
            timeout=60,
        ).stdout
        return {ln[: -len(": test")] for ln in out.splitlines() if ln.endswith(": test")}

    return sorted(names() - names("--ignored"))


def stacks_of(pid: int) -> str:
    """Every thread's stack of a running process (gdb), or why there is none."""
    gdb = shutil.which("gdb")
    if gdb is None:
        return "(no stack: gdb is not installed; scripts/install_test_deps installs it)"
    cmd = [gdb, "-p", str(pid), "-batch", "-nx", "-ex", "thread apply all bt"]
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=60).stdout
    except subprocess.TimeoutExpired:
        return "(no stack: gdb did not answer within 60 s)"
    return "\n".join(ln for ln in out.splitlines() if ln.startswith(("#", "Thread")))


def run_one(binary: Binary, test: str, limit: float) -> Outcome:
    label = f"{binary.name}::{test}"
    env = dict(os.environ, CARGO_MANIFEST_DIR=str(REPO), RUST_BACKTRACE="1")
    cmd = [binary.path, "--exact", test, "--test-threads", "1", "--nocapture"]
    start = time.monotonic()
    with subprocess.Popen(
        cmd, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    ) as proc:
        try:
            output, _ = proc.communicate(timeout=limit)
        except subprocess.TimeoutExpired:
            stack = stacks_of(proc.pid)
            proc.kill()
            output, _ = proc.communicate()
            seconds = time.monotonic() - start
            detail = f"TIMED OUT after {limit:.0f} s\n{output[-4000:]}\n--- stacks ---\n{stack}"
            return Outcome(label, False, seconds, detail)
    seconds = time.monotonic() - start
    if proc.returncode != 0:
        return Outcome(label, False, seconds, f"exit {proc.returncode}\n{output[-6000:]}")
    return Outcome(label, True, seconds)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--profile", default="quick", help="cargo profile (default quick)")
    parser.add_argument("--limit", type=float, default=DEFAULT_LIMIT_S, help="seconds per test")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="tests at once")
    parser.add_argument("filters", nargs="*", help="keep tests whose binary::name contains one")
    args = parser.parse_args()
    if args.limit <= 0 or args.jobs < 1:
        parser.error("--limit must be > 0 and --jobs >= 1")

    jobs = [(b, t) for b in build(args.profile) for t in list_tests(b)]
    if args.filters:
        jobs = [(b, t) for b, t in jobs if any(f in f"{b.name}::{t}" for f in args.filters)]
    print(f"rust tests: {len(jobs)} tests, {args.jobs} at a time, {args.limit:.0f} s limit each")
    start = time.monotonic()
    failed: list[Outcome] = []
    passed = 0
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [
            pool.submit(run_one, b, t, LIMITS.get(f"{b.name}::{t}", args.limit)) for b, t in jobs
        ]
        for done, future in enumerate(as_completed(futures), 1):
            outcome = future.result()
            mark = "ok  " if outcome.passed else "FAIL"
            print(f"[{done:>3}/{len(jobs)}] {mark} {outcome.seconds:6.1f} s  {outcome.test}")
            sys.stdout.flush()
            if outcome.passed:
                passed += 1
            else:
                failed.append(outcome)
                print(outcome.detail)
    wall = time.monotonic() - start
    for outcome in failed:
        print(f"rust tests: FAILED {outcome.test} ({outcome.detail.splitlines()[0]})")
    print(f"rust tests: {wall:.0f} s")
    print(f"rust tests: {passed} passed, {len(failed)} failed")
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
