"""Small, fast sweep settings shared by the sweep tests, and case functions that fail on purpose.

The case functions run on Dask workers, which import them from this module (python/tests is on
their sys.path: the worker processes are spawned with the test process's path).
"""

from __future__ import annotations

import os
from pathlib import Path

from georod_tools.analysis.case import CaseConfig, CaseResult, run_case

#: Values of F for which :func:`flaky_case` raises or kills its worker.
RAISES_AT = 0.9
EXITS_AT = 1.9


def tiny_config(fmu: Path | str) -> CaseConfig:
    """A BuckledBeam case of a few hundredths of a second."""
    return CaseConfig(
        fmu=str(fmu),
        elements=4,
        substeps=16,
        transient_periods=5,
        sample_periods=25,
    )


def tiny_cli_options(fmu: Path | str) -> list[str]:
    """The same settings as command-line options of ``sweep`` (no progress bar)."""
    return [
        "--fmu",
        str(fmu),
        "--elements",
        "4",
        "--substeps",
        "16",
        "--transient",
        "5",
        "--periods",
        "25",
        "--no-progress",
    ]


def flaky_case(cfg: CaseConfig) -> CaseResult:
    """:func:`run_case`, except that F = RAISES_AT raises and F = EXITS_AT kills the worker
    process (a lost worker)."""
    if cfg.F == RAISES_AT:
        raise ValueError(f"injected failure at F = {cfg.F}")
    if cfg.F == EXITS_AT:
        os._exit(17)
    return run_case(cfg)
