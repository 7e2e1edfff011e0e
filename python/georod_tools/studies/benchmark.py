"""Work-precision benchmark of the BuckledBeam FMU (through fmpy), side by side with Exudyn
(``georod-tools benchmark precision``; docs/benchmark.md shows the results).

1. the motion at the benchmark point (10 elements, F = 0.7, Omega = 4500) is periodic
   (stroboscopic samples and the core's Lyapunov exponent);
2. the time-step error of ``w_mid`` over a fixed horizon of 20 forcing periods from the static
   buckled state, at 8 .. 1024 steps per period, against a reference with a much smaller step
   whose convergence is shown by successive refinements; error at the final time and the largest
   error on the communication grid; run time of the integration alone (median of repetitions;
   instantiation and the static initial solve excluded), and the core's own loop;
3. the same for Exudyn (:mod:`.exudyn_beam`), each method against its own converged reference,
   and the ratio of run times at equal error (log-log interpolation);
4. the two models side by side: static ``w_mid`` and the first natural frequencies about the
   buckled state for 10, 20, 40 elements (georod's from the core: the FMU's initial state and
   ``georod modes``);
5. the spatial error (4 .. 160 elements against 320, same step);
6. seconds per simulated forcing period for 10 .. 10000 elements (linear growth).
"""

from __future__ import annotations

import cProfile
import io
import math
import pstats
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from georod_tools.analysis.case import CaseConfig, run_case
from georod_tools.studies.bench_beam import (
    BeamScene,
    convergence_rows,
    core_seconds,
    default_fmu,
    errors,
    fmu_beam,
    fmu_run,
    model_quantities,
)
from georod_tools.studies.exudyn_beam import ExudynBeam

Log = Callable[[str], None]
#: Parts of the benchmark (``--parts``).
PARTS = ("periodic", "time", "models", "space", "scaling", "profile")


@dataclass
class Report:
    sections: list[str] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)

    def add(self, title: str, text: str) -> None:
        self.sections.append(f"### {title}\n\n{text}\n")


@dataclass
class Settings:
    """Sizes of the benchmark (``quick`` = the smoke test's)."""

    periods: int = 20
    steps: tuple[int, ...] = (8, 16, 32, 64, 128, 256, 512, 1024)
    ref_steps: tuple[int, ...] = (4096, 8192, 16384)
    exudyn_ref_steps: tuple[int, ...] = (2048, 4096, 8192)
    repeats: int = 5
    exudyn_repeats: int = 3
    model_elements: tuple[int, ...] = (10, 20, 40)
    space_elements: tuple[int, ...] = (4, 8, 16, 20, 40, 80, 160)
    space_ref_elements: int = 320
    space_steps: int = 256
    scaling_elements: tuple[int, ...] = (10, 100, 1000, 10000)
    scaling_steps: int = 100
    scaling_periods: tuple[int, ...] = (50, 20, 5, 2)
    periodic_transient: int = 100
    periodic_samples: int = 100
    sub_comm: int = 8

    @classmethod
    def quick(cls) -> Settings:
        return cls(
            periods=2,
            steps=(8, 16, 32),
            ref_steps=(128, 256),
            exudyn_ref_steps=(128, 256),
            repeats=1,
            exudyn_repeats=1,
            model_elements=(4, 8),
            space_elements=(4, 8),
            space_ref_elements=16,
            space_steps=32,
            scaling_elements=(10, 100),
            scaling_periods=(2, 1),
            periodic_transient=5,
            periodic_samples=20,
        )


def study_periodicity(scene: BeamScene, s: Settings, fmu: Path | None, log: Log) -> str:
    cfg = CaseConfig(
        fmu=str(fmu or default_fmu()),
        F=scene.F,
        Omega=scene.Omega,
        elements=10,
        substeps=256,
        transient_periods=s.periodic_transient,
        sample_periods=s.periodic_samples,
        align_periods=min(10, s.periodic_samples // 2),
    )
    res = run_case(cfg)
    c = res.classification
    smp = res.samples
    # the first periods (the benchmark horizon): stroboscopic samples from t = 0
    with fmu_beam(scene, 10, scene.period / 256, 256, fmu) as beam:
        w, _, _ = beam.integrate(256 * s.periods)
    strobe = w[::256]
    lines = [
        f"Stroboscopic samples at t = kT after {cfg.transient_periods} transient periods "
        f"(T/256): class **{c.label}** ({c.note}); largest Lyapunov exponent "
        f"{res.exponent_per_period:.4f} per period.",
        "",
        "Last 4 samples (w_mid, v_mid): " + ", ".join(f"({a:.6f}, {b:.2f})" for a, b in smp[-4:]),
        "",
        f"w_mid at t = kT over the benchmark horizon (k = 0..{len(strobe) - 1}): "
        + ", ".join(f"{x:.4f}" for x in strobe),
    ]
    log(lines[0])
    return "\n".join(lines)


def study_time_error(
    scene: BeamScene, s: Settings, fmu: Path | None, use_exudyn: bool, log: Log
) -> tuple[list[dict[str, object]], list[dict[str, object]]]:
    """Work-precision rows and reference-convergence rows."""
    P = s.periods
    rows: list[dict[str, object]] = []
    conv: list[dict[str, object]] = []
    # FMU reference: communication step T/1024 (or the finest benchmark step), sub-steps T/n_ref
    c_ref = max(s.steps)
    refs = {}
    for n in s.ref_steps:
        r = fmu_run(scene, n, P, 1, comm_per_period=c_ref, fmu=fmu)
        refs[n] = r.w
        log(f"fmu reference T/{n}: w_mid(end) = {r.w[-1]:.12f} ({r.seconds:.2f} s)")
    conv += convergence_rows("fmu", refs)
    ref = refs[max(refs)]  # on the T/c_ref grid
    for n in s.steps:
        r = fmu_run(scene, n, P, s.repeats, fmu=fmu)
        ef, em = errors(r.w, ref)
        core = core_seconds(scene, n, P)
        rows.append(
            {
                "method": "fmu",
                "steps_per_period": n,
                "comm_per_period": n,
                "err_final": ef,
                "err_max": em,
                "seconds": r.seconds,
                "seconds_min": min(r.times),
                "newton_per_step": r.extra["newton"] / (P * n),
                "core_seconds": core,
            }
        )
        log(f"fmu T/{n}: err_final {ef:.3e} err_max {em:.3e} {r.seconds:.4f} s (core alone {core})")
        if n >= s.sub_comm and n % s.sub_comm == 0:
            r2 = fmu_run(scene, n, P, s.repeats, comm_per_period=s.sub_comm, fmu=fmu)
            ef2, em2 = errors(r2.w, ref)
            rows.append(
                {
                    "method": f"fmu_comm_T/{s.sub_comm}",
                    "steps_per_period": n,
                    "comm_per_period": s.sub_comm,
                    "err_final": ef2,
                    "err_max": em2,
                    "seconds": r2.seconds,
                    "seconds_min": min(r2.times),
                    "newton_per_step": math.nan,
                    "core_seconds": math.nan,
                }
            )
    if use_exudyn:
        beam = ExudynBeam(scene, 10)
        try:
            erefs = {}
            for n in s.exudyn_ref_steps:
                r = beam.run(n, P, 0, record=True)
                erefs[n] = r.w
                log(f"exudyn reference T/{n}: w_mid(end) = {r.w[-1]:.12f}")
            conv += convergence_rows("exudyn", erefs)
            eref = erefs[max(erefs)]
            for n in s.steps:
                r = beam.run(n, P, s.exudyn_repeats, record=True)
                ef, em = errors(r.w, eref)
                rows.append(
                    {
                        "method": "exudyn",
                        "steps_per_period": n,
                        "comm_per_period": n,
                        "err_final": ef,
                        "err_max": em,
                        "seconds": r.seconds,
                        "seconds_min": min(r.times),
                        "newton_per_step": r.extra["newton"] / (P * n),
                        "core_seconds": math.nan,
                    }
                )
                log(f"exudyn T/{n}: err_final {ef:.3e} err_max {em:.3e} {r.seconds:.4f} s")
            # the two converged references against each other (spatial model difference)
            m = (len(eref) - 1) // (len(ref) - 1) if len(eref) > len(ref) else 1
            k = (len(ref) - 1) // (len(eref) - 1) if len(ref) > len(eref) else 1
            d = np.abs(eref[::m] - ref[::k])
            conv.append(
                {
                    "method": "exudyn - fmu (references)",
                    "n_coarse": 0,
                    "n_fine": 0,
                    "diff_final": float(d[-1]),
                    "diff_max": float(d.max()),
                }
            )
        finally:
            beam.close()
    return rows, conv


def study_models(
    scene: BeamScene, s: Settings, fmu: Path | None, use_exudyn: bool, log: Log
) -> list[dict[str, object]]:
    rows: list[dict[str, object]] = []
    for ne in s.model_elements:
        q = model_quantities(scene, ne, 3, fmu)
        row: dict[str, object] = {
            "elements": ne,
            "w_static_fmu": q.w_static_fmu,
            "fmu_minus_modes": q.w_static_fmu - q.w_static_core,
        }
        for i in range(3):
            row[f"omega{i + 1}_core"] = q.omegas[i]
        if use_exudyn:
            eb = ExudynBeam(scene, ne)
            try:
                fe = eb.frequencies(3)
                row["w_static_exudyn"] = eb.w_static
                for i in range(3):
                    row[f"omega{i + 1}_exudyn"] = float(fe[i])
            finally:
                eb.close()
        rows.append(row)
        log(f"models, {ne} elements: {row}")
    return rows


def study_space(scene: BeamScene, s: Settings, fmu: Path | None, log: Log) -> list[dict]:
    n = s.space_steps
    P = s.periods
    ref = fmu_run(scene, n, P, 1, elements=s.space_ref_elements, fmu=fmu)
    rows = []
    for ne in s.space_elements:
        r = fmu_run(scene, n, P, 3 if ne <= 40 else 1, elements=ne, fmu=fmu)
        ef, em = errors(r.w, ref.w)
        rows.append(
            {
                "elements": ne,
                "w_static": float(r.w[0]),
                "err_static": abs(float(r.w[0] - ref.w[0])),
                "err_final": ef,
                "err_max": em,
                "seconds": r.seconds,
            }
        )
        log(f"space {ne}: err_final {ef:.3e} err_max {em:.3e} {r.seconds:.3f} s")
    rows.append(
        {
            "elements": s.space_ref_elements,
            "w_static": float(ref.w[0]),
            "err_static": 0.0,
            "err_final": 0.0,
            "err_max": 0.0,
            "seconds": ref.seconds,
        }
    )
    return rows


def study_scaling(scene: BeamScene, s: Settings, fmu: Path | None, log: Log) -> list[dict]:
    n = s.scaling_steps
    rows = []
    for ne, periods in zip(s.scaling_elements, s.scaling_periods, strict=False):
        t0 = time.perf_counter()
        with fmu_beam(scene, ne, scene.period / n, n, fmu) as beam:
            t_init = time.perf_counter() - t0
            # one untimed period first (it also counts the Newton corrections), then timed
            _, _, newton_count = beam.integrate(n, count_newton=True)
            reps = [beam.integrate(n * periods) for _ in range(3 if ne <= 1000 else 1)]
        secs = statistics.median(x[1] for x in reps)
        newton = newton_count / n
        rows.append(
            {
                "elements": ne,
                "periods_timed": periods,
                "seconds_per_period": secs / periods,
                "us_per_step_per_element": secs / (periods * n) / ne * 1e6,
                "newton_per_step": newton,
                "init_seconds": t_init,
            }
        )
        log(f"scaling {ne}: {secs / periods:.4f} s per period")
    return rows


def profile_fmu(scene: BeamScene, n: int, periods: int, fmu: Path | None) -> str:
    """cProfile of the FMU integration loop: where the Python side spends its time."""
    with fmu_beam(scene, 10, scene.period / n, n, fmu) as beam:
        beam.integrate(n)
        prof = cProfile.Profile()
        prof.enable()
        beam.integrate(periods * n)
        prof.disable()
    buf = io.StringIO()
    pstats.Stats(prof, stream=buf).sort_stats("tottime").print_stats(8)
    lines = [ln for ln in buf.getvalue().splitlines() if ln.strip()]
    return "\n".join(lines[:20])
