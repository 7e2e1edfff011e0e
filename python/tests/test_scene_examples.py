"""The user scenes of examples/ as FMUs: packaged by `georod fmu` (scripts/build_fmus), valid for
fmpy, simulated through fmpy and libcosim, equal to the Rust core, with their inputs, reactions,
mesh checks and shape outputs; an FMU whose scene file was altered refuses to instantiate."""

from __future__ import annotations

import math
import shutil
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from helpers import REPO, FmuInfo, LogCapture, instantiate, release


def test_examples_are_valid_fmus(examples: dict[str, FmuInfo]) -> None:
    for name, info in examples.items():
        problems = validate_fmu(str(info.path))
        assert problems == [], f"{name}: {problems}"
        names = {v.name for v in info.md.modelVariables}
        supports = ["root"] if name == "Cantilever" else []
        for support in supports:
            assert {f"{support}_Rx", f"{support}_Ry", f"{support}_M"} <= names


def test_cantilever_fmu_equals_the_core_with_a_control_input(
    examples: dict[str, FmuInfo], georod_cli: Path, tmp_path: Path
) -> None:
    """The same scene file through the FMU and through `georod simulate` (input held at a
    constant value in both): bit for bit (1e-12 of the range as a fallback)."""
    info = examples["Cantilever"]
    h, n, f_tip = 1e-3, 50, 10.0
    out = tmp_path / "core.csv"
    cmd = [georod_cli, "simulate", "--scene", REPO / "examples" / "Cantilever.toml"]
    cmd += ["--input", f"f_tip={f_tip}", "--step", str(h), "--stop", str(n * h), "--output", out]
    subprocess.run([str(c) for c in cmd], check=True, timeout=120)
    core = np.genfromtxt(out, delimiter=",", names=True)
    slave = instantiate(info)
    try:
        slave.setReal([info.vr["f_tip"]], [f_tip])
        vrs = [info.vr["w_tip"], info.vr["v_tip"]]
        rows = [slave.getReal(vrs)]
        for k in range(n):
            slave.doStep(k * h, h)
            rows.append(slave.getReal(vrs))
    finally:
        release(slave)
    got = np.array(rows)
    for j, name in enumerate(("w_tip", "v_tip")):
        ref = core[name]
        if not np.array_equal(ref, got[:, j]):
            worst = np.max(np.abs(ref - got[:, j])) / max(np.ptp(ref), 1e-300)
            assert worst <= 1e-12, f"{name}: FMU vs core differ by {worst:.2e} of the range"
    assert np.ptp(core["w_tip"]) > 0.0, "the control force moved nothing"


def test_cantilever_reactions_balance_the_tip_load(examples: dict[str, FmuInfo]) -> None:
    """Static state under P: the root holds P and its moment P x_tip (to 1e-8 of them)."""
    info = examples["Cantilever"]
    load = 1000.0  # N: P L^2 / EI = 4.6 on the 2 m steel bar, a large deflection
    slave = instantiate(info, {"P": load})
    try:
        rx, ry, m, u_tip, w_tip = slave.getReal(
            [info.vr[n] for n in ("root_Rx", "root_Ry", "root_M", "u_tip", "w_tip")]
        )
    finally:
        release(slave)
    x_tip = 2.0 + u_tip
    assert w_tip < 0.0
    assert abs(ry - load) <= 1e-8 * load and abs(rx) <= 1e-8 * load
    assert abs(m - load * x_tip) <= 1e-8 * load * x_tip


def test_beam_on_base_follows_its_inputs(examples: dict[str, FmuInfo]) -> None:
    """Both supports lifted at a constant speed v (the same u2 input on both ends, rising by v h
    per step): after the start has died out (a heavy drag set here, d / (rho A) = 2500 /s, so
    every mode of the aluminium bar decays at 170 /s or faster), the supports hold the beam
    against the drag d v alone, so their reactions add up to d L v, and the beam lags behind them
    by its clamped-clamped deflection under that drag, d v L^4 / (384 EI)."""
    info = examples["BeamOnBase"]
    e, rho, b, height, length = 70e9, 2700.0, 0.05, 0.02, 1.0
    d = 2500.0 * rho * b * height
    ei = e * b * height**3 / 12.0
    slave = instantiate(info, {"d": d})
    h, speed, steps = 1e-3, 0.1, 100
    try:
        inputs = [info.vr["left_u2"], info.vr["right_u2"]]
        for k in range(steps):
            slave.setReal(inputs, [speed * h * (k + 1)] * 2)
            slave.doStep(k * h, h)
        w_mid, left, right = slave.getReal([info.vr[n] for n in ("w_mid", "left_Ry", "right_Ry")])
    finally:
        release(slave)
    sag = d * speed * length**4 / (384.0 * ei)
    # 1 %: the mesh's bending (20 elements) is exact to 1e-3; the start's slowest part (the first
    # mode, overdamped: omega_1^2 / 2500 = 170 /s) has decayed by exp(-17).
    assert math.isclose(steps * h * speed - w_mid, sag, rel_tol=1e-2), (w_mid, sag)
    assert math.isclose(left + right, d * length * speed, rel_tol=1e-2), left + right


def test_three_span_mesh_check_names_the_counts_that_work(examples: dict[str, FmuInfo]) -> None:
    """`elements` declares [3, 100000]: one element per span at least; every count from there
    runs (the elements are spread over the spans), fewer are refused when set."""
    info = examples["ThreeSpan"]
    log = LogCapture()
    slave = instantiate(info, log=log, initialize=False)
    try:
        with pytest.raises(FMICallException):
            slave.setInteger([info.vr["elements"]], [2])
        assert any("[3, 100000]" in m for m in log.messages()), log.messages()
    finally:
        slave.freeInstance()
    for n in (3, 10, 31):
        slave = instantiate(info, {"elements": n})
        try:
            slave.doStep(0.0, 1e-3)
            assert math.isfinite(slave.getReal([info.vr["w_span2"]])[0])
        finally:
            release(slave)


def test_user_scene_runs_in_libcosim(examples: dict[str, FmuInfo]) -> None:
    """libcosim loads the ThreeSpan FMU, steps it, and gets what fmpy gets."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    info = examples["ThreeSpan"]
    execution = CosimExecution.from_step_size(step_size=100_000)
    index = execution.add_local_slave(CosimLocalSlave(fmu_path=str(info.path), instance_name="s"))
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    got = []
    for _ in range(30):
        assert execution.step()
        got.append(observer.last_real_values(index, [info.vr["w_span2"]])[0])
    slave = instantiate(info)
    try:
        ref = []
        for k in range(30):
            slave.doStep(k * 1e-4, 1e-4)
            ref.append(slave.getReal([info.vr["w_span2"]])[0])
    finally:
        release(slave)
    assert np.ptp(ref) > 0.0
    assert np.max(np.abs(np.array(got) - ref)) <= 1e-12 * np.max(np.abs(ref))


def test_altered_scene_file_is_refused(examples: dict[str, FmuInfo], tmp_path: Path) -> None:
    """Change one value in resources/scene.toml of a packaged FMU: instantiation fails with a
    message that says why (the scene no longer gives the GUID of modelDescription.xml)."""
    info = examples["Cantilever"]
    altered = tmp_path / "altered"
    shutil.copytree(info.unzipdir, altered)
    scene = altered / "resources" / "scene.toml"
    scene.write_text(scene.read_text().replace("L = 2.0", "L = 2.5"))
    from fmpy.fmi2 import FMU2Slave

    log = LogCapture()
    slave = FMU2Slave(
        guid=info.md.guid,
        unzipDirectory=str(altered),
        modelIdentifier="Cantilever",
        instanceName="altered",
    )
    with pytest.raises(Exception):  # noqa: B017 - fmpy raises on a NULL component
        slave.instantiate(callbacks=log.callbacks, loggingOn=True)
    assert any("does not match the GUID" in m for m in log.messages()), log.messages()


def test_animate_writes_a_gif(examples: dict[str, FmuInfo], tmp_path: Path) -> None:
    out = tmp_path / "cantilever.gif"
    cmd = [sys.executable, "-m", "georod_tools", "animate", str(examples["Cantilever"].path)]
    cmd += ["--start-values", "f_tip=20", "--stop", "0.2", "--frames", "8", "-o", str(out)]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    with zipfile.ZipFile(examples["Cantilever"].path) as z:
        assert "resources/scene.toml" in z.namelist()
    from PIL import Image

    with Image.open(out) as gif:
        assert gif.n_frames == 9
    assert (tmp_path / "cantilever.gif.json").is_file()
    again = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert again.returncode == 2 and "--overwrite" in again.stderr
    # without -o: a new run folder under out/animate with its run.json (here in tmp_path)
    cmd = cmd[: cmd.index("-o")]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    (folder,) = (tmp_path / "out" / "animate").iterdir()
    assert folder.name.startswith("Cantilever_") and (folder / "run.json").is_file()
    assert (folder / "Cantilever.gif").is_file()


def test_support_follows_input_derivatives(examples: dict[str, FmuInfo]) -> None:
    """canInterpolateInputs: the derivatives set for a support input define its path over the
    step (from where it is); orders other than 1 and 2, and outputs, are refused."""
    info = examples["BeamOnBase"]
    assert info.md.coSimulation.canInterpolateInputs
    log = LogCapture()
    slave = instantiate(info, log=log)
    a, h = 20.0, 1e-3
    try:
        vrs = [info.vr["left_u2"], info.vr["right_u2"]]
        for k in range(10):
            t = k * h
            slave.setRealInputDerivatives(vrs, [1, 1], [a * t, a * t])
            slave.setRealInputDerivatives(vrs, [2, 2], [a, a])
            slave.doStep(t, h)
        y_left = slave.getReal([info.vr["shape_y[1]"]])[0]
        g = 0.5 * a * (10 * h) ** 2
        assert abs(y_left - g) <= 1e-12 * g, (y_left, g)
        with pytest.raises(FMICallException):
            slave.setRealInputDerivatives(vrs[:1], [3], [1.0])
        assert "orders 1 and 2" in log.messages()[-1]
        with pytest.raises(FMICallException):
            slave.setRealInputDerivatives([info.vr["w_mid"]], [1], [1.0])
        assert "not an input" in log.messages()[-1]
    finally:
        release(slave)


def test_shape_outputs_are_the_core_positions(
    examples: dict[str, FmuInfo], georod_cli: Path, tmp_path: Path
) -> None:
    """``shape_x[i]``, ``shape_y[i]`` of the Cantilever FMU (41 points, 20 elements: every other
    point in the middle of an element) are the rod's positions: its reference (s, 0) plus the
    displacements the core reports at the same stations. The core is `georod simulate` on the
    same scene with u1 and u2 sensors added at the shape stations (sensors change nothing of
    the motion, so the states are the same bits); the bent static state and 20 steps under a
    tip force. 1e-12 L: round-off of coordinates of order L."""
    info = examples["Cantilever"]
    example = tomllib.loads((REPO / "examples" / "Cantilever.toml").read_text())
    length = example["geometry"]["L"]
    tip_load = next(p["start"] for p in example["parameter"] if p["name"] == "P")
    # A tenth of the tip load: it moves the tip visibly within 20 steps.
    points, h, n, f_tip = 41, 1e-3, 20, 0.1 * tip_load
    stations = [i / (points - 1) for i in range(points)]
    probes = "".join(
        f'\n[[sensor]]\nname = "p{i}_{q}"\nat = {at!r}\nquantity = "{q}"\n'
        for i, at in enumerate(stations)
        for q in ("u1", "u2")
    )
    scene = tmp_path / "Cantilever.toml"
    scene.write_text((REPO / "examples" / "Cantilever.toml").read_text() + probes)
    out = tmp_path / "core.csv"
    cmd = [georod_cli, "simulate", "--scene", scene, "--input", f"f_tip={f_tip}"]
    cmd += ["--step", str(h), "--stop", str(n * h), "--output", out]
    subprocess.run([str(c) for c in cmd], check=True, timeout=120)
    core = np.genfromtxt(out, delimiter=",", names=True)
    xs = [info.vr[f"shape_x[{i + 1}]"] for i in range(points)]
    ys = [info.vr[f"shape_y[{i + 1}]"] for i in range(points)]
    slave = instantiate(info)
    try:
        slave.setReal([info.vr["f_tip"]], [f_tip])
        for k in range(n + 1):
            x, y = np.array(slave.getReal(xs)), np.array(slave.getReal(ys))
            u1 = np.array([core[f"p{i}_u1"][k] for i in range(points)])
            u2 = np.array([core[f"p{i}_u2"][k] for i in range(points)])
            assert np.max(np.abs(x - (length * np.array(stations) + u1))) < 1e-12 * length, k
            assert np.max(np.abs(y - u2)) < 1e-12 * length, k
            if k < n:
                slave.doStep(k * h, h)
    finally:
        release(slave)
    tip = core["p40_u2"]
    assert tip[0] < -0.2 * length, "the cantilever is bent"
    assert tip[n] < tip[0] - 1e-4 * length, "the tip force moved it"
