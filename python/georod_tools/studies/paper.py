"""Reproduction of the paper's section 6.1 (the harmonically excited buckled beam) with the
BuckledBeam FMU: every case of its Figures 2-5 (:mod:`.paper_cases`), the two bifurcation
diagrams, a check of every case where we differ from the paper (time step, mesh, transient,
initial well), the fine sweeps around the paper's cascades and the effect of the number of
elements (``georod-tools study paper``; figures and tables: :mod:`.paper_report`).

Everything runs through :func:`georod_tools.analysis.case.run_case` (one FMU instance per case,
the core's Lyapunov exponent, deterministic) distributed by
:func:`georod_tools.analysis.sweep.run_sweep` on one local Dask cluster that the study starts once
and hands to every sweep by its address. The cases of the paper are "lines" (fixed Omega, varying
F or fixed F, varying Omega), so every batch is a sweep.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from georod_tools.analysis.case import DEFAULT_SUBSTEPS, CaseConfig, CaseResult
from georod_tools.analysis.classify import CHAOTIC as OUR_CHAOTIC
from georod_tools.analysis.classify import PERIODIC as OUR_PERIODIC
from georod_tools.analysis.sweep import local_cluster, run_sweep, sweep_values
from georod_tools.fmu import FmuModel, lend
from georod_tools.studies.paper_cases import LONG, PAPER_CASES, PERIODIC, WINDOWS, PaperCase


@dataclass(frozen=True)
class StudySettings:
    """Numbers of the study. `full` and `quick` give the two presets of the command line.

    substeps: midpoint sub-steps per forcing period (dt_max = T / substeps).
    transient / periods: forcing periods discarded / sampled per case (the exponent aligns for
        10 of the sampled periods and is averaged over the rest).
    """

    fmu: str
    elements: int = 10
    substeps: int = DEFAULT_SUBSTEPS
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
            window_count=5,
        )

    def config(self, F: float, Omega: float, dense: bool = True) -> CaseConfig:
        """The configuration of one case of the paper (10 elements unless set otherwise)."""
        return CaseConfig(
            fmu=self.fmu,
            F=float(F),
            Omega=float(Omega),
            elements=self.elements,
            substeps=self.substeps,
            transient_periods=self.transient,
            sample_periods=self.periods,
            dense_periods=min(self.dense_periods, self.periods) if dense else 0,
        )


#: Parts of the study (``--parts``); the checks run with the cases.
PARTS = ("cases", "elements", "bifurcations", "windows", "zooms")

#: Variants that check a case where we differ from the paper (name -> changed configuration).
VARIANTS: dict[str, Callable[[CaseConfig], CaseConfig]] = {
    "2x sub-steps": lambda c: replace(c, substeps=2 * c.substeps),
    "4x sub-steps": lambda c: replace(c, substeps=4 * c.substeps),
    "20 elements": lambda c: replace(c, elements=20),
    "3x transient": lambda c: replace(c, transient_periods=3 * c.transient_periods),
    "well = -1": lambda c: c.with_value("well", -1),
}


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


# --------------------------------------------------------------------------- comparisons


def wells(result: CaseResult) -> str:
    """``both`` when w_mid changes sign anywhere in the recorded motion (every stroboscopic
    sample and, if kept, the dense trajectory of the last periods), else ``one (+)`` /
    ``one (-)``. (Until issue 15 only the dense window of the last 30 periods counted, which
    decided by chance for a chaotic motion just past the merging of the two local attractors,
    whose visits to the other well are rare.)"""
    w = result.samples[:, 0]
    d = result.dense
    if d is not None and len(d):
        w = np.concatenate([w, d[:, 1]])
    if w.min() < 0.0 < w.max():
        return "both"
    return "one (+)" if w.min() >= 0.0 else "one (-)"


def agreement(case: PaperCase, result: CaseResult) -> str:
    """``yes``, ``partly`` (same kind of motion, other period or other wells) or ``no``."""
    c = result.classification
    ours = c.kind
    if case.kind == LONG:
        if ours == OUR_CHAOTIC:
            return "no"
        return "yes" if ours != OUR_PERIODIC or (c.period or 0) >= 8 else "partly"
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
    """w_mid of the FMU's static buckled state (t = 0) with `elements` elements."""
    with lend(FmuModel.load(fmu), "static") as inst:
        inst.initialize({"elements": elements})
        return float(inst.get(["w_mid"])[0])


@dataclass
class Check:
    """The variants of one differing case and whether each keeps the base classification."""

    case: PaperCase
    base: CaseResult
    variants: dict[str, CaseResult] = field(default_factory=dict)

    def holds(self, name: str) -> bool:
        return self.variants[name].classification.label == self.base.classification.label


# --------------------------------------------------------------------------- the parts


@dataclass
class StudyReport:
    cases: list[tuple[PaperCase, CaseResult]] = field(default_factory=list)
    checks: list[Check] = field(default_factory=list)
    elements: list[CaseResult] = field(default_factory=list)
    statics: list[float] = field(default_factory=list)
    bifurcations: dict[str, list[CaseResult]] = field(default_factory=dict)
    windows: dict[str, list[CaseResult]] = field(default_factory=dict)
    zooms: dict[str, list[CaseResult]] = field(default_factory=dict)


def run_paper_cases(st: StudySettings, batch: Batch) -> list[tuple[PaperCase, CaseResult]]:
    results = batch.run(st.config(c.F, c.Omega) for c in st.cases)
    return list(zip(st.cases, results, strict=True))


def run_checks(cases: Sequence[tuple[PaperCase, CaseResult]], batch: Batch) -> list[Check]:
    """Every variant of every case that does not fully agree with the paper."""
    seen: dict[tuple[float, float], Check] = {}
    for case, r in cases:
        if agreement(case, r) != "yes" and (case.F, case.Omega) not in seen:
            seen[(case.F, case.Omega)] = Check(case, r)
    checks = list(seen.values())
    configs = [v(ch.base.config) for ch in checks for v in VARIANTS.values()]
    results = iter(batch.run(configs))
    for ch in checks:
        ch.variants = {name: next(results) for name in VARIANTS}
    return checks


def _long(st: StudySettings, F: float, Omega: float) -> CaseConfig:
    """A case of the bifurcation diagrams and fine sweeps (no dense window)."""
    return replace(
        st.config(F, Omega, dense=False),
        transient_periods=st.bif_transient,
        sample_periods=st.bif_periods,
    )


def run_bifurcations(st: StudySettings, batch: Batch) -> dict[str, list[CaseResult]]:
    base = _long(st, 0.7, 3500.0)
    return {
        "F": batch.run(base.with_value("F", v) for v in sweep_values(*st.F_range, st.bif_count)),
        "Omega": batch.run(
            base.with_value("Omega", v) for v in sweep_values(*st.Omega_range, st.bif_count)
        ),
    }


def run_windows(st: StudySettings, batch: Batch) -> dict[str, list[CaseResult]]:
    out = {}
    for w in WINDOWS:
        values = sweep_values(w.start, w.stop, st.window_count)
        base = _long(st, w.F, w.Omega)
        out[w.name] = batch.run(base.with_value(w.param, v) for v in values)
    return out


def run_elements(st: StudySettings, batch: Batch) -> tuple[list[CaseResult], list[float]]:
    base = st.config(*st.element_case)
    results = batch.run(replace(base, elements=n) for n in st.element_counts)
    return results, [static_w_mid(st.fmu, n) for n in st.element_counts]


def run_study(
    st: StudySettings, workers: int = 2, progress: bool = True, parts: Sequence[str] = PARTS
) -> StudyReport:
    """The study (the given `parts`) on a local cluster of `workers` processes."""
    rep = StudyReport()
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
        if "zooms" in parts:
            cases = rep.cases or run_paper_cases(st, batch)
            rep.zooms = run_zooms(st, batch, cases)
    return rep


#: Half-widths of the zoomed sweeps around a disagreeing panel (in Omega, in F) and values.
ZOOM_OMEGA, ZOOM_F, ZOOM_COUNT = 30.0, 0.06, 61


def run_zooms(
    st: StudySettings, batch: Batch, cases: Sequence[tuple[PaperCase, CaseResult]]
) -> dict[str, list[CaseResult]]:
    """A fine sweep around every panel that does not fully agree (``ZOOM_COUNT`` values,
    +-ZOOM_OMEGA rad/s, or +-ZOOM_F for the panels over F), with the bifurcation diagrams'
    transient and samples."""
    out: dict[str, list[CaseResult]] = {}
    for case, r in cases:
        if agreement(case, r) == "yes":
            continue
        base = replace(
            st.config(case.F, case.Omega, dense=False),
            transient_periods=st.bif_transient,
            sample_periods=st.bif_periods,
        )
        if case.figure == 2:
            values = sweep_values(case.F - ZOOM_F, case.F + ZOOM_F, ZOOM_COUNT)
            out[case.name] = batch.run(base.with_value("F", v) for v in values)
        else:
            lo, hi = case.Omega - ZOOM_OMEGA, case.Omega + ZOOM_OMEGA
            out[case.name] = batch.run(
                base.with_value("Omega", v) for v in sweep_values(lo, hi, ZOOM_COUNT)
            )
    return out
