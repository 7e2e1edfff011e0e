"""The settings at which ``georod-tools study paper`` runs section 6.1: the paper's literal data
(the BuckledBeam FMU's defaults) or the setting that reproduces the paper's window structure
best, chosen by the sensitivity study and recorded in
``docs/figures/buckled_beam/paper_settings.json`` (docs/paper_sensitivity.md says why).

A setting other than the literal one is a scene variant (:mod:`.sensitivity_scenes`) packaged into
the run folder; its mesh and time step are the cases' own settings. The side-by-side table puts
the 26 panels at both settings next to each other.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from georod_tools import REPO_ROOT
from georod_tools.analysis.case import CaseResult
from georod_tools.report.tables import markdown, write_text
from georod_tools.studies.paper import StudySettings, agreement, wells
from georod_tools.studies.paper_cases import PaperCase
from georod_tools.studies.sensitivity_scenes import PAPER_SHORTENING, SceneSpec, package

SETTINGS_FILE = REPO_ROOT / "docs" / "figures" / "buckled_beam" / "paper_settings.json"
SETTINGS = ("literal", "chosen", "both")


@dataclass(frozen=True)
class PaperSetting:
    """Model data and discretization of a run of the paper's cases.

    pre_shortening: end shortening (the paper: 0.11); elements; steps_per_period: midpoint
    sub-steps per forcing period; mass, shear_factor, rotational_damping: the scene's [model].
    """

    name: str = "literal"
    pre_shortening: float = PAPER_SHORTENING
    elements: int = 10
    steps_per_period: int = 128
    mass: str = "consistent"
    shear_factor: float = 1.0
    rotational_damping: float = 0.0

    @property
    def scene(self) -> SceneSpec:
        return SceneSpec(
            pre_shortening=self.pre_shortening,
            mass=self.mass,
            shear_factor=self.shear_factor,
            rotational_damping=self.rotational_damping,
        )

    @property
    def is_literal(self) -> bool:
        return replace(self, name="literal", elements=10, steps_per_period=128) == PaperSetting()


def load_setting(path: Path = SETTINGS_FILE) -> PaperSetting:
    """The chosen setting from its JSON file (keys as :class:`PaperSetting`; keys starting with
    an underscore or named ``why`` are documentation)."""
    data = json.loads(path.read_text())
    known = set(PaperSetting.__dataclass_fields__)
    values = {k: v for k, v in data.items() if k in known}
    unknown = sorted(k for k in data if k not in known and not k.startswith("_") and k != "why")
    if unknown:
        raise ValueError(f"{path}: unknown keys {', '.join(unknown)}")
    return PaperSetting(**{"name": "chosen", **values})


def apply(st: StudySettings, setting: PaperSetting, folder: Path) -> StudySettings:
    """`st` at `setting`: its FMU (the literal FMU, or the setting's scene packaged into
    `folder`), mesh and time step."""
    fmu = st.fmu
    if not setting.is_literal:
        fmu = str(package(setting.scene, f"BuckledBeam_{setting.name}", folder).resolve())
    return replace(st, fmu=fmu, elements=setting.elements, substeps=setting.steps_per_period)


def side_by_side(
    literal: Sequence[tuple[PaperCase, CaseResult]],
    chosen: Sequence[tuple[PaperCase, CaseResult]],
) -> list[dict[str, object]]:
    """One row per panel: the paper, then ours and the agreement at both settings."""
    rows = []
    for (case, a), (_, b) in zip(literal, chosen, strict=True):
        rows.append(
            {
                "case": case.name,
                "F": case.F,
                "Omega": case.Omega,
                "paper": case.paper_label + (f" ({case.wells} well)" if case.wells else ""),
                "literal": f"{a.classification.label}, {wells(a)}",
                "literal_agrees": agreement(case, a),
                "chosen": f"{b.classification.label}, {wells(b)}",
                "chosen_agrees": agreement(case, b),
            }
        )
    return rows


def count_line(rows: Sequence[dict[str, object]], key: str) -> str:
    n = len(rows)
    yes = sum(r[key] == "yes" for r in rows)
    partly = sum(r[key] == "partly" for r in rows)
    return f"{yes} of {n} agree, {partly} partly"


def write_side_by_side(rows: Sequence[dict[str, object]], setting: PaperSetting, out: Path) -> Path:
    cols = ("case", "F", "Omega", "paper", "literal", "literal_agrees", "chosen", "chosen_agrees")
    literal, chosen = count_line(rows, "literal_agrees"), count_line(rows, "chosen_agrees")
    head = (
        f"Literal data (pre_shortening 0.11, 10 elements, T/128): {literal}. "
        f"Chosen setting ({setting_text(setting)}): {chosen}."
    )
    return write_text(head + "\n\n" + markdown(rows, cols), out / "table_cases_side_by_side.md")


def setting_text(s: PaperSetting) -> str:
    text = f"pre_shortening {s.pre_shortening:g}, {s.elements} elements, T/{s.steps_per_period}"
    if s.mass != "consistent":
        text += f", {s.mass} mass"
    if s.shear_factor != 1.0:
        text += f", shear factor {s.shear_factor:.4g}"
    if s.rotational_damping:
        text += f", rotational damping {s.rotational_damping:.3g}"
    return text
