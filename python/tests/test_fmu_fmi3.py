"""FMI 3.0: the FMI 3.0 FMU of every scene file (target/fmu3/, from the same library and scene as
target/fmu/) validates and simulates with fmpy, steps bit for bit like the FMI 2.0 FMU, gives
its shape as arrays equal to the FMI 2.0 scalars, and round-trips its state."""

from __future__ import annotations

import ctypes
import re
import shutil
from collections.abc import Iterator
from pathlib import Path

import fmpy
import numpy as np
import pytest
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from fmpy.model_description import ModelDescription
from fmpy.validation import validate_fmu

from helpers import SCENE_FILES

NAMES = [f.stem for f in SCENE_FILES]
#: Every function of the FMI 3.0 standard (fmi3FunctionTypes.h), which the library must export.
FMI3_FUNCTIONS = """GetVersion SetDebugLogging InstantiateModelExchange InstantiateCoSimulation
InstantiateScheduledExecution FreeInstance EnterInitializationMode ExitInitializationMode
EnterEventMode Terminate Reset GetFloat32 GetFloat64 GetInt8 GetUInt8 GetInt16 GetUInt16 GetInt32
GetUInt32 GetInt64 GetUInt64 GetBoolean GetString GetBinary GetClock SetFloat32 SetFloat64 SetInt8
SetUInt8 SetInt16 SetUInt16 SetInt32 SetUInt32 SetInt64 SetUInt64 SetBoolean SetString SetBinary
SetClock GetNumberOfVariableDependencies GetVariableDependencies GetFMUState SetFMUState
FreeFMUState SerializedFMUStateSize SerializeFMUState DeserializeFMUState
GetDirectionalDerivative GetAdjointDerivative EnterConfigurationMode ExitConfigurationMode
GetIntervalDecimal GetIntervalFraction GetShiftDecimal GetShiftFraction SetIntervalDecimal
SetIntervalFraction SetShiftDecimal SetShiftFraction EvaluateDiscreteStates UpdateDiscreteStates
EnterContinuousTimeMode CompletedIntegratorStep SetTime SetContinuousStates
GetContinuousStateDerivatives GetEventIndicators GetContinuousStates
GetNominalsOfContinuousStates GetNumberOfEventIndicators GetNumberOfContinuousStates EnterStepMode
GetOutputDerivatives DoStep ActivateModelPartition""".split()
#: FMI 2.0 names of array elements: `shape_x[3]` -> ("shape_x", 3).
ELEMENT = re.compile(r"^(shape_\w+)\[(\d+)\]$")


class Pair:
    """The FMI 2.0 and 3.0 FMUs of one scene file, extracted, with their model descriptions."""

    def __init__(self, fmu2: Path, fmu3: Path, root: Path) -> None:
        self.fmu2, self.fmu3 = fmu2, fmu3
        self.dir2 = fmpy.extract(str(fmu2), unzipdir=str(root / "2"))
        self.dir3 = fmpy.extract(str(fmu3), unzipdir=str(root / "3"))
        self.md2: ModelDescription = fmpy.read_model_description(self.dir2)
        self.md3: ModelDescription = fmpy.read_model_description(self.dir3)

    def slaves(self) -> tuple[FMU2Slave, FMU3Slave]:
        ident = self.md2.coSimulation.modelIdentifier
        two = FMU2Slave(guid=self.md2.guid, unzipDirectory=self.dir2, modelIdentifier=ident)
        three = FMU3Slave(guid=self.md3.guid, unzipDirectory=self.dir3, modelIdentifier=ident)
        two.instantiate()
        two.setupExperiment(startTime=0.0)
        two.enterInitializationMode()
        two.exitInitializationMode()
        three.instantiate()
        three.enterInitializationMode(startTime=0.0)
        three.exitInitializationMode()
        return two, three


@pytest.fixture(params=NAMES)
def pair(
    request: pytest.FixtureRequest,
    fmu3_paths: dict[Path, tuple[Path, Path]],
    tmp_path_factory: pytest.TempPathFactory,
) -> Iterator[Pair]:
    file = next(f for f in fmu3_paths if f.stem == request.param)
    root = tmp_path_factory.mktemp(f"fmi3_{request.param}")
    yield Pair(*fmu3_paths[file], root)
    shutil.rmtree(root, ignore_errors=True)


def test_validate_and_simulate(pair: Pair) -> None:
    problems = validate_fmu(str(pair.fmu3))
    assert problems == [], "\n".join(problems)
    assert pair.md3.fmiVersion == "3.0"
    assert pair.md3.guid == pair.md2.guid, "the instantiation token is the FMI 2.0 GUID"
    cs = pair.md3.coSimulation
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate  # fmpy spells them so
    assert cs.canHandleVariableCommunicationStepSize
    assert not cs.hasEventMode and not cs.providesIntermediateUpdate
    step = float(pair.md3.defaultExperiment.stepSize)
    result = fmpy.simulate_fmu(str(pair.fmu3), stop_time=20 * step, output_interval=step)
    assert len(result) == 21
    points = [v for v in pair.md3.modelVariables if v.name == "shape_x"][0].dimensions[0].start
    assert result["shape_x"].shape == (21, int(points))
    assert np.all(np.isfinite(result["shape_x"]))


def test_every_function_of_the_standard_is_exported(pair: Pair) -> None:
    ident = pair.md3.coSimulation.modelIdentifier
    lib = ctypes.CDLL(str(Path(pair.dir3) / "binaries" / "x86_64-linux" / f"{ident}.so"))
    missing = [f"fmi3{name}" for name in FMI3_FUNCTIONS if not hasattr(lib, f"fmi3{name}")]
    assert missing == []
    assert (Path(pair.dir3) / "documentation" / "index.html").is_file()


def test_same_names_and_every_shape_family_is_one_array(pair: Pair) -> None:
    arrays: dict[str, int] = {}
    scalars2 = []
    for v in pair.md2.modelVariables:
        m = ELEMENT.match(v.name)
        if m:
            arrays[m.group(1)] = max(arrays.get(m.group(1), 0), int(m.group(2)))
        else:
            scalars2.append((v.name, v.valueReference, v.type, v.causality, v.unit))
    vars3 = {v.name: v for v in pair.md3.modelVariables}
    scalars3 = [
        (v.name, v.valueReference, "Real" if v.type == "Float64" else v.type, v.causality, v.unit)
        for v in pair.md3.modelVariables
        if not v.dimensions and v.name != "time"
    ]
    types = {"Int32": "Integer"}
    scalars3 = [(n, vr, types.get(t, t), c, u) for (n, vr, t, c, u) in scalars3]
    assert scalars3 == scalars2
    assert arrays, "every scene has a shape"
    for name, n in arrays.items():
        v = vars3[name]
        assert v.causality == "output" and v.type == "Float64"
        assert [int(d.start) for d in v.dimensions] == [n]
    assert vars3["time"].causality == "independent"


def test_fmi3_steps_bit_for_bit_like_fmi2_and_its_arrays_are_the_scalars(pair: Pair) -> None:
    two, three = pair.slaves()
    vr2 = {v.name: v.valueReference for v in pair.md2.modelVariables}
    outputs3 = [v for v in pair.md3.modelVariables if v.causality == "output"]
    step = float(pair.md3.defaultExperiment.stepSize)
    try:
        t = 0.0
        for _ in range(20):
            for v in outputs3:
                if v.type == "Int32":
                    assert three.getInt32([v.valueReference]) == two.getInteger([vr2[v.name]])
                    continue
                n = int(v.dimensions[0].start) if v.dimensions else 1
                got = np.array(three.getFloat64([v.valueReference], nValues=n))
                names = [f"{v.name}[{i}]" for i in range(1, n + 1)] if v.dimensions else [v.name]
                want = np.array(two.getReal([vr2[name] for name in names]))
                assert got.tobytes() == want.tobytes(), f"{v.name} at t = {t}"
                if v.dimensions:  # element-wise: one scalar read each
                    for i, name in enumerate(names):
                        assert two.getReal([vr2[name]])[0] == got[i]
            two.doStep(t, step)
            _, terminate, early, last = three.doStep(t, step)
            assert not terminate and not early
            t += step
            assert last == pytest.approx(t, rel=1e-12)
    finally:
        for slave in (two, three):
            slave.terminate()
            slave.freeInstance()


def test_state_round_trip(pair: Pair) -> None:
    _, three = pair.slaves()
    ident = [v for v in pair.md3.modelVariables if v.name == "shape_y"][0]
    n = int(ident.dimensions[0].start)
    step = float(pair.md3.defaultExperiment.stepSize)
    try:
        three.doStep(0.0, step)
        state = three.getFMUState()
        blob = three.serializeFMUState(state)
        for k in range(1, 4):
            three.doStep(k * step, step)
        after = three.getFloat64([ident.valueReference], nValues=n)
        restored = three.deserializeFMUState(blob)
        three.setFMUState(restored)
        for k in range(1, 4):
            three.doStep(k * step, step)
        assert three.getFloat64([ident.valueReference], nValues=n) == after
        three.freeFMUState(restored)
        three.freeFMUState(state)
    finally:
        three.terminate()
        three.freeInstance()
