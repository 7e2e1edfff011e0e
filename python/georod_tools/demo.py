"""The Python half of ``scripts/demo``: the BuckledBeam FMU seen from a host.

    python -m georod_tools.demo [--out DIR] [--transient N] [--periods N]

1. ``fmpy.simulate_fmu`` on the default BuckledBeam FMU with its default experiment: writes
   ``DIR/demo_buckled_beam.png`` (w_mid over time) and prints the static w_mid and the range of
   motion.
2. Poincaré sections of a chaotic case (F = 1.5) and a periodic one (F = 0.4) at Omega = 3500
   (paper, Figure 2e and 2a), short but honest runs (150 transient + 150 sampled periods by
   default): ``DIR/demo_poincare_F<F>.png`` (section, phase portrait, time plot), with the
   classification and the largest Lyapunov exponent printed.

Takes about 10 s on one core.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from georod_tools import fmu_path
from georod_tools.argtypes import int_range, nonnegative_int

#: The two sections of the demo: (F, Omega, what the paper shows there).
SECTION_CASES: tuple[tuple[float, float, str], ...] = (
    (1.5, 3500.0, "paper Fig. 2e: globally chaotic"),
    (0.4, 3500.0, "paper Fig. 2a: small periodic orbit in one well"),
)


@dataclass(frozen=True)
class Summary:
    """What the default experiment shows: the static state and the range of the motion."""

    t_end: float
    static_w_mid: float
    w_min: float
    w_max: float
    v_max: float
    crosses_zero: bool

    def text(self) -> str:
        where = "visits both wells" if self.crosses_zero else "stays in its initial well"
        return (
            f"default experiment, 0..{self.t_end:g} s: static w_mid = {self.static_w_mid:.4f}, "
            f"w_mid in [{self.w_min:.4f}, {self.w_max:.4f}] (range {self.w_max - self.w_min:.4f}), "
            f"|v_mid| <= {self.v_max:.1f}; the midspan {where}"
        )


def summarize(result: np.ndarray) -> Summary:
    """Summary of a ``simulate_fmu`` result with fields ``time``, ``w_mid`` and ``v_mid``."""
    if len(result) == 0:
        raise ValueError("empty simulation result")
    w = np.asarray(result["w_mid"], dtype=float)
    v = np.asarray(result["v_mid"], dtype=float)
    return Summary(
        t_end=float(result["time"][-1]),
        static_w_mid=float(w[0]),
        w_min=float(w.min()),
        w_max=float(w.max()),
        v_max=float(np.abs(v).max()),
        crosses_zero=bool(w.min() < 0.0 < w.max()),
    )


def simulate_default(fmu: Path) -> np.ndarray:
    """The default experiment of `fmu` through ``fmpy.simulate_fmu``."""
    from fmpy import simulate_fmu

    return simulate_fmu(str(fmu), output=["w_mid", "v_mid", "E_kin", "E_strain"])


def plot_time_series(result: np.ndarray, summary: Summary, path: Path) -> Path:
    from georod_tools.plots import plt

    path.parent.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(8, 3.6), constrained_layout=True)
    ax.plot(result["time"], result["w_mid"], lw=0.8)
    ax.axhline(summary.static_w_mid, color="0.6", lw=0.6, ls="--", label="static w_mid")
    ax.set(xlabel="t [s]", ylabel="w_mid", title="BuckledBeam FMU, default experiment (fmpy)")
    ax.legend(loc="upper right", fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def section_case(fmu: Path, F: float, Omega: float, transient: int, periods: int, out: Path):  # noqa: ANN201
    """Runs one case and draws its three-panel figure; returns (result, png path)."""
    from georod_tools.plots import plot_case
    from georod_tools.runner import CaseConfig, run_case

    cfg = CaseConfig(
        fmu=str(fmu),
        F=F,
        Omega=Omega,
        transient_periods=transient,
        sample_periods=periods,
        n_per_period=40,
        dense_periods=min(20, periods),
        lyapunov_discard=min(10, periods - 1),
    )
    result = run_case(cfg)
    return result, plot_case(result, out / f"demo_poincare_F{F:g}.png")


def run_demo(out: Path, transient: int = 150, periods: int = 150, fmu: Path | None = None) -> int:
    fmu = fmu or fmu_path("BuckledBeam")
    if not fmu.is_file():
        print(f"demo: {fmu} not found; run scripts/build_fmus first", file=sys.stderr)
        return 1
    t0 = time.perf_counter()
    res = simulate_default(fmu)
    summary = summarize(res)
    print(summary.text())
    print(f"wrote {plot_time_series(res, summary, out / 'demo_buckled_beam.png')}")
    for F, Omega, paper in SECTION_CASES:
        r, png = section_case(fmu, F, Omega, transient, periods, out)
        ly = r.lyapunov
        lam = f"{ly.per_period:.3f} +- {ly.stderr:.3f} per period" if ly else "n/a"
        print(
            f"F = {F:g}, Omega = {Omega:g} ({transient} + {periods} periods): "
            f"{r.classification.label}, largest Lyapunov exponent {lam}  [{paper}]"
        )
        print(f"wrote {png}")
    print(f"demo done in {time.perf_counter() - t0:.1f} s")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m georod_tools.demo", description=__doc__)
    p.add_argument("--out", type=Path, default=Path("out"), help="output folder (out)")
    p.add_argument(
        "--transient", type=nonnegative_int, default=150, help="transient periods, >= 0 (150)"
    )
    p.add_argument("--periods", type=int_range(2), default=150, help="sampled periods, >= 2 (150)")
    p.add_argument("--fmu", type=Path, help="BuckledBeam FMU (target/fmu/BuckledBeam.fmu)")
    a = p.parse_args(argv)
    if a.transient < 0 or a.periods < 2:
        p.error("--transient must be >= 0 and --periods >= 2")
    return run_demo(a.out, a.transient, a.periods, a.fmu)


if __name__ == "__main__":
    sys.exit(main())
