"""Every FMU in the Ecos co-simulation engine (ecospy): loaded, every parameter set to its start
value through a parameter set (the Integer `integrator` included), initialized and stepped, with
finite outputs; `integrator = 2` reaches the FMU."""

from __future__ import annotations

import math
from pathlib import Path

import fmpy
from ecospy import EcosSimulation, EcosSimulationStructure

from helpers import FMU_DIR, SCENE_FILES


def test_ecos_loads_sets_and_steps_every_fmu(fmu_paths: dict[str, Path]) -> None:
    for scene in SCENE_FILES:
        name = scene.stem
        md = fmpy.read_model_description(str(FMU_DIR / f"{name}.fmu"))
        params = {}
        for v in md.modelVariables:
            if v.causality == "parameter":
                value = int(v.start) if v.type == "Integer" else float(v.start)
                params[f"m::{v.name}"] = value
        params["m::integrator"] = 2
        structure = EcosSimulationStructure()
        structure.add_model("m", str(FMU_DIR / f"{name}.fmu"))
        structure.add_parameter_set("all", params)
        step = float(md.defaultExperiment.stepSize)
        sim = EcosSimulation(structure=structure, step_size=step)
        try:
            sim.init(parameter_set="all")
            sim.step(5)
            assert sim.get_integer("m::integrator") == 2, name
            outputs = [v for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
            assert outputs, name
            for out in outputs:
                assert math.isfinite(sim.get_real(f"m::{out.name}")), f"{name}.{out.name}"
            assert abs(sim.get_time() - 5 * step) < 1e-12, name
        finally:
            sim.terminate()
