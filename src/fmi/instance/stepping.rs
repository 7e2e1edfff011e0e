//! Stepping: `fmi2DoStep` (communication points checked against the instance's clock and the
//! experiment's stopTime; a step that does not converge is discarded and changes nothing),
//! `fmi2CancelStep` and the status queries.
use super::Instance;
use crate::fmi::state_machine::{error, mask, Failure, FmiResult, FmiState};
use crate::simulation::SimError;

/// Communication points agree if within this relative ...
const TIME_REL_TOL: f64 = 1e-9;
/// ... or absolute distance.
const TIME_ABS_TOL: f64 = 1e-12;

impl Instance {
    pub fn do_step(&mut self, current_communication_point: f64, h: f64) -> FmiResult {
        self.require(mask::DO_STEP)?;
        if !(h.is_finite() && h > 0.0) {
            return error(format!(
                "communicationStepSize = {h} must be finite and > 0"
            ));
        }
        let t = self.time();
        let tc = current_communication_point;
        let tol = TIME_ABS_TOL.max(TIME_REL_TOL * t.abs().max(tc.abs()));
        if tc.is_nan() || (tc - t).abs() > tol {
            return error(format!(
                "currentCommunicationPoint = {tc:e} differs from the instance time {t:e} \
                 (difference {:e}); steps must follow each other without gaps",
                tc - t
            ));
        }
        // FMI 2.0 (fmi2SetupExperiment): computing past a defined stopTime is fmi2Error.
        if let Some(stop) = self.experiment.stop_time {
            if t + h > stop + tol.max(TIME_REL_TOL * stop.abs()) {
                return error(format!(
                    "the step would end at t = {:e} (currentCommunicationPoint {tc:e} + \
                     communicationStepSize {h:e}), past stopTime = {stop:e}; nothing was computed: a step of at most {:e} is allowed",
                    t + h,
                    stop - t
                ));
            }
        }
        let inputs: Vec<f64> = (0..self.inputs.len())
            .map(|i| self.input_value(i))
            .collect();
        let Some(sim) = self.sim.as_mut() else {
            return error("internal error: no simulation in state stepComplete");
        };
        for (i, x) in inputs.into_iter().enumerate() {
            sim.set_input(i, x)
                .map_err(|e| Failure::Error(e.to_string()))?;
        }
        for &(i, order, x) in &self.derivatives {
            sim.set_input_derivative(i, order, x)
                .map_err(|e| Failure::Error(e.to_string()))?;
        }
        match sim.advance_checked(h) {
            Ok(report) => {
                self.derivatives.clear();
                self.log.trace(|| {
                    format!(
                        "doStep: t = {t:e} -> {:e}: {} sub-steps, {} Newton iterations, {} cuts",
                        t + h,
                        report.substeps,
                        report.newton_iterations,
                        report.cuts
                    )
                });
                if let Some(warning) = &report.warning {
                    self.log.warning(&format!("doStep: {warning}"));
                }
                Ok(())
            }
            Err(e @ SimError::StepFailed { .. }) => {
                self.enter(FmiState::StepFailed);
                Err(Failure::Discard(format!(
                    "the step from t = {t} with h = {h} did not converge: {e}. The state is still the one \
                     at t = {t} (the last successful time); the host may read values, \
                     restore an FMU state, reset or terminate"
                )))
            }
            Err(e) => error(e.to_string()),
        }
    }

    pub fn cancel_step(&mut self) -> FmiResult {
        error(format!(
            "no asynchronous step in progress (fmi2DoStep never returns fmi2Pending); state is {}",
            self.state.name()
        ))
    }

    /// Status queries: a kind this FMU cannot answer is `fmi2Discard` (standard 4.2.3).
    pub fn status_unavailable(&self, func: &str, kind: &str) -> FmiResult {
        self.require(mask::STATUS)?;
        Err(Failure::Discard(format!(
            "{kind} is not available from {func} (this FMU never runs fmi2DoStep asynchronously)"
        )))
    }

    pub fn last_successful_time(&self) -> FmiResult<f64> {
        self.require(mask::STATUS)?;
        Ok(self.time())
    }

    pub fn terminated(&self) -> FmiResult<bool> {
        self.require(mask::STATUS)?;
        // The slave never asks to end the simulation on its own.
        Ok(false)
    }
}
