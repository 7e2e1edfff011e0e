"""``georod-tools animate`` beyond constant inputs: supports drawn where they are in each frame
(a beam whose supports follow an input table, ``--inputs FILE.csv``), the stretch factor of a y
axis stretched to show a flat motion, bad tables refused before anything is written, and the rod
coloured by a shape field (``--field M`` on `ReadoutCantilever.toml`, whose bending moment at
the root is `-P L` = -40 N m at rest, 1e-3 for the small deflection).

`python/tests/scenes/ShakenBeam.toml`: both ends clamped and moved by inputs. The table lifts
both supports linearly by 0.1 m over 0.01 s: a moving support reaches the input's value at the
end of each step, so at every frame the supports sit at ``(0, 0.1 t / 0.01)`` and
``(10, 0.1 t / 0.01)`` (the shape samples at stations 0 and 1 are the end nodes), to round-off.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np
import pytest

from georod_tools.cli import main
from georod_tools.report.animation import (
    midpoints,
    record,
    segments,
    stretch_factor,
    support_positions,
)
from helpers import FmuInfo
from scene_fmus import package_scene

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def shaken(tmp_path_factory: pytest.TempPathFactory) -> FmuInfo:
    return package_scene("ShakenBeam", Path(tmp_path_factory.mktemp("shaken")))


def write_table(path: Path, header: str) -> Path:
    path.write_text(f"{header}\n0.0,0.0,0.0\n0.01,0.1,0.1\n")
    return path


def test_supports_follow_the_input_table(shaken: FmuInfo, tmp_path: Path) -> None:
    table = write_table(tmp_path / "lift.csv", "time,left_u2,right_u2")
    motion = record(shaken.path, {}, 0.01, 1e-3, 10, table)
    at = support_positions(motion)
    lift = 0.1 * motion.times / 0.01
    assert np.allclose(at[:, 0, 0], 0.0, atol=1e-12) and np.allclose(at[:, 1, 0], 10.0)
    for j in (0, 1):
        assert np.allclose(at[:, j, 1], lift, rtol=0, atol=1e-12), at[:, j, 1]
    out = tmp_path / "lift.gif"
    argv = ["animate", str(shaken.path), "--inputs", str(table), "--stop", "0.01", "--step"]
    assert main([*argv, "1e-3", "--frames", "5", "-o", str(out)]) == 0
    assert out.is_file()


def test_stretch_factor_is_the_ratio_of_the_axes_scales() -> None:
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(8, 4))
    ax = fig.add_axes((0.1, 0.1, 0.8, 0.8))
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 1)
    # y: 0.8 * 4 in per unit, x: 0.8 * 8 / 10 in per unit.
    assert stretch_factor(fig, ax) == pytest.approx(5.0)
    plt.close(fig)


@pytest.mark.parametrize(
    "header, message",
    [
        ("time,left_u2,mid_u2", "mid_u2: not an input of the FMU (its inputs: left_u1"),
        ("t,left_u2,right_u2", "first column is time"),
    ],
)
def test_bad_input_tables_are_refused(
    shaken: FmuInfo,
    tmp_path: Path,
    header: str,
    message: str,
    capsys: pytest.CaptureFixture[str],
) -> None:
    table = write_table(tmp_path / "bad.csv", header)
    out = tmp_path / "never.gif"
    with pytest.raises(SystemExit) as e:
        main(["animate", str(shaken.path), "--inputs", str(table), "-o", str(out)])
    assert e.value.code == 2 and message in capsys.readouterr().err
    assert not out.exists()


@pytest.fixture(scope="module")
def cantilever(tmp_path_factory: pytest.TempPathFactory) -> FmuInfo:
    return package_scene("ReadoutCantilever", Path(tmp_path_factory.mktemp("field")))


def test_the_rod_is_coloured_by_a_field(
    cantilever: FmuInfo, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    motion = record(cantilever.path, {}, 2e-4, 1e-4, 2, field="M")
    assert motion.field is not None and motion.field.shape == (3, 21)
    assert motion.field_unit == "N.m"
    assert motion.field[0, 0] == pytest.approx(-40.0, rel=1e-3)
    assert abs(motion.field[0, -1]) < 1e-9  # a free end carries no moment
    assert segments(motion.x[0], motion.y[0]).shape == (20, 2, 2)
    assert midpoints(np.array([0.0, 2.0, 4.0])).tolist() == [1.0, 3.0]
    out = tmp_path / "moment.gif"
    argv = ["animate", str(cantilever.path), "--field", "M", "--stop", "2e-4", "--step", "1e-4"]
    assert main([*argv, "-o", str(out)]) == 0 and out.is_file()
    never = tmp_path / "never.gif"
    with pytest.raises(SystemExit) as e:
        main(["animate", str(cantilever.path), "--field", "N", "-o", str(never)])
    assert e.value.code == 2
    assert 'add "N" to the scene\'s [shape] fields' in capsys.readouterr().err
    assert not never.exists()
