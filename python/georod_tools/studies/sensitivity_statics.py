"""The static state and the first natural frequency about it, per variant of the sensitivity
study.

Two frequencies:

- ``omega_modes``: ``georod modes`` (the eigenproblem of the mass matrix and the tangent stiffness
  at the static buckled state, no damping, no time step). NaN where it does not reach the buckled
  state: with a dead axial load the continuation in the load finds only the straight state.
- ``omega_free``: measured on the FMU itself, the way the forced runs see it: from the static
  state, a midspan pulse of half a period, then free vibration without the translational
  damping (``d = 0``: with it, the dead-load variant's first mode is overdamped) at the variant's
  own time step (``T / substeps`` at the reference forcing frequency). A Prony fit of order 4 to
  ``w_mid`` gives the poles ``exp(s dt)``; the slowest oscillating one is the first mode. The
  midpoint rule's own frequency error at that step is in it (it shortens no period by more than
  ``(omega dt)^2 / 12``), so the time-step question shows up here; with the default steps the two
  frequencies agree to 1e-4 (checked in the tests).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from georod_tools.fmu import FmuModel, lend
from georod_tools.fmu.core_command import georod

#: Forcing frequency whose period sets the variant's time step (the paper's Figure 2).
OMEGA_REF = 3500.0
#: Size of the midspan pulse (N): a response of about 1e-3 of the static deflection, linear.
PULSE = 0.02
#: Free-vibration periods of the first mode recorded.
FREE_PERIODS = 6.0


@dataclass(frozen=True)
class Statics:
    """w_mid: static midspan deflection (upper well); axial_force: |right_Rx| (NaN with a free
    end); omega_modes, omega_free: first natural frequency (rad/s), see the module docstring;
    dt: the variant's time step."""

    w_mid: float
    axial_force: float
    omega_modes: float
    omega_free: float
    dt: float

    @property
    def omega1(self) -> float:
        """The first frequency the integrator sees: the eigenvalue's, through the midpoint
        rule's map ``tan(omega~ dt / 2) = omega dt / 2`` at the variant's step; the measured
        ``omega_free`` where the eigenproblem does not reach the buckled state."""
        if not math.isfinite(self.omega_modes):
            return self.omega_free
        return 2.0 / self.dt * math.atan(0.5 * self.omega_modes * self.dt)


def modes_omega(scene: Path, elements: int, load_name: str | None = None) -> float:
    """The lowest natural frequency about the upper buckled equilibrium (NaN if not found)."""
    args = ["modes", "--scene", str(scene), "--count", "1", "--set", f"elements={elements}"]
    if load_name:
        args += ["--load-name", load_name, "--stop", "1000"]
    rows = [line.split(",") for line in georod(*args).splitlines()[1:]]
    stable = [r for r in rows if int(r[2]) == 0 and float(r[1]) > 0.0]
    return float(stable[0][5]) if stable else math.nan


def prony_omega(x: np.ndarray, dt: float, order: int = 4) -> float:
    """The undamped frequency |s| of the slowest oscillating pole pair of `x` (samples at `dt`)
    from a linear-prediction (Prony) fit of `order`; NaN if none oscillates."""
    x = np.asarray(x, dtype=float)
    rows = np.column_stack([x[order - 1 - j : len(x) - 1 - j] for j in range(order)])
    coef, *_ = np.linalg.lstsq(rows, x[order:], rcond=None)
    roots = np.roots(np.concatenate([[1.0], -coef]))
    s = np.log(roots.astype(complex)) / dt
    osc = s[s.imag > 1e-6 / dt]
    if not len(osc):
        return math.nan
    slowest = osc[np.argmin(osc.imag)]
    return float(abs(slowest))


def free_omega(fmu: Path, params: dict[str, float], omega_guess: float, dt: float) -> float:
    """``omega_free`` (module docstring): pulse, then free vibration of w_mid at step `dt`."""
    model = FmuModel.load(fmu)
    period = 2.0 * math.pi / omega_guess
    pulse_steps = max(1, round(0.5 * period / dt))
    steps = max(16, round(FREE_PERIODS * period / dt))
    with lend(model, "free") as inst:
        inst.initialize({**params, "F": 0.0, "d": 0.0, "dt_max": dt})
        w_static = float(inst.get(["w_mid"])[0])
        t = 0.0
        inst.set("f_ctrl", PULSE)
        for _ in range(pulse_steps):
            inst.step(t, dt)
            t += dt
        inst.set("f_ctrl", 0.0)
        read = inst.reader(["w_mid"])
        w = np.empty(steps)
        for k in range(steps):
            inst.step(t, dt)
            t += dt
            w[k] = read()[0]
    # ~64 samples per period: a linear-prediction fit on far denser samples is ill-conditioned
    every = max(1, round(period / dt / 64))
    return prony_omega((w - w_static)[::every], dt * every)


def statics(
    fmu: Path, scene: Path, elements: int, substeps: int, params: dict[str, float], dead: bool
) -> Statics:
    """The static state and both first frequencies of one variant."""
    model = FmuModel.load(fmu)
    names = ["w_mid"] + ([] if dead else ["right_Rx"])
    with lend(model, "static") as inst:
        inst.initialize({**params, "elements": elements})
        got = [float(x) for x in inst.get(names)]
    w_mid, axial = got[0], (abs(got[1]) if not dead else math.nan)
    omega_m = modes_omega(scene, elements, "axial" if dead else None)
    dt = 2.0 * math.pi / OMEGA_REF / substeps
    p = {**params, "elements": elements}
    # without a guess from `modes`: a long record first, then one of FREE_PERIODS periods
    guess = omega_m if math.isfinite(omega_m) else free_omega(fmu, p, 0.02 * OMEGA_REF, dt)
    omega_f = free_omega(fmu, p, guess, dt) if math.isfinite(guess) else math.nan
    return Statics(w_mid, axial, omega_m, omega_f, dt)
