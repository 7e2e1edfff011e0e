"""Figures and tables of the sensitivity study (:mod:`.sensitivity`).

- ``sensitivity_<question>.png``: one per question: for each variant a strip over Omega coloured
  by the classification of every case run (scan and refinement), the located edges as ticks, the
  paper's panels at F = 0.7 as dashed lines; the first frequency and static deflection in the
  strip's label.
- ``sensitivity_variants.csv`` / ``table_sensitivity.md``: per variant the statics and every edge.
- ``sensitivity_derivatives.csv`` / ``table_sensitivity_derivatives.md``: d(edge)/d(parameter)
  per question (shortening: least-squares slope over its values; the others: the change against
  the reference), in % of the reference value.
- ``table_sensitivity_choice.md``: per edge, the end shortenings that put it inside the paper's
  bracket, and the one shortening that fits all edges best (:func:`choice_rows`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from georod_tools.analysis.case import CaseResult
from georod_tools.report.figures import plt, save
from georod_tools.report.tables import markdown, write_csv, write_text
from georod_tools.studies.paper_cases import PAPER_CASES
from georod_tools.studies.sensitivity import QUESTIONS, REFERENCE_LABEL, REFERENCE_X, Prepared
from georod_tools.studies.sensitivity_windows import FEATURES, Located, one_well, period

COLORS = {1: "tab:gray", 2: "tab:blue", 3: "tab:green", 4: "tab:cyan", 6: "tab:olive"}


def _color(r: CaseResult | None) -> str:
    if r is None:
        return "black"
    p = period(r)
    if p is not None:
        return COLORS.get(p, "tab:purple")
    if r.classification.kind == "chaotic":
        return "tab:orange" if one_well(r) else "tab:red"
    return "white"


def _members(q: str, prepared: Sequence[Prepared]) -> list[Prepared]:
    """The variants of question `q`, the reference first."""
    return [p for p in prepared if p.variant.question in ("reference", q)]


def _label(p: Prepared, q: str) -> str:
    v = p.variant
    name = REFERENCE_LABEL[q] if v.question == "reference" else v.label
    st = p.statics
    return f"{name}\nw0={st.w_mid:.3f}, om1={st.omega1:.0f}"


def plot_question(
    q: str, prepared: Sequence[Prepared], located: dict[str, Located], path: Path
) -> Path:
    members = _members(q, prepared)
    fig, ax = plt.subplots(figsize=(11, 1.0 + 0.75 * len(members)), constrained_layout=True)
    for row, p in enumerate(members):
        loc = located[p.variant.name]
        cases = [(c.Omega, r) for c, r in zip(loc.scan, loc.results, strict=True)]
        cases += [(r.config.Omega, r) for r in loc.refined]
        cases.sort(key=lambda x: x[0])
        xs = np.array([o for o, _ in cases])
        mids = 0.5 * (xs[1:] + xs[:-1])
        edges = np.concatenate([[xs[0]], mids, [xs[-1]]])
        for (_, r), a, b in zip(cases, edges[:-1], edges[1:], strict=True):
            ax.fill_between([a, b], row - 0.35, row + 0.35, color=_color(r), lw=0)
        for e in loc.edges.values():
            if math.isfinite(e.lo):
                ax.plot([e.position] * 2, [row - 0.45, row + 0.45], "k-", lw=1.0)
    for c in PAPER_CASES:
        if c.F == 0.7:
            ax.axvline(c.Omega, color="k", ls=":", lw=0.6)
    ax.set_yticks(range(len(members)), [_label(p, q) for p in members], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("Omega (rad/s), F = 0.7")
    handles = [
        plt.Rectangle((0, 0), 1, 1, color=c)
        for c in (*COLORS.values(), "tab:purple", "tab:orange", "tab:red", "black")
    ]
    names = [f"period {k}" for k in COLORS] + ["other period", "chaos, one well", "chaos, both"]
    ax.legend(
        handles,
        [*names, "failed"],
        fontsize=7,
        ncol=5,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.35 if len(members) < 4 else -0.15),
    )
    ax.set_title(
        f"{QUESTIONS[q]}: classification over Omega (black ticks: located edges; dotted: the "
        "paper's panels at F = 0.7)",
        fontsize=9,
    )
    return save(fig, path, dpi=110, shrink=True)


def case_rows(prepared: Sequence[Prepared], located: dict[str, Located]) -> list[dict]:
    """Every case run (scan and refinement), by variant and Omega."""
    rows = []
    for p in prepared:
        loc = located[p.variant.name]
        got = [r for r in loc.results if r is not None] + loc.refined
        for r in sorted(got, key=lambda r: r.config.Omega):
            rows.append(
                {
                    "question": p.variant.question,
                    "variant": p.variant.label,
                    "Omega": r.config.Omega,
                    "ours": r.classification.label,
                    "lyapunov_per_period": round(r.exponent_per_period, 4),
                    "one_well": one_well(r),
                }
            )
    return rows


def variant_rows(prepared: Sequence[Prepared], located: dict[str, Located]) -> list[dict]:
    ref = located[prepared[0].variant.name].edges
    rows = []
    for p in prepared:
        v, st = p.variant, p.statics
        row: dict[str, object] = {
            "question": v.question,
            "variant": v.label,
            "pre_shortening": round(p.scene.pre_shortening, 5),
            "elements": v.elements,
            "substeps": v.substeps,
            "w_mid": round(st.w_mid, 4),
            "omega_modes": round(st.omega_modes, 1),
            "omega_free": round(st.omega_free, 1),
            "omega1": round(st.omega1, 1),
        }
        for f in FEATURES:
            e = located[v.name].edges[f.name]
            row[f.name] = round(e.position, 1) if math.isfinite(e.lo) else e.note
            r = ref[f.name]
            shift = (e.position / r.position - 1.0) * 100 if math.isfinite(r.lo) else math.nan
            row[f"{f.name}_pct"] = round(shift, 2) if math.isfinite(shift) else ""
        rows.append(row)
    return rows


def derivative_rows(prepared: Sequence[Prepared], located: dict[str, Located]) -> list[dict]:
    """Per question and non-reference variant: the change of the first frequency, the static
    deflection and every edge against the reference; for the shortening one more row with the
    least-squares slope per 0.001 of shortening."""
    ref = prepared[0]
    ref_edges = located[ref.variant.name].edges
    rows: list[dict] = []

    def pct(a: float, b: float) -> object:
        return round((a / b - 1.0) * 100, 2) if math.isfinite(a) and math.isfinite(b) else ""

    for q in QUESTIONS:
        for p in _members(q, prepared)[1:]:
            row: dict[str, object] = {
                "question": q,
                "change": f"{REFERENCE_LABEL[q]} -> {p.variant.label}",
                "omega1_pct": pct(p.statics.omega1, ref.statics.omega1),
                "w_mid_pct": pct(p.statics.w_mid, ref.statics.w_mid),
            }
            for f in FEATURES:
                row[f"{f.name}_pct"] = pct(
                    located[p.variant.name].edges[f.name].position, ref_edges[f.name].position
                )
            rows.append(row)
    members = _members("shortening", prepared)
    if len(members) >= 2:
        xs = [
            REFERENCE_X["shortening"] if m.variant.question == "reference" else m.variant.x
            for m in members
        ]
        row = {"question": "shortening", "change": "slope per +0.001 (least squares)"}
        row["omega1_pct"] = _slope_pct(xs, [m.statics.omega1 for m in members])
        row["w_mid_pct"] = _slope_pct(xs, [m.statics.w_mid for m in members])
        for f in FEATURES:
            ys = [located[m.variant.name].edges[f.name].position for m in members]
            row[f"{f.name}_pct"] = _slope_pct(xs, ys)
        rows.append(row)
    return rows


def _slope_pct(xs: Sequence[float], ys: Sequence[float]) -> object:
    """Least-squares slope of ys over xs per 0.001 of x, in % of the value at the largest x."""
    pts = [(x, y) for x, y in zip(xs, ys, strict=True) if math.isfinite(y)]
    if len(pts) < 2:
        return ""
    x, y = np.array(pts).T
    slope = np.polyfit(x, y, 1)[0] * 1e-3
    return round(100 * slope / y[np.argmax(x)], 2)


def write_outputs(
    prepared: Sequence[Prepared], located: dict[str, Located], out: Path, questions: Sequence[str]
) -> list[Path]:
    files = [
        plot_question(q, prepared, located, out / f"sensitivity_{q}.png")
        for q in questions
        if len(_members(q, prepared)) > 1
    ]
    var = variant_rows(prepared, located)
    files.append(write_csv(case_rows(prepared, located), out / "sensitivity_cases.csv"))
    der = derivative_rows(prepared, located)
    var_cols = ["question", "variant", "w_mid", "omega_modes", "omega_free", "omega1"]
    var_cols += [f.name for f in FEATURES]
    der_cols = ["question", "change", "omega1_pct", "w_mid_pct"]
    der_cols += [f"{f.name}_pct" for f in FEATURES]
    files += [
        write_csv(var, out / "sensitivity_variants.csv"),
        write_text(markdown(var, var_cols), out / "table_sensitivity.md"),
        write_csv(der, out / "sensitivity_derivatives.csv"),
        write_text(markdown(der, der_cols), out / "table_sensitivity_derivatives.md"),
    ]
    if any(p.variant.question == "shortening" for p in prepared):
        cho = choice_rows(var)
        files.append(write_text(markdown(cho), out / "table_sensitivity_choice.md"))
    return files


def _position(row: dict, name: str) -> float:
    try:
        return float(row[name])
    except (TypeError, ValueError):
        return math.nan


def choice_rows(rows: Sequence[dict], grid: int = 401) -> list[dict]:
    """From the rows of sensitivity_variants.csv (reference and shortening variants): for every
    edge, the range of end shortening over which its position (interpolated linearly between the
    computed shortenings) lies inside the bracket the paper's panels give; then the range over
    which all edges are inside at once (its middle is the choice: one setting for the whole window
    structure), or, if there is none, the shortening that minimizes the sum over all edges of
    the squared distance to their brackets (relative to the bracket's middle)."""
    pts = sorted(
        (float(r["pre_shortening"]), r)
        for r in rows
        if r["question"] in ("reference", "shortening")
    )
    xs = np.array([x for x, _ in pts])
    fine = np.linspace(xs.min(), xs.max(), grid)
    total = np.zeros_like(fine)
    out = []
    for f in FEATURES:
        ys = np.array([_position(r, f.name) for _, r in pts])
        ok = np.isfinite(ys)
        lo, hi = f.paper
        row: dict[str, object] = {"edge": f.name, "meaning": f.label, "paper": f"{lo:g}-{hi:g}"}
        if ok.sum() < 2:
            row.update(inside="not located", **{"at_0.11": ""})
            out.append(row)
            continue
        y = np.interp(fine, xs[ok], ys[ok])
        dist = np.maximum(lo - y, 0.0) + np.maximum(y - hi, 0.0)
        total += (dist / (0.5 * (lo + hi))) ** 2
        inside = fine[dist == 0.0]
        row["inside"] = (
            f"{inside.min():.4f}-{inside.max():.4f}" if len(inside) else "nowhere in the range"
        )
        row["at_0.11"] = round(float(ys[np.argmax(xs)]), 1)
        out.append(row)
    best = float(fine[np.argmin(total)])
    every = fine[total == 0.0]
    text = (
        f"all inside for {every.min():.4f}-{every.max():.4f}, middle "
        f"{0.5 * (every.min() + every.max()):.4f}"
        if len(every)
        else f"no shortening puts all inside; least squares {best:.4f}"
    )
    out.append(
        {"edge": "all", "meaning": "every edge at once", "paper": "", "inside": text, "at_0.11": ""}
    )
    return out
