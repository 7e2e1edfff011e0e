"""`georod-tools case` without a velocity sensor derives the velocity from the displacement sensor's
change over each sample's last sub-step. With more sample periods than dense periods, and several
sub-steps in every sample (a whole period outside the dense window, several sub-steps per dense
point inside it), the derived velocity must agree at every strobe sample with the velocity sensor.

Reference: the same case with the velocity sensor ``v_mid`` and every sub-step kept (dense window
over all sampled periods, one sub-step per dense point). The FMU's integrator is the implicit
midpoint rule, ``u(n+1) - u(n) = dt (v(n) + v(n+1)) / 2``: the derived velocity at a sample is
exactly the mean of the sensor's velocity over the sample's last sub-step, up to round-off.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from helpers import FMU_DIR

BEAM_FMU = FMU_DIR / "BuckledBeam.fmu"
pytestmark = pytest.mark.usefixtures("fmu_paths")  # builds the FMUs when missing or stale

SUBSTEPS = 64  # sub-steps per forcing period
SAMPLES = 8  # sampled periods, of which the last DENSE are kept densely
DENSE = 2
DENSE_STEPS = 8  # dense points per period: 8 sub-steps each


def test_derived_velocity_is_the_sensors_at_every_strobe_sample() -> None:
    from georod_tools.analysis.case import CaseConfig, run_case

    derived_cfg = CaseConfig(
        fmu=str(BEAM_FMU),
        F=0.7,
        substeps=SUBSTEPS,
        transient_periods=2,
        sample_periods=SAMPLES,
        dense_periods=DENSE,
        dense_steps=DENSE_STEPS,
        lyapunov=False,
        velocity="",
    )
    reference_cfg = replace(
        derived_cfg, velocity="v_mid", dense_periods=SAMPLES, dense_steps=SUBSTEPS
    )
    derived, reference = run_case(derived_cfg), run_case(reference_cfg)
    assert reference.dense is not None
    t_ref, w_ref, v_ref = reference.dense.T
    dt = derived_cfg.dt_max

    # The reference's point at each strobe sample, and the one a sub-step before.
    at = np.searchsorted(t_ref, derived.sample_times - 0.5 * dt)
    assert np.allclose(t_ref[at], derived.sample_times, rtol=0.0, atol=1e-3 * dt)
    assert np.allclose(t_ref[at - 1], derived.sample_times - dt, rtol=0.0, atol=1e-3 * dt)

    scale = np.max(np.abs(v_ref))
    w, v = derived.samples.T
    # The same trajectory: the derived run's last sub-step of each sample is taken alone
    # ((T - dt) then dt), which moves the sub-steps' sizes by round-off, grown over ten
    # chaotic periods (exponent below 1 per period: e^10 * 1e-16).
    assert np.allclose(w, w_ref[at], rtol=0.0, atol=1e-9 * np.max(np.abs(w_ref)))
    # Midpoint rule: the sub-step's mean velocity, up to the round-off of a difference of
    # displacements over one sub-step (|w| eps / dt = 1e-11 of the velocity scale) and the
    # trajectory's difference above.
    mean = 0.5 * (v_ref[at - 1] + v_ref[at])
    assert np.allclose(v, mean, rtol=0.0, atol=1e-7 * scale), np.max(np.abs(v - mean)) / scale
    # And so the sensor's own velocity at the sample, to first order in dt: within half the
    # velocity's change over the last sub-step.
    half_change = 0.5 * np.abs(v_ref[at] - v_ref[at - 1])
    assert np.all(np.abs(v - v_ref[at]) <= half_change + 1e-7 * scale)
    assert np.all(np.isfinite(v)) and np.ptp(v) > 0.1 * scale
