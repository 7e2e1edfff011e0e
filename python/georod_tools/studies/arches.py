"""Shallow arches (paper section 6.2): the static crown-load diagram (Figures 6, 10), the
zero-load equilibria and their natural frequencies (from the core's ``georod path`` / ``modes``),
the start in the inverted equilibrium z3 through FMU variables only, and the figures of the forced
dynamics. The study itself: :mod:`.arches_study`.

Starting in z3 (:data:`Z3_PRELUDE`): the FMU starts in z1 (the unloaded arch). With the forcing off,
the crown is pushed down by the input ``f_ctrl``, ramped to 15 (beyond the snap-through limit
load 11.31 of the default PinnedArch) over 10 periods; held 20 periods (the snap's motion dies
down); released to 0 over 40 periods (the arch follows the inverted branch back quasi-statically:
the snap-back load is -10.14, never reached); and left 80 periods to settle under its damping.
It ends in z3 to the digits of the static solution (w_mid -3.99334692, velocity ~1e-5 m/s,
kinetic energy 1e-14 of the strain energy); the forcing then starts at that period boundary.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from georod_tools.analysis.case import CaseResult
from georod_tools.analysis.prelude import Prelude
from georod_tools.fmu import core_command
from georod_tools.report.figures import plt, poincare_axes, save
from georod_tools.report.labels import label

#: From z1 into z3 through the crown force input (see the module documentation).
Z3_PRELUDE = Prelude("f_ctrl", peak=15.0, rise=10, hold=20, release=40, settle=80)


@dataclass
class StaticDiagram:
    """The crown-load path: ``load``, ``w_mid``, ``negative`` per point (path order), the refined
    critical points ``(kind, load, w_mid, before, after)`` and the zero-load equilibria
    ``(name, w_mid, negative)``."""

    scene: str
    load: np.ndarray
    w_mid: np.ndarray
    negative: np.ndarray
    critical: list[tuple[str, float, float, int, int]]
    equilibria: list[tuple[str, float, int]]
    csv: str


def static_diagram(
    scene: str,
    overrides: dict[str, float] | None = None,
    max_load: float = 60.0,
    imperfection: float = 0.0,
) -> StaticDiagram:
    """Traces the static path with ``georod path`` and parses it."""
    text = core_command.static_path(scene, overrides, max_load, imperfection)
    rows, critical, equilibria = [], [], []
    for line in text.splitlines()[1:]:
        if line.startswith("# critical,"):
            _, kind, p, w, a, b = line[2:].split(",")
            critical.append((kind, float(p), float(w), int(a), int(b)))
        elif line.startswith("# equilibrium,"):
            _, name, _p, w, n = line[2:].split(",")
            equilibria.append((name, float(w), int(n)))
        elif not line.startswith("#"):
            p, w, _s, n = line.split(",")
            rows.append((float(p), float(w), int(n)))
    a = np.asarray(rows, dtype=float)
    return StaticDiagram(scene, a[:, 0], a[:, 1], a[:, 2].astype(int), critical, equilibria, text)


def plot_static(d: StaticDiagram, path: str | Path, extra: StaticDiagram | None = None) -> Path:
    """Load against crown deflection: stable solid, unstable dashed, critical points and the
    zero-load equilibria marked (`extra`: e.g. the imperfect path, drawn thin)."""
    fig, ax = plt.subplots(figsize=(6.4, 4.6), constrained_layout=True)
    if extra is not None:
        ax.plot(
            extra.w_mid,
            extra.load,
            "-",
            lw=0.8,
            color="tab:orange",
            label="with asymmetric imperfection",
        )
    stable = d.negative == 0
    start = 0
    for i in range(1, len(stable) + 1):
        if i == len(stable) or stable[i] != stable[start]:
            seg = slice(start, min(i + 1, len(stable)))
            ax.plot(d.w_mid[seg], d.load[seg], "-" if stable[start] else "--", color="k", lw=1.4)
            start = i
    ax.plot([], [], "-", color="k", label="stable")
    ax.plot([], [], "--", color="k", label="unstable")
    for kind, p, w, *_ in d.critical:
        marker = "o" if kind == "LimitPoint" else "s"
        ax.plot(w, p, marker, mfc="none", color="tab:red", ms=7)
        ax.annotate(
            f"{'limit' if marker == 'o' else 'bif.'} {p:.2f}",
            (w, p),
            textcoords="offset points",
            xytext=(6, 4),
            fontsize=8,
            color="tab:red",
        )
    for name, w, n in d.equilibria:
        ax.plot(w, 0.0, "o", color="tab:blue" if n == 0 else "white", mec="tab:blue", ms=7)
        ax.annotate(name, (w, 0.0), textcoords="offset points", xytext=(-4, -14), fontsize=9)
    ax.axhline(0.0, color="0.7", lw=0.6)
    ax.set(
        xlabel="crown deflection w_mid [m] (along e2)",
        ylabel="crown load P [N] (along -e2)",
        title=f"{d.scene}: static crown-load path",
    )
    ax.legend(fontsize=8, loc="best")
    return save(fig, path)


def modes_table(scene: str, overrides: dict[str, float] | None = None, count: int = 4) -> str:
    """``georod modes``' CSV: the lowest `count` frequencies about every zero-load equilibrium."""
    args = ["modes", "--scene", scene, "--count", str(count)]
    return core_command.georod(*args, *core_command.set_options(overrides))


def lowest_frequency(scene: str, overrides: dict[str, float] | None = None) -> float:
    """Lowest angular frequency (rad/s) about z1."""
    for m in core_command.modes(scene, overrides, count=1):
        if m.equilibrium == "z1":
            return m.omega
    raise RuntimeError(f"{scene}: georod modes reports no z1")


def poincare_grid(
    results: list[CaseResult], titles: list[str], path: str | Path, ncols: int = 4
) -> Path:
    """Poincaré sections of several cases side by side."""
    nrows = math.ceil(len(results) / ncols)
    fig, axes = plt.subplots(
        nrows, ncols, figsize=(3.2 * ncols, 3.0 * nrows), constrained_layout=True, squeeze=False
    )
    for ax in axes.flat[len(results) :]:
        ax.axis("off")
    for ax, r, t in zip(axes.flat, results, titles, strict=False):
        title = f"{t}\n{r.classification.label}, λ={r.exponent_per_period:.2f}"
        poincare_axes(ax, r.samples, r.size, r.config.fmu, title, small=True)
    return save(fig, path, dpi=80)


# --------------------------------------------------------------------------------------------
# ClampedArch: the modulated (quasi-periodic) motion of the paper's Figure 11 and the doubling
# of its ring (Figure 12), found by the scan documented in docs/arches.md section 4.

CLAMPED_RING = {"Omega": 2000.0, "F": 112.0, "d": 1e-4}
"""Figure 11 analogue: a ring in the Poincaré section (Neimark-Sacker window F = 110..113 at
Omega = 2000, d = 1e-4; period-1 at F = 115, the ring breaks up below F = 110)."""

CLAMPED_DOUBLING_OMEGA = 1950.0
CLAMPED_DOUBLING_FORCES = (99.0, 101.0, 102.0, 105.0)
"""Figure 12 analogue at Omega = 1950, d = 1e-4: ring (99), ring wound twice (101), break-up
(102, exponent ~0.01), chaotic modulated motion (105)."""


def rotation_number(samples: np.ndarray) -> float:
    """Mean fraction of a turn per forcing period of the section points about their centroid
    (coordinates scaled by their ranges); meaningful for a ring that encloses its centroid."""
    s = np.asarray(samples, dtype=float)
    z = (s[:, 0] - s[:, 0].mean()) / np.ptp(s[:, 0]) + 1j * (s[:, 1] - s[:, 1].mean()) / np.ptp(
        s[:, 1]
    )
    a = np.unwrap(np.angle(z))
    return float(abs(a[-1] - a[0]) / (len(a) - 1) / (2.0 * math.pi))


def plot_clamped_ring(r: CaseResult, path: str | Path, zoom_periods: int = 16) -> Path:
    """Figure 11 analogue: Poincaré section (the ring); w_mid(t) over the last `zoom_periods`
    periods with the stroboscopic points; the stroboscopic w_mid(kT) over all sampled periods
    (the modulation); phase portrait over the dense periods."""
    fig, (ax_p, ax_t, ax_k, ax_ph) = plt.subplots(1, 4, figsize=(19, 4.4), constrained_layout=True)
    s, fmu = r.samples, r.config.fmu
    period = r.config.period
    poincare_axes(ax_p, s, r.size, fmu, f"Poincaré section (t = kT), {len(s)} periods")
    ax_k.plot(np.rint(r.sample_times / period), s[:, 0], ".-", ms=3, lw=0.4, color="tab:red")
    ax_k.ticklabel_format(useOffset=False)
    ax_k.set(title="modulation: w_mid(kT)", xlabel="period k [1]", ylabel=label("w_mid", fmu))
    if r.dense is not None and r.dense.shape[0] > 1:
        d = r.dense
        last = d[d[:, 0] >= d[-1, 0] - zoom_periods * period - 1e-12]
        in_zoom = r.sample_times >= last[0, 0] - 1e-12
        ax_t.plot(last[:, 0], last[:, 1], "-", lw=0.8, color="tab:blue")
        ax_t.plot(r.sample_times[in_zoom], s[in_zoom, 0], ".", ms=5, color="tab:red")
        in_window = r.sample_times >= d[0, 0] - 1e-12
        ax_ph.plot(d[:, 1], d[:, 2], "-", lw=0.4, color="tab:blue")
        ax_ph.plot(s[in_window, 0], s[in_window, 1], ".", ms=4, color="tab:red")
    ax_t.set(
        title=f"w_mid(t), last {zoom_periods} periods (red: t = kT)",
        xlabel=label("t"),
        ylabel=label("w_mid", fmu),
    )
    ax_ph.set(
        title="phase portrait (red: t = kT)", xlabel=label("w_mid", fmu), ylabel=label("v_mid", fmu)
    )
    for ax in (ax_t, ax_ph):
        ax.ticklabel_format(useOffset=False)
    c = r.config
    fig.suptitle(
        f"ClampedArch, Omega = {c.Omega:g}, F = {c.F:g}, {dict(c.params)}: "
        f"{r.classification.label}, λ = {r.exponent_per_period:.4f}/period, "
        f"dimension {r.classification.dimension:.2f}, rotation number {rotation_number(s):.3f}"
    )
    return save(fig, path, dpi=90)


def plot_ring_doubling(results: list[CaseResult], path: str | Path) -> Path:
    """Figure 12 analogue: Poincaré sections along F, consecutive samples in alternating colours
    (a ring wound twice is one curve: both colours lie on it)."""
    fig, axes = plt.subplots(
        1, len(results), figsize=(3.6 * len(results), 3.5), constrained_layout=True, squeeze=False
    )
    for ax, r in zip(axes.flat, results, strict=True):
        title = (
            f"Omega = {r.config.Omega:g}, F = {r.config.F:g}\n{r.classification.label}, "
            f"λ = {r.exponent_per_period:.3f}, dim {r.classification.dimension:.2f}"
        )
        poincare_axes(ax, r.samples, r.size, r.config.fmu, title, small=True)
        s = r.samples
        ax.plot(s[1::2, 0], s[1::2, 1], ".", ms=2, color="tab:orange")
    return save(fig, path, dpi=90)
