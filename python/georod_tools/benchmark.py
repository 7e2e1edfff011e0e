"""Work-precision benchmark of the BuckledBeam FMU (through fmpy), side by side with Exudyn.

    python -m georod_tools benchmark [--quick] [--no-exudyn] [--out DIR] [--figures DIR]

What it measures (docs/benchmark.md shows the results):

1. the motion at the benchmark point (10 elements, F = 0.7, Omega = 4500) is periodic
   (stroboscopic samples and Lyapunov exponent through :func:`georod_tools.runner.run_case`);
2. the time-step error of ``w_mid`` over a fixed horizon of 20 forcing periods from the static
   buckled state, at 8 .. 1024 steps per period, against a reference with a much smaller step
   whose convergence is shown by successive refinements; error at the final time and the largest
   error on the communication grid; run time of the integration alone (median of repetitions;
   instantiation and the static initial solve excluded);
3. the same for Exudyn (ObjectBeamGeometricallyExact2D, generalized-alpha with spectral radius 1
   = trapezoidal rule), each method against its own converged reference, and the ratio of run
   times at equal error (log-log interpolation);
4. the two models side by side: static ``w_mid`` and the first natural frequencies about the
   buckled state for 10, 20, 40 elements;
5. the spatial error (4 .. 160 elements against 320, same step);
6. seconds per simulated forcing period for 10 .. 10000 elements (linear growth).

Exudyn is optional (``exudyn`` in python/requirements.txt); without it the Exudyn parts are
skipped and say so.
"""

from __future__ import annotations

import argparse
import contextlib
import cProfile
import csv
import io
import math
import os
import pstats
import shutil
import statistics
import subprocess
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from georod_tools.runner import CaseConfig, FmuModel, Instance, run_case

DEFAULT_OUT = Path("out") / "benchmark"
DEFAULT_FIGURES = Path("docs") / "figures"

# ------------------------------------------------------------------------------------- the scene


@dataclass(frozen=True)
class BeamScene:
    """The BuckledBeam scene of model.md (defaults = the FMU's) at one excitation."""

    E: float = 1.2e4
    nu: float = 0.2
    rho: float = 1.0e-6
    d: float = 5.0e-4
    b: float = 1.0
    h: float = 1.0
    L: float = 10.0
    pre_shortening: float = 0.11
    well: int = 1
    F: float = 0.7
    Omega: float = 4500.0

    @property
    def period(self) -> float:
        return 2.0 * math.pi / self.Omega

    def fmu_parameters(self) -> dict[str, float]:
        return {
            "E": self.E,
            "nu": self.nu,
            "rho": self.rho,
            "d": self.d,
            "b": self.b,
            "h": self.h,
            "L": self.L,
            "pre_shortening": self.pre_shortening,
            "well": self.well,
            "F": self.F,
            "Omega": self.Omega,
        }


def default_fmu() -> Path:
    from georod_tools import fmu_path

    return fmu_path("BuckledBeam")


def machine_load() -> str:
    """The 1/5/15-minute load averages and the CPU count, for the record."""
    try:
        a, b, c = os.getloadavg()
        return f"load average {a:.2f} {b:.2f} {c:.2f} on {os.cpu_count()} CPUs"
    except OSError:
        return f"load average unknown, {os.cpu_count()} CPUs"


# ----------------------------------------------------------------------------- the FMU (fmpy)


@dataclass
class Run:
    """One integration over a horizon: ``w`` at the communication points ``k h`` (``w[0]`` is the
    static state), the median wall time of the integration loop and every repetition's time."""

    w: np.ndarray
    seconds: float
    times: list[float]
    extra: dict[str, float] = field(default_factory=dict)


class FmuBeam:
    """One initialized BuckledBeam FMU instance (static solve done in the constructor) that can
    integrate the horizon repeatedly from its saved initial FMU state."""

    def __init__(
        self,
        scene: BeamScene,
        elements: int,
        dt_max: float,
        n_comm: int,
        fmu: Path | None = None,
    ) -> None:
        self.model = FmuModel.load(fmu or default_fmu())
        params = scene.fmu_parameters()
        params.update({"elements": elements, "dt_max": dt_max})
        self.inst = Instance(self.model, params, scene.Omega, n_comm, name="benchmark")
        self.slave = self.inst.slave
        self.h = self.inst.h
        self.vr_w = [self.model.vr["w_mid"]]
        self.vr_newton = [self.model.vr["newton_iterations"]]
        self.state0 = self.slave.getFMUstate()

    def w_static(self) -> float:
        self.slave.setFMUstate(self.state0)
        return float(self.slave.getReal(self.vr_w)[0])

    def integrate(self, steps: int, count_newton: bool = False) -> tuple[np.ndarray, float, int]:
        """`steps` communication steps from the initial state; returns w_mid at every
        communication point, the loop's wall time and (with `count_newton`, which adds one
        `fmi2GetInteger` per step to the loop) the total Newton corrections."""
        slave, h, vr, vrn = self.slave, self.h, self.vr_w, self.vr_newton
        slave.setFMUstate(self.state0)
        w = np.empty(steps + 1)
        w[0] = slave.getReal(vr)[0]
        newton = 0
        do_step, get_real, get_integer = slave.doStep, slave.getReal, slave.getInteger
        t0 = time.perf_counter()
        if count_newton:
            for k in range(steps):
                do_step(k * h, h)
                w[k + 1] = get_real(vr)[0]
                newton += get_integer(vrn)[0]
        else:
            for k in range(steps):
                do_step(k * h, h)
                w[k + 1] = get_real(vr)[0]
        seconds = time.perf_counter() - t0
        return w, seconds, newton

    def run(self, steps: int, repeats: int) -> Run:
        """One untimed run that counts the Newton corrections (instrumentation, like Exudyn's
        sensor run), then `repeats` timed runs of `fmi2DoStep` + `fmi2GetReal(w_mid)`."""
        _, _, newton = self.integrate(steps, count_newton=True)
        times: list[float] = []
        w = np.empty(0)
        for _ in range(max(1, repeats)):
            w, s, _ = self.integrate(steps)
            times.append(s)
        return Run(w, statistics.median(times), times, {"newton": float(newton)})

    def close(self) -> None:
        with contextlib.suppress(Exception):
            self.slave.freeFMUstate(self.state0)
        self.inst.close()


@contextlib.contextmanager
def fmu_beam(
    scene: BeamScene, elements: int, dt_max: float, n_comm: int, fmu: Path | None = None
) -> Iterator[FmuBeam]:
    beam = FmuBeam(scene, elements, dt_max, n_comm, fmu)
    try:
        yield beam
    finally:
        beam.close()


def fmu_run(
    scene: BeamScene,
    n: int,
    periods: int,
    repeats: int,
    elements: int = 10,
    comm_per_period: int | None = None,
    fmu: Path | None = None,
) -> Run:
    """`periods` forcing periods with ``dt_max = T / n`` and communication step ``T / c``
    (``c = comm_per_period`` or `n`; `n` must be a multiple of c)."""
    c = comm_per_period or n
    if n % c:
        raise ValueError(f"{n} steps per period is not a multiple of {c} communication steps")
    # dt_max a hair above T/n so that the FMU cuts T/c into exactly n/c sub-steps
    with fmu_beam(scene, elements, scene.period / n * (1 + 1e-9), c, fmu) as beam:
        return beam.run(periods * c, repeats)


def core_seconds(scene: BeamScene, n: int, periods: int, elements: int = 10) -> float | None:
    """Wall time of the Rust core alone (``georod bench-steps``, no FMI, no Python) for the same
    integration; None when the binary is missing."""
    from georod_tools import REPO_ROOT

    exe = REPO_ROOT / "target" / "release" / "georod"
    if not exe.is_file():
        return None
    args = [str(exe), "bench-steps", "--scene", "BuckledBeam"]
    for k, v in scene.fmu_parameters().items():
        args += ["--set", f"{k}={v!r}"]
    dt = scene.period / n
    args += ["--set", f"elements={elements}", "--set", f"dt_max={dt * (1 + 1e-9)!r}"]
    args += ["--steps", str(periods * n), "--dt", repr(dt)]
    times = []
    for _ in range(3):  # median of 3: the machine is shared
        out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
        times.append(float(out.split()[0]))  # seconds of the stepping loop alone
    return statistics.median(times)


# ------------------------------------------------------------------------------------- Exudyn


def exudyn_status() -> tuple[bool, str]:
    """(importable, version or the reason it is not)."""
    try:
        import exudyn

        try:
            version = exudyn.config.Version()
        except Exception:  # noqa: BLE001 - older API
            version = exudyn.__version__
        return True, str(version)
    except Exception as e:  # noqa: BLE001
        return False, f"{type(e).__name__}: {e}"


class ExudynBeam:
    """The BuckledBeam in Exudyn: ObjectBeamGeometricallyExact2D elements on NodeRigidBody2D,
    pinned ends by coordinate constraints (right end u1 = -pre_shortening via the constraint
    offset), translational viscous damping d as a consistent 6x6 damping matrix per element
    (ObjectGenericODE2, d l/6 [[2, 1], [1, 2]] on u1, u2), the uniform load F cos(Omega t) along
    -e2 as nodal loads (F l on interior nodes = the consistent load of a uniform q) through a
    symbolic (C++) user function, and the static buckled state (Newton from a half-sine guess in
    the chosen well, no load) as the initial state.
    """

    def __init__(self, scene: BeamScene, elements: int, python_load: bool = False) -> None:
        import exudyn as exu

        self.exu = exu
        self.scene = scene
        self.elements = elements
        self.python_load = python_load
        self._keep: list[object] = []
        self._tmp = tempfile.mkdtemp(prefix="georod_exudyn_")
        q_static, ae_static = self._static_state()
        self.w_static = float(q_static[3 * (elements // 2) + 1])
        self.SC, self.mbs, self.nodes, self.sensor = self._build(True, q_static, ae_static)
        self.q_static = q_static

    def settings(self) -> object:
        exu = self.exu
        ss = exu.SimulationSettings()
        ss.solution.file.write = False
        ss.solution.sensors.active = False
        ss.solution.restart.write = False
        ss.solution.solverInformationFileName = os.path.join(self._tmp, "solverInformation.txt")
        ss.displayStatistics = False
        ss.displayComputationTime = False
        ss.staticSolver.verboseMode = 0
        ss.staticSolver.newton.relativeTolerance = 1e-10
        ss.staticSolver.newton.absoluteTolerance = 1e-12
        ss.timeIntegration.verboseMode = 0
        ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0  # trapezoidal rule
        # tight enough that Newton never limits the error measured here
        ss.timeIntegration.newton.relativeTolerance = 1e-10
        ss.timeIntegration.newton.absoluteTolerance = 1e-12
        return ss

    def _build(
        self,
        loaded: bool,
        q0: np.ndarray | None,
        ae0: np.ndarray | None,
    ) -> tuple[object, object, list[int], object]:
        exu = self.exu
        import exudyn.itemInterface as ii

        sc = self.scene
        ne = self.elements
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        length = sc.L / ne
        A, Iz = sc.b * sc.h, sc.b * sc.h**3 / 12.0
        G = sc.E / (2.0 * (1.0 + sc.nu))
        amp = 0.33 * sc.well  # half-sine guess of the buckled shape (Newton finds the state)
        nodes = []
        for i in range(ne + 1):
            x = i * length
            if q0 is None:
                init = [
                    -sc.pre_shortening * x / sc.L,
                    amp * math.sin(math.pi * x / sc.L),
                    amp * math.pi / sc.L * math.cos(math.pi * x / sc.L),
                ]
            else:
                init = [float(v) for v in q0[3 * i : 3 * i + 3]]
            nodes.append(
                mbs.AddNode(
                    ii.NodeRigidBody2D(referenceCoordinates=[x, 0.0, 0.0], initialCoordinates=init)
                )
            )
        c = sc.d * length / 6.0
        damping = np.zeros((6, 6))
        for i in (0, 1):
            for j in (0, 1):
                f = c * (2.0 if i == j else 1.0)
                damping[3 * i, 3 * j] = f
                damping[3 * i + 1, 3 * j + 1] = f
        for e in range(ne):
            mbs.AddObject(
                ii.ObjectBeamGeometricallyExact2D(
                    nodeNumbers=[nodes[e], nodes[e + 1]],
                    length=length,
                    massPerLength=sc.rho * A,
                    crossSectionInertia=sc.rho * Iz,
                    bendingStiffness=sc.E * Iz,
                    axialStiffness=sc.E * A,
                    shearStiffness=G * A,  # no shear correction factor (model.md)
                    visualization=ii.VObjectBeamGeometricallyExact2D(show=False),
                )
            )
            if sc.d > 0:
                mbs.AddObject(
                    ii.ObjectGenericODE2(
                        nodeNumbers=[nodes[e], nodes[e + 1]],
                        dampingMatrix=damping,
                        visualization=ii.VObjectGenericODE2(show=False),
                    )
                )
        ground = mbs.AddNode(ii.NodePointGround())
        mg = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
        for node, coord, offset in (
            (nodes[0], 0, 0.0),
            (nodes[0], 1, 0.0),
            (nodes[-1], 0, -sc.pre_shortening),
            (nodes[-1], 1, 0.0),
        ):
            m = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=node, coordinate=coord))
            mbs.AddObject(
                ii.ObjectConnectorCoordinate(
                    markerNumbers=[mg, m],
                    offset=offset,
                    visualization=ii.VObjectConnectorCoordinate(show=False),
                )
            )
        if loaded:
            omega = sc.Omega
            if self.python_load:

                def load(mbs_: object, t: float, v: Sequence[float]) -> list[float]:
                    s = math.cos(omega * t)
                    return [v[0] * s, v[1] * s, v[2] * s]

                uf: object = load
            else:
                from exudyn.advancedUtilities import CreateSymbolicUserFunction

                esym = exu.symbolic

                def load_sym(mbs_: object, t: object, v: object) -> object:
                    return v * esym.cos(omega * t)  # type: ignore[operator]

                uf = CreateSymbolicUserFunction(
                    mbs, load_sym, "loadVectorUserFunction", itemTypeName="LoadForceVector"
                )
                self._keep.append(uf)
            for node in nodes[1:-1]:
                m = mbs.AddMarker(ii.MarkerNodePosition(nodeNumber=node))
                mbs.AddLoad(
                    ii.LoadForceVector(
                        markerNumber=m,
                        loadVector=[0.0, -sc.F * length, 0.0],
                        loadVectorUserFunction=uf,
                        visualization=ii.VLoadForceVector(show=False),
                    )
                )
        sensor = mbs.AddSensor(
            ii.SensorNode(
                nodeNumber=nodes[ne // 2],
                outputVariableType=exu.OutputVariableType.Coordinates,
                storeInternal=True,
                writeToFile=False,
                visualization=ii.VSensorNode(show=False),
            )
        )
        mbs.Assemble()
        if ae0 is not None:
            mbs.systemData.SetAECoordinates(ae0, configuration=exu.ConfigurationType.Initial)
        return SC, mbs, nodes, sensor

    def _static_state(self) -> tuple[np.ndarray, np.ndarray]:
        exu = self.exu
        SC, mbs, _, _ = self._build(False, None, None)
        ss = self.settings()
        if not mbs.SolveStatic(ss):
            raise RuntimeError("Exudyn: static solve of the buckled beam failed")
        q = np.array(mbs.systemData.GetODE2Coordinates(), dtype=float)
        ae = np.array(mbs.systemData.GetAECoordinates(), dtype=float)
        # solvers start from the initial configuration: make it the static state
        mbs.systemData.SetODE2Coordinates(q.tolist(), configuration=exu.ConfigurationType.Initial)
        mbs.systemData.SetAECoordinates(ae.tolist(), configuration=exu.ConfigurationType.Initial)
        self._static_system = (SC, mbs)
        del exu
        return q, ae

    def frequencies(self, count: int) -> np.ndarray:
        """The lowest `count` natural frequencies (rad/s) about the static state: Exudyn's mass
        matrix and ODE2 Jacobian (its own differentiation), prescribed coordinates removed,
        generalized symmetric eigenproblem in numpy."""
        exu = self.exu
        _, mbs = self._static_system
        solver = exu.MainSolverStatic()
        ss = self.settings()
        solver.InitializeSolver(mbs, ss)
        n = solver.GetODE2size()
        solver.ComputeMassMatrix(mbs)
        M = np.array(solver.GetSystemMassMatrix())[:n, :n]
        solver.ComputeJacobianODE2RHS(
            mbs, scalarFactor_ODE2=-1.0, scalarFactor_ODE2_t=0.0, scalarFactor_ODE1=0.0
        )
        K = np.array(solver.GetSystemJacobian())[:n, :n]
        solver.FinalizeSolver(mbs, ss)
        ne = self.elements
        fixed = [0, 1, 3 * ne, 3 * ne + 1]
        return generalized_frequencies(K, M, fixed, count)

    def run(self, n: int, periods: int, repeats: int, record: bool = True) -> Run:
        """`periods` forcing periods with step ``T / n``; the timed part is the solver's
        SolveSteps (InitializeSolver, which also computes the initial accelerations, and
        FinalizeSolver are outside). With `record`, one more (untimed) run stores w_mid at every
        step through an internal sensor; the timed runs have every output off."""
        exu = self.exu
        mbs = self.mbs
        sc = self.scene
        steps = periods * n
        times: list[float] = []
        newton = 0.0
        w_end = math.nan
        if not record:
            repeats = max(1, repeats)
        for rep in range(repeats + (1 if record else 0)):
            recording = record and rep == repeats
            ss = self.settings()
            ss.timeIntegration.endTime = periods * sc.period
            ss.timeIntegration.numberOfSteps = steps
            ss.solution.sensors.active = recording
            ss.solution.sensors.writePeriod = 0.0
            solver = exu.MainSolverImplicitSecondOrder()
            solver.InitializeSolver(mbs, ss)
            t0 = time.perf_counter()
            ok = solver.SolveSteps(mbs, ss)
            seconds = time.perf_counter() - t0
            it = solver.it
            newton = float(it.newtonStepsCount)
            solver.FinalizeSolver(mbs, ss)
            if not ok or it.numberOfSteps != steps:
                raise RuntimeError(f"Exudyn: integration with T/{n} failed or changed its step")
            w_end = float(
                mbs.GetNodeOutput(
                    self.nodes[self.elements // 2], exu.OutputVariableType.Coordinates
                )[1]
            )
            if not recording:
                times.append(seconds)
        if record:
            data = np.array(mbs.GetSensorStoredData(self.sensor), dtype=float)
            w = data[:, 2]
            if len(w) != steps + 1:  # sensor rows per step: keep one per step time
                tgrid = np.arange(steps + 1) * sc.period / n
                w = np.interp(tgrid, data[:, 0], data[:, 2])
        else:
            w = np.array([self.w_static, w_end])
        secs = statistics.median(times) if times else math.nan
        return Run(w, secs, times, {"newton": newton, "w_end": w_end})

    def close(self) -> None:
        shutil.rmtree(self._tmp, ignore_errors=True)


def generalized_frequencies(
    K: np.ndarray, M: np.ndarray, fixed: Sequence[int], count: int
) -> np.ndarray:
    """sqrt of the lowest `count` eigenvalues of ``K x = lambda M x`` with the `fixed` rows and
    columns removed (K symmetrized; a negative eigenvalue gives a negative frequency)."""
    free = np.setdiff1d(np.arange(K.shape[0]), np.asarray(fixed, dtype=int))
    Kf = K[np.ix_(free, free)]
    Kf = 0.5 * (Kf + Kf.T)
    Mf = M[np.ix_(free, free)]
    Lc = np.linalg.cholesky(0.5 * (Mf + Mf.T))
    Li = np.linalg.inv(Lc)
    lam = np.linalg.eigvalsh(Li @ Kf @ Li.T)[:count]
    return np.sign(lam) * np.sqrt(np.abs(lam))


# ------------------------------------------------------- georod's own tangent (model.md, numpy)


def georod_internal_force(q: np.ndarray, scene: BeamScene, elements: int) -> np.ndarray:
    """Internal force of model.md's hybrid element for a straight rod (alpha = 0), vectorized:
    2 Gauss points for the strains, constant n = C b(u) / l, exact bending. Used only to get the
    linearized frequencies about the FMU's static state (the FMU has no Jacobian output); its
    residual at that state is checked to be at round-off."""
    sc = scene
    ne = elements
    length = sc.L / ne
    A, Iz = sc.b * sc.h, sc.b * sc.h**3 / 12.0
    EA, GA, EI = sc.E * A, sc.E / (2 * (1 + sc.nu)) * A, sc.E * Iz
    u = q.reshape(ne + 1, 3)
    a, b = u[:-1], u[1:]
    du1 = (b[:, 0] - a[:, 0]) / length
    du2 = (b[:, 1] - a[:, 1]) / length
    kappa = (b[:, 2] - a[:, 2]) / length
    g = 1.0 / math.sqrt(3.0)
    bvec = np.zeros((ne, 2))
    B = np.zeros((ne, 2, 6))
    for xi in (-g, g):
        n1, n2 = (1 - xi) / 2, (1 + xi) / 2
        w = n1 * a[:, 2] + n2 * b[:, 2]
        cw, sw = np.cos(w), np.sin(w)
        e1 = cw * (1 + du1) + sw * du2 - 1
        e2 = -sw * (1 + du1) + cw * du2
        half = length / 2
        bvec[:, 0] += half * e1
        bvec[:, 1] += half * e2
        # d e1 / d(u1a, u2a, wa, u1b, u2b, wb); d e1/dw = e2, d e2/dw = -(e1 + 1)
        B[:, 0, 0] += half * (-cw / length)
        B[:, 0, 3] += half * (cw / length)
        B[:, 0, 1] += half * (-sw / length)
        B[:, 0, 4] += half * (sw / length)
        B[:, 0, 2] += half * e2 * n1
        B[:, 0, 5] += half * e2 * n2
        B[:, 1, 0] += half * (sw / length)
        B[:, 1, 3] += half * (-sw / length)
        B[:, 1, 1] += half * (-cw / length)
        B[:, 1, 4] += half * (cw / length)
        B[:, 1, 2] += half * (-(e1 + 1)) * n1
        B[:, 1, 5] += half * (-(e1 + 1)) * n2
    S = np.stack([EA * bvec[:, 0], GA * bvec[:, 1]], axis=1) / length
    fe = np.einsum("eij,ei->ej", B, S)
    fe[:, 2] -= EI * kappa
    fe[:, 5] += EI * kappa
    f = np.zeros((ne + 1, 3))
    f[:-1] += fe[:, :3]
    f[1:] += fe[:, 3:]
    return f.ravel()


def georod_mass(scene: BeamScene, elements: int) -> np.ndarray:
    sc = scene
    ne = elements
    length = sc.L / ne
    A, Iz = sc.b * sc.h, sc.b * sc.h**3 / 12.0
    n = 3 * (ne + 1)
    M = np.zeros((n, n))
    for e in range(ne):
        for i in (0, 1):
            for j in (0, 1):
                f = length / 6.0 * (2.0 if i == j else 1.0)
                for dof, m in ((0, sc.rho * A), (1, sc.rho * A), (2, sc.rho * Iz)):
                    M[3 * (e + i) + dof, 3 * (e + j) + dof] += m * f
    return M


def fmu_static_state(scene: BeamScene, elements: int, fmu: Path | None = None) -> np.ndarray:
    """The FMU's static initial displacements (decoded from its serialized state)."""
    from georod_tools.fmu_state import decode_state

    with fmu_beam(scene, elements, 1e-5, 1, fmu) as beam:
        return np.array(decode_state(beam.inst.serialize()).displacements, dtype=float)


def georod_frequencies(
    scene: BeamScene, elements: int, count: int, fmu: Path | None = None
) -> tuple[np.ndarray, float, float]:
    """(lowest `count` frequencies about the FMU's static state, its w_mid, the relative
    residual of model.md's internal force there on the free coordinates)."""
    q = fmu_static_state(scene, elements, fmu)
    ne = elements
    fixed = [0, 1, 3 * ne, 3 * ne + 1]
    f = georod_internal_force(q, scene, ne)
    free = np.setdiff1d(np.arange(q.size), fixed)
    scale = np.abs(georod_internal_force(q + 1e-3 * np.abs(q).max(), scene, ne)).max()
    residual = float(np.abs(f[free]).max() / scale)
    eps = 1e-7
    K = np.empty((q.size, q.size))
    for j in range(q.size):
        dq = np.zeros(q.size)
        dq[j] = eps
        K[:, j] = (
            georod_internal_force(q + dq, scene, ne) - georod_internal_force(q - dq, scene, ne)
        ) / (2 * eps)
    freq = generalized_frequencies(K, georod_mass(scene, ne), fixed, count)
    return freq, float(q[3 * (ne // 2) + 1]), residual


# --------------------------------------------------------------------------------- the studies


@dataclass
class Settings:
    """Sizes of the benchmark (``quick`` = the smoke test's)."""

    periods: int = 20
    steps: tuple[int, ...] = (8, 16, 32, 64, 128, 256, 512, 1024)
    ref_steps: tuple[int, ...] = (4096, 8192, 16384)
    exudyn_ref_steps: tuple[int, ...] = (2048, 4096, 8192)
    repeats: int = 5
    exudyn_repeats: int = 3
    model_elements: tuple[int, ...] = (10, 20, 40)
    space_elements: tuple[int, ...] = (4, 8, 16, 20, 40, 80, 160)
    space_ref_elements: int = 320
    space_steps: int = 256
    scaling_elements: tuple[int, ...] = (10, 100, 1000, 10000)
    scaling_steps: int = 100
    scaling_periods: tuple[int, ...] = (50, 20, 5, 2)
    periodic_transient: int = 100
    periodic_samples: int = 100
    sub_comm: int = 8

    @classmethod
    def quick(cls) -> Settings:
        return cls(
            periods=2,
            steps=(8, 16, 32),
            ref_steps=(128, 256),
            exudyn_ref_steps=(128, 256),
            repeats=1,
            exudyn_repeats=1,
            model_elements=(4, 8),
            space_elements=(4, 8),
            space_ref_elements=16,
            space_steps=32,
            scaling_elements=(10, 100),
            scaling_periods=(2, 1),
            periodic_transient=5,
            periodic_samples=20,
        )


def errors(w: np.ndarray, ref: np.ndarray) -> tuple[float, float]:
    """(|error| at the final time, max |error| over the grid of `w`); `ref` is on a grid that
    refines it by an integer factor."""
    n, m = len(w) - 1, len(ref) - 1
    if m % n:
        raise ValueError(f"reference grid {m} does not refine {n}")
    r = ref[:: m // n]
    e = np.abs(w - r)
    return float(e[-1]), float(e.max())


def convergence_rows(name: str, runs: dict[int, np.ndarray]) -> list[dict[str, object]]:
    """Differences between successive refinements of a reference (on the coarsest grid)."""
    ns = sorted(runs)
    rows = []
    for a, b in zip(ns, ns[1:], strict=False):
        step = (len(runs[b]) - 1) // (len(runs[ns[0]]) - 1)
        step_a = (len(runs[a]) - 1) // (len(runs[ns[0]]) - 1)
        wa, wb = runs[a][::step_a], runs[b][::step]
        d = np.abs(wa - wb)
        rows.append(
            {
                "method": name,
                "n_coarse": a,
                "n_fine": b,
                "diff_final": float(d[-1]),
                "diff_max": float(d.max()),
            }
        )
    return rows


def equal_error_ratio(
    fmu: Sequence[tuple[float, float]], other: Sequence[tuple[float, float]]
) -> list[tuple[float, float, float, float]]:
    """For every (error, seconds) point of `fmu` inside the error range of `other`, the other's
    seconds interpolated in log-log at that error: rows (error, t_fmu, t_other, ratio). Uses the
    part of `other` where the error falls monotonically with time."""
    pts = sorted((t, e) for e, t in other if e > 0)
    mono: list[tuple[float, float]] = []
    for t, e in pts:
        if not mono or e < mono[-1][1]:
            mono.append((t, e))
    if len(mono) < 2:
        return []
    le = np.log([e for _, e in mono])[::-1]
    lt = np.log([t for t, _ in mono])[::-1]
    rows = []
    for e, t in fmu:
        if e <= 0 or not (le[0] <= math.log(e) <= le[-1]):
            continue
        t_other = float(np.exp(np.interp(math.log(e), le, lt)))
        rows.append((e, t, t_other, t_other / t))
    return rows


Log = Callable[[str], None]


def _md_table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    def fmt(v: object) -> str:
        if isinstance(v, float):
            if v == 0 or (1e-3 <= abs(v) < 1e5):
                return f"{v:.4g}"
            return f"{v:.3e}"
        return str(v)

    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(fmt(v) for v in r) + " |" for r in rows]
    return "\n".join(out)


def _write_csv(path: Path, rows: Sequence[dict[str, object]]) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as fh:
        if rows:
            w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
    return path


@dataclass
class Report:
    sections: list[str] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)

    def add(self, title: str, text: str) -> None:
        self.sections.append(f"### {title}\n\n{text}\n")


def study_periodicity(scene: BeamScene, s: Settings, fmu: Path | None, log: Log) -> str:
    cfg = CaseConfig(
        fmu=str(fmu or default_fmu()),
        F=scene.F,
        Omega=scene.Omega,
        elements=10,
        dt_max=scene.period / 256 * (1 + 1e-9),
        n_per_period=256,
        transient_periods=s.periodic_transient,
        sample_periods=s.periodic_samples,
        lyapunov_discard=min(10, s.periodic_samples // 2),
    )
    res = run_case(cfg)
    c = res.classification
    smp = res.samples
    # the first periods (the benchmark horizon): stroboscopic samples from t = 0
    with fmu_beam(scene, 10, scene.period / 256 * (1 + 1e-9), 256, fmu) as beam:
        w, _, _ = beam.integrate(256 * s.periods)
    strobe = w[::256]
    lines = [
        f"Stroboscopic samples at t = kT after {cfg.transient_periods} transient periods "
        f"(T/256): class **{c.label}** ({c.note}); largest Lyapunov exponent "
        f"{res.exponent_per_period:.4f} per period.",
        "",
        "Last 4 samples (w_mid, v_mid): " + ", ".join(f"({a:.6f}, {b:.2f})" for a, b in smp[-4:]),
        "",
        f"w_mid at t = kT over the benchmark horizon (k = 0..{len(strobe) - 1}): "
        + ", ".join(f"{x:.4f}" for x in strobe),
    ]
    log(lines[0])
    return "\n".join(lines)


def study_time_error(
    scene: BeamScene, s: Settings, fmu: Path | None, use_exudyn: bool, log: Log
) -> tuple[list[dict[str, object]], list[dict[str, object]]]:
    """Work-precision rows and reference-convergence rows."""
    P = s.periods
    rows: list[dict[str, object]] = []
    conv: list[dict[str, object]] = []
    # FMU reference: communication step T/1024 (or the finest benchmark step), sub-steps T/n_ref
    c_ref = max(s.steps)
    refs = {}
    for n in s.ref_steps:
        r = fmu_run(scene, n, P, 1, comm_per_period=c_ref, fmu=fmu)
        refs[n] = r.w
        log(f"fmu reference T/{n}: w_mid(end) = {r.w[-1]:.12f} ({r.seconds:.2f} s)")
    conv += convergence_rows("fmu", refs)
    ref = refs[max(refs)]  # on the T/c_ref grid
    for n in s.steps:
        r = fmu_run(scene, n, P, s.repeats, fmu=fmu)
        ef, em = errors(r.w, ref)
        core = core_seconds(scene, n, P)
        rows.append(
            {
                "method": "fmu",
                "steps_per_period": n,
                "comm_per_period": n,
                "err_final": ef,
                "err_max": em,
                "seconds": r.seconds,
                "seconds_min": min(r.times),
                "newton_per_step": r.extra["newton"] / (P * n),
                "core_seconds": core if core is not None else math.nan,
            }
        )
        log(f"fmu T/{n}: err_final {ef:.3e} err_max {em:.3e} {r.seconds:.4f} s (core alone {core})")
        if n >= s.sub_comm and n % s.sub_comm == 0:
            r2 = fmu_run(scene, n, P, s.repeats, comm_per_period=s.sub_comm, fmu=fmu)
            ef2, em2 = errors(r2.w, ref)
            rows.append(
                {
                    "method": f"fmu_comm_T/{s.sub_comm}",
                    "steps_per_period": n,
                    "comm_per_period": s.sub_comm,
                    "err_final": ef2,
                    "err_max": em2,
                    "seconds": r2.seconds,
                    "seconds_min": min(r2.times),
                    "newton_per_step": math.nan,
                    "core_seconds": math.nan,
                }
            )
    if use_exudyn:
        beam = ExudynBeam(scene, 10)
        try:
            erefs = {}
            for n in s.exudyn_ref_steps:
                r = beam.run(n, P, 0, record=True)
                erefs[n] = r.w
                log(f"exudyn reference T/{n}: w_mid(end) = {r.w[-1]:.12f}")
            conv += convergence_rows("exudyn", erefs)
            eref = erefs[max(erefs)]
            for n in s.steps:
                r = beam.run(n, P, s.exudyn_repeats, record=True)
                ef, em = errors(r.w, eref)
                rows.append(
                    {
                        "method": "exudyn",
                        "steps_per_period": n,
                        "comm_per_period": n,
                        "err_final": ef,
                        "err_max": em,
                        "seconds": r.seconds,
                        "seconds_min": min(r.times),
                        "newton_per_step": r.extra["newton"] / (P * n),
                        "core_seconds": math.nan,
                    }
                )
                log(f"exudyn T/{n}: err_final {ef:.3e} err_max {em:.3e} {r.seconds:.4f} s")
            # the two converged references against each other (spatial model difference)
            m = (len(eref) - 1) // (len(ref) - 1) if len(eref) > len(ref) else 1
            k = (len(ref) - 1) // (len(eref) - 1) if len(ref) > len(eref) else 1
            d = np.abs(eref[::m] - ref[::k])
            conv.append(
                {
                    "method": "exudyn - fmu (references)",
                    "n_coarse": 0,
                    "n_fine": 0,
                    "diff_final": float(d[-1]),
                    "diff_max": float(d.max()),
                }
            )
        finally:
            beam.close()
    return rows, conv


def study_models(
    scene: BeamScene, s: Settings, fmu: Path | None, use_exudyn: bool, log: Log
) -> list[dict[str, object]]:
    rows: list[dict[str, object]] = []
    for ne in s.model_elements:
        fg, wg, res = georod_frequencies(scene, ne, 3, fmu)
        row: dict[str, object] = {"elements": ne, "w_static_fmu": wg, "residual_fmu_state": res}
        for i in range(3):
            row[f"omega{i + 1}_fmu"] = float(fg[i])
        if use_exudyn:
            eb = ExudynBeam(scene, ne)
            try:
                fe = eb.frequencies(3)
                row["w_static_exudyn"] = eb.w_static
                for i in range(3):
                    row[f"omega{i + 1}_exudyn"] = float(fe[i])
            finally:
                eb.close()
        rows.append(row)
        log(f"models, {ne} elements: {row}")
    return rows


def study_space(scene: BeamScene, s: Settings, fmu: Path | None, log: Log) -> list[dict]:
    n = s.space_steps
    P = s.periods
    ref = fmu_run(scene, n, P, 1, elements=s.space_ref_elements, fmu=fmu)
    rows = []
    for ne in s.space_elements:
        r = fmu_run(scene, n, P, 3 if ne <= 40 else 1, elements=ne, fmu=fmu)
        ef, em = errors(r.w, ref.w)
        rows.append(
            {
                "elements": ne,
                "w_static": float(r.w[0]),
                "err_static": abs(float(r.w[0] - ref.w[0])),
                "err_final": ef,
                "err_max": em,
                "seconds": r.seconds,
            }
        )
        log(f"space {ne}: err_final {ef:.3e} err_max {em:.3e} {r.seconds:.3f} s")
    rows.append(
        {
            "elements": s.space_ref_elements,
            "w_static": float(ref.w[0]),
            "err_static": 0.0,
            "err_final": 0.0,
            "err_max": 0.0,
            "seconds": ref.seconds,
        }
    )
    return rows


def study_scaling(scene: BeamScene, s: Settings, fmu: Path | None, log: Log) -> list[dict]:
    n = s.scaling_steps
    rows = []
    for ne, periods in zip(s.scaling_elements, s.scaling_periods, strict=False):
        t0 = time.perf_counter()
        with fmu_beam(scene, ne, scene.period / n * (1 + 1e-9), n, fmu) as beam:
            t_init = time.perf_counter() - t0
            # one untimed period first (it also counts the Newton corrections), then timed
            _, _, newton_count = beam.integrate(n, count_newton=True)
            reps = [beam.integrate(n * periods) for _ in range(3 if ne <= 1000 else 1)]
        secs = statistics.median(x[1] for x in reps)
        newton = newton_count / n
        rows.append(
            {
                "elements": ne,
                "periods_timed": periods,
                "seconds_per_period": secs / periods,
                "us_per_step_per_element": secs / (periods * n) / ne * 1e6,
                "newton_per_step": newton,
                "init_seconds": t_init,
            }
        )
        log(f"scaling {ne}: {secs / periods:.4f} s per period")
    return rows


def profile_fmu(scene: BeamScene, n: int, periods: int, fmu: Path | None) -> str:
    """cProfile of the FMU integration loop: where the Python side spends its time."""
    with fmu_beam(scene, 10, scene.period / n * (1 + 1e-9), n, fmu) as beam:
        beam.integrate(n)
        prof = cProfile.Profile()
        prof.enable()
        beam.integrate(periods * n)
        prof.disable()
    buf = io.StringIO()
    pstats.Stats(prof, stream=buf).sort_stats("tottime").print_stats(8)
    lines = [ln for ln in buf.getvalue().splitlines() if ln.strip()]
    return "\n".join(lines[:20])


# ------------------------------------------------------------------------------------- plotting


def plot_work_precision(rows: Sequence[dict[str, object]], path: Path, which: str) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
    ax.set_ylabel(f"|error of w_mid| {what}")
    ax.set_title(
        "BuckledBeam, 10 elements, F = 0.7, Omega = 4500: work-precision\n"
        "(labels: steps per forcing period)",
        fontsize=10,
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_scaling(rows: Sequence[dict[str, object]], path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ne = np.array([float(r["elements"]) for r in rows])  # type: ignore[arg-type]
    t = np.array([float(r["seconds_per_period"]) for r in rows])  # type: ignore[arg-type]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.loglog(ne, t, "o-", label="FMU via fmpy, dt = T/100")
    ax.loglog(ne, t[-1] * ne / ne[-1], "k--", alpha=0.5, label="linear in elements")
    ax.set_xlabel("elements")
    ax.set_ylabel("seconds per forcing period")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


# ------------------------------------------------------------------------------------ the driver


def run_benchmark(
    out: Path,
    figures: Path,
    quick: bool = False,
    use_exudyn: bool = True,
    fmu: Path | None = None,
    parts: Sequence[str] = ("periodic", "time", "models", "space", "scaling", "profile"),
    log: Log = print,
) -> Report:
    scene = BeamScene()
    s = Settings.quick() if quick else Settings()
    ok, version = exudyn_status()
    if use_exudyn and not ok:
        log(f"Exudyn not available ({version}): its parts are skipped")
    use_exudyn = use_exudyn and ok
    rep = Report()
    rep.add("Machine", f"{machine_load()} at start; exudyn: {version if ok else 'missing'}")
    prefix = "benchmark_quick_" if quick else "benchmark_"
    if "periodic" in parts:
        rep.add("Periodicity", study_periodicity(scene, s, fmu, log))
    if "time" in parts:
        rows, conv = study_time_error(scene, s, fmu, use_exudyn, log)
        rep.files.append(_write_csv(out / "work_precision.csv", rows))
        rep.files.append(_write_csv(out / "reference_convergence.csv", conv))
        rep.add(
            "Reference convergence",
            _md_table(
                ["method", "coarse", "fine", "|diff| final", "max |diff|"],
                [
                    [r["method"], r["n_coarse"], r["n_fine"], r["diff_final"], r["diff_max"]]
                    for r in conv
                ],
            ),
        )
        rep.add(
            "Work-precision",
            _md_table(
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
                    rows, figures / f"{prefix}work_precision_{which.split('_')[1]}.png", which
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
                    _md_table(
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
        rep.files.append(_write_csv(out / "models.csv", mrows))
        keys = list(mrows[0].keys())
        rep.add("Models side by side", _md_table(keys, [[r.get(k) for k in keys] for r in mrows]))
    if "space" in parts:
        srows = study_space(scene, s, fmu, log)
        rep.files.append(_write_csv(out / "space.csv", srows))
        keys = list(srows[0].keys())
        rep.add("Spatial error", _md_table(keys, [[r[k] for k in keys] for r in srows]))
    if "scaling" in parts:
        crows = study_scaling(scene, s, fmu, log)
        rep.files.append(_write_csv(out / "scaling.csv", crows))
        rep.files.append(plot_scaling(crows, figures / f"{prefix}scaling.png"))
        keys = list(crows[0].keys())
        rep.add("Scaling", _md_table(keys, [[r[k] for k in keys] for r in crows]))
    if "profile" in parts:
        rep.add(
            "cProfile of the FMU loop (T/128, 20 periods)",
            "```\n" + profile_fmu(scene, 128, s.periods, fmu) + "\n```",
        )
    rep.add("Machine (end)", machine_load())
    md = out / "benchmark.md"
    md.parent.mkdir(parents=True, exist_ok=True)
    md.write_text("\n".join(rep.sections))
    rep.files.append(md)
    return rep


def add_benchmark_parser(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = sub.add_parser("benchmark", help="work-precision benchmark, FMU vs Exudyn, scaling")
    add_benchmark_options(p)


def add_benchmark_options(p: argparse.ArgumentParser) -> None:
    """The options of ``benchmark`` (subcommand and ``python -m georod_tools.benchmark``)."""
    p.add_argument("--quick", action="store_true", help="smoke-test sizes (seconds)")
    p.add_argument("--no-exudyn", action="store_true", help="skip the Exudyn runs")
    p.add_argument("--fmu", type=Path, help="BuckledBeam FMU (default target/fmu/BuckledBeam.fmu)")
    p.add_argument("--out", type=Path, default=DEFAULT_OUT, help=f"CSV/markdown ({DEFAULT_OUT})")
    p.add_argument(
        "--figures", type=Path, default=DEFAULT_FIGURES, help=f"PNG folder ({DEFAULT_FIGURES})"
    )
    p.add_argument(
        "--parts",
        default="periodic,time,models,space,scaling,profile",
        help="comma-separated subset of periodic,time,models,space,scaling,profile",
    )


def run_benchmark_command(parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
    parts = [x.strip() for x in args.parts.split(",") if x.strip()]
    known = {"periodic", "time", "models", "space", "scaling", "profile"}
    bad = [x for x in parts if x not in known]
    if bad:
        parser.error(f"--parts: unknown {', '.join(bad)}; choose from {', '.join(sorted(known))}")
    if args.fmu is not None and not args.fmu.is_file():
        parser.error(f"--fmu {args.fmu}: no such file (build with scripts/build_fmus)")
    rep = run_benchmark(
        args.out,
        args.figures,
        quick=args.quick,
        use_exudyn=not args.no_exudyn,
        fmu=args.fmu,
        parts=parts,
    )
    for f in rep.files:
        print(f"wrote {f}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m georod_tools.benchmark``: the same as ``python -m georod_tools benchmark``."""
    ap = argparse.ArgumentParser(
        prog="python -m georod_tools.benchmark",
        description="Work-precision benchmark of the BuckledBeam FMU, side by side with Exudyn.",
    )
    add_benchmark_options(ap)
    return run_benchmark_command(ap, ap.parse_args(argv))


if __name__ == "__main__":
    raise SystemExit(main())
