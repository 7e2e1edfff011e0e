"""examples/control/: georod's BuckledBeam FMU under velocity feedback from a controller FMU,
coupled by an SSP file and run by two third-party co-simulation engines, libcosim (through
libcosimpy) and Ecos (through ecospy).

    .venv/bin/python examples/control/run.py      (after scripts/build_fmus)
    .venv/bin/python examples/control/run.py --build-only [--out DIR]    (scripts/build_ssp)

builds target/control/ControlledBeam.ssp (or DIR/ControlledBeam.ssp: this folder's
SystemStructure.ssd, target/fmu/BuckledBeam.fmu and the controller FMU that pythonfmu builds from
velocity_feedback.py, under resources/), then, without --build-only, runs it in both engines with
the SSP's gain and with the gain 0 (uncontrolled), and prints the beam's midspan amplitude over
the second half of the run and the controller's work W_ctrl."""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
BEAM_FMU = REPO / "target" / "fmu" / "BuckledBeam.fmu"
STEP = 1.0e-4  # s: BuckledBeam's default communication step
STOP = 0.2  # s: the SSP's DefaultExperiment


@dataclass
class Outcome:
    engine: str
    gain: float
    amplitude: float  # half the peak-to-peak w_mid over the second half of the run
    w_ctrl: float  # the control force's work on the beam (negative: energy removed)


def build_ssp(out_dir: Path) -> Path:
    """out_dir/ControlledBeam.ssp: SystemStructure.ssd with both FMUs under resources/."""
    if not BEAM_FMU.is_file():
        raise FileNotFoundError(f"{BEAM_FMU} is missing: run scripts/build_fmus first")
    out_dir.mkdir(parents=True, exist_ok=True)
    pythonfmu = Path(sys.executable).with_name("pythonfmu")
    build = out_dir / "controller"
    shutil.rmtree(build, ignore_errors=True)
    cmd = [
        str(pythonfmu),
        "build",
        "-f",
        str(HERE / "velocity_feedback.py"),
        "-d",
        str(build),
    ]
    r = subprocess.run(cmd, capture_output=True, text=True, check=False)
    controller = build / "VelocityFeedback.fmu"
    if r.returncode != 0 or not controller.is_file():
        raise RuntimeError(
            f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stdout}{r.stderr}"
        )
    ssp = out_dir / "ControlledBeam.ssp"
    with zipfile.ZipFile(ssp, "w", zipfile.ZIP_DEFLATED) as z:
        z.write(HERE / "SystemStructure.ssd", "SystemStructure.ssd")
        z.write(BEAM_FMU, "resources/BuckledBeam.fmu")
        z.write(controller, "resources/VelocityFeedback.fmu")
    return ssp


def amplitude(w: np.ndarray) -> float:
    half = w[len(w) // 2 :]
    return float(np.ptp(half) / 2.0)


def run_libcosim(ssp: Path, gain: float | None = None) -> Outcome:
    """The SSP in libcosim; `gain` overrides the SSP's controller gain when given."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    log_output_level(CosimLogLevel.WARNING)  # its default (debug) logs every FMI call

    # libcosim opens the .ssp itself (from_ssp_file takes the archive or its .ssd)
    execution = CosimExecution.from_ssp_file(str(ssp), step_size=round(STEP * 1e9))
    beam = execution.slave_index_from_instance_name("beam")
    controller = execution.slave_index_from_instance_name("controller")
    vr = {v.name.decode(): v.reference for v in execution.slave_variables(beam)}
    ctrl_vr = {
        v.name.decode(): v.reference for v in execution.slave_variables(controller)
    }
    if gain is not None:
        assert execution.real_initial_value(controller, ctrl_vr["gain"], gain)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    w = []
    for _ in range(round(STOP / STEP)):
        if not execution.step():
            raise RuntimeError(f"libcosim step failed: {execution.status()}")
        w.append(observer.last_real_values(beam, [vr["w_mid"]])[0])
    w_ctrl = observer.last_real_values(beam, [vr["W_ctrl"]])[0]
    used = observer.last_real_values(controller, [ctrl_vr["gain"]])[0]
    return Outcome("libcosim", used, amplitude(np.asarray(w)), w_ctrl)


def run_ecos(ssp: Path, gain: float | None = None) -> Outcome:
    """The SSP in Ecos; `gain` overrides the SSP's controller gain when given."""
    from ecospy import EcosSimulation

    sim = EcosSimulation(step_size=STEP, ssp_path=str(ssp))
    try:
        # Ecos applies an SSP parameter set only when named at initialization.
        sim.init(parameter_set="feedback")
        if gain is not None:
            sim.set_real("controller::gain", gain)
        w = []
        for _ in range(round(STOP / STEP)):
            sim.step()
            w.append(sim.get_real("beam::w_mid"))
        used = sim.get_real("controller::gain")
        return Outcome(
            "Ecos", used, amplitude(np.asarray(w)), sim.get_real("beam::W_ctrl")
        )
    finally:
        sim.terminate()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--build-only", action="store_true", help="write the .ssp, run nothing"
    )
    parser.add_argument(
        "--out", type=Path, default=REPO / "target" / "control", help="folder"
    )
    args = parser.parse_args()
    ssp = build_ssp(args.out)
    if args.build_only:
        print(f"wrote {ssp}")
        return
    print(f"{ssp}: {STOP} s in steps of {STEP} s")
    print("| engine | gain | w_mid amplitude (2nd half) | W_ctrl |")
    print("|---|---:|---:|---:|")
    for run in (run_libcosim, run_ecos):
        for gain in (0.0, None):
            o = run(ssp, gain)
            print(f"| {o.engine} | {o.gain:g} | {o.amplitude:.4f} | {o.w_ctrl:.3f} |")


if __name__ == "__main__":
    main()
