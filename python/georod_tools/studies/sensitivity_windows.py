"""Where the main windows of the paper's Figures 3-5 sit in Omega (F = 0.7), per variant: a
coarse scan over Omega, then refinement of each window edge on the classification.

Every case is :func:`georod_tools.analysis.case.run_case` with the same rules (stroboscopic
samples after a stated transient, the core's Lyapunov exponent, :mod:`..analysis.classify`).
The features (:data:`FEATURES`), each an edge of a run of scan points:

- the **period-3 window** (the longest run of period-3 points): its upper end ``p3_top``, its
  lower end ``p3_doubling`` (period 3 -> 6), and the end of its doubling cascade ``p3_chaos``
  (last point of period 3 * 2^n, n >= 0, going down);
- the **period-2 branch** (the longest run of period-2 points): ``p2_doubling`` (2 -> 4),
  ``p2_chaos`` (end of the run of periods 2^n: onset of chaos in the upper well) and ``merge``
  (end of the run of motions that stay in one well: the local chaos spreads over both wells).

An edge lies between a point of the run and its neighbour outside. Each refinement round runs
`points_per_round` equally spaced points inside every bracket and keeps the part where the run
ends (a run tolerates one isolated point outside it, where the start lands on a coexisting
attractor: :func:`_runs`), so the bracket shrinks by ``points_per_round + 1`` per round. All
brackets of all variants advance together, one Dask batch per round. The scan range of a
variant is the reference range scaled by the variant's first frequency over the reference's, so
a variant that only rescales the frequencies finds its windows at the same relative places.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from georod_tools.analysis.case import CaseConfig, CaseResult, run_case
from georod_tools.analysis.classify import PERIODIC
from georod_tools.analysis.failure import CaseFailure
from georod_tools.analysis.sweep import local_cluster, run_on_worker
from georod_tools.fmu.worker import FmuPayload, install

Member = Callable[[CaseResult], bool]


def period(r: CaseResult) -> int | None:
    c = r.classification
    return c.period if c.kind == PERIODIC else None


def one_well(r: CaseResult) -> bool:
    """The stroboscopic w_mid keeps its sign (the motion stays in one well)."""
    w = r.samples[:, 0]
    return not (w.min() < 0.0 < w.max())


def _cascade(base: int) -> Member:
    return lambda r: (p := period(r)) is not None and p % base == 0 and _pow2(p // base)


def _pow2(n: int) -> bool:
    return n >= 1 and n & (n - 1) == 0


def _is(k: int) -> Member:
    return lambda r: period(r) == k


@dataclass(frozen=True)
class Feature:
    """An edge of the run of scan points where `member` holds, the run chosen by the most
    `anchor` points; `side` ``top`` (upper end) or ``bottom``. `paper`: the Omega bracket the
    paper's panels give for it."""

    name: str
    label: str
    anchor: Member
    member: Member
    side: str
    paper: tuple[float, float]


FEATURES: tuple[Feature, ...] = (
    Feature("p3_top", "upper end of period 3", _is(3), _is(3), "top", (3600.0, 4000.0)),
    Feature("p3_doubling", "period 3 -> 6", _is(3), _is(3), "bottom", (3480.0, 3500.0)),
    Feature(
        "p3_chaos", "end of the 3*2^n cascade", _is(3), _cascade(3), "bottom", (3430.0, 3460.0)
    ),
    Feature("p2_doubling", "period 2 -> 4", _is(2), _is(2), "bottom", (4150.0, 4200.0)),
    Feature("p2_chaos", "end of the 2^n cascade", _is(2), _cascade(2), "bottom", (4050.0, 4150.0)),
    Feature("merge", "one well -> both wells", _is(2), one_well, "bottom", (4000.0, 4050.0)),
)


@dataclass(frozen=True)
class WindowSettings:
    """F, the reference scan (Omega range and count), the refinement rounds and the case
    lengths (transient and sampled periods: see docs/paper_sensitivity.md for the choice)."""

    F: float = 0.7
    scan: tuple[float, float] = (3250.0, 4600.0)
    scan_count: int = 55
    rounds: int = 3
    points_per_round: int = 4
    transient: int = 1000
    periods: int = 300

    def config(self, fmu: Path, elements: int, substeps: int, Omega: float) -> CaseConfig:
        return CaseConfig(
            fmu=str(fmu),
            F=self.F,
            Omega=float(f"{Omega:.10g}"),
            elements=elements,
            substeps=substeps,
            transient_periods=self.transient,
            sample_periods=self.periods,
        )


class Runner:
    """Runs batches of cases (any FMUs) on one local Dask cluster, caching each case."""

    def __init__(self, workers: int, progress: bool = True) -> None:
        from dask.distributed import Client

        self.cluster = local_cluster(workers)
        self.client = Client(self.cluster)
        self.progress = progress
        self.installed: dict[str, FmuPayload] = {}
        self.cache: dict[CaseConfig, CaseResult | None] = {}

    def close(self) -> None:
        self.client.close()
        self.cluster.close()

    def __enter__(self) -> Runner:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _payload(self, fmu: str) -> FmuPayload:
        if fmu not in self.installed:
            self.installed[fmu] = FmuPayload.read(fmu)
            install(self.client, self.installed[fmu])
        return self.installed[fmu]

    def run(self, configs: Sequence[CaseConfig], desc: str = "cases") -> list[CaseResult | None]:
        """Results of `configs` in order; a failed case is None (reported on stderr)."""
        from dask.distributed import as_completed

        todo = [c for c in dict.fromkeys(configs) if c not in self.cache]
        if todo:
            payloads = [self._payload(c.fmu) for c in todo]
            futures = self.client.map(
                run_on_worker,
                todo,
                [c.Omega for c in todo],
                [p.sha256 for p in payloads],
                [p.name for p in payloads],
                case_fn=run_case,
                pure=False,
            )
            index = {f.key: c for f, c in zip(futures, todo, strict=True)}
            bar = None
            if self.progress:
                from tqdm import tqdm

                bar = tqdm(total=len(futures), desc=desc, unit="case")
            for fut in as_completed(futures):
                cfg = index[fut.key]
                try:
                    got = fut.result()
                except Exception as e:  # noqa: BLE001 - a lost worker: the case counts as failed
                    got = CaseFailure(cfg.Omega, "worker", f"{type(e).__name__}: {e}")
                fut.release()
                if isinstance(got, CaseFailure):
                    print(
                        f"case failed ({Path(cfg.fmu).name}, Omega {cfg.Omega}): {got.reason}",
                        file=sys.stderr,
                    )
                    self.cache[cfg] = None
                else:
                    self.cache[cfg] = got
                if bar is not None:
                    bar.update(1)
            if bar is not None:
                bar.close()
        return [self.cache[c] for c in configs]


@dataclass
class Edge:
    """A located feature: the bracket ``(lo, hi)`` in Omega (NaN when not found) and a note."""

    feature: str
    lo: float = math.nan
    hi: float = math.nan
    note: str = ""

    @property
    def position(self) -> float:
        return 0.5 * (self.lo + self.hi)

    @property
    def width(self) -> float:
        return self.hi - self.lo


@dataclass
class Located:
    """The scan of one variant (its configs and results) and its located edges."""

    scan: list[CaseConfig]
    results: list[CaseResult | None]
    edges: dict[str, Edge] = field(default_factory=dict)
    refined: list[CaseResult] = field(default_factory=list)


def _runs(flags: Sequence[bool], gap: int = 1) -> list[tuple[int, int]]:
    """Runs ``(first, last)`` of True in `flags`, two runs separated by at most `gap` False
    entries counting as one (an isolated point where the start lands on a coexisting attractor
    does not end a window: the reference shows a period-9 orbit at Omega = 3675 inside its
    period-3 window, for instance)."""
    out: list[tuple[int, int]] = []
    for i, f in enumerate(flags):
        if not f:
            continue
        if out and i - out[-1][1] - 1 <= gap:
            out[-1] = (out[-1][0], i)
        else:
            out.append((i, i))
    return out


def initial_bracket(feature: Feature, omegas: Sequence[float], results: Sequence) -> Edge:
    """The bracket of `feature` from the scan (sorted by Omega)."""
    ok = [r is not None and feature.member(r) for r in results]
    anchors = [r is not None and feature.anchor(r) for r in results]
    runs = [(a, b) for a, b in _runs(ok) if any(anchors[a : b + 1])]
    if not runs:
        return Edge(feature.name, note="not found in the scan")
    a, b = max(runs, key=lambda ab: sum(anchors[ab[0] : ab[1] + 1]))
    if feature.side == "bottom":
        if a == 0:
            return Edge(feature.name, note=f"below the scan (< {omegas[0]:g})")
        return Edge(feature.name, omegas[a - 1], omegas[a])
    if b == len(omegas) - 1:
        return Edge(feature.name, note=f"above the scan (> {omegas[-1]:g})")
    return Edge(feature.name, omegas[b], omegas[b + 1])


def refine(edge: Edge, side: str, points: Sequence[tuple[float, bool]]) -> None:
    """Narrows `edge` from the members (True) / non-members among `points` inside it: the run
    that contains the bracket's inner end (with the same gap tolerance as the scan) ends at the
    new inner end, and the point beyond it is the new outer end."""
    inner, outer = (edge.hi, edge.lo) if side == "bottom" else (edge.lo, edge.hi)
    pts = sorted([(inner, True), (outer, False), *points], reverse=(side == "bottom"))
    flags = [f for _, f in pts]
    first_run = _runs(flags)[0]  # starts at the inner end (index 0, a member)
    end = first_run[1]
    new_inner, new_outer = pts[end][0], pts[end + 1][0]
    if side == "bottom":
        edge.lo, edge.hi = new_outer, new_inner
    else:
        edge.lo, edge.hi = new_inner, new_outer


def scan_omegas(ws: WindowSettings, scale: float) -> list[float]:
    lo, hi = ws.scan
    return [float(f"{x:.6g}") for x in np.linspace(lo * scale, hi * scale, ws.scan_count)]


def locate(
    runner: Runner,
    ws: WindowSettings,
    variants: Sequence[tuple[str, Path, int, int, float]],
) -> dict[str, Located]:
    """Locates every feature of every variant ``(name, fmu, elements, substeps, scale)``."""
    out: dict[str, Located] = {}
    scans = {
        name: [ws.config(fmu, n, s, om) for om in scan_omegas(ws, scale)]
        for name, fmu, n, s, scale in variants
    }
    flat = [c for cfgs in scans.values() for c in cfgs]
    results = iter(runner.run(flat, "scan"))
    for name, cfgs in scans.items():
        res = [next(results) for _ in cfgs]
        omegas = [c.Omega for c in cfgs]
        loc = Located(cfgs, res)
        loc.edges = {f.name: initial_bracket(f, omegas, res) for f in FEATURES}
        out[name] = loc
    base = {name: cfgs[0] for name, cfgs in scans.items()}
    features = {f.name: f for f in FEATURES}
    k = ws.points_per_round
    for rnd in range(ws.rounds):
        todo = []
        for name, loc in out.items():
            for e in loc.edges.values():
                if not math.isfinite(e.lo):
                    continue
                for j in range(1, k + 1):
                    om = float(f"{e.lo + j * e.width / (k + 1):.10g}")
                    todo.append((name, e, replace(base[name], Omega=om)))
        got = runner.run([c for _, _, c in todo], f"refinement {rnd + 1}/{ws.rounds}")
        points: dict[int, list[tuple[float, bool]]] = {}
        for (name, e, cfg), r in zip(todo, got, strict=True):
            f = features[e.feature]
            if r is not None and all(x.config != cfg for x in out[name].refined):
                out[name].refined.append(r)
            points.setdefault(id(e), []).append((cfg.Omega, r is not None and f.member(r)))
        for loc in out.values():
            for e in loc.edges.values():
                if id(e) in points:
                    refine(e, features[e.feature].side, points[id(e)])
    return out
