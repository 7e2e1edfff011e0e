"""Figures and CSV files of the analyses (matplotlib, Agg backend: no display needed).

- :func:`plot_case`: one figure per case as in the paper's section 6.1: Poincaré section,
  phase portrait (w_mid, v_mid) with the section points on it, displacement-time diagram.
- :func:`plot_sweep`: bifurcation diagram (stroboscopic w_mid against the swept parameter) with
  the largest Lyapunov exponent beneath it, failed cases marked by red bands.
- :func:`write_case_csv` / :func:`write_sweep_csv`: the numbers behind the figures.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 - the backend must be chosen first
from matplotlib.axes import Axes  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from georod_tools.failure import CaseFailure  # noqa: E402
from georod_tools.runner import CaseResult  # noqa: E402


def case_title(result: CaseResult) -> str:
    """``F = 0.7, Omega = 3500: chaotic (lambda = 0.60 / period)``."""
    cfg = result.config
    text = f"F = {cfg.F:g}, Omega = {cfg.Omega:g}: {result.classification.label}"
    if result.lyapunov is not None:
        text += f"  (lambda = {result.exponent_per_period:.3f} / period)"
    return text


def plot_case(result: CaseResult, path: str | Path) -> Path:
    """Writes the three-panel figure of one case to `path` (PNG)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    ax_p, ax_ph, ax_t = axes
    s = result.samples
    ax_p.plot(s[:, 0], s[:, 1], ".", ms=3, color="k")
    ax_p.set(title="Poincaré section (t = k T)", xlabel="w_mid", ylabel="v_mid")
    if result.dense is not None and result.dense.shape[0] > 1:
        d = result.dense
        ax_ph.plot(d[:, 1], d[:, 2], "-", lw=0.5, color="tab:blue")
        t0 = d[0, 0]
        in_window = result.sample_times >= t0 - 1e-12
        ax_ph.plot(s[in_window, 0], s[in_window, 1], ".", ms=4, color="tab:red")
        ax_t.plot(d[:, 0], d[:, 1], "-", lw=0.6, color="tab:blue")
    else:
        for ax in (ax_ph, ax_t):
            ax.text(0.5, 0.5, "no dense trajectory recorded", ha="center", transform=ax.transAxes)
    ax_ph.set(title="phase portrait", xlabel="w_mid", ylabel="v_mid")
    ax_t.set(title="displacement-time diagram", xlabel="t", ylabel="w_mid")
    fig.suptitle(case_title(result))
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_case_csv(result: CaseResult, path: str | Path) -> Path:
    """The stroboscopic samples: columns k (period index), t, w_mid, v_mid."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    period = result.config.period
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["k", "t", "w_mid", "v_mid"])
        for t, (wm, vm) in zip(result.sample_times, result.samples, strict=True):
            w.writerow([round(t / period), repr(float(t)), repr(float(wm)), repr(float(vm))])
    return path


def write_dense_csv(result: CaseResult, path: str | Path) -> Path | None:
    """The dense trajectory (t, w_mid, v_mid), if recorded."""
    if result.dense is None:
        return None
    path = Path(path)
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t", "w_mid", "v_mid"])
        for row in result.dense:
            w.writerow([repr(float(x)) for x in row])
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
    for r in results:
        x = sweep_value(r, param)
        ax_b.plot([x] * len(r.samples), r.samples[:, 0], ".", ms=1.5, mew=0, color="k")
    title = f"bifurcation diagram over {param}"
    if failures:
        title += f" ({len(failures)} failed case{'s' if len(failures) > 1 else ''})"
    ax_b.set(ylabel="w_mid at t = k T", title=title)
    xs = [sweep_value(r, param) for r in results]
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
    ax_l.set(xlabel=param, ylabel="largest Lyapunov exp. / period")
    return fig


def _mark_failures(
    axes: Sequence[Axes], xs: Sequence[float], failures: Sequence[CaseFailure]
) -> None:
    """A red band half a value spacing wide (a line when there is no spacing) at each failure."""
    gaps = [b - a for a, b in zip(xs, xs[1:], strict=False) if b > a]
    half = 0.25 * min(gaps) if gaps else 0.0
    for i, f in enumerate(failures):
        for ax in axes:
            label = "failed case" if i == 0 and ax is axes[0] else None
            if half > 0:
                ax.axvspan(
                    f.value - half, f.value + half, color="tab:red", alpha=0.3, lw=0, label=label
                )
            else:
                ax.axvline(f.value, color="tab:red", alpha=0.6, lw=2, label=label)


def plot_sweep(
    param: str,
    results: Sequence[CaseResult],
    path: str | Path,
    chaos_threshold: float | None = None,
    failures: Sequence[CaseFailure] = (),
) -> Path:
    """Writes :func:`sweep_figure` to `path` (PNG)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig = sweep_figure(param, results, chaos_threshold, failures)
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def sweep_value(result: CaseResult, param: str) -> float:
    """The value of the swept parameter in `result`'s config."""
    cfg = result.config
    if param in ("F", "Omega", "dt_max", "elements"):
        return float(getattr(cfg, param))
    return float(dict(cfg.params)[param])


def write_sweep_csv(
    param: str,
    results: Sequence[CaseResult],
    path: str | Path,
    failures: Sequence[CaseFailure] = (),
    wall_time: bool = True,
) -> tuple[Path, Path]:
    """Two files: `path` with one row per case sorted by value (value, class, period, exponents,
    wall time unless `wall_time` is False, and the reason of a failed case, whose class is
    ``failed``) and `<stem>_samples.csv` with every stroboscopic sample (value, k, w_mid, v_mid).
    Without the wall time the table depends only on the cases (deterministic)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    samples_path = path.with_name(path.stem + "_samples.csv")
    header = [
        param,
        "class",
        "period",
        "lyapunov_per_period",
        "lyapunov_per_second",
        "lyapunov_stderr",
        "correlation_dimension",
    ]
    rows: list[tuple[float, list[object]]] = []
    for r in results:
        c = r.classification
        x = sweep_value(r, param)
        row: list[object] = [
            repr(x),
            c.kind,
            c.period or "",
            repr(r.exponent_per_period),
            repr(r.exponent_per_second),
            repr(r.lyapunov.stderr if r.lyapunov else math.nan),
            repr(c.dimension),
        ]
        rows.append((x, [*row, *([f"{r.wall_time:.3f}"] if wall_time else []), ""]))
    for fl in failures:
        row = [repr(fl.value), "failed", "", "", "", "", ""]
        rows.append((fl.value, [*row, *([""] if wall_time else []), f"{fl.kind}: {fl.reason}"]))
    rows.sort(key=lambda t: t[0])
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow([*header, *(["wall_time_s"] if wall_time else []), "failure"])
        w.writerows(row for _, row in rows)
    with samples_path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow([param, "k", "w_mid", "v_mid"])
        for r in results:
            x = repr(sweep_value(r, param))
            for t, (wm, vm) in zip(r.sample_times, r.samples, strict=True):
                w.writerow([x, round(t / r.config.period), repr(float(wm)), repr(float(vm))])
    return path, samples_path
