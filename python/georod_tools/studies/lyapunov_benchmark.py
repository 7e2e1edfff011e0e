"""The Lyapunov methods side by side (``georod-tools benchmark lyapunov``): one bifurcation
diagram over F with the largest exponent computed by

- ``core``: the core's tangent map (one FMU instance, ``lyapunov_count = 1``), what the analyses
  use;
- ``twin``: the two-instance cross-check (:mod:`georod_tools.analysis.twin`: a second instance
  restarted from the reference's serialized state and kicked through ``perturbation``), the
  method the analyses used before the core had the exponent;
- ``plain``: no exponent (one instance), the cost of the trajectory alone;

on the same trajectories and sub-steps, each as a Dask sweep with 1, 2, ... local workers. It
reports the wall time of each sweep (cluster already started; its start is timed apart), the
ratio twin / core, the cost per midpoint sub-step against the core's own loop (``georod
bench-steps``, with and without the tangent map), and how far the two exponents agree.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from georod_tools.analysis.case import CaseConfig, CaseResult, run_case, run_case_plain
from georod_tools.analysis.sweep import local_cluster, run_sweep, sweep_values
from georod_tools.analysis.twin import twin_case
from georod_tools.fmu import FmuModel, core_command
from georod_tools.report.figures import plt, save
from georod_tools.report.tables import markdown, write_csv, write_text

METHODS: dict[str, Callable[[CaseConfig], CaseResult]] = {
    "core": run_case,
    "twin": twin_case,
    "plain": run_case_plain,
}


@dataclass(frozen=True)
class BenchSettings:
    """count values of F in F_range at Omega, transient + periods each, N sub-steps per period,
    10 elements. N = 180: the sub-steps of the former sweeps at Omega = 3500 (dt_max = 1e-5 s
    cutting each of 20 communication steps per period into 9), so the twin runs the former
    analyses' trajectories and steps."""

    fmu: str
    count: int = 100
    F_range: tuple[float, float] = (0.4, 2.0)
    Omega: float = 3500.0
    transient: int = 200
    periods: int = 200
    substeps: int = 180
    workers: tuple[int, ...] = (1, 2)
    bench_steps: int = 20_000

    @classmethod
    def quick(cls, fmu: str) -> BenchSettings:
        return cls(fmu=fmu, count=6, transient=50, periods=50, workers=(1, 2), bench_steps=2000)

    def base(self) -> CaseConfig:
        return CaseConfig(
            fmu=self.fmu,
            Omega=self.Omega,
            substeps=self.substeps,
            transient_periods=self.transient,
            sample_periods=self.periods,
        )

    def substeps_of(self, method: str) -> int:
        """Midpoint sub-steps a sweep takes (the twin's second instance runs the sampled
        periods)."""
        per_case = (self.transient + self.periods) * self.substeps
        if method == "twin":
            per_case += self.periods * self.substeps
        return self.count * per_case


def default_workers() -> tuple[int, ...]:
    """1, 2, 4, ... up to the machine's cores."""
    cores = os.cpu_count() or 1
    out, w = [], 1
    while w <= cores:
        out.append(w)
        w *= 2
    return tuple(out)


def core_loop_us(st: BenchSettings) -> dict[str, float]:
    """Microseconds per sub-step of the core's own loop (``georod bench-steps``) at the
    benchmark's step, without and with the tangent map (median of 3)."""
    dt = 2.0 * np.pi / st.Omega / st.substeps
    model = FmuModel.load(st.fmu)
    scene = str(model.unzipdir / "resources" / "scene.toml")
    out = {}
    for name, extra in (("plain", {}), ("core", {"lyapunov_count": 1})):
        sets = {"F": 1.2, "Omega": st.Omega, "dt_max": dt, **extra}
        times = [core_command.bench_steps(scene, sets, st.bench_steps, dt) for _ in range(3)]
        out[name] = float(np.median(times)) / st.bench_steps * 1e6
    return out


def run_methods(
    st: BenchSettings, progress: bool = True, say: Callable[[str], None] = print
) -> tuple[list[dict[str, object]], dict[str, list[CaseResult]]]:
    """Every method with every worker count; rows of timings and the results (of the run with
    the most workers) by method."""
    values = sweep_values(*st.F_range, st.count)
    base = st.base()
    rows: list[dict[str, object]] = []
    results: dict[str, list[CaseResult]] = {}
    for workers in st.workers:
        t0 = time.perf_counter()
        with local_cluster(workers) as cluster:
            started = time.perf_counter() - t0
            address = cluster.scheduler_address
            # every worker loads the FMU and imports each method before anything is timed
            for case_fn in METHODS.values():
                run_sweep(
                    replace(base, transient_periods=1, sample_periods=12),
                    "F",
                    values[:workers],
                    scheduler=address,
                    progress=False,
                    case_fn=case_fn,
                )
            for method, case_fn in METHODS.items():
                t1 = time.perf_counter()
                got = run_sweep(
                    base, "F", values, scheduler=address, progress=progress, case_fn=case_fn
                )
                wall = time.perf_counter() - t1
                results[method] = got
                case_s = sum(r.wall_time for r in got)
                rows.append(
                    {
                        "method": method,
                        "workers": workers,
                        "wall_s": round(wall, 2),
                        "cluster_start_s": round(started, 2),
                        "sum_case_s": round(case_s, 2),
                        "substeps": st.substeps_of(method),
                        "us_per_substep": round(case_s / st.substeps_of(method) * 1e6, 3),
                    }
                )
                say(f"{method}, {workers} worker(s): {wall:.1f} s ({case_s:.1f} s in cases)")
    return rows, results


def add_ratios(st: BenchSettings, rows: list[dict[str, object]], loop: dict[str, float]) -> None:
    """twin / core wall time at the same worker count, speed-up against 1 worker, and the cost
    per sub-step against the core's own loop for the same mix of sub-steps (core: plain steps
    in the transient, steps with the tangent map in the sampled periods; twin, plain: plain)."""
    wall = {(r["method"], r["workers"]): float(r["wall_s"]) for r in rows}  # type: ignore[arg-type]
    mixed = (st.transient * loop["plain"] + st.periods * loop["core"]) / (st.transient + st.periods)
    for r in rows:
        m, w = r["method"], r["workers"]
        r["wall_vs_core"] = round(wall[(m, w)] / wall[("core", w)], 2)
        one = wall.get((m, 1))
        r["speedup_vs_1_worker"] = round(one / wall[(m, w)], 2) if one else ""
        ref = mixed if m == "core" else loop["plain"]
        r["core_loop_us"] = round(ref, 3)
        r["vs_core_loop"] = round(float(r["us_per_substep"]) / ref, 2)  # type: ignore[arg-type]


def agreement_rows(results: dict[str, list[CaseResult]]) -> list[dict[str, object]]:
    """Per value of F: the class and exponent of the core and of the twin."""
    rows = []
    for c, t in zip(results["core"], results["twin"], strict=True):
        rows.append(
            {
                "F": c.config.F,
                "class_core": c.classification.label,
                "lyapunov_core": round(c.exponent_per_period, 4),
                "class_twin": t.classification.label,
                "lyapunov_twin": round(t.exponent_per_period, 4),
                "same_samples": bool(np.array_equal(c.samples, t.samples)),
            }
        )
    return rows


def plot_exponents(results: dict[str, list[CaseResult]], path: Path) -> Path:
    """The two exponents against F."""
    fig, ax = plt.subplots(figsize=(8, 3.8), constrained_layout=True)
    for method, style in (("core", ".-"), ("twin", "x")):
        res = results[method]
        ax.plot(
            [r.config.F for r in res],
            [r.exponent_per_period for r in res],
            style,
            ms=4,
            lw=0.7,
            label=f"{method}",
        )
    ax.axhline(0.05, color="tab:red", lw=0.6, ls="--", label="chaos threshold")
    ax.set(
        xlabel="F [N/m]",
        ylabel="largest Lyapunov exponent [1/period]",
        title="core tangent map against the two-instance twin, same trajectories",
    )
    ax.legend(fontsize=8)
    return save(fig, path, dpi=110)


def summary(
    st: BenchSettings,
    rows: Sequence[dict[str, object]],
    agree: Sequence[dict],
    loop: dict[str, float],
) -> str:
    same = sum(a["class_core"] == a["class_twin"] for a in agree)
    diffs = [abs(float(a["lyapunov_core"]) - float(a["lyapunov_twin"])) for a in agree]
    cols = (
        "method",
        "workers",
        "wall_s",
        "wall_vs_core",
        "speedup_vs_1_worker",
        "sum_case_s",
        "us_per_substep",
        "core_loop_us",
        "vs_core_loop",
        "cluster_start_s",
    )
    return "\n".join(
        [
            f"{st.count} values of F in [{st.F_range[0]:g}, {st.F_range[1]:g}] at Omega = "
            f"{st.Omega:g}, {st.transient} + {st.periods} periods, T/{st.substeps} sub-steps, "
            f"10 elements; {os.cpu_count()} CPU cores. wall_s: the sweep on a running local "
            "cluster (its start: cluster_start_s); us_per_substep: time in the cases over "
            "their midpoint sub-steps; core_loop_us: georod bench-steps at the same step, "
            f"{loop['plain']:.3f} us plain and {loop['core']:.3f} us with the tangent map "
            "(core: weighted by its transient and sampled periods).",
            "",
            markdown(list(rows), cols),
            "",
            f"Classification equal for {same} of {len(agree)} values; |exponent core - twin| "
            f"median {np.median(diffs):.3g}, max {max(diffs):.3g} per period.",
        ]
    )


def run_lyapunov_benchmark(
    st: BenchSettings, out: Path, progress: bool = True, say: Callable[[str], None] = print
) -> list[Path]:
    """The whole benchmark into `out`; prints and returns the table's files."""
    loop = core_loop_us(st)
    rows, results = run_methods(st, progress, say)
    add_ratios(st, rows, loop)
    agree = agreement_rows(results)
    text = summary(st, rows, agree, loop)
    say(text)
    return [
        write_csv(rows, out / "lyapunov_methods.csv"),
        write_csv(agree, out / "lyapunov_agreement.csv"),
        write_text(text, out / "lyapunov_methods.md"),
        plot_exponents(results, out / "lyapunov_methods.png"),
    ]
