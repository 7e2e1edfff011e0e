"""Stability study (docs/stability.md): energy histories of the two integrators through the FMUs,
and the plots of the energy histories (these and the Rust stability tests' CSV files).
The command is ``georod-tools study stability`` (scripts/study_stability also runs the Rust
tests that write their CSV files).

FMU runs: an undamped scene (``d = 0``) is kicked by its excitation for ``kick_periods`` forcing
periods, then ``F`` is set to 0 and it vibrates freely for ``steps`` communication steps of
``h`` (one sub-step each, ``dt_max = h``). The energy ``E_kin + E_strain`` should stay constant
after the kick; the CSV holds it with ``energy_error`` (the FMU's own balance) for
``integrator = 1`` (midpoint) and ``2`` (energy-momentum). A discarded step (fmi2Discard) ends
the run and is recorded, never raised.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

from tqdm import tqdm

from georod_tools.fmu import FmuError, FmuModel, lend
from georod_tools.report.figures import save

ENERGY_OUTPUTS = ("E_kin", "E_strain", "energy_error", "w_mid")


@dataclass(frozen=True)
class EnergyCase:
    """An undamped free vibration through an FMU after a kick by the excitation."""

    name: str
    scene: str
    F: float
    Omega: float
    h: float
    kick_periods: int = 2
    params: tuple[tuple[str, float], ...] = ()


CASES: tuple[EnergyCase, ...] = (
    # Buckled beam kicked hard (F = 10 x the paper's 0.7) for 2 periods, then free.
    EnergyCase("beam", "BuckledBeam", F=7.0, Omega=3500.0, h=2e-5),
    EnergyCase("beam_coarse", "BuckledBeam", F=7.0, Omega=3500.0, h=1e-4),
    # Pinned arch kicked through snap-through (F = 300 at the crown).
    EnergyCase("arch", "PinnedArch", F=100.0, Omega=1000.0, h=5e-5),
)


@dataclass
class EnergyRun:
    case: EnergyCase
    integrator: int
    times: list[float]
    energy: list[float]
    energy_error: list[float]
    w_mid: list[float]
    discarded_at: float | None
    message: str

    @property
    def reference(self) -> float:
        """The energy right after the kick."""
        return self.energy[0] if self.energy else math.nan

    def max_rel_drift(self) -> float:
        e0 = self.reference
        return max((abs(e - e0) / abs(e0) for e in self.energy), default=math.nan)


def run_energy(
    fmu_dir: Path, case: EnergyCase, integrator: int, steps: int, every: int = 1
) -> EnergyRun:
    """One FMU run of `case` with `integrator` (1 midpoint, 2 energy-momentum)."""
    model = FmuModel.load(fmu_dir / f"{case.scene}.fmu")
    params = {
        "F": case.F,
        "Omega": case.Omega,
        "d": 0.0,
        "dt_max": case.h,
        "integrator": integrator,
        **dict(case.params),
    }
    # Steps of T / n (n = T / h rounded): whole periods of kick, one sub-step each.
    n_per_period = max(1, round(2.0 * math.pi / case.Omega / case.h))
    h = 2.0 * math.pi / case.Omega / n_per_period
    kick = case.kick_periods * n_per_period
    vrs = ENERGY_OUTPUTS
    out = EnergyRun(case, integrator, [], [], [], [], None, "")
    with lend(model, "stability") as inst:
        inst.initialize(params)
        read = inst.reader(vrs)
        k = 0
        try:
            for k in range(kick):
                inst.step(k * h, h)
        except FmuError as e:
            out.discarded_at = k * h
            out.message = f"during the kick: {e}"
            return out
        inst.set("F", 0.0)
        desc = f"{case.name}, integrator {integrator}"
        for j in tqdm(range(steps + 1), desc=desc, unit="step", leave=False, mininterval=1.0):
            t = (kick + j) * h
            if j % every == 0 or j == steps:
                e_kin, e_strain, err, w = read()
                out.times.append(t)
                out.energy.append(e_kin + e_strain)
                out.energy_error.append(err)
                out.w_mid.append(w)
            if j < steps:
                try:
                    inst.step(t, h)
                except FmuError as e:
                    out.discarded_at = t
                    out.message = str(e)
                    break
    return out


def write_energy_csv(run: EnergyRun, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as f:
        f.write(
            f"# {run.case.scene} F={run.case.F} Omega={run.case.Omega} kick "
            f"{run.case.kick_periods} periods, then free, d=0, h=dt_max={run.case.h:g}, "
            f"integrator={run.integrator}"
            + (f"; discarded at t={run.discarded_at:g}: {run.message}" if run.message else "")
            + "\n"
        )
        w = csv.writer(f)
        w.writerow(["time", "energy", "rel_energy_error", "energy_error", "w_mid"])
        e0 = run.reference
        for t, e, err, wm in zip(run.times, run.energy, run.energy_error, run.w_mid, strict=False):
            w.writerow([f"{t:.9e}", f"{e:.12e}", f"{(e - e0) / e0:.6e}", f"{err:.6e}", f"{wm:.8e}"])
    return path


def read_csv(path: Path) -> tuple[str, dict[str, list[float]]]:
    """(comment line, columns) of a CSV written here or by the Rust stability tests."""
    lines = path.read_text().splitlines()
    comment = lines[0].lstrip("# ") if lines and lines[0].startswith("#") else ""
    rows = [r for r in csv.reader(line for line in lines if not line.startswith("#"))]
    header, data = rows[0], rows[1:]
    cols: dict[str, list[float]] = {h: [] for h in header}
    for r in data:
        for h, v in zip(header, r, strict=False):
            cols[h].append(float(v))
    return comment, cols


def plot_pairs(csv_dir: Path, out_dir: Path) -> list[Path]:
    """For every pair of CSVs `<stem>_Midpoint.csv` / `<stem>_EnergyMomentum.csv` (Rust) or
    `<stem>_int1.csv` / `<stem>_int2.csv` (FMU), a PNG `<stem>.png` with the relative energy
    error of both integrators side by side (symlog scale)."""
    from georod_tools.report.figures import plt

    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    pairs: dict[str, dict[str, Path]] = {}
    for p in sorted(csv_dir.glob("*.csv")):
        for tag, label in (
            ("_Midpoint", "midpoint"),
            ("_EnergyMomentum", "energy-momentum"),
            ("_int1", "midpoint"),
            ("_int2", "energy-momentum"),
        ):
            if p.stem.endswith(tag):
                pairs.setdefault(p.stem[: -len(tag)], {})[label] = p
    for stem, files in pairs.items():
        fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), sharey=False)
        for ax, label in zip(axes, ("midpoint", "energy-momentum"), strict=False):
            if label not in files:
                ax.set_visible(False)
                continue
            comment, cols = read_csv(files[label])
            x = cols.get("time") or cols.get("step")
            y = cols["rel_energy_error"]
            ax.plot(x, y, lw=0.8)
            ax.set_yscale("symlog", linthresh=1e-12)
            ax.set_xlabel("t [s]" if "time" in cols else "step [1]")
            ax.set_ylabel("relative energy change (E - E0) / E0 [1]")
            ax.set_title(label)
            ax.grid(True, alpha=0.3)
            ax.text(
                0.01,
                0.02,
                f"{len(x)} samples, last t = {x[-1]:.4g}" if x else "",
                transform=ax.transAxes,
                fontsize=7,
            )
            fig.suptitle(f"{stem}: {comment[:150]}", fontsize=8)
        fig.tight_layout()
        written.append(save(fig, out_dir / f"{stem}.png", dpi=110))
    return written


def run_fmu_cases(
    fmu_dir: Path, csv_dir: Path, steps: int, every: int, names: list[str], say=print
) -> list[Path]:
    """Every case of `names` with both integrators; one CSV each; prints a line per run."""
    files = []
    for case in (c for c in CASES if c.name in names):
        for integrator in (1, 2):
            run = run_energy(fmu_dir, case, integrator, steps, every)
            final = run.energy_error[-1] if run.energy_error else math.nan
            files.append(
                write_energy_csv(run, csv_dir / f"stability_fmu_{case.name}_int{integrator}.csv")
            )
            gone = (
                f", DISCARDED at t = {run.discarded_at:.6g}" if run.discarded_at is not None else ""
            )
            say(
                f"{case.name:<12} integrator {integrator}: {len(run.times)} samples, "
                f"max |dE|/E0 = {run.max_rel_drift():.3e}, final energy_error = {final:.3e}{gone}"
            )
    return files
