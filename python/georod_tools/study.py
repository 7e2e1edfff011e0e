"""Reproduction of the paper's section 6.1 (the harmonically excited buckled beam) with the
BuckledBeam FMU: every case of its Figures 2-5, the two bifurcation diagrams, a check of every
case where we differ from the paper (time step, mesh, transient, initial well), the effect of the
number of elements, and the wall time of a bifurcation diagram with 1 and 2 Dask workers.

    python -m georod_tools study [--quick] [--workers N] [--out DIR]
    python -m georod_tools study --timing [--out DIR]        (only the timing benchmark)

Everything runs through :func:`georod_tools.runner.run_case` (one fresh FMU instance per case,
deterministic) distributed by :func:`georod_tools.sweep.run_sweep` on one local Dask cluster that
the study starts once and hands to every sweep by its address. The cases of the paper are
"lines" (fixed Omega, varying F or fixed F, varying Omega), so every batch is a sweep.

Outputs in DIR: ``cases/<case>.png`` (three panels per case), ``overview_fig<N>.png`` (grid of
Poincaré sections per paper figure), ``bifurcation_F.png`` / ``bifurcation_Omega.png``,
``window_<name>.png`` (fine sweeps), ``elements.png``, CSV files (``classifications``,
``convergence``, ``elements``, ``bifurcations``, ``windows``), ``timing.json``, one markdown
fragment per table (``table_*.md``, ``timing.md``) and ``study.md`` with all of them.
``--parts`` runs a subset; the tables of the other parts already in DIR stay in study.md.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import time
from collections import defaultdict
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from georod_tools.argtypes import positive_int
from georod_tools.runner import CaseConfig, CaseResult, FmuModel, Instance
from georod_tools.sweep import run_sweep, sweep_values

PERIODIC, CHAOTIC, LONG = "periodic", "chaotic", "long-period"


# --------------------------------------------------------------------------- the paper's cases


@dataclass(frozen=True)
class PaperCase:
    """One panel of the paper's Figures 2-5 with what the paper says about it.

    kind: ``periodic`` (with `period`), ``chaotic`` or ``long-period`` (a period too long to name).
    wells: ``one``, ``both`` or None when the paper does not say whether the motion stays in one
        potential well or visits both.
    """

    figure: int
    panel: str
    F: float
    Omega: float
    description: str
    kind: str
    period: int | None = None
    wells: str | None = None

    @property
    def name(self) -> str:
        return f"fig{self.figure}{self.panel}"

    @property
    def paper_label(self) -> str:
        return f"period-{self.period}" if self.kind == PERIODIC else self.kind


def _fig(figure: int, fixed: dict[str, float], rows: Sequence[tuple]) -> list[PaperCase]:
    out = []
    for panel, value, desc, kind, period, wells in rows:
        var = {"F": value} if "Omega" in fixed else {"Omega": value}
        out.append(
            PaperCase(
                figure,
                panel,
                **fixed,
                **var,
                description=desc,
                kind=kind,
                period=period,
                wells=wells,
            )
        )
    return out


#: Figures 2-5 of section 6.1, captions quoted (periods in brackets are implied, not stated).
PAPER_CASES: tuple[PaperCase, ...] = tuple(
    _fig(
        2,
        {"Omega": 3500.0},
        [
            ("a", 0.4, "small orbit around the right equilibrium [period-1]", PERIODIC, 1, "one"),
            ("b", 0.6, "chaotic motion around both stable equilibria", CHAOTIC, None, "both"),
            ("c", 0.7, "globally three-period motion", PERIODIC, 3, "both"),
            ("d", 0.9, "chaotic, period-doubling of the odd-period motion", CHAOTIC, None, None),
            ("e", 1.5, "globally chaotic motion", CHAOTIC, None, "both"),
            (
                "f",
                2.0,
                "periodic large orbit around all equilibria [period-1]",
                PERIODIC,
                1,
                "both",
            ),
        ],
    )
    + _fig(
        3,
        {"F": 0.7},
        [
            ("a", 4200.0, "two-period motion", PERIODIC, 2, None),
            ("b", 4050.0, "locally chaotic, period-doubling of (a)", CHAOTIC, None, "one"),
            ("c", 4000.0, "chaotic around both equilibrium positions", CHAOTIC, None, "both"),
            ("d", 3600.0, "three-period motion", PERIODIC, 3, None),
            ("e", 3550.0, "doubling of the three-period motion [period-6]", PERIODIC, 6, None),
            ("f", 3400.0, "globally chaotic, period-doubling of (e)", CHAOTIC, None, "both"),
        ],
    )
    + _fig(
        4,
        {"F": 0.7},
        [
            ("a", 3500.0, "three-period motion", PERIODIC, 3, "both"),
            ("b", 3480.0, "(2x3)-period motion", PERIODIC, 6, None),
            ("c", 3465.0, "(4x3)-period motion", PERIODIC, 12, None),
            ("d", 3460.0, "(8x3)-period motion", PERIODIC, 24, None),
            ("e", 3450.0, "a very long period", LONG, None, None),
            ("f", 3430.0, "chaos due to the period-doubling", CHAOTIC, None, None),
            ("g", 3420.0, "chaos due to the period-doubling", CHAOTIC, None, None),
            ("h", 3400.0, "globally chaotic", CHAOTIC, None, "both"),
        ],
    )
    + _fig(
        5,
        {"F": 0.7},
        [
            ("a", 4300.0, "two-period motion", PERIODIC, 2, "one"),
            ("b", 4200.0, "two-period motion", PERIODIC, 2, "one"),
            ("c", 4150.0, "four-period motion", PERIODIC, 4, "one"),
            ("d", 4120.0, "large period motion", LONG, None, "one"),
            ("e", 4050.0, "locally chaotic", CHAOTIC, None, "one"),
            ("f", 4000.0, "globally chaotic due to symmetry", CHAOTIC, None, "both"),
        ],
    )
)


# --------------------------------------------------------------------------- settings


@dataclass(frozen=True)
class StudySettings:
    """Numbers of the study. `full` and `quick` give the two presets of the command line.

    transient / periods: forcing periods discarded / sampled per case (the Lyapunov exponent is
        averaged over the sampled periods, so a case costs about transient + 2 periods).
    n_per_period: communication steps per period (the FMU cuts each into equal sub-steps of at
        most dt_max); also the resolution of the phase portraits.
    """

    fmu: str
    elements: int = 10
    dt_max: float = 1e-5
    n_per_period: int = 40
    transient: int = 2000
    periods: int = 500
    dense_periods: int = 30
    bif_count: int = 100
    bif_transient: int = 2000
    bif_periods: int = 300
    F_range: tuple[float, float] = (0.4, 2.0)
    Omega_range: tuple[float, float] = (3400.0, 4300.0)
    element_counts: tuple[int, ...] = (2, 4, 6, 8, 10, 16, 20)
    element_case: tuple[float, float] = (0.7, 3500.0)
    convergence: bool = True
    cases: tuple[PaperCase, ...] = PAPER_CASES
    timing_count: int = 100
    timing_periods: tuple[int, int] = (200, 200)
    window_count: int = 41

    @classmethod
    def full(cls, fmu: str) -> StudySettings:
        return cls(fmu=fmu)

    @classmethod
    def quick(cls, fmu: str) -> StudySettings:
        return cls(
            fmu=fmu,
            transient=150,
            periods=100,
            dense_periods=10,
            bif_count=8,
            bif_transient=150,
            bif_periods=60,
            timing_count=8,
            window_count=5,
        )

    def config(self, F: float, Omega: float, dense: bool = True) -> CaseConfig:
        """The configuration of one case of the paper (10 elements unless set otherwise)."""
        return CaseConfig(
            fmu=self.fmu,
            F=float(F),
            Omega=float(Omega),
            elements=self.elements,
            dt_max=self.dt_max,
            transient_periods=self.transient,
            sample_periods=self.periods,
            n_per_period=self.n_per_period,
            dense_periods=min(self.dense_periods, self.periods) if dense else 0,
        )


@dataclass(frozen=True)
class Window:
    """A fine sweep around a structure of the paper that we find at shifted parameters."""

    name: str
    param: str
    start: float
    stop: float
    F: float
    Omega: float
    paper: str


#: Fine sweeps: where our model shows the paper's sequences (Figures 2, 4 and 5).
WINDOWS: tuple[Window, ...] = (
    Window(
        "F_onset",
        "F",
        0.50,
        0.70,
        0.7,
        3500.0,
        "Fig. 2a-2c: small orbit (0.4), chaos (0.6), period-3 (0.7)",
    ),
    Window(
        "Omega_period3",
        "Omega",
        3530.0,
        3610.0,
        0.7,
        3500.0,
        "Fig. 4: period 3, 6, 12, 24 at Omega = 3500, 3480, 3465, 3460, chaos below",
    ),
    Window(
        "Omega_period2",
        "Omega",
        4220.0,
        4300.0,
        0.7,
        3500.0,
        "Fig. 5: period 2 (4300, 4200), 4 (4150), long (4120), local chaos (4050)",
    ),
)

#: Parameter swept by each fine sweep.
SWEPT: dict[str, str] = {w.name: w.param for w in WINDOWS}

#: Parts of the study (``--parts``); the checks run with the cases.
PARTS = ("cases", "elements", "bifurcations", "windows")

#: Variants that check a case where we differ from the paper (name -> changed configuration).
VARIANTS: dict[str, Callable[[CaseConfig], CaseConfig]] = {
    "dt_max/2": lambda c: replace(c, dt_max=c.dt_max / 2),
    "dt_max/4": lambda c: replace(c, dt_max=c.dt_max / 4),
    "20 elements": lambda c: replace(c, elements=20),
    "3x transient": lambda c: replace(c, transient_periods=3 * c.transient_periods),
    "well = -1": lambda c: c.with_value("well", -1),
}


# --------------------------------------------------------------------------- running


class Batch:
    """Runs sets of cases on one Dask cluster through :func:`run_sweep`, caching the results.

    A set of configurations is cut into lines (all equal but Omega, or all equal but F); each line
    is one sweep. `scheduler` is the address of a running scheduler (None: every sweep starts its
    own local cluster of `workers` processes).
    """

    def __init__(self, scheduler: str | None, workers: int = 1, progress: bool = True) -> None:
        self.scheduler, self.workers, self.progress = scheduler, workers, progress
        self.results: dict[CaseConfig, CaseResult] = {}

    def run(self, configs: Iterable[CaseConfig]) -> list[CaseResult]:
        """The results of `configs`, in their order (each distinct case runs once)."""
        configs = list(configs)
        todo = [c for c in dict.fromkeys(configs) if c not in self.results]
        for base, param, values in lines(todo):
            for r in run_sweep(
                base,
                param,
                values,
                workers=self.workers,
                scheduler=self.scheduler,
                progress=self.progress,
            ):
                self.results[r.config] = r
        return [self.results[c] for c in configs]


def lines(configs: Sequence[CaseConfig]) -> list[tuple[CaseConfig, str, list[float]]]:
    """Cuts `configs` into sweeps ``(base, param, values)``: first lines of varying Omega with
    more than one case, then lines of varying F (which take every remaining case)."""
    out: list[tuple[CaseConfig, str, list[float]]] = []
    rest = list(configs)
    for param, last in (("Omega", False), ("F", True)):
        groups: dict[CaseConfig, list[CaseConfig]] = defaultdict(list)
        for c in rest:
            groups[replace(c, **{param: 1.0})].append(c)
        rest = []
        for base, members in groups.items():
            if len(members) > 1 or last:
                out.append((base, param, [getattr(c, param) for c in members]))
            else:
                rest.extend(members)
    return out


# --------------------------------------------------------------------------- analysis


def wells(result: CaseResult) -> str:
    """``both`` when w_mid changes sign over the recorded motion (dense trajectory if kept, else
    the stroboscopic samples), else ``one (+)`` / ``one (-)``."""
    w = (
        result.dense[:, 1]
        if result.dense is not None and len(result.dense)
        else result.samples[:, 0]
    )
    if w.min() < 0.0 < w.max():
        return "both"
    return "one (+)" if w.min() >= 0.0 else "one (-)"


def agreement(case: PaperCase, result: CaseResult) -> str:
    """``yes``, ``partly`` (same kind of motion, other period or other wells) or ``no``."""
    c = result.classification
    ours = c.kind
    if case.kind == LONG:
        if ours == CHAOTIC:
            return "no"
        return "yes" if ours != PERIODIC or (c.period or 0) >= 8 else "partly"
    if case.kind != ours:
        return "no"
    if case.kind == PERIODIC and case.period != c.period:
        return "partly"
    if case.wells is not None and not wells(result).startswith(case.wells):
        return "partly"
    return "yes"


def spread(result: CaseResult) -> tuple[float, float]:
    """Range of the stroboscopic w_mid and v_mid samples (0 for a period-1 orbit)."""
    s = result.samples
    return float(np.ptp(s[:, 0])), float(np.ptp(s[:, 1]))


def static_w_mid(fmu: str, elements: int) -> float:
    """w_mid of the static buckled state (t = 0) with `elements` elements."""
    inst = Instance(FmuModel.load(fmu), {"elements": elements}, 3500.0, 1, name="static")
    try:
        return inst.outputs()[0]
    finally:
        inst.close()


@dataclass
class Check:
    """The variants of one differing case and whether each keeps the base classification."""

    case: PaperCase
    base: CaseResult
    variants: dict[str, CaseResult] = field(default_factory=dict)

    def holds(self, name: str) -> bool:
        return self.variants[name].classification.label == self.base.classification.label


# --------------------------------------------------------------------------- figures


def _plt():  # noqa: ANN202 - matplotlib's pyplot module
    from georod_tools import plots  # selects the Agg backend

    return plots.plt


def _section(ax, result: CaseResult, title: str, color: str = "k") -> None:  # noqa: ANN001
    s = result.samples
    ax.plot(s[:, 0], s[:, 1], ".", ms=2.5 if len(s) > 50 else 5, color="k")
    span = np.ptp(s, axis=0)
    for lim, centre, size, sp in zip(
        (ax.set_xlim, ax.set_ylim), s.mean(axis=0), result.size, span, strict=True
    ):
        if sp < 1e-3 * size:  # a finite set of points: show it on the scale of the orbit
            lim(centre - size / 2, centre + size / 2)
    ax.set_title(title, fontsize=8, color=color)
    ax.tick_params(labelsize=7)
    ax.set_xlabel("w_mid", fontsize=7)
    ax.set_ylabel("v_mid", fontsize=7)


def _lam(result: CaseResult) -> str:
    return f"{result.exponent_per_period:.3f}"


def plot_overview(
    figure: int, cases: Sequence[PaperCase], results: Sequence[CaseResult], path: Path
) -> Path:
    """Grid of the Poincaré sections of one paper figure; red titles where we differ."""
    plt = _plt()
    ncols = math.ceil(len(cases) / 2)
    fig, axes = plt.subplots(2, ncols, figsize=(3.3 * ncols, 6.4), constrained_layout=True)
    for ax, case, r in zip(axes.flat, cases, results, strict=False):
        agree = agreement(case, r)
        title = (
            f"({case.panel}) F={case.F:g}, Omega={case.Omega:g}\n"
            f"ours: {r.classification.label}, lambda={_lam(r)}\npaper: {case.paper_label}"
        )
        _section(ax, r, title, {"yes": "k", "partly": "tab:orange"}.get(agree, "tab:red"))
    for ax in list(axes.flat)[len(cases) :]:
        ax.set_visible(False)
    fig.suptitle(
        f"Figure {figure} of the paper: Poincaré sections (t = k T), "
        f"{results[0].config.elements} elements",
        fontsize=10,
    )
    return _save(fig, path)


def plot_elements(results: Sequence[CaseResult], statics: Sequence[float], path: Path) -> Path:
    """Grid of Poincaré sections of the element study."""
    plt = _plt()
    ncols = math.ceil(len(results) / 2)
    fig, axes = plt.subplots(2, ncols, figsize=(3.3 * ncols, 6.4), constrained_layout=True)
    for ax, r, w0 in zip(axes.flat, results, statics, strict=False):
        title = (
            f"{r.config.elements} elements (static w_mid {w0:.3f})\n"
            f"{r.classification.label}, lambda={_lam(r)}"
        )
        _section(ax, r, title)
    for ax in list(axes.flat)[len(results) :]:
        ax.set_visible(False)
    c = results[0].config
    fig.suptitle(f"Number of elements: F = {c.F:g}, Omega = {c.Omega:g}", fontsize=10)
    return _save(fig, path)


def _save(fig, path: Path, dpi: int = 100) -> Path:  # noqa: ANN001
    plt = _plt()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return shrink_png(path)


def shrink_png(path: Path, limit: int = 200_000) -> Path:
    """Re-encodes a PNG as a 256-colour palette image when it exceeds `limit` bytes."""
    if path.stat().st_size <= limit:
        return path
    from PIL import Image

    with Image.open(path) as im:
        im.convert("RGB").quantize(colors=256).save(path, optimize=True)
    return path


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
        "dt_max": r.config.dt_max,
        "transient": r.config.transient_periods,
        "wall_s": round(r.wall_time, 2),
    }


def write_csv(rows: Sequence[dict[str, object]], path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as f:
        if rows:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    return path


def markdown(rows: Sequence[dict[str, object]], columns: Sequence[str]) -> str:
    """A markdown table of `columns` of `rows`."""
    out = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    out += ["| " + " | ".join(str(r[c]) for c in columns) + " |" for r in rows]
    return "\n".join(out)


def convergence_rows(checks: Sequence[Check]) -> list[dict[str, object]]:
    rows: list[dict[str, object]] = []
    for ch in checks:
        runs = {"base": ch.base, **ch.variants}
        for name, r in runs.items():
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
TIME_COLUMNS = ("workers", "repeat", "wall_s", "sum_case_s", "speedup", "load_before")


# --------------------------------------------------------------------------- the study


@dataclass
class StudyReport:
    cases: list[tuple[PaperCase, CaseResult]]
    checks: list[Check]
    elements: list[CaseResult]
    statics: list[float]
    bifurcations: dict[str, list[CaseResult]]
    windows: dict[str, list[CaseResult]]
    files: list[Path]


def run_paper_cases(st: StudySettings, batch: Batch) -> list[tuple[PaperCase, CaseResult]]:
    results = batch.run(st.config(c.F, c.Omega) for c in st.cases)
    return list(zip(st.cases, results, strict=True))


def run_checks(cases: Sequence[tuple[PaperCase, CaseResult]], batch: Batch) -> list[Check]:
    """Every variant of every case that does not fully agree with the paper."""
    differing = {c.name: (c, r) for c, r in cases if agreement(c, r) != "yes"}
    seen: dict[tuple[float, float], Check] = {}
    for case, r in differing.values():
        if (case.F, case.Omega) not in seen:
            seen[(case.F, case.Omega)] = Check(case, r)
    checks = list(seen.values())
    configs = [v(ch.base.config) for ch in checks for v in VARIANTS.values()]
    results = iter(batch.run(configs))
    for ch in checks:
        ch.variants = {name: next(results) for name in VARIANTS}
    return checks


def run_bifurcations(st: StudySettings, batch: Batch) -> dict[str, list[CaseResult]]:
    base = replace(
        st.config(0.7, 3500.0, dense=False),
        transient_periods=st.bif_transient,
        sample_periods=st.bif_periods,
    )
    return {
        "F": batch.run(base.with_value("F", v) for v in sweep_values(*st.F_range, st.bif_count)),
        "Omega": batch.run(
            base.with_value("Omega", v) for v in sweep_values(*st.Omega_range, st.bif_count)
        ),
    }


def run_windows(st: StudySettings, batch: Batch) -> dict[str, list[CaseResult]]:
    out = {}
    for w in WINDOWS:
        base = replace(
            st.config(w.F, w.Omega, dense=False),
            transient_periods=st.bif_transient,
            sample_periods=st.bif_periods,
        )
        values = sweep_values(w.start, w.stop, st.window_count)
        out[w.name] = batch.run(base.with_value(w.param, v) for v in values)
    return out


def label_ranges(param: str, results: Sequence[CaseResult]) -> str:
    """``0.5-0.545: period-1; 0.55: chaotic; ...``: runs of equal classification."""
    runs: list[tuple[float, float, str]] = []
    for r in results:
        x, lab = float(getattr(r.config, param)), r.classification.label
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
            rows.append(
                {
                    "window": w.name,
                    "fixed": fixed,
                    "paper": w.paper,
                    "ours": label_ranges(w.param, windows[w.name]),
                }
            )
    return rows


def run_elements(st: StudySettings, batch: Batch) -> tuple[list[CaseResult], list[float]]:
    base = st.config(*st.element_case)
    results = batch.run(replace(base, elements=n) for n in st.element_counts)
    return results, [static_w_mid(st.fmu, n) for n in st.element_counts]


def write_outputs(st: StudySettings, rep: StudyReport, out: Path) -> list[Path]:
    """The figures and tables of the parts that ran; study.md from every table present."""
    files = _write_cases(rep, out) if rep.cases else []
    if rep.elements:
        files.append(plot_elements(rep.elements, rep.statics, out / "elements.png"))
        elem = element_rows(rep.elements, rep.statics)
        files += [
            write_csv(elem, out / "elements.csv"),
            write_table(markdown(elem, ELEM_COLUMNS), out / "table_elements.md"),
        ]
    if rep.bifurcations:
        files += _write_sweeps(rep.bifurcations, "bifurcation", out)
        files.append(write_csv(bifurcation_rows(rep.bifurcations), out / "bifurcations.csv"))
    if rep.windows:
        files += _write_sweeps(rep.windows, "window", out)
        win = window_rows(rep.windows)
        files += [
            write_csv(win, out / "windows.csv"),
            write_table(markdown(win, WINDOW_COLUMNS), out / "table_windows.md"),
        ]
    files.append(write_markdown(st, out))
    return files


def _write_cases(rep: StudyReport, out: Path) -> list[Path]:
    from georod_tools.plots import plot_case

    files = [shrink_png(plot_case(r, out / "cases" / f"{c.name}.png")) for c, r in rep.cases]
    for fig_no in sorted({c.figure for c, _ in rep.cases}):
        sel = [(c, r) for c, r in rep.cases if c.figure == fig_no]
        files.append(
            plot_overview(
                fig_no, [c for c, _ in sel], [r for _, r in sel], out / f"overview_fig{fig_no}.png"
            )
        )
    case_rows = [case_row(c, r) for c, r in rep.cases]
    files += [
        write_csv(case_rows, out / "classifications.csv"),
        write_table(markdown(case_rows, CASE_COLUMNS), out / "table_cases.md"),
    ]
    if rep.checks:  # else keep the tables of an earlier run
        conv = convergence_rows(rep.checks)
        files += [
            write_csv(conv, out / "convergence.csv"),
            write_table(markdown(conv, CONV_COLUMNS), out / "table_checks.md"),
        ]
    return files


def _write_sweeps(sweeps: dict[str, list[CaseResult]], prefix: str, out: Path) -> list[Path]:
    from georod_tools.plots import plot_sweep

    files = []
    for name, res in sweeps.items():
        param = SWEPT.get(name, name)
        png = plot_sweep(
            param,
            res,
            out / f"{prefix}_{name}.png",
            chaos_threshold=res[0].config.classify_settings.chaos_threshold,
        )
        files.append(shrink_png(png))
    return files


def write_table(text: str, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text + "\n")
    return path


def bifurcation_rows(bif: dict[str, list[CaseResult]]) -> list[dict[str, object]]:
    return [
        {
            "param": p,
            "value": getattr(r.config, p),
            "ours": r.classification.label,
            "lyapunov_per_period": round(r.exponent_per_period, 4),
            "wells": wells(r),
            "spread_w": f"{spread(r)[0]:.4g}",
        }
        for p, res in bif.items()
        for r in res
    ]


#: study.md: (title, table file) in order; a table is included when its file exists.
SECTIONS = (
    ("Cases of Figures 2-5", "table_cases.md"),
    ("Checks of the cases that differ", "table_checks.md"),
    ("Fine sweeps: the paper's sequences in our model", "table_windows.md"),
    ("Number of elements", "table_elements.md"),
    ("Timing", "timing.md"),
)


def write_markdown(st: StudySettings, out: Path) -> Path:
    """study.md: the settings and every table file present in `out`."""
    text = [
        "# Section 6.1 reproduced (generated by `python -m georod_tools study`)",
        "",
        f"{st.elements} elements, dt_max = {st.dt_max:g} s, {st.n_per_period} communication "
        f"steps per period; cases: {st.transient} transient + {st.periods} sampled periods; "
        f"bifurcation diagrams: {st.bif_count} values, fine sweeps {st.window_count} values, "
        f"{st.bif_transient} + {st.bif_periods} periods; element study at F = "
        f"{st.element_case[0]:g}, Omega = {st.element_case[1]:g}; chaotic when the largest "
        "Lyapunov exponent exceeds 0.05 per period.",
        "",
    ]
    for title, name in SECTIONS:
        if (out / name).exists():
            text += [f"## {title}", "", (out / name).read_text(), ""]
    path = out / "study.md"
    path.write_text("\n".join(text))
    return path


def local_cluster(workers: int):  # noqa: ANN201 - a dask.distributed.LocalCluster
    import logging

    from dask.distributed import LocalCluster

    return LocalCluster(
        n_workers=workers,
        threads_per_worker=1,
        processes=True,
        dashboard_address=":0",
        silence_logs=logging.WARNING,
    )


def run_study(
    st: StudySettings,
    out: Path,
    workers: int = 2,
    progress: bool = True,
    parts: Sequence[str] = PARTS,
) -> StudyReport:
    """The study (the given `parts`) on a local cluster of `workers` processes; writes its
    figures and tables to `out`."""
    rep = StudyReport([], [], [], [], {}, {}, [])
    with local_cluster(workers) as cluster:
        batch = Batch(cluster.scheduler_address, workers, progress)
        if "cases" in parts:
            rep.cases = run_paper_cases(st, batch)
            rep.checks = run_checks(rep.cases, batch) if st.convergence else []
        if "elements" in parts:
            rep.elements, rep.statics = run_elements(st, batch)
        if "bifurcations" in parts:
            rep.bifurcations = run_bifurcations(st, batch)
        if "windows" in parts:
            rep.windows = run_windows(st, batch)
    rep.files = write_outputs(st, rep, out)
    return rep


# --------------------------------------------------------------------------- timing


def run_timing(
    st: StudySettings, out: Path, workers: Sequence[int] = (1, 2), repeats: int = 1
) -> list[dict[str, object]]:
    """Wall time of one bifurcation diagram over F (`timing_count` values, transient + sampled =
    `timing_periods`, Lyapunov exponent on, the `sweep` command's 20 steps per period), with each
    number of workers, `repeats` times; includes starting the local cluster. Writes timing.json."""
    tr, sp = st.timing_periods
    base = CaseConfig(
        fmu=st.fmu,
        elements=st.elements,
        dt_max=st.dt_max,
        transient_periods=tr,
        sample_periods=sp,
        n_per_period=20,
    )
    values = sweep_values(*st.F_range, st.timing_count)
    rows: list[dict[str, object]] = []
    for rep in range(1, repeats + 1):
        for w in workers:
            load = os.getloadavg()[0]
            t0 = time.perf_counter()
            res = run_sweep(base, "F", values, workers=w, progress=False)
            wall = time.perf_counter() - t0
            rows.append(
                {
                    "workers": w,
                    "repeat": rep,
                    "wall_s": round(wall, 1),
                    "sum_case_s": round(sum(r.wall_time for r in res), 1),
                    "speedup": "",
                    "load_before": round(load, 2),
                }
            )
    _speedups(rows)
    desc = (
        f"One bifurcation diagram over F in [{st.F_range[0]:g}, {st.F_range[1]:g}]: "
        f"{st.timing_count} values, {tr} transient + {sp} sampled periods each (Lyapunov "
        f"exponent on), {st.elements} elements, dt_max = {st.dt_max:g}, 20 steps per period, "
        f"{os.cpu_count()} CPU cores; wall time includes starting the Dask cluster; "
        "load_before = 1-minute load average before the run (other users)."
    )
    out.mkdir(parents=True, exist_ok=True)
    (out / "timing.json").write_text(json.dumps({"description": desc, "rows": rows}, indent=1))
    write_table(desc + "\n\n" + markdown(rows, TIME_COLUMNS), out / "timing.md")
    write_markdown(st, out)
    return rows


def _speedups(rows: list[dict[str, object]]) -> None:
    """speedup = best single-worker wall time / this row's wall time."""
    ones = [float(r["wall_s"]) for r in rows if r["workers"] == 1]  # type: ignore[arg-type]
    if ones:
        for r in rows:
            r["speedup"] = round(min(ones) / float(r["wall_s"]), 2)  # type: ignore[arg-type]


# --------------------------------------------------------------------------- command line


def add_study_parser(sub: argparse._SubParsersAction) -> None:
    """The ``study`` subcommand (registered by :mod:`georod_tools.cli`)."""
    p = sub.add_parser("study", help="reproduce the paper's section 6.1 (figures, tables, checks)")
    add_study_options(p)


def add_study_options(p: argparse.ArgumentParser) -> None:
    """The options of ``study`` (subcommand and ``python -m georod_tools.study``)."""
    p.add_argument("--quick", action="store_true", help="short runs, few bifurcation values")
    p.add_argument(
        "--workers", type=positive_int, default=2, help="local Dask worker processes, >= 1 (2)"
    )
    p.add_argument("--out", type=Path, default=Path("out") / "study", help="output folder")
    p.add_argument("--fmu", type=Path, help="BuckledBeam FMU (default: target/fmu/BuckledBeam.fmu)")
    p.add_argument("--no-convergence", action="store_true", help="skip the checks of differences")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.add_argument("--timing", action="store_true", help="only the 1- vs 2-worker timing")
    p.add_argument("--repeats", type=positive_int, default=1, help="timing repetitions, >= 1 (1)")
    p.add_argument(
        "--parts",
        default=",".join(PARTS),
        help=f"comma-separated parts to run ({','.join(PARTS)}); the others' tables are kept",
    )


def run_study_command(parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
    from georod_tools import fmu_path

    fmu = args.fmu or fmu_path("BuckledBeam")
    if not Path(fmu).is_file():
        parser.error(f"FMU {fmu} not found: build it with scripts/build_fmus or pass --fmu")
    parts = [x.strip() for x in args.parts.split(",") if x.strip()]
    if not parts or any(x not in PARTS for x in parts):
        parser.error(f"--parts {args.parts}: choose from {','.join(PARTS)}")
    make = StudySettings.quick if args.quick else StudySettings.full
    st = replace(make(str(Path(fmu).resolve())), convergence=not args.no_convergence)
    t0 = time.perf_counter()
    if args.timing:
        rows = run_timing(st, args.out, workers=sorted({1, args.workers}), repeats=args.repeats)
        print(markdown(rows, TIME_COLUMNS))
        return 0
    rep = run_study(st, args.out, args.workers, not args.no_progress, parts)
    rows = [case_row(c, r) for c, r in rep.cases]
    print(
        markdown(
            rows, ("case", "F", "Omega", "paper_class", "ours", "lyapunov_per_period", "agrees")
        )
    )
    print(f"study done in {time.perf_counter() - t0:.0f} s; {len(rep.files)} files in {args.out}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m georod_tools.study``: the same as ``python -m georod_tools study``."""
    ap = argparse.ArgumentParser(
        prog="python -m georod_tools.study",
        description="Reproduction of the paper's section 6.1 with the BuckledBeam FMU.",
    )
    add_study_options(ap)
    return run_study_command(ap, ap.parse_args(argv))


if __name__ == "__main__":
    raise SystemExit(main())
