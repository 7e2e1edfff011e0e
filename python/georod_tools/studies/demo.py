"""The Python half of ``scripts/demo``: the BuckledBeam FMU seen from a host
(``georod-tools demo``).

1. ``fmpy.simulate_fmu`` on the default BuckledBeam FMU with its default experiment: writes
   ``demo_buckled_beam.png`` (w_mid over time) and prints the static w_mid and the range of
   motion.
2. Poincaré sections of a chaotic case (F = 1.5) and a periodic one (F = 0.4) at Omega = 3500
   (paper, Figure 2e and 2a), short but honest runs (150 transient + 150 sampled periods by
   default): ``demo_poincare_F<F>.png`` (section, phase portrait, time plot), with the
   classification and the largest Lyapunov exponent (the core's) printed.
3. ``summary.txt``: what was printed.

Takes a few seconds on one core.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from georod_tools.analysis.case import CaseConfig, CaseResult, run_case
from georod_tools.report.figures import plot_case, plt
from georod_tools.report.labels import label

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


def plot_time_series(result: np.ndarray, summary: Summary, path: Path, fmu: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(8, 3.6), constrained_layout=True)
    ax.plot(result["time"], result["w_mid"], lw=0.8)
    ax.axhline(summary.static_w_mid, color="0.6", lw=0.6, ls="--", label="static w_mid")
    ax.set(
        xlabel=label("t"),
        ylabel=label("w_mid", fmu, "midspan deflection"),
        title="BuckledBeam FMU, default experiment (fmpy)",
    )
    ax.legend(loc="upper right", fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def section_case(
    fmu: Path, F: float, Omega: float, transient: int, periods: int, out: Path
) -> tuple[CaseResult, Path]:
    """Runs one case and draws its three-panel figure; returns (result, png path)."""
    cfg = CaseConfig(
        fmu=str(fmu),
        F=F,
        Omega=Omega,
        transient_periods=transient,
        sample_periods=periods,
        dense_periods=min(20, periods),
        align_periods=min(10, periods - 1),
    )
    result = run_case(cfg)
    return result, plot_case(result, out / f"demo_poincare_F{F:g}.png")


def run_demo(
    out: Path, fmu: Path, transient: int = 150, periods: int = 150, say: Callable = print
) -> list[Path]:
    """The demo into the folder `out`; returns the files written (summary.txt last)."""
    t0 = time.perf_counter()
    lines: list[str] = []

    def tell(text: str) -> None:
        lines.append(text)
        say(text)

    res = simulate_default(fmu)
    summary = summarize(res)
    tell(summary.text())
    files = [plot_time_series(res, summary, out / "demo_buckled_beam.png", fmu)]
    for F, Omega, paper in SECTION_CASES:
        r, png = section_case(fmu, F, Omega, transient, periods, out)
        ly = r.lyapunov
        lam = f"{ly.per_period:.3f} +- {ly.stderr:.3f} per period" if ly else "n/a"
        tell(
            f"F = {F:g}, Omega = {Omega:g} ({transient} + {periods} periods): "
            f"{r.classification.label}, largest Lyapunov exponent {lam}  [{paper}]"
        )
        files.append(png)
    tell(f"demo done in {time.perf_counter() - t0:.1f} s")
    summary_path = out / "summary.txt"
    summary_path.write_text("\n".join(lines) + "\n")
    return [*files, summary_path]
