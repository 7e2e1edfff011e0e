"""The ``study`` command: the long studies behind the docs, each into a new folder under
``out/study/`` with its run.json; ``--update-docs`` copies the figures (and tables) into docs/.

    georod-tools study paper [--quick] [--workers N] [--parts LIST]   # docs/chaos_buckled_beam.md
    georod-tools study sensitivity [--quick] [--questions LIST]       # docs/paper_sensitivity.md
    georod-tools study arches [--quick]                               # docs/arches.md
    georod-tools study arch-path --scene PinnedArch [--set H=2]       # one static diagram
    georod-tools study stability [--steps N] [--rust-csv DIR]         # docs/stability.md
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

from georod_tools import REPO_ROOT
from georod_tools.cli.args import add_output_options, name_value, positive_float, positive_int
from georod_tools.cli.runs import finish_run, start_run

DEFAULT_OUT = Path("out") / "study"
DOCS = REPO_ROOT / "docs" / "figures"


#: The line `georod-tools --help` shows.
HELP = "the long studies: paper, sensitivity, arches, arch-path, stability"


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "study",
        help=HELP,
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    studies = p.add_subparsers(dest="study", required=True)
    from georod_tools.studies.paper import PARTS

    s = studies.add_parser("paper", help="the paper's section 6.1: figures, tables, checks")
    s.add_argument("--quick", action="store_true", help="short runs, few bifurcation values")
    s.add_argument("--workers", type=positive_int, default=2, help="Dask workers, >= 1 (2)")
    s.add_argument(
        "--substeps",
        type=positive_int,
        help="midpoint sub-steps per forcing period, >= 1 (128; the former study's: 200)",
    )
    s.add_argument("--fmu", type=Path, help="BuckledBeam FMU (target/fmu/BuckledBeam.fmu)")
    s.add_argument("--no-convergence", action="store_true", help="skip the checks of differences")
    s.add_argument("--no-progress", action="store_true", help="no progress bars")
    s.add_argument(
        "--parts", default=",".join(PARTS), help=f"comma-separated parts to run ({','.join(PARTS)})"
    )
    s.add_argument(
        "--setting",
        choices=("literal", "chosen", "both"),
        default="literal",
        help="the paper's literal data (the FMU's defaults), the chosen setting of "
        "docs/figures/buckled_beam/paper_settings.json, or both: the 26 panels at the literal "
        "data (with their checks) beside every part at the chosen setting, each in its own "
        "subfolder (docs: buckled_beam/literal and /chosen) (literal)",
    )
    s.add_argument("--settings-file", type=Path, help="another settings file for --setting chosen")
    add_output_options(s, f"{DEFAULT_OUT}/paper", "docs/figures/buckled_beam")
    s.set_defaults(run=run_paper, _parser=s)

    from georod_tools.studies.sensitivity import QUESTIONS

    s = studies.add_parser(
        "sensitivity",
        help="what the windows of section 6.1 depend on: shortening, mesh, mass, shear, damping, "
        "loading, time step",
    )
    s.add_argument("--quick", action="store_true", help="smoke run: few variants, short cases")
    s.add_argument("--workers", type=positive_int, default=2, help="Dask workers, >= 1 (2)")
    s.add_argument(
        "--questions",
        default=",".join(QUESTIONS),
        help=f"comma-separated questions ({','.join(QUESTIONS)})",
    )
    s.add_argument("--no-progress", action="store_true", help="no progress bars")
    add_output_options(s, f"{DEFAULT_OUT}/sensitivity", "docs/figures/buckled_beam")
    s.set_defaults(run=run_sensitivity, _parser=s)

    s = studies.add_parser("arches", help="section 6.2: static paths, frequencies, forced arches")
    s.add_argument("--quick", action="store_true", help="short smoke-test runs")
    add_output_options(s, f"{DEFAULT_OUT}/arches", "docs/figures")
    s.set_defaults(run=run_arches, _parser=s)

    s = studies.add_parser("arch-path", help="the static load-displacement diagram of one scene")
    s.add_argument("--scene", choices=["PinnedArch", "ClampedArch"], default="PinnedArch")
    s.add_argument(
        "--set",
        type=name_value,
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a parameter of the scene, e.g. H=1.5 or elements=20",
    )
    s.add_argument(
        "--max-load", type=positive_float, default=60.0, help="largest |crown load| in N, > 0 (60)"
    )
    add_output_options(s, f"{DEFAULT_OUT}/arch-path")
    s.set_defaults(run=run_arch_path, _parser=s)

    from georod_tools.studies.stability import CASES

    s = studies.add_parser("stability", help="integrator 1 vs 2 through the FMUs, energy plots")
    s.add_argument(
        "--steps",
        type=positive_int,
        default=100_000,
        help="free-vibration communication steps, >= 1 (100000)",
    )
    s.add_argument("--every", type=positive_int, default=20, help="steps between CSV rows (20)")
    names = [c.name for c in CASES]
    s.add_argument("--cases", nargs="*", choices=names, default=names, help="cases (all)")
    s.add_argument(
        "--rust-csv",
        type=Path,
        help="a folder of the Rust stability tests' CSV files (and logs) to keep and plot too",
    )
    add_output_options(s, f"{DEFAULT_OUT}/stability", "docs/figures")
    s.set_defaults(run=run_stability, _parser=s)


def run_paper(
    parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]
) -> int:
    from georod_tools import fmu_path
    from georod_tools.studies.paper import PARTS, StudySettings
    from georod_tools.studies.paper_setting import (
        SETTINGS_FILE,
        PaperSetting,
        load_setting,
        side_by_side,
        write_side_by_side,
    )

    fmu = args.fmu or fmu_path("BuckledBeam")
    parts = [x.strip() for x in args.parts.split(",") if x.strip()]
    if not parts or any(x not in PARTS for x in parts):
        parser.error(f"--parts {args.parts}: choose from {','.join(PARTS)}")
    make = StudySettings.quick if args.quick else StudySettings.full
    st = replace(make(str(Path(fmu).resolve())), convergence=not args.no_convergence)
    if args.substeps is not None:
        st = replace(st, substeps=args.substeps)
    settings: dict[str, PaperSetting] = {}
    if args.setting in ("literal", "both"):
        settings["literal"] = PaperSetting(steps_per_period=st.substeps)
    if args.setting in ("chosen", "both"):
        path = args.settings_file or SETTINGS_FILE
        if not path.is_file():
            parser.error(f"--settings-file {path}: no such file")
        settings["chosen"] = load_setting(path)
    record = start_run(
        parser,
        args,
        argv,
        DEFAULT_OUT,
        "study paper",
        {"settings": st, "parts": parts, "setting": settings},
        [fmu],
    )
    t0 = time.perf_counter()
    docs = DOCS / "buckled_beam"
    files: list[Path] = []
    cases = {}
    for name, setting in settings.items():
        both = len(settings) == 2
        sub = record.folder / name if both else record.folder
        where = docs / name if both or name == "chosen" else docs
        # side by side: the literal data's table only; every asked part at the chosen setting
        todo = [p for p in parts if p == "cases"] if both and name == "literal" else parts
        # beside the chosen setting, the literal data's per-panel figures stay in the run folder
        skip = "cases" if both and name == "literal" else None
        got, cases[name] = _paper_at(st, setting, todo, args, sub, where, skip)
        files += got
    if len(cases) == 2 and all(cases.values()):
        rows = side_by_side(cases["literal"], cases["chosen"])
        files.append(write_side_by_side(rows, settings["chosen"], record.folder))
        print((record.folder / "table_cases_side_by_side.md").read_text())
    print(f"study done in {time.perf_counter() - t0:.0f} s")
    code = finish_run(record, files, args, docs, "table_cases_side_by_side.md")
    return code


def _paper_at(
    st0: object,
    setting: object,
    parts: Sequence[str],
    args: argparse.Namespace,
    out: Path,
    docs: Path,
    keep_out_of_docs: str | None = None,
) -> tuple[list[Path], list]:
    """The study's parts at one setting into `out` (with --update-docs also into `docs`)."""
    from georod_tools.report.records import publish
    from georod_tools.report.tables import markdown
    from georod_tools.studies.paper import run_study
    from georod_tools.studies.paper_report import case_row, write_markdown, write_outputs
    from georod_tools.studies.paper_setting import apply, setting_text

    out.mkdir(parents=True, exist_ok=True)
    st = apply(st0, setting, out / "scene")  # type: ignore[arg-type]
    print(f"== {setting.name}: {setting_text(setting)}")  # type: ignore[attr-defined]
    rep = run_study(st, args.workers, not args.no_progress, parts)
    files = write_outputs(st, rep, out)
    rows = [case_row(c, r) for c, r in rep.cases]
    if rows:
        cols = ("case", "F", "Omega", "paper_class", "ours", "lyapunov_per_period", "agrees")
        print(markdown(rows, cols))
    if args.update_docs:
        skip = out / keep_out_of_docs if keep_out_of_docs else None
        publish([f for f in files if skip is None or skip not in f.parents], docs, out)
        write_markdown(st, docs)  # study.md from every table now in docs
    return files, rep.cases


def run_sensitivity(
    parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]
) -> int:
    from georod_tools import fmu_path
    from georod_tools.studies.sensitivity import QUESTIONS, SensitivitySettings, run_study
    from georod_tools.studies.sensitivity_report import write_outputs

    questions = tuple(x.strip() for x in args.questions.split(",") if x.strip())
    if not questions or any(q not in QUESTIONS for q in questions):
        parser.error(f"--questions {args.questions}: choose from {','.join(QUESTIONS)}")
    st = SensitivitySettings.make_quick() if args.quick else SensitivitySettings.full()
    st = replace(st, questions=questions)
    fmu = fmu_path("BuckledBeam")
    record = start_run(
        parser, args, argv, DEFAULT_OUT, "study sensitivity", {"settings": st}, [fmu]
    )
    t0 = time.perf_counter()
    prepared, located = run_study(st, record.folder, args.workers, not args.no_progress)
    files = write_outputs(prepared, located, record.folder, questions)
    print((record.folder / "table_sensitivity_derivatives.md").read_text())
    print(f"study done in {time.perf_counter() - t0:.0f} s")
    files += sorted((record.folder / "scenes").glob("*.toml"))
    return finish_run(record, files, args, DOCS / "buckled_beam", "*sensitivity*")


def run_arches(
    parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]
) -> int:
    from georod_tools import fmu_path
    from georod_tools.studies.arches_study import study

    fmus = [fmu_path("PinnedArch"), fmu_path("ClampedArch")]
    record = start_run(parser, args, argv, DEFAULT_OUT, "study arches", {"quick": args.quick}, fmus)
    files = study(record.folder, quick=args.quick)
    return finish_run(record, files, args, DOCS, "arches_*.png")


def run_arch_path(
    parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]
) -> int:
    from georod_tools.report.tables import write_text
    from georod_tools.studies.arches import plot_static, static_diagram

    settings = {"scene": args.scene, "set": dict(args.set), "max_load": args.max_load}
    record = start_run(parser, args, argv, DEFAULT_OUT, "study arch-path", settings, [])
    d = static_diagram(args.scene, dict(args.set), args.max_load)
    out = record.folder
    files = [
        write_text(d.csv, out / f"static_{args.scene}.csv"),
        plot_static(d, out / f"static_{args.scene}.png"),
    ]
    for kind, load, w, before, after in d.critical:
        print(
            f"{kind} at load {load:.6g} N (w_mid {w:.5g} m), negative eigenvalues {before}->{after}"
        )
    for name, w, n in d.equilibria:
        print(
            f"zero-load equilibrium {name}: w_mid = {w:.5g} m "
            f"({'stable' if n == 0 else 'unstable'})"
        )
    return finish_run(record, files, args, DOCS)


def run_stability(
    parser: argparse.ArgumentParser, args: argparse.Namespace, argv: Sequence[str]
) -> int:
    from georod_tools import FMU_DIR
    from georod_tools.studies.stability import plot_pairs, run_fmu_cases

    settings = {
        "steps": args.steps,
        "every": args.every,
        "cases": args.cases,
        "rust_csv": str(args.rust_csv) if args.rust_csv else None,
    }
    if args.rust_csv is not None and not args.rust_csv.is_dir():
        parser.error(f"--rust-csv {args.rust_csv}: no such folder")
    fmus = sorted({FMU_DIR / "BuckledBeam.fmu", FMU_DIR / "PinnedArch.fmu"})
    record = start_run(parser, args, argv, DEFAULT_OUT, "study stability", settings, fmus)
    csv_dir = record.folder / "csv"
    files = run_fmu_cases(FMU_DIR, csv_dir, args.steps, args.every, args.cases)
    if args.rust_csv is not None:
        import shutil

        for f in sorted([*args.rust_csv.glob("*.csv"), *args.rust_csv.glob("*.txt")]):
            shutil.copyfile(f, csv_dir / f.name)  # the tests' CSV files and their printed logs
    files += plot_pairs(csv_dir, record.folder)
    for f in files:
        if f.suffix == ".png":
            print(f"wrote {f}")
    return finish_run(record, files, args, DOCS, "stability_*.png")
