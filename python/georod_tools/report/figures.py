"""Figures of the analyses (matplotlib, Agg backend: no display needed).

- :func:`plot_case`: one figure per case as in the paper's section 6.1: Poincaré section,
  phase portrait (w_mid, v_mid) with the section points on it, displacement-time diagram.
- :func:`plot_sweep`: bifurcation diagram (stroboscopic w_mid against the swept parameter) with
  the largest Lyapunov exponent beneath it, failed cases marked by red bands.
- :func:`poincare_axes`: a Poincaré section that a reader can read: a periodic orbit's few points
  shown on the scale of the orbit's swing (not zoomed in to the round-off between its repeats),
  no offset notation, labels with units.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 - the backend must be chosen first
import numpy as np  # noqa: E402
from matplotlib.axes import Axes  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from georod_tools.analysis.case import CaseResult  # noqa: E402
from georod_tools.analysis.failure import CaseFailure  # noqa: E402
from georod_tools.report.labels import label  # noqa: E402

#: A coordinate of a section whose points spread less than this fraction of the orbit's swing is
#: shown on the scale of the swing: a finite set of points, not a cloud.
POINT_SET = 1e-3


def case_title(result: CaseResult) -> str:
    """``F = 0.7, Omega = 3500: chaotic (lambda = 0.60 / period)`` (unforced: ``T = 0.01 s``)."""
    cfg = result.config
    what = f"F = {cfg.F:g}, Omega = {cfg.Omega:g}" if cfg.forced else f"T = {cfg.period:g} s"
    text = f"{what}: {result.classification.label}"
    if result.lyapunov is not None:
        text += f"  (lambda = {result.exponent_per_period:.3f} / period)"
    return text


def poincare_axes(
    ax: Axes,
    samples: np.ndarray,
    size: np.ndarray,
    fmu: str | None = None,
    title: str = "",
    small: bool = False,
    color: str = "k",
    names: tuple[str, str] = ("w_mid", "v_mid"),
) -> None:
    """The section points (displacement, velocity: their output `names`) on `ax`. A coordinate
    in which the points spread less than :data:`POINT_SET` of the swing `size` is centred on them
    with the width of the swing, so a period-1 point is a point and a period-k orbit shows its k
    points apart."""
    s = np.asarray(samples, dtype=float)
    ax.plot(s[:, 0], s[:, 1], ".", ms=2.5 if len(s) > 50 else 5, color="k")
    ax.margins(0.08)  # points of a period-k orbit are not drawn on the frame
    for setter, centre, spread, swing in zip(
        (ax.set_xlim, ax.set_ylim), s.mean(axis=0), np.ptp(s, axis=0), size, strict=True
    ):
        if swing > 0 and spread < POINT_SET * swing:
            setter(centre - 0.5 * swing, centre + 0.5 * swing)
    ax.ticklabel_format(useOffset=False)
    fs = 7 if small else None
    ax.set_xlabel(label(names[0], fmu), fontsize=fs)
    ax.set_ylabel(label(names[1], fmu), fontsize=fs)
    if small:
        ax.tick_params(labelsize=7)
        ax.xaxis.set_major_locator(MaxNLocator(4))  # readable tick labels in a narrow panel
    if title:
        ax.set_title(title, fontsize=8 if small else None, color=color)


def plot_case(result: CaseResult, path: str | Path) -> Path:
    """Writes the three-panel figure of one case to `path` (PNG)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fmu = result.config.fmu
    names = (result.config.sensor, result.config.velocity_name)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    ax_p, ax_ph, ax_t = axes
    s = result.samples
    title = f"Poincaré section (t = k T), {len(s)} periods"
    poincare_axes(ax_p, s, result.size, fmu, title, names=names)
    if result.dense is not None and result.dense.shape[0] > 1:
        d = result.dense
        ax_ph.plot(d[:, 1], d[:, 2], "-", lw=0.5, color="tab:blue")
        in_window = result.sample_times >= d[0, 0] - 1e-12
        ax_ph.plot(s[in_window, 0], s[in_window, 1], ".", ms=4, color="tab:red")
        ax_t.plot(d[:, 0], d[:, 1], "-", lw=0.6, color="tab:blue")
        ax_t.plot(result.sample_times[in_window], s[in_window, 0], ".", ms=4, color="tab:red")
    else:
        for ax in (ax_ph, ax_t):
            ax.text(0.5, 0.5, "no dense trajectory recorded", ha="center", transform=ax.transAxes)
    ax_ph.set(title="phase portrait (red: t = k T)", xlabel=label(names[0], fmu))
    ax_ph.set_ylabel(label(names[1], fmu))
    ax_t.set(title="displacement-time diagram", xlabel=label("t"), ylabel=label(names[0], fmu))
    for ax in (ax_ph, ax_t):
        ax.ticklabel_format(useOffset=False)
    fig.suptitle(case_title(result))
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def sweep_figure(
    param: str,
    results: Sequence[CaseResult],
    chaos_threshold: float | None = None,
    failures: Sequence[CaseFailure] = (),
) -> Figure:
    """The bifurcation diagram (stroboscopic w_mid against `param`) with the exponent beneath;
    each failed case is a red band at its value on both panels ("failed case" in the legend)."""
    fig, (ax_b, ax_l) = plt.subplots(
        2, 1, figsize=(10, 7), sharex=True, height_ratios=(3, 1.3), constrained_layout=True
    )
    fmu = results[0].config.fmu if results else None
    sensor = results[0].config.sensor if results else "w_mid"
    if results:
        # One artist for all cases (one per case draws several times slower).
        xs_all = np.concatenate([np.full(len(r.samples), r.config.value(param)) for r in results])
        ys_all = np.concatenate([r.samples[:, 0] for r in results])
        ax_b.plot(xs_all, ys_all, ".", ms=1.5, mew=0, color="k")
    title = f"bifurcation diagram over {param}"
    if failures:
        title += f" ({len(failures)} failed case{'s' if len(failures) > 1 else ''})"
    ax_b.set(ylabel=label(sensor, fmu, "stroboscopic") + " at t = k T", title=title)
    xs = [r.config.value(param) for r in results]
    lam = [r.exponent_per_period for r in results]
    if any(math.isfinite(v) for v in lam):
        ax_l.plot(xs, lam, ".-", ms=3, lw=0.7, color="tab:blue")
        ax_l.axhline(0.0, color="0.6", lw=0.6)
        if chaos_threshold is not None:
            ax_l.axhline(chaos_threshold, color="tab:red", lw=0.6, ls="--", label="chaos threshold")
    _mark_failures((ax_b, ax_l), sorted(xs + [f.value for f in failures]), failures)
    for ax in (ax_b, ax_l):
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper right", fontsize=8)
    ax_l.set(xlabel=label(param, fmu), ylabel="largest Lyapunov exp. [1/period]")
    return fig


def _mark_failures(
    axes: Sequence[Axes], xs: Sequence[float], failures: Sequence[CaseFailure]
) -> None:
    """A red band half a value spacing wide (a line when there is no spacing) at each failure."""
    gaps = [b - a for a, b in zip(xs, xs[1:], strict=False) if b > a]
    half = 0.25 * min(gaps) if gaps else 0.0
    for i, f in enumerate(failures):
        for ax in axes:
            name = "failed case" if i == 0 and ax is axes[0] else None
            if half > 0:
                ax.axvspan(
                    f.value - half, f.value + half, color="tab:red", alpha=0.3, lw=0, label=name
                )
            else:
                ax.axvline(f.value, color="tab:red", alpha=0.6, lw=2, label=name)


def plot_sweep(
    param: str,
    results: Sequence[CaseResult],
    path: str | Path,
    chaos_threshold: float | None = None,
    failures: Sequence[CaseFailure] = (),
) -> Path:
    """Writes :func:`sweep_figure` to `path` (PNG)."""
    fig = sweep_figure(param, results, chaos_threshold, failures)
    return save(fig, path, dpi=130)


def save(fig: Figure, path: str | Path, dpi: int = 100, shrink: bool = False) -> Path:
    """Saves and closes `fig`; with `shrink`, re-encodes a large PNG as a palette image."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return shrink_png(path) if shrink else path


def shrink_png(path: Path, limit: int = 200_000) -> Path:
    """Re-encodes a PNG as a 256-colour palette image when it exceeds `limit` bytes."""
    if path.stat().st_size <= limit:
        return path
    from PIL import Image

    with Image.open(path) as im:
        im.convert("RGB").quantize(colors=256).save(path, optimize=True)
    return path
