"""Declared bounds are honest and outputs are finite (issue 13, items 6 and 7), for every FMU of
scenes/ and examples/:

- every min and max a modelDescription.xml declares is accepted when set exactly (FMI 2.0 bounds
  are inclusive), and, set alone, initializes with every output finite: a declared bound is a
  value the FMU works with (e.g. `elements` of ThreeSpan declares [3, 100000]: one element per
  span at least). The only exceptions are the bounds listed in
  UNREPRESENTABLE, where double precision runs out; there initialization may instead be refused
  with fmi2Error and a message;
- with an extreme in-range combination, initialization either succeeds with every output finite,
  or fails with fmi2Error and a message;
- each step after a successful initialization either succeeds with every output finite, or is
  discarded with a message.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path

import fmpy
import pytest
from fmpy.fmi1 import FMICallException

from helpers import FMU_DIR, REPO, LogCapture

ERROR, DISCARD = 3, 2
NAMES = tuple(sorted(p.stem for d in ("scenes", "examples") for p in (REPO / d).glob("*.toml")))
#: The smallest positive normal number, the declared minimum of every positive quantity.
TINY = 2.2250738585072014e-308
#: Declared bounds at which a scene may be unrepresentable in double precision, so that its
#: initialization may be refused with a message (docs/fmu_hardening.md): a modulus, density,
#: section (b, h; a tube's D, t; a general section's A, I, As; each also as a frame member's
#: `<member>_<dimension>`), span or rise of 2.2e-308 underflows the stiffnesses or masses
#: (I = b h^3 / 12 = 0) or
#: overflows an arc's radius; nu = -0.9999999999999999, the double next to -1, makes
#: G = E / (2 (1 + nu)) about 4.5e15 E, and the tangent of a bent rod is singular to round-off.
UNREPRESENTABLE = frozenset(
    {(name, TINY) for name in ("E", "rho", "b", "h", "D", "t", "A", "I", "As", "L", "H")}
    | {("nu", -0.9999999999999999)}
)
#: A frame member's own section dimensions are parameters `<member>_<dimension>`.
DIMENSIONS = frozenset({"b", "h", "D", "t", "A", "I", "As", "depth"})


def dimension_of(name: str) -> str:
    """`column_h` -> `h`: a member's section dimension stands for the dimension; other names
    stand for themselves."""
    member, _, dimension = name.rpartition("_")
    return dimension if member and dimension in DIMENSIONS else name


#: A declared element count above this is checked by its own test (a slow initialization).
LARGE_MESH = 1000
#: The scenes whose largest mesh the suite checks: every one that takes under 2.5 s (rods with
#: and without a static initial state, arches, a frame, stops, a moving load). The others, 3 to
#: 13 s each (a clamped rod's continuation, a truss bridge, an arch on columns), are
#: `exhaustive`: scripts/test_exhaustive runs them.
LARGEST_MESH_IN_SUITE = frozenset(
    {
        "BeamOnBase",
        "BeamOnFoundation",
        "Bridge",
        "ClampedArch",
        "ElasticBearings",
        "ImpactingCantilever",
        "PinnedArch",
        "PortalFrame",
        "ThreeSpan",
    }
)
#: Extreme combinations inside the declared ranges (parameters a scene lacks are skipped).
EXTREMES: tuple[dict[str, float], ...] = (
    {"E": 1e30, "rho": 1e-30},
    {"E": 1e-30, "rho": 1e30},
    {"h": 1e-6, "b": 1e-6},
    {"h": 1e6, "b": 1e6},
    {"L": 1e-9},
    {"L": 1e9, "H": 1e-9},
    {"H": 1e-12},
    {"d": 1e12, "F": 1e12},
    {"nu": -0.9999999999999999, "E": 1e200},
    {"dt_max": 1e-300},
    {"P0": 1e9},
    {"P": -1e9},
    {"pre_shortening": 9.0},
)


def check_run(path: Path, values: dict[str, float], steps: int = 3) -> str:
    """Sets `values`, initializes and steps; asserts the contract; returns what happened."""
    md = fmpy.read_model_description(str(path))
    variables = {v.name: v for v in md.modelVariables}
    outputs = [v for v in md.modelVariables if v.causality == "output"]
    log = LogCapture()
    slave = new_slave_for(md, extracted(path))
    slave.instantiate(callbacks=log.callbacks, loggingOn=True)
    try:
        slave.setupExperiment(startTime=0.0)
        for name, value in values.items():
            v = variables[name]
            if v.type == "Real":
                slave.setReal([v.valueReference], [value])
            else:
                slave.setInteger([v.valueReference], [int(value)])
        slave.enterInitializationMode()
        try:
            slave.exitInitializationMode()
        except FMICallException as e:
            assert e.status == ERROR, f"{values}: init returned {e.status}"
            assert log.messages(), f"{values}: init refused without a message"
            return "init refused"
        finite(slave, outputs, f"{path.stem} {values} after init")
        h = float(md.defaultExperiment.stepSize)
        for k in range(steps):
            try:
                slave.doStep(k * h, h)
            except FMICallException as e:
                assert e.status in (DISCARD, ERROR), f"{values}: step returned {e.status}"
                assert log.messages(), f"{values}: step refused without a message"
                return f"step {k} refused"
            finite(slave, outputs, f"{path.stem} {values} after step {k}")
        return "ran"
    finally:
        slave.freeInstance()


def inside(v: object, x: float) -> bool:
    """Whether `x` is within variable `v`'s declared min and max."""
    lo, hi = getattr(v, "min", None), getattr(v, "max", None)
    return (lo is None or float(lo) <= x) and (hi is None or x <= float(hi))


@functools.cache
def extracted(path: Path) -> str:
    return str(fmpy.extract(str(path)))


def new_slave_for(md: fmpy.model_description.ModelDescription, unzipdir: str):  # noqa: ANN201
    from fmpy.fmi2 import FMU2Slave

    return FMU2Slave(
        guid=md.guid,
        unzipDirectory=unzipdir,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="bounds",
    )


def finite(slave, outputs, where: str) -> None:  # noqa: ANN001
    reals = [v.valueReference for v in outputs if v.type == "Real"]
    values = slave.getReal(reals)
    bad = [
        v.name
        for v, x in zip((v for v in outputs if v.type == "Real"), values, strict=True)
        if not math.isfinite(x)
    ]
    assert not bad, f"{where}: non-finite outputs {bad[:5]}"


@pytest.mark.parametrize("name", NAMES)
def test_every_declared_bound_is_accepted_and_outputs_stay_finite(
    fmu_paths: dict[str, Path], name: str
) -> None:
    path = FMU_DIR / f"{name}.fmu"
    md = fmpy.read_model_description(str(path))
    outcomes = {}
    for v in md.modelVariables:
        if v.causality != "parameter":
            continue
        for bound in (v.min, v.max):
            if bound is None:
                continue
            value = float(bound)
            if v.name == "elements" and value > LARGE_MESH:
                continue  # test_the_largest_declared_mesh_initializes_and_steps
            outcomes[(v.name, value)] = check_run(path, {v.name: value})
    assert outcomes, f"{name}: no declared bounds"
    print(name, outcomes)
    refused = [k for k, what in outcomes.items() if what == "init refused"]
    assert {(dimension_of(n), v) for n, v in refused} <= UNREPRESENTABLE, (
        f"{name}: declared bounds that do not initialize: {sorted(refused)}"
    )


@pytest.mark.parametrize(
    "name",
    [
        n if n in LARGEST_MESH_IN_SUITE else pytest.param(n, marks=pytest.mark.exhaustive)
        for n in NAMES
    ],
)
def test_the_largest_declared_mesh_initializes_and_steps(
    fmu_paths: dict[str, Path], name: str
) -> None:
    """`elements` at its declared maximum (100000): the initial state (static continuation where
    the scene has one) and one step, every output finite. One step is enough: each step's cost is
    linear in the elements, and the bound is about the mesh being valid."""
    path = FMU_DIR / f"{name}.fmu"
    md = fmpy.read_model_description(str(path))
    (elements,) = [v for v in md.modelVariables if v.name == "elements"]
    assert float(elements.max) > LARGE_MESH
    assert check_run(path, {"elements": float(elements.max)}, steps=1) == "ran"


@pytest.mark.parametrize("name", NAMES)
def test_extreme_combinations_keep_outputs_finite(fmu_paths: dict[str, Path], name: str) -> None:
    path = FMU_DIR / f"{name}.fmu"
    md = fmpy.read_model_description(str(path))
    variables = {v.name: v for v in md.modelVariables}
    ran = 0
    for combination in EXTREMES:
        # Within the scene's declared ranges (a frame's L is its size, fixed at one value).
        values = {
            k: v for k, v in combination.items() if k in variables and inside(variables[k], v)
        }
        if not values:
            continue
        check_run(path, values)
        ran += 1
    assert ran > 0
