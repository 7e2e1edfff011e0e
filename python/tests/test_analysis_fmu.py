"""End to end through the BuckledBeam FMU: stroboscopic sampling, the core's Lyapunov exponent,
classifier, figures and the command line; ``case`` and ``sweep`` agree. Each case is short."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from georod_tools.analysis.classify import CHAOTIC, PERIODIC
from helpers import FMU_DIR, FmuInfo, trajectory

BEAM_FMU = FMU_DIR / "BuckledBeam.fmu"
pytestmark = pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale


def config(**kw):  # noqa: ANN003, ANN201
    from georod_tools.analysis.case import CaseConfig

    base = {"fmu": str(BEAM_FMU), "transient_periods": 150, "sample_periods": 100}
    base.update(kw)
    return CaseConfig(**base)


def test_small_orbit_is_period_one() -> None:
    """Paper Fig. 2a (F = 0.4, Omega = 3500): small orbit around one equilibrium."""
    from georod_tools.analysis.case import run_case

    r = run_case(config(F=0.4, dense_periods=5))
    c = r.classification
    assert (c.kind, c.period) == (PERIODIC, 1), c.note
    assert abs(r.exponent_per_period) < 0.05  # near zero: almost undamped rotations
    assert r.exponent_per_second == pytest.approx(r.exponent_per_period * 3500 / (2 * math.pi))
    t_period = 2 * math.pi / 3500
    k = np.arange(151, 251)
    assert np.allclose(r.sample_times, k * t_period, rtol=1e-13, atol=0)  # samples at t = k T
    assert r.samples.shape == (100, 2)
    assert r.dense is not None and r.dense.shape == (5 * 64 + 1, 3)  # T/64 points (N = 128)
    assert np.all(r.size > 0)
    assert np.all(r.samples[:, 0] > 0)  # stays in the upper well (well = +1)


def test_chaotic_case() -> None:
    """F = 1.5 (paper Fig. 2e: globally chaotic): a clearly positive exponent."""
    from georod_tools.analysis.case import run_case

    r = run_case(config(F=1.5))
    assert r.classification.kind == CHAOTIC, r.classification.note
    assert r.exponent_per_period > 0.2
    assert np.ptp(r.samples[:, 0]) > 0.5  # visits both wells


def test_runs_are_deterministic() -> None:
    from georod_tools.analysis.case import run_case

    cfg = config(F=0.9, transient_periods=20, sample_periods=30, params=(("well", -1),))
    a, b = run_case(cfg), run_case(cfg)
    assert np.array_equal(a.samples, b.samples)
    assert a.lyapunov is not None and b.lyapunov is not None
    assert np.array_equal(a.lyapunov.log_growth, b.lyapunov.log_growth)
    assert a.lyapunov.periods == pytest.approx(30 - 10)  # 10 of the 30 periods align
    no_lyap = run_case(replace(cfg, lyapunov=False))
    assert np.array_equal(no_lyap.samples, a.samples)  # the tangent map leaves the motion alone
    dense = run_case(replace(cfg, dense_periods=7))
    assert np.array_equal(dense.samples, a.samples)  # so does the dense window (T/64 steps)
    assert dense.exponent_per_period == a.exponent_per_period


@pytest.mark.parametrize("forcing", [0.9, 1.5])
def test_well_minus_one_is_the_exact_mirror_image_of_well_plus_one(
    fmus: dict[str, FmuInfo], forcing: float
) -> None:
    """The symmetric beam mirrored about its axis (u2 -> -u2, w -> -w) with the excitation
    mirrored (F -> -F) is the same problem: the strains go to (e1, -e2, -k), the energy is even in
    them. The initial state of well = -1 is the mirror of well = +1 (the guess is, and Newton
    keeps it: every operation is odd or even in the mirrored values, and IEEE arithmetic and the
    libm sin/cos are exactly odd/even), so the trajectories are mirror images bit for bit, even in
    the chaotic regime (F = 0.9, 1.5) over 60 periods. Without flipping F they are not."""
    beam = fmus["BuckledBeam"]
    names = ("w_mid", "v_mid", "E_kin", "E_strain", "W_ext", "E_damped")
    h, n = 2 * math.pi / 3500.0 / 20, 20 * 60
    up = trajectory(beam, {"F": forcing, "well": 1}, h, n, names=names)
    down = trajectory(beam, {"F": -forcing, "well": -1}, h, n, names=names)
    assert up[0, 0] > 0.3 and np.array_equal(down[:, :2], -up[:, :2])
    assert np.array_equal(down[:, 2:], up[:, 2:])  # energies and works are even
    unflipped = trajectory(beam, {"F": forcing, "well": -1}, h, n, names=("w_mid",))
    assert np.max(np.abs(unflipped[:, 0] + up[:, 0])) > 0.5


def test_bad_parameters() -> None:
    from georod_tools.analysis.case import run_case
    from georod_tools.fmu import FmuError

    with pytest.raises(ValueError, match="no parameter 'H'.*pre_shortening"):
        run_case(config(params=(("H", 1.0),), transient_periods=1, sample_periods=20))
    with pytest.raises(FmuError, match="d"):
        run_case(config(params=(("d", -1.0),), transient_periods=1, sample_periods=20))
    with pytest.raises(ValueError, match="Omega"):
        config(Omega=0.0)
    with pytest.raises(ValueError, match="dense_steps = 48 must divide substeps = 128"):
        config(dense_steps=48)
    with pytest.raises(ValueError, match="params dt_max: set by the case itself"):
        config(params=(("dt_max", 1e-5),))  # dt_max is T / substeps, never overridden


def test_case_figure_and_csv(tmp_path: Path) -> None:
    from georod_tools.analysis.case import run_case
    from georod_tools.report.case_files import write_case_csv
    from georod_tools.report.figures import plot_case

    r = run_case(config(F=0.7, transient_periods=20, sample_periods=40, dense_periods=10))
    png = plot_case(r, tmp_path / "case.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    lines = write_case_csv(r, tmp_path / "case.csv").read_text().splitlines()
    assert lines[0] == "k,t,w_mid,v_mid" and len(lines) == 41
    assert lines[1].startswith("21,")


def test_cli_case(tmp_path: Path) -> None:
    cmd = [
        sys.executable,
        "-m",
        "georod_tools",
        "case",
        "--fmu",
        str(BEAM_FMU),
        "--F",
        "0.4",
        "--transient",
        "100",
        "--periods",
        "60",
        "--out",
        str(tmp_path),
    ]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, check=False)
    assert r.returncode == 0, r.stderr
    assert "class: period-1" in r.stdout
    assert (tmp_path / "BuckledBeam_F0.4_Omega3500.png").is_file()
    assert (tmp_path / "BuckledBeam_F0.4_Omega3500_samples.csv").is_file()


def test_period_one_section_is_shown_on_the_scale_of_the_orbit() -> None:
    """A period-1 orbit's samples repeat to ~1e-6 of its swing: the section shows them as one
    point on the scale of the swing (not zoomed in to the round-off), without offset notation,
    and the axes say what and in which unit."""
    from georod_tools.analysis.case import run_case
    from georod_tools.report.figures import plt, poincare_axes

    r = run_case(config(F=0.4, transient_periods=150, sample_periods=30))
    assert np.ptp(r.samples[:, 0]) < 1e-4 * r.size[0]
    fig, ax = plt.subplots()
    poincare_axes(ax, r.samples, r.size, str(BEAM_FMU))
    lo, hi = ax.get_xlim()
    assert hi - lo == pytest.approx(r.size[0]) and lo < r.samples[0, 0] < hi
    assert ax.get_ylim()[1] - ax.get_ylim()[0] == pytest.approx(r.size[1])
    assert ax.get_xlabel() == "w_mid [m]" and ax.get_ylabel() == "v_mid [m/s]"
    fig.canvas.draw()
    assert ax.xaxis.get_offset_text().get_text() == ""
    plt.close(fig)


def test_case_and_sweep_agree(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The ``case`` and ``sweep`` commands with their defaults (T/128 sub-steps, 200 + 200
    periods) at F = 1.208, Omega = 3500, where the former code disagreed (its case and sweep cut
    the period into 200 and 180 sub-steps): now the same sub-steps, hence the same samples bit
    for bit, the same exponent and the same class."""
    import csv

    from georod_tools.cli import main

    case_out, sweep_out = tmp_path / "case", tmp_path / "sweep"
    argv = ["--fmu", str(BEAM_FMU), "--F", "1.208", "--Omega", "3500"]
    assert main(["case", *argv, "--out", str(case_out)]) == 0
    argv = ["--fmu", str(BEAM_FMU), "--start", "1.208", "--stop", "1.208", "--count", "1"]
    assert main(["sweep", *argv, "--workers", "1", "--no-progress", "--out", str(sweep_out)]) == 0
    out = capsys.readouterr().out
    assert "class: chaotic" in out
    with (case_out / "BuckledBeam_F1.208_Omega3500_samples.csv").open() as f:
        case_rows = [(r["w_mid"], r["v_mid"]) for r in csv.DictReader(f)]
    with (sweep_out / "BuckledBeam_sweep_F_1.208_1.208_1_samples.csv").open() as f:
        sweep_rows = [(r["w_mid"], r["v_mid"]) for r in csv.DictReader(f)]
    assert len(case_rows) == 200 and case_rows == sweep_rows
    case_json = json.loads((case_out / "run.json").read_text())["result"]
    with (sweep_out / "BuckledBeam_sweep_F_1.208_1.208_1.csv").open() as f:
        (row,) = list(csv.DictReader(f))
    assert row["class"] == case_json["class"] == "chaotic"
    assert float(row["lyapunov_per_period"]) == case_json["lyapunov_per_period"] > 0.05


@pytest.mark.parametrize(
    "args, message",
    [
        (["case", "--elements", "1"], "allowed range 2..100000"),
        (["case", "--Omega", "-3"], "must be > 0"),
        (["case", "--period-tol", "2"], "allowed range (0, 1)"),
        (["case", "--set", "well"], "expected NAME=VALUE"),
        (["case", "--set", "H=1"], "no such parameter"),
        (["case", "--set", "dt_max=1e-5"], "--set dt_max: set by georod_tools"),
        (["case", "--periods", "5"], "at least one averaged Lyapunov period"),
        (["case", "--dense-steps", "48"], "must divide --substeps 128"),
        (["sweep", "--param", "dt_max", "--start", "1e-5", "--stop", "2e-5"], "--param dt_max"),
        (["sweep", "--start", "0.4", "--stop", "2", "--count", "0"], "allowed range 1..100000"),
        (["sweep", "--param", "Omega", "--start", "0", "--stop", "2"], "must be > 0"),
        (["case", "--fmu", "/nonexistent.fmu"], "no such file"),
    ],
)
def test_cli_errors(args: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    from georod_tools.cli import main

    with pytest.raises(SystemExit) as e:
        main([*args, "--fmu", str(BEAM_FMU)] if "--fmu" not in args else args)
    assert e.value.code == 2
    assert message in capsys.readouterr().err


def test_instances_are_reused_after_reset_and_after_a_failure() -> None:
    """One instance serves case after case (fmi2Reset between them, no new instantiation, the
    core keeps its static initial state when the fixed parameters agree), and a case the FMU
    refuses leaves the instance usable: the next case gives the same bits as a fresh process."""
    from georod_tools.analysis.case import run_case
    from georod_tools.fmu import FmuError, FmuModel

    model = FmuModel.load(BEAM_FMU)
    cfg = config(F=0.9, transient_periods=5, sample_periods=15, substeps=32)
    first = run_case(cfg)
    idle = list(model.idle)  # earlier tests may have left instances too
    inst = idle[-1]  # the one this case used: given back last, lent first
    again = run_case(cfg)
    assert model.idle == idle and model.idle[-1] is inst  # the same instance, given back
    assert np.array_equal(first.samples, again.samples)
    assert first.exponent_per_period == again.exponent_per_period
    with pytest.raises(FmuError, match="fmi2Discard"):
        run_case(config(F=1000.0, elements=4, transient_periods=5, sample_periods=15, substeps=16))
    assert model.idle == idle
    after = run_case(cfg)
    assert np.array_equal(after.samples, first.samples)
