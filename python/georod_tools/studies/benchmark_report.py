"""The figures and the driver of the work-precision benchmark (:mod:`.benchmark`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from georod_tools.report.figures import plt, save
from georod_tools.report.tables import grid, write_csv, write_text
from georod_tools.studies.bench_beam import BeamScene, equal_error_ratio, machine_load
from georod_tools.studies.benchmark import (
    PARTS,
    Log,
    Report,
    Settings,
    profile_fmu,
    study_models,
    study_periodicity,
    study_scaling,
    study_space,
    study_time_error,
)
from georod_tools.studies.exudyn_beam import exudyn_status


def plot_work_precision(rows: Sequence[dict[str, object]], path: Path, which: str) -> Path:
    fig, ax = plt.subplots(figsize=(7, 5))
    labels = {
        "fmu": "georod FMU via fmpy (comm. step = dt)",
        "exudyn": "Exudyn 2D geom. exact beam, trapezoidal",
    }
    methods = sorted({str(r["method"]) for r in rows})
    for m in methods:
        pts = sorted(
            (float(r["seconds"]), float(r[which]), int(r["steps_per_period"]))  # type: ignore[arg-type]
            for r in rows
            if r["method"] == m
        )
        label = labels.get(m, f"georod FMU, comm. step T/{m.split('/')[-1]}, sub-steps = dt")
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=label)
        for t, e, n in pts:
            ax.annotate(str(n), (t, e), textcoords="offset points", xytext=(4, 3), fontsize=7)
    core = sorted(  # by step count (the core's times are single noisy points on a busy machine)
        (float(r[which]), float(r["core_seconds"]))  # type: ignore[arg-type]
        for r in rows
        if r["method"] == "fmu" and not math.isnan(float(r["core_seconds"]))  # type: ignore[arg-type]
    )
    if core:
        ax.loglog(
            [p[1] for p in core],
            [p[0] for p in core],
            "s--",
            alpha=0.6,
            label="georod Rust core alone (bench-steps, no FMI)",
        )
    ax.set_xlabel("run time of the integration [s] (20 forcing periods, median)")
    what = "at the final time" if which == "err_final" else "max over the horizon"
    ax.set_ylabel(f"|error of w_mid| {what} [m]")
    ax.set_title(
        "BuckledBeam, 10 elements, F = 0.7, Omega = 4500: work-precision\n"
        "(labels: steps per forcing period)",
        fontsize=10,
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save(fig, path, dpi=120)


def plot_scaling(rows: Sequence[dict[str, object]], path: Path) -> Path:
    ne = np.array([float(r["elements"]) for r in rows])  # type: ignore[arg-type]
    t = np.array([float(r["seconds_per_period"]) for r in rows])  # type: ignore[arg-type]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.loglog(ne, t, "o-", label="FMU via fmpy, dt = T/100")
    ax.loglog(ne, t[-1] * ne / ne[-1], "k--", alpha=0.5, label="linear in elements")
    ax.set_xlabel("elements [1]")
    ax.set_ylabel("run time per forcing period [s]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return save(fig, path, dpi=120)


def run_benchmark(
    out: Path,
    quick: bool = False,
    use_exudyn: bool = True,
    fmu: Path | None = None,
    parts: Sequence[str] = PARTS,
    log: Log = print,
) -> Report:
    """The benchmark (the given `parts`); every table, CSV and figure (``benchmark_*.png``) into
    the folder `out`, and benchmark.md with all tables."""
    scene = BeamScene()
    s = Settings.quick() if quick else Settings()
    ok, version = exudyn_status()
    if use_exudyn and not ok:
        log(f"Exudyn not available ({version}): its parts are skipped")
    use_exudyn = use_exudyn and ok
    rep = Report()
    rep.add("Machine", f"{machine_load()} at start; exudyn: {version if ok else 'missing'}")
    if "periodic" in parts:
        rep.add("Periodicity", study_periodicity(scene, s, fmu, log))
    if "time" in parts:
        rows, conv = study_time_error(scene, s, fmu, use_exudyn, log)
        rep.files.append(write_csv(rows, out / "work_precision.csv"))
        rep.files.append(write_csv(conv, out / "reference_convergence.csv"))
        rep.add(
            "Reference convergence",
            grid(
                ["method", "coarse", "fine", "|diff| final", "max |diff|"],
                [
                    [r["method"], r["n_coarse"], r["n_fine"], r["diff_final"], r["diff_max"]]
                    for r in conv
                ],
            ),
        )
        rep.add(
            "Work-precision",
            grid(
                [
                    "method",
                    "steps/T",
                    "comm/T",
                    "err final",
                    "err max",
                    "seconds",
                    "corrections/step",
                    "core s",
                ],
                [
                    [
                        r["method"],
                        r["steps_per_period"],
                        r["comm_per_period"],
                        r["err_final"],
                        r["err_max"],
                        r["seconds"],
                        r["newton_per_step"],
                        r["core_seconds"],
                    ]
                    for r in rows
                ],
            ),
        )
        for which in ("err_final", "err_max"):
            rep.files.append(
                plot_work_precision(
                    rows, out / f"benchmark_work_precision_{which.split('_')[1]}.png", which
                )
            )
            ex = [(float(r[which]), float(r["seconds"])) for r in rows if r["method"] == "exudyn"]
            for method in dict.fromkeys(str(r["method"]) for r in rows if r["method"] != "exudyn"):
                fm = [(float(r[which]), float(r["seconds"])) for r in rows if r["method"] == method]
                ratios = equal_error_ratio(fm, ex)
                if not ratios:
                    continue
                rep.add(
                    f"Run-time ratio Exudyn / {method} at equal error ({which})",
                    grid(
                        ["error", f"{method} s", "Exudyn s (interp.)", "ratio"],
                        [list(r) for r in ratios],
                    ),
                )
                log(
                    f"ratio Exudyn / {method} at equal {which}: "
                    + ", ".join(f"{r[3]:.1f}" for r in ratios)
                )
    if "models" in parts:
        mrows = study_models(scene, s, fmu, use_exudyn, log)
        rep.files.append(write_csv(mrows, out / "models.csv"))
        keys = list(mrows[0].keys())
        rep.add("Models side by side", grid(keys, [[r.get(k) for k in keys] for r in mrows]))
    if "space" in parts:
        srows = study_space(scene, s, fmu, log)
        rep.files.append(write_csv(srows, out / "space.csv"))
        keys = list(srows[0].keys())
        rep.add("Spatial error", grid(keys, [[r[k] for k in keys] for r in srows]))
    if "scaling" in parts:
        crows = study_scaling(scene, s, fmu, log)
        rep.files.append(write_csv(crows, out / "scaling.csv"))
        rep.files.append(plot_scaling(crows, out / "benchmark_scaling.png"))
        keys = list(crows[0].keys())
        rep.add("Scaling", grid(keys, [[r[k] for k in keys] for r in crows]))
    if "profile" in parts:
        rep.add(
            "cProfile of the FMU loop (T/128, 20 periods)",
            "```\n" + profile_fmu(scene, 128, s.periods, fmu) + "\n```",
        )
    rep.add("Machine (end)", machine_load())
    rep.files.append(write_text("\n".join(rep.sections), out / "benchmark.md"))
    return rep
