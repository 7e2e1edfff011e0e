"""The arches study (``georod-tools study arches``, docs/arches.md): every figure and table of the
page into one run folder.

1. static diagrams (Figures 6 and 10) and the natural frequencies about the equilibria;
2. the PinnedArch's chaotic attractor (Figure 7);
3. two cascades (Figure 8): from z1 (the FMU's initial state) and from z3 (reached by
   :data:`georod_tools.studies.arches.Z3_PRELUDE`);
4. the ClampedArch near its 1:2 internal resonance (Figures 11, 12): the ring and its doubling;
5. the onset of chaos against the element count (Figure 9).

Sub-steps: those of the earlier runs that docs/arches.md quotes (a period cut into 20
communication steps, each into pieces of at most 1e-5 s: T/640 at Omega = 1000, T/320 at 2000).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

from georod_tools import fmu_path
from georod_tools.analysis.case import CaseConfig, CaseResult
from georod_tools.analysis.case import run_case as run_one
from georod_tools.report.figures import plot_case, plt, save
from georod_tools.report.tables import write_text
from georod_tools.studies.arches import (
    CLAMPED_DOUBLING_FORCES,
    CLAMPED_DOUBLING_OMEGA,
    CLAMPED_RING,
    Z3_PRELUDE,
    modes_table,
    plot_clamped_ring,
    plot_ring_doubling,
    plot_static,
    poincare_grid,
    rotation_number,
    static_diagram,
)


def earlier_substeps(omega: float) -> int:
    """Sub-steps per period of the earlier runs: T/20 cut into pieces of at most 1e-5 s."""
    return 20 * math.ceil(2.0 * math.pi / omega / 20 / 1e-5 * (1 - 1e-12))


def arch_case(scene: str, **kw: object) -> CaseConfig:
    """A case of the study (Omega = 1000, 150 + 150 periods unless `kw` says otherwise)."""
    base: dict[str, object] = dict(
        fmu=str(fmu_path(scene)), Omega=1000.0, transient_periods=150, sample_periods=150
    )
    base.update(kw)
    base.setdefault("substeps", earlier_substeps(float(base["Omega"])))  # type: ignore[arg-type]
    return CaseConfig(**base)  # type: ignore[arg-type]


def clamped_ring_case(
    F: float = CLAMPED_RING["F"],
    Omega: float = CLAMPED_RING["Omega"],
    d: float = CLAMPED_RING["d"],
    transient_periods: int = 1500,
    sample_periods: int = 400,
    dense_periods: int = 60,
) -> CaseConfig:
    """The ClampedArch's quasi-periodic case (defaults: Figure 11 analogue) from the FMU's
    initial state, 10 elements."""
    return arch_case(
        "ClampedArch",
        F=F,
        Omega=Omega,
        params=(("d", d),),
        transient_periods=transient_periods,
        sample_periods=sample_periods,
        dense_periods=dense_periods,
    )


def study(out: Path, quick: bool = False, say: Callable[[str], None] = print) -> list[Path]:
    """Runs the whole study into `out`; returns the files written (figures ``arches_*.png``)."""
    from tqdm import tqdm

    out.mkdir(parents=True, exist_ok=True)
    log: list[str] = []
    files: list[Path] = []
    bar = tqdm(desc="arches: cases run", unit="case", leave=False)

    def tell(line: str) -> None:
        bar.clear()
        say(line)
        log.append(line)

    def run_case(cfg: CaseConfig) -> CaseResult:
        result = run_one(cfg)
        bar.update(1)
        return result

    # 1. static diagrams (Figures 6 and 10) and the natural frequencies about the equilibria.
    pinned = static_diagram("PinnedArch", max_load=30.0)
    imperfect = static_diagram("PinnedArch", max_load=30.0, imperfection=0.01)
    clamped = static_diagram("ClampedArch", max_load=60.0)
    for name, d in (("pinned", pinned), ("pinned_imperfect", imperfect), ("clamped", clamped)):
        files.append(write_text(d.csv, out / f"static_{name}.csv"))
        for c in d.critical:
            tell(f"static {name}: {c[0]} at P = {c[1]:.6f}, w_mid = {c[2]:.5f} ({c[3]}->{c[4]})")
        for e in d.equilibria:
            tell(f"static {name}: zero-load equilibrium {e[0]} w_mid = {e[1]:.6f}, neg {e[2]}")
    files.append(plot_static(pinned, out / "arches_static_pinned.png", extra=imperfect))
    files.append(plot_static(clamped, out / "arches_static_clamped.png"))
    for scene in ("PinnedArch", "ClampedArch"):
        table = modes_table(scene, count=4)
        files.append(write_text(table, out / f"modes_{scene}.csv"))
        tell(f"modes {scene}:\n{table}")
    # 2. PinnedArch chaotic attractor (Figure 7).
    chaos = run_case(arch_case("PinnedArch", F=20.0, sample_periods=300, dense_periods=20))
    files.append(plot_case(chaos, out / "arches_chaos_pinned.png"))
    tell(
        f"Figure 7 analogue: F = 20, Omega = 1000: {chaos.classification.label}, exponent "
        f"{chaos.exponent_per_period:.3f}/period ({chaos.classification.note})"
    )
    # 3. Two cascades (Figure 8): from z1 and from z3 (pushed there through f_ctrl).
    grids: list[CaseResult] = []
    titles: list[str] = []
    forces_z1 = [8.0, 11.0, 12.0, 13.0, 14.0, 15.0, 16.0, 20.0]
    forces_z3 = [2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0]
    if quick:
        forces_z1, forces_z3 = forces_z1[::3], forces_z3[::3]
    for start, forces, prelude in (("z1", forces_z1, None), ("z3", forces_z3, Z3_PRELUDE)):
        for f in forces:
            r = run_case(arch_case("PinnedArch", F=f, prelude=prelude))
            grids.append(r)
            titles.append(f"from {start}, F = {f:g}")
            w = r.samples[:, 0]
            tell(
                f"cascade from {start}: F = {f:g}: {r.classification.label}, exponent "
                f"{r.exponent_per_period:.3f}, w_mid in [{w.min():.3f}, {w.max():.3f}]"
            )
    files.append(poincare_grid(grids, titles, out / "arches_cascades.png"))
    # 4. ClampedArch (Figures 11, 12): near the 1:2 internal resonance (omega_2 = 2.03 omega_1)
    #    with lighter damping d = 1e-4, forced at Omega ~ 2 omega_1.
    clamped_cases = [(2000.0, 15.0), (2000.0, 30.0), (2000.0, 60.0), (2100.0, 60.0)]
    if quick:
        clamped_cases = clamped_cases[:1]
    rs = []
    for om, f in clamped_cases:
        r = run_case(
            arch_case(
                "ClampedArch",
                F=f,
                Omega=om,
                params=(("d", 1e-4),),
                transient_periods=400,
                sample_periods=300,
            )
        )
        rs.append(r)
        tell(
            f"ClampedArch d = 1e-4, Omega = {om:g}, F = {f:g}: {r.classification.label}, "
            f"exponent {r.exponent_per_period:.4f} ({r.classification.note})"
        )
    titles = [f"Omega = {om:g}, F = {f:g}" for om, f in clamped_cases]
    files.append(poincare_grid(rs, titles, out / "arches_clamped.png"))
    ring = run_case(
        clamped_ring_case(
            transient_periods=400 if quick else 1500, sample_periods=300 if quick else 400
        )
    )
    files.append(plot_clamped_ring(ring, out / "arches_clamped_ring.png"))
    tell(
        f"Figure 11 analogue: ClampedArch {CLAMPED_RING}: {ring.classification.label}, exponent "
        f"{ring.exponent_per_period:.4f} ({ring.classification.note}), rotation number "
        f"{rotation_number(ring.samples):.3f}"
    )
    doubling = []
    for f in CLAMPED_DOUBLING_FORCES[:1] if quick else CLAMPED_DOUBLING_FORCES:
        r = run_case(
            clamped_ring_case(
                F=f, Omega=CLAMPED_DOUBLING_OMEGA, transient_periods=3000, sample_periods=600
            )
        )
        doubling.append(r)
        tell(
            f"Figure 12 analogue: Omega = {CLAMPED_DOUBLING_OMEGA:g}, F = {f:g}, d = 1e-4: "
            f"{r.classification.label}, exponent {r.exponent_per_period:.4f} "
            f"({r.classification.note})"
        )
    files.append(plot_ring_doubling(doubling, out / "arches_clamped_doubling.png"))
    # 5. Onset of chaos against the element count (Figure 9): smallest F in the list classified
    #    chaotic, at Omega = 1000, from z1.
    files += onset_vs_elements(out, quick, tell, run_case)
    bar.close()
    files.append(write_text("\n".join(log), out / "study_log.txt"))
    return files


def onset_vs_elements(
    out: Path,
    quick: bool,
    tell: Callable[[str], None],
    run_case: Callable[[CaseConfig], CaseResult] = run_one,
) -> list[Path]:
    counts = [2, 3, 4, 6, 8, 10, 12, 16, 20] if not quick else [4, 10]
    forces = [10.0, 12.0, 14.0, 15.0, 16.0, 18.0, 20.0, 24.0, 28.0]
    thresholds: list[tuple[int, float]] = []
    for n in counts:
        onset = math.nan
        for f in forces:
            cfg = arch_case(
                "PinnedArch", F=f, elements=n, transient_periods=100, sample_periods=100
            )
            if run_case(cfg).classification.kind == "chaotic":
                onset = f
                break
        thresholds.append((n, onset))
        tell(f"Figure 9 analogue: {n} elements: chaos from F = {onset}")
    csv = write_text(
        "elements,onset_F\n" + "".join(f"{n},{f}\n" for n, f in thresholds),
        out / "onset_vs_elements.csv",
    )
    fig, ax = plt.subplots(figsize=(5, 3.4), constrained_layout=True)
    ax.plot([n for n, _ in thresholds], [f for _, f in thresholds], "o-", color="k")
    ax.set(
        xlabel="elements [1]",
        ylabel="smallest chaotic F on the grid [N]",
        title="PinnedArch, Omega = 1000 rad/s: onset of chaos",
    )
    return [csv, save(fig, out / "arches_onset_elements.png")]
