"""Shallow arches (issue 5, paper section 6.2): the static crown-load diagram (Figures 6, 10), the
zero-load equilibria and their natural frequencies, and the forced dynamics through the FMUs
(chaos, local and global period-doubling, element-count dependence, modulated motion).

The static part calls the core CLI (``target/release/georod path`` / ``modes``); the dynamic part
reuses :mod:`georod_tools.runner` (fmpy), :mod:`georod_tools.sweep` (Dask) and
:mod:`georod_tools.plots`. A run that starts in another equilibrium than the FMU's initial state
(the unloaded arch z1), e.g. in the inverted well z3, patches a serialized FMU state with the
statically computed displacements (:func:`run_case_from`).
"""

from __future__ import annotations

import math
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from georod_tools.runner import CaseConfig, CaseResult, run_case  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
GEOROD = REPO / "target" / "release" / "georod"


def fmu_path(scene: str) -> Path:
    return REPO / "target" / "fmu" / f"{scene}.fmu"


def _georod(*args: str) -> str:
    if not GEOROD.exists():
        raise FileNotFoundError(f"{GEOROD} missing: cargo build --release --bin georod")
    return subprocess.run([str(GEOROD), *args], check=True, capture_output=True, text=True).stdout


def _sets(overrides: dict[str, float] | None) -> list[str]:
    out: list[str] = []
    for k, v in (overrides or {}).items():
        out += ["--set", f"{k}={v}"]
    return out


@dataclass
class StaticDiagram:
    """The crown-load path: ``load``, ``w_mid``, ``negative`` per point (path order), the refined
    critical points ``(kind, load, w_mid, before, after)`` and the zero-load equilibria
    ``(name, w_mid, negative)``."""

    scene: str
    load: np.ndarray
    w_mid: np.ndarray
    negative: np.ndarray
    critical: list[tuple[str, float, float, int, int]]
    equilibria: list[tuple[str, float, int]]
    csv: str


def static_diagram(
    scene: str,
    overrides: dict[str, float] | None = None,
    max_load: float = 60.0,
    imperfection: float = 0.0,
) -> StaticDiagram:
    """Traces the static path with ``georod path`` and parses it."""
    args = ["path", "--scene", scene, "--stop", str(max_load), *_sets(overrides)]
    if imperfection:
        args += ["--imperfection", str(imperfection)]
    text = _georod(*args)
    rows, critical, equilibria = [], [], []
    for line in text.splitlines()[1:]:
        if line.startswith("# critical,"):
            _, kind, p, w, a, b = line[2:].split(",")
            critical.append((kind, float(p), float(w), int(a), int(b)))
        elif line.startswith("# equilibrium,"):
            _, name, _p, w, n = line[2:].split(",")
            equilibria.append((name, float(w), int(n)))
        elif not line.startswith("#"):
            p, w, _s, n = line.split(",")
            rows.append((float(p), float(w), int(n)))
    a = np.asarray(rows, dtype=float)
    return StaticDiagram(scene, a[:, 0], a[:, 1], a[:, 2].astype(int), critical, equilibria, text)


def plot_static(d: StaticDiagram, path: str | Path, extra: StaticDiagram | None = None) -> Path:
    """Load against crown deflection: stable solid, unstable dashed, critical points and the
    zero-load equilibria marked (`extra`: e.g. the imperfect path, drawn thin)."""
    path = Path(path)
    fig, ax = plt.subplots(figsize=(6.4, 4.6), constrained_layout=True)
    if extra is not None:
        ax.plot(
            extra.w_mid,
            extra.load,
            "-",
            lw=0.8,
            color="tab:orange",
            label="with asymmetric imperfection",
        )
    stable = d.negative == 0
    start = 0
    for i in range(1, len(stable) + 1):
        if i == len(stable) or stable[i] != stable[start]:
            seg = slice(start, min(i + 1, len(stable)))
            ax.plot(d.w_mid[seg], d.load[seg], "-" if stable[start] else "--", color="k", lw=1.4)
            start = i
    ax.plot([], [], "-", color="k", label="stable")
    ax.plot([], [], "--", color="k", label="unstable")
    for kind, p, w, *_ in d.critical:
        marker = "o" if kind == "LimitPoint" else "s"
        ax.plot(w, p, marker, mfc="none", color="tab:red", ms=7)
        ax.annotate(
            f"{'limit' if marker == 'o' else 'bif.'} {p:.2f}",
            (w, p),
            textcoords="offset points",
            xytext=(6, 4),
            fontsize=8,
            color="tab:red",
        )
    for name, w, n in d.equilibria:
        ax.plot(w, 0.0, "o", color="tab:blue" if n == 0 else "white", mec="tab:blue", ms=7)
        ax.annotate(name, (w, 0.0), textcoords="offset points", xytext=(-4, -14), fontsize=9)
    ax.axhline(0.0, color="0.7", lw=0.6)
    ax.set(
        xlabel="w_mid (crown deflection, e2)",
        ylabel="crown load P (along -e2)",
        title=f"{d.scene}: static crown-load path",
    )
    ax.legend(fontsize=8, loc="best")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def modes_table(scene: str, overrides: dict[str, float] | None = None, count: int = 4) -> str:
    return _georod("modes", "--scene", scene, "--count", str(count), *_sets(overrides))


def equilibrium_states(
    scene: str, overrides: dict[str, float] | None = None, load: float = 0.0
) -> dict[str, np.ndarray]:
    """Displacement vectors of the zero-load (or `load`) equilibria by name (z1 highest)."""
    out = REPO / "target" / f"arches_states_{scene}_{time.time_ns()}.csv"
    try:
        _georod(
            "modes",
            "--scene",
            scene,
            "--count",
            "1",
            "--load",
            str(load),
            "--states",
            str(out),
            *_sets(overrides),
        )
        states = {}
        for line in out.read_text().splitlines():
            parts = line.split(",")
            states[parts[0]] = np.asarray([float(x) for x in parts[3:]])
        return states
    finally:
        out.unlink(missing_ok=True)


def lowest_frequency(scene: str, overrides: dict[str, float] | None = None) -> float:
    """Lowest angular frequency (rad/s) about z1."""
    for line in modes_table(scene, overrides, 1).splitlines()[1:]:
        parts = line.split(",")
        if parts[0] == "z1":
            return float(parts[5])
    raise RuntimeError("no z1")


def run_case_from(config: CaseConfig, u0: np.ndarray | None = None) -> CaseResult:
    """:func:`georod_tools.runner.run_case` from the displacements `u0` at rest (e.g. the
    static equilibrium z3) instead of the FMU's initial state."""
    return run_case(config, u0)


def poincare_grid(
    results: list[CaseResult], titles: list[str], path: str | Path, ncols: int = 4
) -> Path:
    """Poincaré sections of several cases side by side."""
    path = Path(path)
    nrows = math.ceil(len(results) / ncols)
    fig, axes = plt.subplots(
        nrows, ncols, figsize=(3.2 * ncols, 2.9 * nrows), constrained_layout=True, squeeze=False
    )
    for ax in axes.flat[len(results) :]:
        ax.axis("off")
    for ax, r, t in zip(axes.flat, results, titles, strict=False):
        s = r.samples
        ax.plot(s[:, 0], s[:, 1], ".", ms=2, color="k")
        # A settled periodic orbit scatters by round-off: show at least 0.05 x 50 around it.
        for lo, hi, span, setter in (
            (s[:, 0].min(), s[:, 0].max(), 0.05, ax.set_xlim),
            (s[:, 1].min(), s[:, 1].max(), 50.0, ax.set_ylim),
        ):
            if hi - lo < span:
                c = 0.5 * (lo + hi)
                setter(c - 0.6 * span, c + 0.6 * span)
        ax.ticklabel_format(useOffset=False)
        ax.set_title(f"{t}\n{r.classification.label}, λ={r.exponent_per_period:.2f}", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_xlabel("w_mid", fontsize=7)
        ax.set_ylabel("v_mid", fontsize=7)
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return path


# --------------------------------------------------------------------------------------------
# ClampedArch: the modulated (quasi-periodic) motion of the paper's Figure 11 and the doubling
# of its ring (Figure 12), found by the scan documented in docs/arches.md section 4.

CLAMPED_RING = {"Omega": 2000.0, "F": 112.0, "d": 1e-4}
"""Figure 11 analogue: a ring in the Poincaré section (Neimark-Sacker window F = 110..113 at
Omega = 2000, d = 1e-4; period-1 at F = 115, the ring breaks up below F = 110)."""

CLAMPED_DOUBLING_OMEGA = 1950.0
CLAMPED_DOUBLING_FORCES = (99.0, 101.0, 102.0, 105.0)
"""Figure 12 analogue at Omega = 1950, d = 1e-4: ring (99), ring wound twice (101), break-up
(102, exponent ~0.01), chaotic modulated motion (105)."""


def clamped_ring_case(
    F: float = CLAMPED_RING["F"],
    Omega: float = CLAMPED_RING["Omega"],
    d: float = CLAMPED_RING["d"],
    transient_periods: int = 1500,
    sample_periods: int = 400,
    dense_periods: int = 60,
    lyapunov: bool = True,
) -> CaseResult:
    """The ClampedArch's quasi-periodic case (defaults: Figure 11 analogue) from the FMU's initial
    state, 20 communication steps per period, dt_max = 1e-5, 10 elements. The short version used
    by the test (400 + 300 periods, ~5-8 s) classifies the same."""
    return run_case_from(
        _case(
            "ClampedArch",
            F=F,
            Omega=Omega,
            params=(("d", d),),
            transient_periods=transient_periods,
            sample_periods=sample_periods,
            dense_periods=dense_periods,
            lyapunov=lyapunov,
        )
    )


def rotation_number(samples: np.ndarray) -> float:
    """Mean fraction of a turn per forcing period of the section points about their centroid
    (coordinates scaled by their ranges); meaningful for a ring that encloses its centroid."""
    s = np.asarray(samples, dtype=float)
    z = (s[:, 0] - s[:, 0].mean()) / np.ptp(s[:, 0]) + 1j * (s[:, 1] - s[:, 1].mean()) / np.ptp(
        s[:, 1]
    )
    a = np.unwrap(np.angle(z))
    return float(abs(a[-1] - a[0]) / (len(a) - 1) / (2.0 * math.pi))


def plot_clamped_ring(r: CaseResult, path: str | Path, zoom_periods: int = 16) -> Path:
    """Figure 11 analogue: Poincaré section (the ring); w_mid(t) over the last `zoom_periods`
    periods with the stroboscopic points; the stroboscopic w_mid(kT) over all sampled periods
    (the modulation); phase portrait over the dense periods."""
    path = Path(path)
    fig, (ax_p, ax_t, ax_k, ax_ph) = plt.subplots(1, 4, figsize=(19, 4.4), constrained_layout=True)
    s = r.samples
    period = r.config.period
    ax_p.plot(s[:, 0], s[:, 1], ".", ms=3, color="k")
    ax_p.ticklabel_format(useOffset=False)
    ax_p.set(title=f"Poincaré section (t = kT), {len(s)} periods", xlabel="w_mid", ylabel="v_mid")
    ax_k.plot(np.rint(r.sample_times / period), s[:, 0], ".-", ms=3, lw=0.4, color="tab:red")
    ax_k.ticklabel_format(useOffset=False)
    ax_k.set(title="modulation: w_mid(kT)", xlabel="period k", ylabel="w_mid(kT)")
    if r.dense is not None and r.dense.shape[0] > 1:
        d = r.dense
        last = d[d[:, 0] >= d[-1, 0] - zoom_periods * period - 1e-12]
        in_zoom = r.sample_times >= last[0, 0] - 1e-12
        ax_t.plot(last[:, 0], last[:, 1], "-", lw=0.8, color="tab:blue")
        ax_t.plot(r.sample_times[in_zoom], s[in_zoom, 0], ".", ms=5, color="tab:red")
        in_window = r.sample_times >= d[0, 0] - 1e-12
        ax_ph.plot(d[:, 1], d[:, 2], "-", lw=0.4, color="tab:blue")
        ax_ph.plot(s[in_window, 0], s[in_window, 1], ".", ms=4, color="tab:red")
    ax_t.set(title=f"w_mid(t), last {zoom_periods} periods (red: t = kT)", xlabel="t (s)")
    ax_ph.set(title="phase portrait (red: t = kT)", xlabel="w_mid", ylabel="v_mid")
    c = r.config
    fig.suptitle(
        f"ClampedArch, Omega = {c.Omega:g}, F = {c.F:g}, {dict(c.params)}: "
        f"{r.classification.label}, λ = {r.exponent_per_period:.4f}/period, "
        f"dimension {r.classification.dimension:.2f}, rotation number {rotation_number(s):.3f}"
    )
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def plot_ring_doubling(results: list[CaseResult], path: str | Path) -> Path:
    """Figure 12 analogue: Poincaré sections along F, consecutive samples in alternating colours
    (a ring wound twice is one curve: both colours lie on it)."""
    path = Path(path)
    fig, axes = plt.subplots(
        1, len(results), figsize=(3.6 * len(results), 3.4), constrained_layout=True, squeeze=False
    )
    for ax, r in zip(axes.flat, results, strict=True):
        s = r.samples
        ax.plot(s[::2, 0], s[::2, 1], ".", ms=2, color="k")
        ax.plot(s[1::2, 0], s[1::2, 1], ".", ms=2, color="tab:orange")
        ax.ticklabel_format(useOffset=False)
        ax.tick_params(labelsize=7)
        ax.set_xlabel("w_mid", fontsize=8)
        ax.set_ylabel("v_mid", fontsize=8)
        ax.set_title(
            f"Omega = {r.config.Omega:g}, F = {r.config.F:g}\n{r.classification.label}, "
            f"λ = {r.exponent_per_period:.3f}, dim {r.classification.dimension:.2f}",
            fontsize=8,
        )
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


# --------------------------------------------------------------------------------------------
# The study (scripts/study_arches): every figure of docs/arches.md.


def _case(scene: str, **kw: object) -> CaseConfig:
    base: dict[str, object] = dict(
        fmu=str(fmu_path(scene)), Omega=1000.0, transient_periods=150, sample_periods=150
    )
    base.update(kw)
    return CaseConfig(**base)  # type: ignore[arg-type]


def _log(rows: list[str], line: str) -> None:
    print(line, flush=True)
    rows.append(line)


def study(out: Path, figures: Path, quick: bool = False) -> None:
    """Runs the whole study; writes CSV/text to `out` and the PNGs to `figures`."""
    from georod_tools.plots import plot_case

    out.mkdir(parents=True, exist_ok=True)
    figures.mkdir(parents=True, exist_ok=True)
    log: list[str] = []
    # 1. static diagrams (Figures 6 and 10) and the natural frequencies about the equilibria.
    pinned = static_diagram("PinnedArch", max_load=30.0)
    imperfect = static_diagram("PinnedArch", max_load=30.0, imperfection=0.01)
    clamped = static_diagram("ClampedArch", max_load=60.0)
    for name, d in (("pinned", pinned), ("pinned_imperfect", imperfect), ("clamped", clamped)):
        (out / f"static_{name}.csv").write_text(d.csv)
        for c in d.critical:
            _log(
                log, f"static {name}: {c[0]} at P = {c[1]:.6f}, w_mid = {c[2]:.5f} ({c[3]}->{c[4]})"
            )
        for e in d.equilibria:
            _log(log, f"static {name}: zero-load equilibrium {e[0]} w_mid = {e[1]:.6f}, neg {e[2]}")
    plot_static(pinned, figures / "arches_static_pinned.png", extra=imperfect)
    plot_static(clamped, figures / "arches_static_clamped.png")
    for scene in ("PinnedArch", "ClampedArch"):
        table = modes_table(scene, count=4)
        (out / f"modes_{scene}.csv").write_text(table)
        _log(log, f"modes {scene}:\n{table}")
    # 2. PinnedArch chaotic attractor (Figure 7).
    chaos = run_case_from(_case("PinnedArch", F=20.0, sample_periods=300, dense_periods=20))
    plot_case(chaos, figures / "arches_chaos_pinned.png")
    _log(
        log,
        f"Figure 7 analogue: F = 20, Omega = 1000: {chaos.classification.label}, "
        f"exponent {chaos.exponent_per_period:.3f}/period ({chaos.classification.note})",
    )
    # 3. Two cascades (Figure 8): from z1 (the FMU's initial state) and from z3 (patched state).
    z3 = equilibrium_states("PinnedArch")["z3"]
    grids: list[CaseResult] = []
    titles: list[str] = []
    forces_z1 = [8.0, 11.0, 12.0, 13.0, 14.0, 15.0, 16.0, 20.0]
    forces_z3 = [2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0]
    if quick:
        forces_z1, forces_z3 = forces_z1[::3], forces_z3[::3]
    for start, forces, u0 in (("z1", forces_z1, None), ("z3", forces_z3, z3)):
        for f in forces:
            r = run_case_from(_case("PinnedArch", F=f), u0)
            grids.append(r)
            titles.append(f"from {start}, F = {f:g}")
            w = r.samples[:, 0]
            _log(
                log,
                f"cascade from {start}: F = {f:g}: {r.classification.label}, exponent "
                f"{r.exponent_per_period:.3f}, w_mid in [{w.min():.3f}, {w.max():.3f}]",
            )
    poincare_grid(grids, titles, figures / "arches_cascades.png")
    # 4. ClampedArch (Figures 11, 12): near the 1:2 internal resonance (omega_2 = 2.03 omega_1)
    #    with lighter damping d = 1e-4, forced at Omega ~ 2 omega_1.
    clamped_cases = [(2000.0, 15.0), (2000.0, 30.0), (2000.0, 60.0), (2100.0, 60.0)]
    rs = []
    for om, f in clamped_cases if not quick else clamped_cases[:1]:
        r = run_case_from(
            _case(
                "ClampedArch",
                F=f,
                Omega=om,
                params=(("d", 1e-4),),
                transient_periods=400,
                sample_periods=300,
            )
        )
        rs.append(r)
        _log(
            log,
            f"ClampedArch d = 1e-4, Omega = {om:g}, F = {f:g}: {r.classification.label}, "
            f"exponent {r.exponent_per_period:.4f} ({r.classification.note})",
        )
    poincare_grid(
        rs,
        [f"Omega = {om:g}, F = {f:g}" for om, f in clamped_cases],
        figures / "arches_clamped.png",
    )
    #    Figure 11 analogue: the ring (quasi-periodic modulated motion), and Figure 12: its ring
    #    wound twice, break-up and chaos along F at Omega = 1950.
    ring = clamped_ring_case(
        transient_periods=400 if quick else 1500, sample_periods=300 if quick else 400
    )
    plot_clamped_ring(ring, figures / "arches_clamped_ring.png")
    _log(
        log,
        f"Figure 11 analogue: ClampedArch {CLAMPED_RING}: {ring.classification.label}, "
        f"exponent {ring.exponent_per_period:.4f} ({ring.classification.note}), rotation number "
        f"{rotation_number(ring.samples):.3f}",
    )
    doubling = []
    for f in CLAMPED_DOUBLING_FORCES[:1] if quick else CLAMPED_DOUBLING_FORCES:
        r = clamped_ring_case(
            F=f, Omega=CLAMPED_DOUBLING_OMEGA, transient_periods=3000, sample_periods=600
        )
        doubling.append(r)
        _log(
            log,
            f"Figure 12 analogue: Omega = {CLAMPED_DOUBLING_OMEGA:g}, F = {f:g}, d = 1e-4: "
            f"{r.classification.label}, exponent {r.exponent_per_period:.4f} "
            f"({r.classification.note})",
        )
    plot_ring_doubling(doubling, figures / "arches_clamped_doubling.png")
    # 5. Onset of chaos against the element count (Figure 9): smallest F in the list classified
    #    chaotic, at Omega = 1000, from z1.
    counts = [2, 3, 4, 6, 8, 10, 12, 16, 20] if not quick else [4, 10]
    forces = [10.0, 12.0, 14.0, 15.0, 16.0, 18.0, 20.0, 24.0, 28.0]
    thresholds: list[tuple[int, float]] = []
    for n in counts:
        onset = math.nan
        for f in forces:
            r = run_case_from(
                _case("PinnedArch", F=f, elements=n, transient_periods=100, sample_periods=100)
            )
            if r.classification.kind == "chaotic":
                onset = f
                break
        thresholds.append((n, onset))
        _log(log, f"Figure 9 analogue: {n} elements: chaos from F = {onset}")
    (out / "onset_vs_elements.csv").write_text(
        "elements,onset_F\n" + "".join(f"{n},{f}\n" for n, f in thresholds)
    )
    fig, ax = plt.subplots(figsize=(5, 3.4), constrained_layout=True)
    ax.plot([n for n, _ in thresholds], [f for _, f in thresholds], "o-", color="k")
    ax.set(
        xlabel="elements",
        ylabel="smallest chaotic F (grid)",
        title="PinnedArch, Omega = 1000: onset of chaos",
    )
    fig.savefig(figures / "arches_onset_elements.png", dpi=100)
    plt.close(fig)
    (out / "study_log.txt").write_text("\n".join(log) + "\n")


def _name_value(text: str) -> tuple[str, float]:
    name, sep, value = text.partition("=")
    if not sep or not name:
        raise ValueError(f"--set takes NAME=VALUE, got {text!r}")
    try:
        x = float(value)
    except ValueError:
        raise ValueError(f"--set {name}: {value!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"--set {name}={value}: must be a finite number")
    return name, x


def main(argv: list[str] | None = None) -> int:
    """``python -m georod_tools.arches [study] [--quick]``: the whole study;
    ``python -m georod_tools.arches static --scene PinnedArch [--set H=2] [--max-load 40]``: the
    load-displacement diagram of one scene (CSV and PNG)."""
    import argparse

    from georod_tools.argtypes import positive_float

    ap = argparse.ArgumentParser(
        prog="python -m georod_tools.arches",
        description="Shallow arches: static diagrams and the study",
    )
    sub = ap.add_subparsers(dest="command")
    st = sub.add_parser("static", help="load-displacement diagram of one scene (CSV and PNG)")
    st.add_argument("--scene", choices=["PinnedArch", "ClampedArch"], default="PinnedArch")
    st.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="an FMU parameter of the scene, e.g. H=1.5 or elements=20",
    )
    st.add_argument(
        "--max-load", type=positive_float, default=60.0, help="largest |crown load|, > 0 (60)"
    )
    st.add_argument("--out", default=str(REPO / "out" / "arches"), help="output folder")
    for p in (ap, sub.add_parser("study", help="the whole study (default)")):
        p.add_argument("--out", default=str(REPO / "out" / "arches"), help="output folder")
        p.add_argument("--figures", default=str(REPO / "docs" / "figures"), help="PNG folder")
        p.add_argument("--quick", action="store_true", help="short smoke-test runs")
    a = ap.parse_args(argv)
    if a.command == "static":
        try:
            overrides = dict(_name_value(t) for t in a.set)
        except ValueError as e:
            ap.error(str(e))
        d = static_diagram(a.scene, overrides, a.max_load)
        out = Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        csv = out / f"static_{a.scene}.csv"
        csv.write_text(d.csv)
        png = plot_static(d, out / f"static_{a.scene}.png")
        for kind, load, w, before, after in d.critical:
            print(
                f"{kind} at load {load:.6g} (w_mid {w:.5g}), negative eigenvalues {before}->{after}"
            )
        for name, w, n in d.equilibria:
            stability = "stable" if n == 0 else "unstable"
            print(f"zero-load equilibrium {name}: w_mid = {w:.5g} ({stability})")
        print(f"wrote {csv} and {png}")
        return 0
    study(Path(a.out), Path(a.figures), quick=a.quick)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
