//! One FMU instance: the FMI 2.0 Co-Simulation state machine, parameter and value handling, and
//! the simulation it drives. Pure Rust (slices, `&str`); `api.rs` does the C side.
//!
//! Decisions worth knowing:
//! - A refused call (wrong state, bad argument) changes nothing and leaves the state as it was.
//!   The instance enters the `error` state only when something really failed: the initial state
//!   could not be built in `fmi2ExitInitializationMode`, or a Rust panic was caught.
//! - `fmi2Get*` is also accepted in `instantiated` (the standard allows it from
//!   `initializationMode` on; answering earlier is harmless). Outputs requested before
//!   `fmi2ExitInitializationMode` are those of the initial static state, computed from the
//!   current parameters on demand (and kept for `fmi2ExitInitializationMode` if the fixed
//!   parameters do not change); `newton_iterations` is 0 until the first step.
//! - The simulation clock is `startTime + sim.time()`; the excitation `F cos(Omega t)` is phased
//!   from `startTime`.
//! - Inputs the host never set keep their start values (a support motion input: the support's
//!   prescribed value for the current parameters, so the support stays where it is).
use super::fmu_state::StateData;
use super::interface::Interface;
use super::logging::Logger;
use super::state_registry::StateRegistry;
use crate::scene::variables::input_start;
use crate::scene::{ParamValues, Scene, Variability};
use crate::simulation::{SimError, Simulation};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::sync::Arc;

/// Marks a live `Instance` allocation (detects garbage and freed pointers where cheap).
pub const INSTANCE_MAGIC: u64 = 0x4745_4f52_4f44_4649; // "GEORODFI"
pub const FREED_MAGIC: u64 = 0xdead_beef_dead_beef;

/// Communication points agree if within this relative ...
const TIME_REL_TOL: f64 = 1e-9;
/// ... or absolute distance.
const TIME_ABS_TOL: f64 = 1e-12;

/// The FMI 2.0 Co-Simulation states (standard section 4.2.4). `stepInProgress` is never entered
/// (no asynchronous steps), `fatal` never either (a panic only corrupts its own instance).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum FmiState {
    Instantiated,
    InitializationMode,
    StepComplete,
    StepFailed,
    StepCanceled,
    Terminated,
    Error,
}

impl FmiState {
    const ALL: [FmiState; 7] = [
        FmiState::Instantiated,
        FmiState::InitializationMode,
        FmiState::StepComplete,
        FmiState::StepFailed,
        FmiState::StepCanceled,
        FmiState::Terminated,
        FmiState::Error,
    ];

    pub(crate) fn bit(self) -> u16 {
        1 << self as u16
    }

    pub fn name(self) -> &'static str {
        match self {
            FmiState::Instantiated => "instantiated",
            FmiState::InitializationMode => "initializationMode",
            FmiState::StepComplete => "stepComplete",
            FmiState::StepFailed => "stepFailed",
            FmiState::StepCanceled => "stepCanceled",
            FmiState::Terminated => "terminated",
            FmiState::Error => "error",
        }
    }
}

/// Sets of states in which a function may be called (the table of standard section 4.2.4).
pub mod mask {
    use super::FmiState::*;
    const I: u16 = 1 << Instantiated as u16;
    const IM: u16 = 1 << InitializationMode as u16;
    const SC: u16 = 1 << StepComplete as u16;
    const SF: u16 = 1 << StepFailed as u16;
    const SCAN: u16 = 1 << StepCanceled as u16;
    const T: u16 = 1 << Terminated as u16;
    const E: u16 = 1 << Error as u16;

    pub const ANY: u16 = I | IM | SC | SF | SCAN | T | E;
    pub const SETUP_EXPERIMENT: u16 = I;
    pub const ENTER_INITIALIZATION: u16 = I;
    pub const EXIT_INITIALIZATION: u16 = IM;
    pub const TERMINATE: u16 = SC | SF | SCAN;
    /// Also `instantiated`: see the module documentation.
    pub const GET: u16 = I | IM | SC | SF | SCAN | T | E;
    pub const SET: u16 = I | IM | SC;
    pub const FIXED_PARAMETER: u16 = I | IM;
    pub const DIRECTIONAL_DERIVATIVE: u16 = IM | SC | SF | SCAN | T | E;
    pub const SET_INPUT_DERIVATIVES: u16 = I | IM | SC;
    pub const GET_OUTPUT_DERIVATIVES: u16 = SC | SF | SCAN | T | E;
    pub const DO_STEP: u16 = SC;
    /// Only `stepInProgress`, which this FMU never enters.
    pub const CANCEL_STEP: u16 = 0;
    pub const STATUS: u16 = SC | SF | SCAN | T;
}

pub(crate) fn state_list(mask: u16) -> String {
    let names: Vec<&str> = FmiState::ALL
        .iter()
        .filter(|s| mask & s.bit() != 0)
        .map(|s| s.name())
        .collect();
    if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    }
}

/// Why a call did not return `fmi2OK`; the message is logged by the C wrapper.
#[derive(Clone, Debug, PartialEq)]
pub enum Failure {
    /// `fmi2Error`
    Error(String),
    /// `fmi2Discard`
    Discard(String),
}

pub type FmiResult<T = ()> = Result<T, Failure>;

pub(crate) fn error<T>(message: impl Into<String>) -> FmiResult<T> {
    Err(Failure::Error(message.into()))
}

/// What `fmi2SetupExperiment` said.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Experiment {
    pub tolerance: Option<f64>,
    pub start_time: f64,
    pub stop_time: Option<f64>,
}

impl Default for Experiment {
    fn default() -> Self {
        Experiment {
            tolerance: None,
            start_time: 0.0,
            stop_time: None,
        }
    }
}

/// Whether two parameter sets give the same initial state (the tunable ones aside).
pub(crate) fn same_fixed(scene: &Scene, a: &ParamValues, b: &ParamValues) -> bool {
    scene
        .params
        .iter()
        .zip(a.0.iter().zip(&b.0))
        .all(|(p, (x, y))| p.variability == Variability::Tunable || x == y)
}

#[repr(C)]
pub struct Instance {
    /// First field, so it can be checked through a raw pointer before anything else is read.
    magic: u64,
    pub log: Logger,
    interface: Interface,
    state: FmiState,
    resource_location: Option<String>,
    resource_dir: Option<PathBuf>,
    experiment: Experiment,
    /// The parameter values the host set (the simulation is built from them).
    params: ParamValues,
    /// The inputs the host set (`None`: the start value).
    inputs: Vec<Option<f64>>,
    /// Input derivatives for the next step (`fmi2SetRealInputDerivatives`): (input, order,
    /// value); cleared by a successful step.
    derivatives: Vec<(usize, usize, f64)>,
    /// From `fmi2ExitInitializationMode` on: the running simulation. Before: possibly the initial
    /// state built for an early output request, at `t = 0`, reused if the parameters still fit.
    sim: Option<Simulation>,
    /// The FMU states handed out to the host (freed with the instance).
    pub states: StateRegistry,
}

impl Instance {
    pub fn new(
        interface: Interface,
        log: Logger,
        resource_location: Option<String>,
        resource_dir: Option<PathBuf>,
    ) -> Instance {
        Instance {
            magic: INSTANCE_MAGIC,
            log,
            params: interface.scene.defaults(),
            inputs: vec![None; interface.scene.inputs.len()],
            derivatives: Vec::new(),
            interface,
            state: FmiState::Instantiated,
            resource_location,
            resource_dir,
            experiment: Experiment::default(),
            sim: None,
            states: StateRegistry::default(),
        }
    }

    /// The instance behind an `fmi2Component`, or `None` for NULL, misaligned or unmarked
    /// pointers (nothing can be logged then: the logger lives in the instance).
    ///
    /// # Safety
    /// `c` must be NULL or readable for 8 bytes; it is then taken for a live `Instance` if its
    /// magic number matches (a best-effort check against garbage and freed pointers).
    pub unsafe fn from_raw<'a>(c: *mut std::ffi::c_void) -> Option<&'a mut Instance> {
        let p = c as *mut Instance;
        if p.is_null() || !p.is_aligned() || std::ptr::addr_of!((*p).magic).read() != INSTANCE_MAGIC
        {
            return None;
        }
        Some(&mut *p)
    }

    /// Frees an instance made by `Box::into_raw`.
    ///
    /// # Safety
    /// `inst` must come from `Box::into_raw(Box<Instance>)` and not have been freed.
    pub unsafe fn free(inst: &mut Instance) {
        inst.magic = FREED_MAGIC;
        drop(Box::from_raw(inst as *mut Instance));
    }

    pub fn scene(&self) -> &Arc<Scene> {
        &self.interface.scene
    }

    pub fn interface(&self) -> &Interface {
        &self.interface
    }

    /// The value of input `i` the next step holds: the host's, or its start value.
    pub(crate) fn input_value(&self, i: usize) -> f64 {
        self.inputs[i].unwrap_or_else(|| input_start(self.scene(), i, &self.params))
    }

    pub fn state(&self) -> FmiState {
        self.state
    }

    pub fn params(&self) -> &ParamValues {
        &self.params
    }

    pub fn resource_location(&self) -> Option<&str> {
        self.resource_location.as_deref()
    }

    pub fn resource_dir(&self) -> Option<&std::path::Path> {
        self.resource_dir.as_deref()
    }

    /// Current simulation time (`startTime` before initialization).
    pub fn time(&self) -> f64 {
        self.experiment.start_time + self.sim_time()
    }

    fn sim_time(&self) -> f64 {
        match self.state {
            FmiState::Instantiated | FmiState::InitializationMode => 0.0,
            _ => self.sim.as_ref().map_or(0.0, Simulation::time),
        }
    }

    /// Refuses the call unless the current state is in `allowed`.
    pub fn require(&self, allowed: u16) -> FmiResult {
        if allowed & self.state.bit() != 0 {
            return Ok(());
        }
        error(format!(
            "not allowed in state {} (allowed in: {})",
            self.state.name(),
            state_list(allowed)
        ))
    }

    /// After a caught panic: the instance may be half-updated, so drop the simulation and
    /// accept only what the `error` state allows (reset, free, get/set FMU state, get values).
    pub fn poison(&mut self) {
        self.sim = None;
        self.state = FmiState::Error;
    }

    // ----- life cycle -------------------------------------------------------------------------

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
                error(format!("{why}; the instance is now in the error state (call fmi2Reset or fmi2FreeInstance)"))
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

    fn enter(&mut self, state: FmiState) {
        let from = self.state;
        self.state = state;
        self.log
            .event(|| format!("state {} -> {}", from.name(), state.name()));
    }

    /// The simulation at `t = 0` for the current parameters: the kept one if its fixed
    /// parameters still match, else a new one (validation + initial static solve).
    pub(crate) fn initial_simulation(&mut self) -> FmiResult<&mut Simulation> {
        let scene = self.scene().clone();
        let reusable = self
            .sim
            .as_ref()
            .is_some_and(|s| same_fixed(&scene, s.values(), &self.params));
        if !reusable {
            self.sim = None; // release the old mesh before building the new one
            let sim = Simulation::new(scene.clone(), self.params.clone())
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

    /// `fmi2SetRealInputDerivatives`: derivatives of inputs for the next step (orders 1 and 2).
    pub fn set_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> FmiResult {
        self.require(mask::SET_INPUT_DERIVATIVES)?;
        let mut set = Vec::with_capacity(vrs.len());
        for ((&vr, &order), &value) in vrs.iter().zip(orders).zip(values) {
            let Some(var) = self.interface.by_vr(vr) else {
                return error(format!("unknown value reference {vr}"));
            };
            let crate::scene::variables::Role::Input(i) = var.role else {
                return error(format!("`{}` (vr {vr}) is not an input", var.name));
            };
            if !(1..=2).contains(&order) {
                return error(format!(
                    "`{}`: derivative order {order}: this FMU interpolates with orders 1 and 2",
                    var.name
                ));
            }
            if !value.is_finite() {
                return error(format!("`{}`: derivative {value} is not finite", var.name));
            }
            set.push((i, order as usize, value));
        }
        for d in set {
            self.derivatives.retain(|&(i, o, _)| (i, o) != (d.0, d.1));
            self.derivatives.push(d);
        }
        Ok(())
    }

    pub(crate) fn simulation_mut(&mut self) -> Option<&mut Simulation> {
        self.sim.as_mut()
    }

    pub(crate) fn set_params_and_inputs(&mut self, params: ParamValues, inputs: &[(usize, f64)]) {
        self.params = params;
        for &(i, x) in inputs {
            self.inputs[i] = Some(x);
        }
    }

    /// The simulation the outputs are read from.
    pub(crate) fn output_simulation(&mut self) -> FmiResult<&Simulation> {
        match self.state {
            FmiState::Instantiated | FmiState::InitializationMode => {
                Ok(&*self.initial_simulation()?)
            }
            _ => match &self.sim {
                Some(sim) => Ok(sim),
                None => error(
                    "no simulation state to read outputs from (initialization failed); call fmi2Reset",
                ),
            },
        }
    }

    // ----- stepping ------------------------------------------------------------------------

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
                     communicationStepSize {h:e}), past stopTime = {stop:e} of \
                     fmi2SetupExperiment; nothing was computed: a step of at most {:e} is allowed",
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
                        "fmi2DoStep: t = {t:e} -> {:e}: {} sub-steps, {} Newton iterations, {} cuts",
                        t + h,
                        report.substeps,
                        report.newton_iterations,
                        report.cuts
                    )
                });
                if let Some(warning) = &report.warning {
                    self.log.warning(&format!("fmi2DoStep: {warning}"));
                }
                Ok(())
            }
            Err(e @ SimError::StepFailed { .. }) => {
                self.enter(FmiState::StepFailed);
                Err(Failure::Discard(format!(
                    "the step from t = {t} with h = {h} did not converge: {e}. The state is still the one \
                     at t = {t} (fmi2GetRealStatus(fmi2LastSuccessfulTime)); the host may read values, \
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

    // ----- FMU state -----------------------------------------------------------------------

    pub fn get_fmu_state(&self) -> FmiResult<StateData> {
        self.require(mask::ANY)?;
        let snapshot = match self.state {
            FmiState::Instantiated | FmiState::InitializationMode => None,
            _ => self.sim.as_ref().map(Simulation::snapshot),
        };
        self.log.event(|| {
            format!(
                "FMU state taken in state {} at t = {}",
                self.state.name(),
                self.time()
            )
        });
        Ok(StateData {
            scene: self.scene().name.clone(),
            fmi_state: self.state,
            experiment: self.experiment.clone(),
            params: self.params.clone(),
            inputs: self.inputs.clone(),
            snapshot,
        })
    }

    /// The serialized form of the state behind `handle` (one this instance gave out).
    pub fn serialize_state(&self, handle: super::types::fmi2FMUstate) -> FmiResult<Vec<u8>> {
        let data = self.states.get(handle, "FMUstate")?;
        super::fmu_state::serialize(data, self.scene(), &self.interface.guid)
            .map_err(Failure::Error)
    }

    /// A serialized state read back and checked against this instance.
    pub fn deserialize_state(&self, bytes: &[u8]) -> FmiResult<StateData> {
        let (scene, guid) = (self.scene(), &self.interface.guid);
        super::fmu_state::deserialize(bytes, scene, guid, self.params.elements())
            .map_err(Failure::Error)
    }

    /// Checks that an FMU state fits this instance (scene and element count).
    pub fn check_compatible(&self, scene: &str, elements: usize) -> FmiResult {
        if scene != self.scene().name {
            return error(format!(
                "the FMU state belongs to the {scene} scene, this instance is a {}",
                self.scene().name
            ));
        }
        if elements != self.params.elements() {
            return error(format!(
                "the FMU state has {elements} elements, this instance has {} (set `elements` first)",
                self.params.elements()
            ));
        }
        Ok(())
    }

    pub fn set_fmu_state(&mut self, data: &StateData) -> FmiResult {
        self.require(mask::ANY)?;
        self.check_compatible(&data.scene, data.params.elements())?;
        let simulated = !matches!(
            data.fmi_state,
            FmiState::Instantiated | FmiState::InitializationMode
        );
        if simulated && data.snapshot.is_none() && data.fmi_state != FmiState::Error {
            return error(format!(
                "the FMU state ({}) holds no simulation state",
                data.fmi_state.name()
            ));
        }
        match data.snapshot.as_ref().filter(|_| simulated) {
            Some(snapshot) => {
                let scene = self.scene().clone();
                let reusable = self
                    .sim
                    .as_ref()
                    .is_some_and(|s| same_fixed(&scene, s.values(), &data.params));
                if reusable {
                    let sim = self.sim.as_mut().expect("checked");
                    let backup = sim.snapshot();
                    if let Err(e) = sim.restore(snapshot) {
                        sim.restore(&backup)
                            .expect("a snapshot of this simulation restores");
                        return error(e.to_string());
                    }
                } else {
                    let mut sim = Simulation::new(scene, data.params.clone())
                        .map_err(|e| Failure::Error(e.to_string()))?;
                    sim.restore(snapshot)
                        .map_err(|e| Failure::Error(e.to_string()))?;
                    self.sim = Some(sim);
                }
            }
            None => {
                // A state from before initialization: the kept simulation (if any) goes back to
                // t = 0, ready to be reused by fmi2ExitInitializationMode.
                if let Some(sim) = &mut self.sim {
                    sim.reset();
                }
            }
        }
        self.experiment = data.experiment.clone();
        self.params = data.params.clone();
        self.inputs.clone_from(&data.inputs);
        self.derivatives.clear();
        self.enter(data.fmi_state);
        self.log
            .event(|| format!("FMU state restored at t = {}", self.time()));
        Ok(())
    }
}
