"""The benchmark's BuckledBeam in Exudyn (``ObjectBeamGeometricallyExact2D``, its implicit
trapezoidal rule), the comparison solver of :mod:`.benchmark`, and the natural frequencies of a
discrete model from its stiffness and mass matrices.

Exudyn is optional (``exudyn`` in python/requirements.txt); :func:`exudyn_status` says whether it
can be imported.
"""

from __future__ import annotations

import math
import os
import shutil
import statistics
import tempfile
import time
from collections.abc import Sequence

import numpy as np

from georod_tools.studies.bench_beam import BeamScene, Run


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
        ss.show.statistics = False
        ss.show.computationTime = False
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
