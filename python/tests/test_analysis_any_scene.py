"""The analysis tools on scenes that do not look like the paper's: sensors not named w_mid /
v_mid, a harmonic load whose amplitude is not F, a scene without a harmonic load, a mesh of the
scene's own. `case` and `sweep` sample the sensor asked for (default: the scene's first
displacement sensor) with its velocity partner (or, without one, the sensor's change over the
last sub-step of each step), take the period from the harmonic load or from
`--period`, sweep any parameter of the scene by name and use the FMU's own mesh; a scene that
cannot be analysed so is refused (exit status 2) before any case runs, with the reason and what
to add; a sweep whose every case fails exits 1.

`python/tests/scenes/UserShaker.toml` (a thick clamped-pinned beam, harmonic point load `shake`
at 200 rad/s, damped at 25 1/s, so that 40 forcing periods settle every mode: after them it moves
with the forcing, period 1) and `UserSwing.toml` (a cantilever released under a tip load,
no harmonic load, damped towards its loaded equilibrium: period 1 at any sampling period once
settled; its first sensor `mid` has no velocity partner).

The sampled velocity: the midpoint rule moves a sensor by `dt (v_n + v_(n+1)) / 2` in a sub-step
(the sensor interpolates the nodes linearly), so the sensor's change over the last sub-step
divided by `dt` is the mean of the velocities at its two ends: it differs from the velocity at
the end by at most `dt / 2` times the largest acceleration (taken here from the partner's dense
trajectory, sampled at every sub-step).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from georod_tools.cli import main
from helpers import FmuInfo
from scene_fmus import package_scene

QUICK = ["--substeps", "32", "--transient", "40", "--periods", "20", "--no-lyapunov"]


@pytest.fixture(scope="module")
def shaker(tmp_path_factory: pytest.TempPathFactory) -> FmuInfo:
    return package_scene("UserShaker", Path(tmp_path_factory.mktemp("user_shaker")))


@pytest.fixture(scope="module")
def swing(tmp_path_factory: pytest.TempPathFactory) -> FmuInfo:
    return package_scene("UserSwing", Path(tmp_path_factory.mktemp("user_swing")))


def samples(folder: Path) -> list[dict[str, str]]:
    (path,) = folder.glob("*_samples.csv")
    with path.open() as f:
        return list(csv.DictReader(f))


def test_case_samples_the_first_displacement_sensor_of_a_forced_scene(
    shaker: FmuInfo, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "case"
    assert main(["case", "--fmu", str(shaker.path), *QUICK, "--out", str(out)]) == 0
    text = capsys.readouterr().out
    # The FMU's own 6 elements, its Omega, its sensors; F is the FMU's start value (unused).
    assert "6 elements" in text and "Omega = 200" in text and "sampling defl" in text, text
    assert "class: period-1" in text, text
    rows = samples(out)
    assert list(rows[0]) == ["k", "t", "defl", "defl_rate"] and len(rows) == 20
    assert json.loads((out / "run.json").read_text())["result"]["class"] == "period-1"


def test_case_of_an_unforced_scene_takes_the_period_and_the_named_sensor(
    swing: FmuInfo, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "case"
    argv = ["case", "--fmu", str(swing.path), "--sensor", "tip", "--period", "0.05", *QUICK]
    assert main([*argv, "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "T = 0.05 s" in text and "4 elements" in text and "sampling tip" in text, text
    rows = samples(out)
    assert list(rows[0]) == ["k", "t", "tip", "tip_rate"]
    assert float(rows[-1]["t"]) == pytest.approx(60 * 0.05)
    # Settled on the loaded equilibrium: the tip hangs below the axis.
    assert float(rows[-1]["tip"]) < 0.0
    # Rerunning into the same folder: the refusal offers what `case` has.
    with pytest.raises(SystemExit) as e:
        main([*argv, "--out", str(out)])
    err = capsys.readouterr().err
    assert e.value.code == 2 and "--overwrite" in err and "--resume" not in err, err


def test_without_a_velocity_sensor_the_velocity_is_sampled(
    swing: FmuInfo, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import math
    from dataclasses import replace

    import numpy as np

    from georod_tools.analysis.case import CaseConfig, run_case

    out = tmp_path / "case"
    argv = ["case", "--fmu", str(swing.path), "--period", "0.05", *QUICK, "--out", str(out)]
    assert main(argv) == 0
    assert "sampling mid" in capsys.readouterr().out
    assert list(samples(out)[0]) == ["k", "t", "mid", "d(mid)/dt"]
    # The same sensor with and without its partner.
    partner = CaseConfig(
        fmu=str(swing.path),
        F=0.0,
        Omega=2.0 * math.pi / 0.05,
        elements=4,
        substeps=32,
        transient_periods=0,
        sample_periods=4,
        dense_periods=4,
        dense_steps=32,
        lyapunov=False,
        sensor="tip",
        velocity="tip_rate",
        forced=False,
    )
    exact = run_case(partner)
    sampled = run_case(replace(partner, velocity=""))
    dt = partner.dt_max
    assert exact.dense is not None
    accel = np.max(np.abs(np.diff(exact.dense[:, 2]))) / dt
    gap = np.max(np.abs(sampled.samples[:, 1] - exact.samples[:, 1]))
    assert gap <= 0.5 * dt * accel * 1.05 + 1e-12, (gap, 0.5 * dt * accel)
    assert gap > 0.0
    assert np.allclose(sampled.samples[:, 0], exact.samples[:, 0], rtol=1e-9, atol=0.0)


@pytest.mark.parametrize(
    "scene, args, message",
    [
        ("swing", ["--sensor", "tip"], "has no harmonic load: pass --period T"),
        ("swing", ["--sensor", "tip", "--period", "0.1", "--Omega", "3"], "--Omega: UserSwing"),
        ("swing", ["--sensor", "nothing", "--period", "0.1"], "not a sensor of UserSwing"),
        ("shaker", ["--sensor", "moment"], "reads M, not a displacement"),
        ("shaker", ["--period", "0.1"], "set --Omega instead"),
        ("shaker", ["--set", "F_amp=1"], "UserShaker has no such parameter"),
    ],
)
def test_scenes_that_cannot_be_analysed_are_refused_before_any_case(
    scene: str,
    args: list[str],
    message: str,
    request: pytest.FixtureRequest,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    info: FmuInfo = request.getfixturevalue(scene)
    out = tmp_path / "never"
    with pytest.raises(SystemExit) as e:
        main(["case", "--fmu", str(info.path), *args, "--out", str(out)])
    assert e.value.code == 2
    assert message in capsys.readouterr().err
    assert not out.exists(), "refused before anything was written"


def test_sweep_over_a_scene_parameter_and_a_sweep_that_fails_throughout(
    shaker: FmuInfo, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    base = ["sweep", "--fmu", str(shaker.path), *QUICK, "--workers", "1"]
    out = tmp_path / "sweep"
    argv = [*base, "--param", "shake", "--start", "0.02", "--stop", "0.05", "--count", "2"]
    assert main([*argv, "--out", str(out)]) == 0
    with (out / "UserShaker_sweep_shake_0.02_0.05_2.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert [r["shake"] for r in rows] == ["0.02", "0.05"]
    assert all(r["class"] == "periodic" and r["period"] == "1" for r in rows)
    assert list(samples(out)[0]) == ["shake", "k", "defl", "defl_rate"]
    capsys.readouterr()
    # E must be > 0: the FMU refuses every case.
    argv = [*base, "--param", "E", "--start", "-2", "--stop", "-1", "--count", "2"]
    assert main([*argv, "--out", str(tmp_path / "failing")]) == 1
    assert "every case failed (2)" in capsys.readouterr().err
