//! The life cycle of an instance: debug logging, `fmi2SetupExperiment`, initialization mode,
//! terminate and reset, and the initial state they build (kept for reuse while the fixed
//! parameters allow).
use super::Instance;
use crate::fmi::experiment::Experiment;
use crate::fmi::state_machine::{error, mask, Failure, FmiResult, FmiState};
use crate::scene::{ParamValues, Scene, Variability};
use crate::simulation::Simulation;

/// Whether two parameter sets give the same initial state (the tunable ones aside).
pub(crate) fn same_fixed(scene: &Scene, a: &ParamValues, b: &ParamValues) -> bool {
    scene
        .params
        .iter()
        .zip(a.0.iter().zip(&b.0))
        .all(|(p, (x, y))| p.variability == Variability::Tunable || x == y)
}

impl Instance {
    pub fn set_debug_logging(&mut self, on: bool, categories: &[&str]) -> FmiResult {
        self.require(mask::ANY)?;
        self.log
            .set_debug_logging(on, categories)
            .map_err(Failure::Error)
    }

    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> FmiResult {
        self.require(mask::SETUP_EXPERIMENT)?;
        if !start_time.is_finite() {
            return error(format!("startTime = {start_time} is not finite"));
        }
        if let Some(tol) = tolerance {
            if !(tol.is_finite() && tol > 0.0) {
                return error(format!("tolerance = {tol} must be finite and > 0"));
            }
        }
        if let Some(stop) = stop_time {
            if !(stop.is_finite() && stop >= start_time) {
                return error(format!(
                    "stopTime = {stop} must be finite and >= startTime = {start_time}"
                ));
            }
        }
        self.experiment = Experiment {
            tolerance,
            start_time,
            stop_time,
        };
        self.log.event(|| {
            format!(
                "experiment: startTime = {start_time}, stopTime = {stop_time:?}, tolerance = {tolerance:?} \
                 (the tolerance is not used: Newton converges to round-off, steps are bounded by dt_max)"
            )
        });
        Ok(())
    }

    /// FMI 3.0: configuration mode, where structural parameters are set. The scenes have none
    /// (array sizes come from the scene file), so the mode only has to be entered and left.
    pub fn enter_configuration_mode(&mut self) -> FmiResult {
        self.require(mask::ENTER_CONFIGURATION)?;
        self.enter(FmiState::ConfigurationMode);
        Ok(())
    }

    pub fn exit_configuration_mode(&mut self) -> FmiResult {
        self.require(mask::EXIT_CONFIGURATION)?;
        self.enter(FmiState::Instantiated);
        Ok(())
    }

    pub fn enter_initialization_mode(&mut self) -> FmiResult {
        self.require(mask::ENTER_INITIALIZATION)?;
        self.enter(FmiState::InitializationMode);
        Ok(())
    }

    /// Validates the parameters and builds the initial static state; a failure leaves the
    /// instance in the `error` state (reset or free it).
    pub fn exit_initialization_mode(&mut self) -> FmiResult {
        self.require(mask::EXIT_INITIALIZATION)?;
        match self.initial_simulation() {
            Ok(_) => {
                self.enter(FmiState::StepComplete);
                Ok(())
            }
            Err(Failure::Error(why)) | Err(Failure::Discard(why)) => {
                self.enter(FmiState::Error);
                error(format!(
                    "{why}; the instance is now in the error state (reset or free it)"
                ))
            }
        }
    }

    pub fn terminate(&mut self) -> FmiResult {
        self.require(mask::TERMINATE)?;
        self.enter(FmiState::Terminated);
        Ok(())
    }

    /// Back to `instantiated` with the start values, time 0 and counters 0. Debug logging
    /// settings are kept. The initial state already computed is kept for reuse.
    pub fn reset(&mut self) -> FmiResult {
        self.require(mask::ANY)?;
        self.params = self.scene().defaults();
        self.inputs.fill(None);
        self.derivatives.clear();
        self.experiment = Experiment::default();
        if let Some(sim) = &mut self.sim {
            sim.reset();
        }
        self.enter(FmiState::Instantiated);
        Ok(())
    }

    /// The simulation at `t = 0` for the current parameters: the kept one if its fixed
    /// parameters still match, else a new one (validation + initial static solve).
    pub(crate) fn initial_simulation(&mut self) -> FmiResult<&mut Simulation> {
        let scene = self.scene().clone();
        // Moving supports set during initialization mode are part of the initial state.
        let inputs: Vec<f64> = (0..scene.inputs.len())
            .map(|i| self.input_value(i))
            .collect();
        let reusable = self.sim.as_ref().is_some_and(|s| {
            same_fixed(&scene, s.values(), &self.params) && s.initial_inputs() == inputs
        });
        if !reusable {
            self.sim = None; // release the old mesh before building the new one
            let sim = Simulation::with_inputs(scene.clone(), self.params.clone(), inputs)
                .map_err(|e| Failure::Error(e.to_string()))?;
            self.log
                .event(|| format!("initial state of the {} scene computed", scene.name));
            self.sim = Some(sim);
        }
        let sim = self.sim.as_mut().expect("just ensured");
        for (i, &x) in self.params.0.iter().enumerate() {
            if sim.values().get(i) != x {
                sim.set_param(i, x)
                    .map_err(|e| Failure::Error(e.to_string()))?;
            }
        }
        Ok(sim)
    }
}
