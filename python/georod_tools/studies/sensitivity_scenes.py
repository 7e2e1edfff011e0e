"""The scene files of the sensitivity study: variants of ``scenes/BuckledBeam.toml`` written as
text into the run folder and packaged with ``georod fmu`` (no rebuild).

A variant changes only what its question asks (:class:`SceneSpec`): the end shortening, the
``[model]`` keys (mass matrix, shear factor, rotational damping) or the way the end shortening is
applied (:data:`LOADINGS`):

- ``prescribed``: the repository's model: the right support is pushed in by `pre_shortening`
  and holds its axial position (the paper: "fixed in simple supports which restricts its axial
  motion").
- ``dead``: a dead axial load ``P_axial`` at the right end, which is free to move axially. With
  ``P_axial`` equal to the axial force of the prescribed state, the static state is the very same
  equilibrium (same shortening, same deflection); only the dynamics differ, since the axial
  force no longer changes as the beam swings.
- ``buckling``: the paper's 0.11 read as the buckling part of the shortening only, i.e. the end
  is pushed in by 0.11 plus the axial strain part ``N L / EA`` (N: the axial force of that
  buckled state, found by fixed-point iteration).

Each generated file is checked by reading it back with ``tomllib``; every text edit must match
exactly once, so a change of the base scene file fails loudly instead of silently.
"""

from __future__ import annotations

import math
import re
import subprocess
import tomllib
from dataclasses import dataclass
from pathlib import Path

from georod_tools import REPO_ROOT, SCENE_DIR
from georod_tools.command import executable
from georod_tools.fmu import FmuModel, lend

BASE_SCENE = SCENE_DIR / "BuckledBeam.toml"
LIBRARY = REPO_ROOT / "target" / "libs" / "libgeorod.so"
LOADINGS = ("prescribed", "dead", "buckling")
#: The paper's end shortening (the FMU's default `pre_shortening`).
PAPER_SHORTENING = 0.11


@dataclass(frozen=True)
class SceneSpec:
    """What a variant scene changes against ``scenes/BuckledBeam.toml``.

    pre_shortening: end shortening (prescribed / buckling: the support's displacement; dead: the
        static shortening the dead load is calibrated to).
    mass: ``consistent`` or ``lumped`` ([model] mass).
    shear_factor: [model] shear_factor (1: the model's).
    rotational_damping: [model] rotational_damping, per unit length (0: the model's).
    loading: one of :data:`LOADINGS`.
    axial_load: the dead load ``P_axial`` (loading ``dead`` only; set by :func:`calibrate`).
    """

    pre_shortening: float = PAPER_SHORTENING
    mass: str = "consistent"
    shear_factor: float = 1.0
    rotational_damping: float = 0.0
    loading: str = "prescribed"
    axial_load: float | None = None

    def __post_init__(self) -> None:
        if self.loading not in LOADINGS:
            raise ValueError(f"loading {self.loading!r}: one of {', '.join(LOADINGS)}")
        if self.mass not in ("consistent", "lumped"):
            raise ValueError(f"mass {self.mass!r}: consistent or lumped")
        if self.loading == "dead" and self.axial_load is None:
            raise ValueError("a dead-load scene needs its axial_load (see calibrate)")


def _sub(text: str, pattern: str, repl: str) -> str:
    """`text` with the one match of `pattern` replaced; ValueError unless exactly one match."""
    new, n = re.subn(pattern, repl, text, flags=re.MULTILINE | re.DOTALL)
    if n != 1:
        raise ValueError(f"{BASE_SCENE.name}: pattern {pattern!r} matched {n} times, not once")
    return new


def scene_text(spec: SceneSpec, name: str) -> str:
    """The TOML text of the variant `spec` of the BuckledBeam scene, named `name`."""
    text = BASE_SCENE.read_text()
    text = _sub(text, r'^name = "BuckledBeam"$', f'name = "{name}"')
    shortening = spec.pre_shortening
    text = _sub(
        text,
        r'(name = "pre_shortening"\nstart = )[0-9.eE+-]+',
        rf"\g<1>{shortening!r}",
    )
    if spec.loading == "dead":
        text = _sub(
            text,
            r'(name = "right"\nat = 1.0\n)fix = \["u1", "u2"\]\ndisplace = \{[^}]*\}\n',
            r'\g<1>fix = ["u2"]                     # free to move axially under P_axial\n',
        )
        text += (
            "\n[[parameter]]\n"
            'name = "P_axial"\n'
            f"start = {spec.axial_load!r}\n"
            'unit = "N"\n'
            "min = 0.0\n"
            'description = "Dead axial load at the right end (calibrated to the shortening)"\n'
            "\n[[load]]\n"
            'name = "axial"\n'
            'kind = "point"\n'
            "at = 1.0\n"
            'direction = "-e1"\n'
            'value = "P_axial"\n'
            "\n[[sensor]]\n"
            'name = "u_end"\n'
            "at = 1.0\n"
            'quantity = "u1"\n'
            'description = "Axial displacement of the right end"\n'
        )
    model = []
    if spec.mass != "consistent":
        model.append(f'mass = "{spec.mass}"')
    if spec.shear_factor != 1.0:
        model.append(f"shear_factor = {spec.shear_factor!r}")
    if spec.rotational_damping != 0.0:
        model.append(f"rotational_damping = {spec.rotational_damping!r}")
    if model:
        text += "\n[model]\n" + "\n".join(model) + "\n"
    header = f"# Generated by georod-tools study sensitivity from scenes/BuckledBeam.toml: {spec}\n"
    text = header + text
    _check(text, spec, name)
    return text


def _check(text: str, spec: SceneSpec, name: str) -> None:
    data = tomllib.loads(text)
    assert data["name"] == name
    start = {p["name"]: p["start"] for p in data.get("parameter", [])}
    assert start["pre_shortening"] == spec.pre_shortening
    model = data.get("model", {})
    assert model.get("mass", "consistent") == spec.mass
    assert model.get("shear_factor", 1.0) == spec.shear_factor
    assert model.get("rotational_damping", 0.0) == spec.rotational_damping
    right = next(s for s in data["support"] if s["name"] == "right")
    assert ("u1" in right["fix"]) == (spec.loading != "dead")


def package(spec: SceneSpec, name: str, folder: Path) -> Path:
    """Writes ``folder/<name>.toml`` and packages it into ``folder/<name>.fmu``."""
    folder.mkdir(parents=True, exist_ok=True)
    scene = folder / f"{name}.toml"
    scene.write_text(scene_text(spec, name))
    fmu = folder / f"{name}.fmu"
    cmd = [str(executable()), "fmu", str(scene), "-o", str(fmu), "--lib", str(LIBRARY)]
    r = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if r.returncode != 0:
        raise RuntimeError(f"georod fmu {scene} failed: {r.stderr.strip()}")
    return fmu


def static_outputs(fmu: Path, names: list[str], params: dict[str, float]) -> list[float]:
    """Outputs of the FMU's initial (static) state with `params` set."""
    with lend(FmuModel.load(fmu), "static") as inst:
        inst.initialize(params)
        return [float(x) for x in inst.get(names)]


def axial_force(fmu: Path, shortening: float, elements: int) -> float:
    """The compressive axial force of the prescribed static state (|right_Rx|)."""
    return abs(
        static_outputs(fmu, ["right_Rx"], {"pre_shortening": shortening, "elements": elements})[0]
    )


def axial_stiffness(fmu: Path) -> float:
    """EA / L of the scene's defaults (E b h / L)."""
    model = FmuModel.load(fmu)
    E, b, h, L = (model.start(n) for n in ("E", "b", "h", "L"))
    assert E and b and h and L
    return E * b * h / L


def buckling_shortening(fmu: Path, buckling_part: float, elements: int, rounds: int = 4) -> float:
    """The end displacement whose buckling part (total minus the axial strain part N L / EA) is
    `buckling_part`: fixed-point iteration on N (which changes by well under 1 % per round)."""
    k = axial_stiffness(fmu)
    total = buckling_part + axial_force(fmu, buckling_part, elements) / k
    for _ in range(rounds):
        total = buckling_part + axial_force(fmu, total, elements) / k
    if not math.isfinite(total):
        raise RuntimeError("no buckled state for the buckling-part reading")
    return total
