"""Session fixtures: the scenes' FMUs (built by scripts/build_fmus when missing or stale), each
extracted once for the FMU2Slave tests, the examples' FMUs, and the core's CLI for the reference
trajectories.

No silent skips: a test that needs something absent builds it (the FMUs, the CLI) or fails with
a message saying what is missing; a skip (pytest.skip, a skip mark) is reported as a failure."""

from __future__ import annotations

import fcntl
import os
import shutil
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import fmpy
import pytest

from helpers import (
    FMU3_DIR,
    FMU_DIR,
    GEOROD_LIB,
    REPO,
    SCENE_FILES,
    SCENES,
    FmuInfo,
    run_cmd,
    stale_fmus,
)
from scene_fmus import ensure_georod

BUILD_FMUS = REPO / "scripts" / "build_fmus"


#: The time limit of a test meant to be quick (a few FMI calls, a parser, a classifier): the
#: slowest of them takes about 20 s on a loaded 2-core machine. Every other test has the
#: generous default of python/pyproject.toml.
QUICK_LIMIT_S = 120


def is_quick(module: str) -> bool:
    """Test modules of FMI calls (not valgrind's), of parsers and of the classifier."""
    if module.startswith("test_fmu_"):
        return module != "test_fmu_valgrind"
    return module in {"test_analysis_classify", "test_cli_args", "test_scene_files_regression"}


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The quick modules' tests get QUICK_LIMIT_S unless they carry a limit of their own."""
    for item in items:
        module = item.module.__name__ if isinstance(item, pytest.Function) else ""
        if is_quick(module) and item.get_closest_marker("timeout") is None:
            item.add_marker(pytest.mark.timeout(QUICK_LIMIT_S))


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]):  # noqa: ANN201
    """Turns every skip into a failure: in this suite a skipped test is a check that did not
    run while the run still says OK."""
    outcome = yield
    report = outcome.get_result()
    if report.skipped and not hasattr(report, "wasxfail"):
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else report.longrepr
        report.outcome = "failed"
        report.longrepr = f"skipped, and skips are failures in this suite: {reason}"


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector: pytest.Collector):  # noqa: ANN201
    """The same for a whole module skipped at collection (pytest.importorskip, ...)."""
    outcome = yield
    report = outcome.get_result()
    if report.skipped:
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else report.longrepr
        report.outcome = "failed"
        report.longrepr = f"skipped at collection, and skips are failures here: {reason}"


@pytest.fixture(scope="session")
def fmu_paths() -> dict[str, Path]:
    """target/fmu/<Scene>.fmu for every scene of scenes/; runs scripts/build_fmus once if the FMU
    of any scene file (scenes/ and examples/, all of which it packages), in either FMI version, is
    missing, older than the library of target/libs or older than its scene file."""

    def stale() -> list[str]:
        return [
            *stale_fmus(SCENE_FILES, FMU_DIR, GEOROD_LIB),
            *(f"fmu3/{why}" for why in stale_fmus(SCENE_FILES, FMU3_DIR, GEOROD_LIB)),
        ]

    # One pytest-xdist worker builds, the others wait and then find the FMUs up to date.
    with build_lock():
        build_stale_fmus(stale)
    return {s: FMU_DIR / f"{s}.fmu" for s in SCENES}


@contextmanager
def build_lock() -> Iterator[None]:
    """An exclusive lock on target/.fmu-build.lock: the workers of one pytest run (xdist) never
    package the FMUs at once, nor read them while another packages them."""
    lock = REPO / "target" / ".fmu-build.lock"
    lock.parent.mkdir(parents=True, exist_ok=True)
    with lock.open("w") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def build_stale_fmus(stale: Callable[[], list[str]]) -> None:
    """Runs scripts/build_fmus when `stale` names any FMU; fails when it cannot."""
    if stale():
        if not BUILD_FMUS.exists():
            pytest.fail(f"FMUs missing or stale and {BUILD_FMUS} does not exist")
        r = run_cmd([BUILD_FMUS], timeout=1200, env=dict(os.environ, PROFILE="quick"))
        if r.returncode != 0:
            pytest.fail(
                f"scripts/build_fmus failed ({r.returncode}):\n"
                f"{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
            )
        left = stale()
        if left:
            pytest.fail(f"scripts/build_fmus left FMUs out of date: {'; '.join(left)}")


@pytest.fixture(scope="session")
def fmus(
    fmu_paths: dict[str, Path], tmp_path_factory: pytest.TempPathFactory
) -> Iterator[dict[str, FmuInfo]]:
    """Each FMU extracted once (fmpy.extract) with its model description and name -> vr table."""
    root = tmp_path_factory.mktemp("fmus")
    infos: dict[str, FmuInfo] = {}
    for scene, path in fmu_paths.items():
        unzipdir = Path(fmpy.extract(str(path), unzipdir=str(root / scene)))
        md = fmpy.read_model_description(str(unzipdir))
        infos[scene] = FmuInfo.from_model_description(scene, path, unzipdir, md)
    yield infos
    shutil.rmtree(root, ignore_errors=True)


@pytest.fixture(scope="session")
def fmu3_paths(fmu_paths: dict[str, Path]) -> dict[Path, tuple[Path, Path]]:
    """Every scene file (scenes/ and examples/) -> its (FMI 2.0, FMI 3.0) FMU, both up to date
    (fmu_paths builds them)."""
    return {f: (FMU_DIR / f"{f.stem}.fmu", FMU3_DIR / f"{f.stem}.fmu") for f in SCENE_FILES}


EXAMPLES = tuple(sorted(p.stem for p in (REPO / "examples").glob("*.toml")))


@pytest.fixture(scope="session")
def examples(
    fmu_paths: dict[str, Path], tmp_path_factory: pytest.TempPathFactory
) -> dict[str, FmuInfo]:
    """The example FMUs (scripts/build_fmus packages them with the scenes), each extracted once."""
    root = tmp_path_factory.mktemp("examples")
    infos = {}
    for name in EXAMPLES:
        path = FMU_DIR / f"{name}.fmu"
        assert path.is_file(), f"{path} missing: scripts/build_fmus packages examples/*.toml"
        unzipdir = Path(fmpy.extract(str(path), unzipdir=str(root / name)))
        md = fmpy.read_model_description(str(unzipdir))
        infos[name] = FmuInfo.from_model_description(name, path, unzipdir, md)
    return infos


@pytest.fixture(params=SCENES)
def scene(request: pytest.FixtureRequest) -> str:
    return str(request.param)


@pytest.fixture
def fmu(fmus: dict[str, FmuInfo], scene: str) -> FmuInfo:
    return fmus[scene]


@pytest.fixture
def beam(fmus: dict[str, FmuInfo]) -> FmuInfo:
    return fmus["BuckledBeam"]


@pytest.fixture(scope="session")
def georod_cli() -> Path:
    """target/libs/georod (the core without FMI); built by scripts/build_libs if missing or
    stale."""
    return ensure_georod()
