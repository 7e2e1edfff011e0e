"""Figures and tables of the paper study (:mod:`.paper`).

Output folder: ``cases/<case>.png`` (three panels per case), ``overview_fig<N>.png`` (grid of
Poincaré sections per paper figure), ``bifurcation_F.png`` / ``bifurcation_Omega.png``,
``window_<name>.png`` (fine sweeps), ``elements.png``, CSV files (``classifications``,
``convergence``, ``elements``, ``bifurcations``, ``windows``), one markdown fragment per table
(``table_*.md``) and ``study.md`` with all of them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

from georod_tools.analysis.case import CaseResult
from georod_tools.report.figures import (
    plot_case,
    plot_sweep,
    plt,
    poincare_axes,
    save,
    shrink_png,
    sweep_figure,
)
from georod_tools.report.tables import markdown, write_csv, write_text
from georod_tools.studies.paper import Check, StudyReport, StudySettings, agreement, spread, wells
from georod_tools.studies.paper_cases import SWEPT, WINDOWS, PaperCase


def _lam(result: CaseResult) -> str:
    return f"{result.exponent_per_period:.3f}"


def _grid(n: int) -> tuple[object, list]:
    ncols = math.ceil(n / 2)
    fig, axes = plt.subplots(2, ncols, figsize=(3.3 * ncols, 6.6), constrained_layout=True)
    flat = list(axes.flat)
    for ax in flat[n:]:
        ax.set_visible(False)
    return fig, flat


def plot_overview(
    figure: int, cases: Sequence[PaperCase], results: Sequence[CaseResult], path: Path
) -> Path:
    """Grid of the Poincaré sections of one paper figure; red titles where we differ."""
    fig, axes = _grid(len(cases))
    for ax, case, r in zip(axes, cases, results, strict=False):
        title = (
            f"({case.panel}) F={case.F:g}, Omega={case.Omega:g}\n"
            f"ours: {r.classification.label}, lambda={_lam(r)}\npaper: {case.paper_label}"
        )
        color = {"yes": "k", "partly": "tab:orange"}.get(agreement(case, r), "tab:red")
        poincare_axes(ax, r.samples, r.size, r.config.fmu, title, small=True, color=color)
    fig.suptitle(  # type: ignore[attr-defined]
        f"Figure {figure} of the paper: Poincaré sections (t = k T), "
        f"{results[0].config.elements} elements",
        fontsize=10,
    )
    return save(fig, path, shrink=True)  # type: ignore[arg-type]


def plot_elements(results: Sequence[CaseResult], statics: Sequence[float], path: Path) -> Path:
    """Grid of Poincaré sections of the element study."""
    fig, axes = _grid(len(results))
    for ax, r, w0 in zip(axes, results, statics, strict=False):
        title = (
            f"{r.config.elements} elements (static w_mid {w0:.3f} m)\n"
            f"{r.classification.label}, lambda={_lam(r)}"
        )
        poincare_axes(ax, r.samples, r.size, r.config.fmu, title, small=True)
    c = results[0].config
    fig.suptitle(f"Number of elements: F = {c.F:g}, Omega = {c.Omega:g}", fontsize=10)  # type: ignore[attr-defined]
    return save(fig, path, shrink=True)  # type: ignore[arg-type]


# --------------------------------------------------------------------------- tables


def case_row(case: PaperCase, r: CaseResult) -> dict[str, object]:
    """One row of classifications.csv."""
    c, (sw, sv) = r.classification, spread(r)
    return {
        "case": case.name,
        "F": case.F,
        "Omega": case.Omega,
        "paper": case.description,
        "paper_class": case.paper_label,
        "ours": c.label,
        "period": c.period or "",
        "wells": wells(r),
        "lyapunov_per_period": round(r.exponent_per_period, 4),
        "lyapunov_stderr": round(r.lyapunov.stderr, 4) if r.lyapunov else "",
        "samples": len(r.samples),
        "spread_w": f"{sw:.4g}",
        "spread_v": f"{sv:.4g}",
        "agrees": agreement(case, r),
        "elements": r.config.elements,
        "substeps": r.config.substeps,
        "transient": r.config.transient_periods,
        "wall_s": round(r.wall_time, 2),
    }


def check_rows(checks: Sequence[Check]) -> list[dict[str, object]]:
    rows: list[dict[str, object]] = []
    for ch in checks:
        for name, r in {"base": ch.base, **ch.variants}.items():
            rows.append(
                {
                    "case": ch.case.name,
                    "F": ch.case.F,
                    "Omega": ch.case.Omega,
                    "paper": ch.case.paper_label,
                    "variant": name,
                    "ours": r.classification.label,
                    "lyapunov_per_period": round(r.exponent_per_period, 4),
                    "wells": wells(r),
                    "holds": "-" if name == "base" else ("yes" if ch.holds(name) else "NO"),
                    "agrees_with_paper": agreement(ch.case, r),
                }
            )
    return rows


def element_rows(results: Sequence[CaseResult], statics: Sequence[float]) -> list[dict]:
    return [
        {
            "elements": r.config.elements,
            "static_w_mid": f"{w0:.4f}",
            "ours": r.classification.label,
            "lyapunov_per_period": round(r.exponent_per_period, 4),
            "wells": wells(r),
            "spread_w": f"{spread(r)[0]:.4g}",
            "samples": len(r.samples),
        }
        for r, w0 in zip(results, statics, strict=True)
    ]


def label_ranges(param: str, results: Sequence[CaseResult]) -> str:
    """``0.5-0.545: period-1; 0.55: chaotic; ...``: runs of equal classification."""
    runs: list[tuple[float, float, str]] = []
    for r in results:
        x, lab = r.config.value(param), r.classification.label
        if runs and runs[-1][2] == lab:
            runs[-1] = (runs[-1][0], x, lab)
        else:
            runs.append((x, x, lab))
    return "; ".join(f"{a:g}: {lab}" if a == b else f"{a:g}-{b:g}: {lab}" for a, b, lab in runs)


def window_rows(windows: dict[str, list[CaseResult]]) -> list[dict[str, object]]:
    rows: list[dict[str, object]] = []
    for w in WINDOWS:
        if w.name in windows:
            fixed = f"Omega = {w.Omega:g}" if w.param == "F" else f"F = {w.F:g}"
            ours = label_ranges(w.param, windows[w.name])
            rows.append({"window": w.name, "fixed": fixed, "paper": w.paper, "ours": ours})
    return rows


def bifurcation_rows(bif: dict[str, list[CaseResult]]) -> list[dict[str, object]]:
    return [
        {
            "param": p,
            "value": r.config.value(p),
            "ours": r.classification.label,
            "lyapunov_per_period": round(r.exponent_per_period, 4),
            "wells": wells(r),
            "spread_w": f"{spread(r)[0]:.4g}",
        }
        for p, res in bif.items()
        for r in res
    ]


CASE_COLUMNS = (
    "case",
    "F",
    "Omega",
    "paper",
    "ours",
    "wells",
    "lyapunov_per_period",
    "samples",
    "spread_w",
    "agrees",
)
CONV_COLUMNS = (
    "case",
    "paper",
    "variant",
    "ours",
    "lyapunov_per_period",
    "wells",
    "holds",
    "agrees_with_paper",
)
ELEM_COLUMNS = ("elements", "static_w_mid", "ours", "lyapunov_per_period", "wells", "spread_w")
WINDOW_COLUMNS = ("window", "fixed", "paper", "ours")

#: study.md: (title, table file) in order; a table is included when its file exists.
SECTIONS = (
    ("Cases of Figures 2-5", "table_cases.md"),
    ("Checks of the cases that differ", "table_checks.md"),
    ("Fine sweeps: the paper's sequences in our model", "table_windows.md"),
    ("Number of elements", "table_elements.md"),
)


def write_outputs(st: StudySettings, rep: StudyReport, out: Path) -> list[Path]:
    """The figures and tables of the parts that ran, and study.md from every table present."""
    files = _write_cases(rep, out) if rep.cases else []
    if rep.elements:
        elem = element_rows(rep.elements, rep.statics)
        files += [
            plot_elements(rep.elements, rep.statics, out / "elements.png"),
            write_csv(elem, out / "elements.csv"),
            write_text(markdown(elem, ELEM_COLUMNS), out / "table_elements.md"),
        ]
    if rep.bifurcations:
        files += _write_sweeps(rep.bifurcations, "bifurcation", out)
        files.append(write_csv(bifurcation_rows(rep.bifurcations), out / "bifurcations.csv"))
    if rep.windows:
        files += _write_sweeps(rep.windows, "window", out)
        win = window_rows(rep.windows)
        files += [
            write_csv(win, out / "windows.csv"),
            write_text(markdown(win, WINDOW_COLUMNS), out / "table_windows.md"),
        ]
    if rep.zooms:
        files += write_zooms(rep.zooms, [c for c, _ in rep.cases] or list(st.cases), out)
    files.append(write_markdown(st, out))
    return files


def _write_cases(rep: StudyReport, out: Path) -> list[Path]:
    files = [shrink_png(plot_case(r, out / "cases" / f"{c.name}.png")) for c, r in rep.cases]
    for fig_no in sorted({c.figure for c, _ in rep.cases}):
        sel = [(c, r) for c, r in rep.cases if c.figure == fig_no]
        path = out / f"overview_fig{fig_no}.png"
        files.append(plot_overview(fig_no, [c for c, _ in sel], [r for _, r in sel], path))
    case_rows = [case_row(c, r) for c, r in rep.cases]
    files += [
        write_csv(case_rows, out / "classifications.csv"),
        write_text(markdown(case_rows, CASE_COLUMNS), out / "table_cases.md"),
    ]
    if rep.checks:
        conv = check_rows(rep.checks)
        files += [
            write_csv(conv, out / "convergence.csv"),
            write_text(markdown(conv, CONV_COLUMNS), out / "table_checks.md"),
        ]
    return files


def _write_sweeps(sweeps: dict[str, list[CaseResult]], prefix: str, out: Path) -> list[Path]:
    files = []
    for name, res in sweeps.items():
        threshold = res[0].config.classify_settings.chaos_threshold
        png = plot_sweep(SWEPT.get(name, name), res, out / f"{prefix}_{name}.png", threshold)
        files.append(shrink_png(png))
    return files


def write_markdown(st: StudySettings, out: Path) -> Path:
    """study.md: the settings and every table file present in `out`."""
    text = [
        "# Section 6.1 reproduced (generated by `georod-tools study paper`)",
        "",
        f"{st.elements} elements, {st.substeps} midpoint sub-steps per forcing period "
        f"(dt_max = T/{st.substeps}); cases: {st.transient} transient + {st.periods} sampled "
        f"periods; bifurcation diagrams: {st.bif_count} values, fine sweeps {st.window_count} "
        f"values, {st.bif_transient} + {st.bif_periods} periods; element study at F = "
        f"{st.element_case[0]:g}, Omega = {st.element_case[1]:g}; the largest Lyapunov exponent "
        "from the core's tangent map (aligned 10 periods, averaged over the rest); chaotic when "
        "it exceeds 0.05 per period.",
        "",
    ]
    for title, name in SECTIONS:
        if (out / name).exists():
            text += [f"## {title}", "", (out / name).read_text(), ""]
    return write_text("\n".join(text), out / "study.md")


def write_zooms(
    zooms: dict[str, list[CaseResult]], cases: Sequence[PaperCase], out: Path
) -> list[Path]:
    """``zoom_<case>.png`` (bifurcation diagram, the panel's value dashed) and zooms.csv."""
    by_name = {c.name: c for c in cases}
    files, rows = [], []
    for name, results in zooms.items():
        case = by_name[name]
        param = "F" if case.figure == 2 else "Omega"
        threshold = results[0].config.classify_settings.chaos_threshold
        fig = sweep_figure(param, results, threshold)
        for ax in fig.axes:
            ax.axvline(getattr(case, param), color="tab:green", ls="--", lw=1.0)
        fig.axes[0].set_title(
            f"{name}: paper {case.paper_label} at {param} = {getattr(case, param):g} (dashed); "
            f"{results[0].config.elements} elements, T/{results[0].config.substeps}"
        )
        files.append(save(fig, out / f"zoom_{name}.png", dpi=110, shrink=True))
        rows += [
            {
                "case": name,
                "param": param,
                "value": r.config.value(param),
                "ours": r.classification.label,
                "lyapunov_per_period": round(r.exponent_per_period, 4),
                "wells": wells(r),
            }
            for r in results
        ]
    if rows:
        files.append(write_csv(rows, out / "zooms.csv"))
    return files
