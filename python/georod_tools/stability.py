"""Stability study (issue 7): energy histories of the two integrators through the FMUs, and the
plots of docs/stability.md.

    python -m georod_tools.stability fmu  --out DIR [--steps N]  # integrator 1 vs 2 -> CSV
    python -m georod_tools.stability plot --csv DIR --out DIR       # every CSV -> PNG

FMU runs: an undamped scene (``d = 0``) is kicked by its excitation for ``kick_periods`` forcing
periods, then ``F`` is set to 0 and it vibrates freely for ``steps`` communication steps of
``h`` (one sub-step each, ``dt_max = h``). The energy ``E_kin + E_strain`` should stay constant
after the kick; the CSV holds it with ``energy_error`` (the FMU's own balance) for
``integrator = 1`` (midpoint) and ``2`` (energy-momentum). A discarded step (fmi2Discard) ends
the run and is recorded, never raised.
"""

from __future__ import annotations

import argparse
import csv
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from georod_tools.argtypes import positive_int
from georod_tools.runner import FmuError, FmuModel, Instance

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
    # runner.Instance sets non-"Integer" parameters with fmi2SetReal; an Enumeration is set
    # with fmi2SetInteger (FMI 2.0), so present it as an Integer.
    if model.types.get("integrator") == "Enumeration":
        model.types["integrator"] = "Integer"
    params = {
        "F": case.F,
        "Omega": case.Omega,
        "d": 0.0,
        "dt_max": case.h,
        "integrator": integrator,
        **dict(case.params),
    }
    period = 2.0 * math.pi / case.Omega
    n_per_period = max(1, round(period / case.h))
    inst = Instance(model, params, case.Omega, n_per_period)
    vrs = [model.vr[n] for n in ENERGY_OUTPUTS]
    out = EnergyRun(case, integrator, [], [], [], [], None, "")
    try:
        try:
            for _ in range(case.kick_periods * n_per_period):
                inst.step()
        except FmuError as e:
            out.discarded_at = inst.time
            out.message = f"during the kick: {e}"
            return out
        inst.slave.setReal([model.vr["F"]], [0.0])
        for k in range(steps + 1):
            if k % every == 0 or k == steps:
                e_kin, e_strain, err, w = inst.slave.getReal(vrs)
                out.times.append(inst.time)
                out.energy.append(e_kin + e_strain)
                out.energy_error.append(err)
                out.w_mid.append(w)
            if k < steps:
                try:
                    inst.step()
                except FmuError as e:
                    out.discarded_at = inst.time
                    out.message = str(e)
                    break
    finally:
        inst.close()
    return out


def write_csv(run: EnergyRun, path: Path) -> None:
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
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
            ax.set_xlabel("time [s]" if "time" in cols else "step")
            ax.set_ylabel("(E - E0) / E0")
            ax.set_title(label)
            ax.grid(True, alpha=0.3)
            if len(x) and x[-1] < max(x):
                pass
            ax.text(
                0.01,
                0.02,
                f"{len(x)} samples, last t = {x[-1]:.4g}" if x else "",
                transform=ax.transAxes,
                fontsize=7,
            )
            fig.suptitle(f"{stem}: {comment[:150]}", fontsize=8)
        fig.tight_layout()
        path = out_dir / f"{stem}.png"
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        prog="python -m georod_tools.stability",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    sub = ap.add_subparsers(dest="cmd", required=True)
    f = sub.add_parser("fmu", help="FMU energy runs, integrator 1 vs 2 -> CSV")
    f.add_argument(
        "--fmu-dir", type=Path, default=Path("target/fmu"), help="folder of the FMUs (target/fmu)"
    )
    f.add_argument("--out", type=Path, required=True, help="CSV folder")
    f.add_argument(
        "--steps",
        type=positive_int,
        default=100_000,
        help="free-vibration communication steps, >= 1 (100000)",
    )
    f.add_argument(
        "--every", type=positive_int, default=20, help="steps between CSV rows, >= 1 (20)"
    )
    names = [c.name for c in CASES]
    f.add_argument("--cases", nargs="*", choices=names, default=names, help="cases to run (all)")
    p = sub.add_parser("plot", help="CSV pairs -> PNG")
    p.add_argument("--csv", type=Path, required=True, help="folder of the CSV pairs")
    p.add_argument("--out", type=Path, required=True, help="PNG folder")
    args = ap.parse_args(argv)
    if args.cmd == "fmu":
        for case in (c for c in CASES if c.name in args.cases):
            for integrator in (1, 2):
                run = run_energy(args.fmu_dir, case, integrator, args.steps, args.every)
                final = run.energy_error[-1] if run.energy_error else math.nan
                write_csv(run, args.out / f"stability_fmu_{case.name}_int{integrator}.csv")
                print(
                    f"{case.name:<12} integrator {integrator}: {len(run.times)} samples, "
                    f"max |dE|/E0 = {run.max_rel_drift():.3e}, "
                    f"final energy_error = {final:.3e}"
                    + (
                        f", DISCARDED at t = {run.discarded_at:.6g}"
                        if run.discarded_at is not None
                        else ""
                    )
                )
    else:
        for path in plot_pairs(args.csv, args.out):
            print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
