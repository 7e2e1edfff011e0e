"""Sensitivity of the paper's section 6.1 to the data it gives loosely and to discretization
choices it does not state (``georod-tools study sensitivity``; docs/paper_sensitivity.md).

Each **question** varies one thing against the reference (the repository's BuckledBeam at the
paper's literal data: end shortening 0.11 prescribed at the right support, 10 elements,
consistent mass, no shear factor, translations damped only, ``T/128`` midpoint sub-steps):

- ``shortening``: the end shortening 0.100 ... 0.110 (the paper gives 0.11, two digits);
- ``elements``: 10, 20, 40;
- ``mass``: consistent or lumped mass (and damping) matrices;
- ``shear``: shear correction factor 1 or 5/6;
- ``rotational_damping``: off, or mass-proportional ``d I / A`` (:data:`ROT_DAMPING`);
- ``loading``: how the 0.11 is applied (:mod:`.sensitivity_scenes`: prescribed end
  displacement, dead axial load with the end free axially, or 0.11 as the buckling part only);
- ``time_step``: midpoint sub-steps per forcing period (the paper does not give its step).

Per variant: the static midspan deflection, the first natural frequency about the buckled state
(:mod:`.sensitivity_statics`) and the Omega positions of the main windows at F = 0.7
(:mod:`.sensitivity_windows`). Every variant is a scene file written into the run folder and
packaged with ``georod fmu``; mesh and time step are the cases' own settings.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path

from georod_tools.analysis.case import DEFAULT_SUBSTEPS
from georod_tools.studies.sensitivity_scenes import (
    PAPER_SHORTENING,
    SceneSpec,
    axial_force,
    axial_stiffness,
    buckling_shortening,
    package,
)
from georod_tools.studies.sensitivity_statics import Statics, statics
from georod_tools.studies.sensitivity_windows import Located, Runner, WindowSettings, locate

#: Translational damping of the paper (per unit length) and the section (b = h = 1).
D_PAPER, AREA, INERTIA = 5.0e-4, 1.0, 1.0 / 12.0
#: Rotational damping proportional to the rotational inertia as d is to the mass:
#: ``d_w / (rho I) = d / (rho A)``, i.e. ``d_w = d I / A`` (the damping matrix stays
#: proportional to the mass matrix, so every mode decays at the same rate d / (2 rho A)).
ROT_DAMPING = D_PAPER * INERTIA / AREA

#: The questions in the order of the report, with the parameter each varies (its unit).
QUESTIONS: dict[str, str] = {
    "shortening": "end shortening (m)",
    "elements": "elements",
    "mass": "mass matrix (0 consistent, 1 lumped)",
    "shear": "shear correction factor",
    "rotational_damping": "rotational damping d_w (per unit length)",
    "loading": "how the end shortening is applied",
    "time_step": "midpoint sub-steps per forcing period",
}


@dataclass(frozen=True)
class Variant:
    """One variant: its question, a label, the numeric value `x` its derivative is taken in
    (NaN for a category without an order), the scene and the cases' mesh and time step."""

    question: str
    label: str
    x: float
    scene: SceneSpec = field(default_factory=SceneSpec)
    elements: int = 10
    substeps: int = DEFAULT_SUBSTEPS

    @property
    def name(self) -> str:
        """File-safe name, also the scene's name (``BB_<question>_<label>``)."""
        safe = "".join(c if c.isalnum() else "_" for c in self.label)
        return f"BB_{self.question}_{safe}"

    @property
    def key(self) -> tuple:
        """What makes two variants the same runs (the reference appears in every question)."""
        return (self.scene, self.elements, self.substeps)


REFERENCE = Variant("reference", "reference", 0.0)


def variants(quick: bool = False) -> list[Variant]:
    """Every variant of every question (the reference first). `quick`: fewer values per
    question, each question still asked."""
    shortenings = (0.105,) if quick else (0.100, 0.1025, 0.105, 0.106, 0.107, 0.108, 0.109)
    elements = (20,) if quick else (20, 40)
    steps = (32,) if quick else (16, 32, 64, 256)
    out = [REFERENCE]
    out += [
        Variant("shortening", f"{s:g}", s, replace(SceneSpec(), pre_shortening=s))
        for s in shortenings
    ]
    out += [Variant("elements", f"{n}", float(n), elements=n) for n in elements]
    out.append(Variant("mass", "lumped", 1.0, SceneSpec(mass="lumped")))
    out.append(Variant("shear", "5/6", 5.0 / 6.0, SceneSpec(shear_factor=5.0 / 6.0)))
    out.append(
        Variant(
            "rotational_damping",
            "dI/A",
            ROT_DAMPING,
            SceneSpec(rotational_damping=ROT_DAMPING),
        )
    )
    out.append(
        Variant("loading", "dead load", float("nan"), SceneSpec(loading="dead", axial_load=0.0))
    )
    out.append(Variant("loading", "buckling part", float("nan"), SceneSpec(loading="buckling")))
    out += [Variant("time_step", f"T/{n}", float(n), substeps=n) for n in steps]
    return out


#: The reference's value of each question's parameter (its x).
REFERENCE_X: dict[str, float] = {
    "shortening": PAPER_SHORTENING,
    "elements": 10.0,
    "mass": 0.0,
    "shear": 1.0,
    "rotational_damping": 0.0,
    "loading": float("nan"),
    "time_step": float(DEFAULT_SUBSTEPS),
}
#: The reference's label in each question.
REFERENCE_LABEL: dict[str, str] = {
    "shortening": "0.11",
    "elements": "10",
    "mass": "consistent",
    "shear": "1",
    "rotational_damping": "off",
    "loading": "prescribed",
    "time_step": f"T/{DEFAULT_SUBSTEPS}",
}


@dataclass
class Prepared:
    """A variant ready to run: its calibrated scene, scene file, FMU and statics."""

    variant: Variant
    scene: SceneSpec
    scene_file: Path
    fmu: Path
    statics: Statics


def prepare(variant: Variant, folder: Path, reference_fmu: Path | None = None) -> Prepared:
    """Calibrates the variant's scene (dead load: the axial force of the prescribed state;
    buckling part: the end displacement), writes and packages it into `folder`, and computes
    its statics. `reference_fmu`: an already packaged reference (for the calibrations)."""
    spec = variant.scene
    if spec.loading != "prescribed":
        ref = reference_fmu or package(SceneSpec(), "BB_calibration", folder)
        if spec.loading == "dead":
            force = axial_force(ref, spec.pre_shortening, variant.elements)
            spec = replace(spec, axial_load=force)
        else:
            total = buckling_shortening(ref, spec.pre_shortening, variant.elements)
            spec = replace(spec, pre_shortening=total)
    fmu = package(spec, variant.name, folder)
    scene_file = fmu.with_suffix(".toml")
    st = statics(fmu, scene_file, variant.elements, variant.substeps, {}, spec.loading == "dead")
    return Prepared(variant, spec, scene_file, fmu, st)


def strain_part(fmu: Path, shortening: float, elements: int = 10) -> float:
    """The axial strain part ``N L / EA`` of an end shortening (prescribed)."""
    return axial_force(fmu, shortening, elements) / axial_stiffness(fmu)


#: The scan is the reference's range times the frequency ratio when that lies in these bounds;
#: outside them (the dead load's first frequency is ~1/60 of the reference's) the variant is a
#: different system, and the reference range shows what it does at the paper's frequencies.
SCALE_BOUNDS = (0.5, 2.5)


@dataclass(frozen=True)
class SensitivitySettings:
    """The study's numbers: which questions, their variants (`quick`: fewer) and the window
    search (:class:`~.sensitivity_windows.WindowSettings`)."""

    windows: WindowSettings = field(default_factory=WindowSettings)
    questions: tuple[str, ...] = tuple(QUESTIONS)
    quick: bool = False

    @classmethod
    def full(cls) -> SensitivitySettings:
        return cls()

    @classmethod
    def make_quick(cls) -> SensitivitySettings:
        ws = WindowSettings(scan=(3500.0, 4400.0), scan_count=6, rounds=1, transient=40, periods=40)
        return cls(windows=ws, quick=True)


def scan_scale(p: Prepared, ref: Prepared) -> float:
    """The factor on the reference scan range for variant `p` (see :data:`SCALE_BOUNDS`)."""
    ratio = p.statics.omega1 / ref.statics.omega1
    lo, hi = SCALE_BOUNDS
    return ratio if math.isfinite(ratio) and lo <= ratio <= hi else 1.0


def run_study(
    st: SensitivitySettings, folder: Path, workers: int = 2, progress: bool = True
) -> tuple[list[Prepared], dict[str, Located]]:
    """Prepares every variant (scene files and FMUs under ``folder/scenes``) and locates the
    windows of all of them together on one local cluster of `workers` processes."""
    from tqdm import tqdm

    chosen = [v for v in variants(st.quick) if v.question in ("reference", *st.questions)]
    prepared: list[Prepared] = []
    for v in tqdm(chosen, desc="variants (scenes, statics)", disable=not progress):
        ref_fmu = prepared[0].fmu if prepared else None
        prepared.append(prepare(v, folder / "scenes", ref_fmu))
    ref = prepared[0]
    jobs = [
        (p.variant.name, p.fmu, p.variant.elements, p.variant.substeps, scan_scale(p, ref))
        for p in prepared
    ]
    with Runner(workers, progress) as runner:
        located = locate(runner, st.windows, jobs)
    return prepared, located
