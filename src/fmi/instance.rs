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
use super::fmu_state::StateData;
use super::logging::Logger;
use super::state_registry::StateRegistry;
use crate::scene::{SceneKind, SceneParams};
use crate::simulation::{Outputs, SimError, Simulation};
use crate::variables::{self, Causality, VarType, Variability, Variable};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

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

    fn bit(self) -> u16 {
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

fn state_list(mask: u16) -> String {
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

/// The scene whose GUID this is.
pub fn scene_for_guid(guid: &str) -> Option<SceneKind> {
    let index = variables::GUIDS.iter().position(|g| *g == guid)?;
    SceneKind::ALL.get(index).copied()
}

/// `` `name` (vr N) `` for messages.
fn describe(var: &Variable) -> String {
    format!("`{}` (vr {})", var.name, var.vr)
}

/// The FMI function family that reads and writes a type (enumerations use the Integer ones).
fn type_name(t: VarType) -> &'static str {
    match t {
        VarType::Real => "Real",
        VarType::Integer | VarType::Enumeration => "Integer",
    }
}

/// Whether two parameter sets give the same initial state (the tunable `F`, `Omega` aside).
fn same_fixed(a: &SceneParams, b: &SceneParams) -> bool {
    let mut a = a.clone();
    a.forcing_amplitude = b.forcing_amplitude;
    a.forcing_frequency = b.forcing_frequency;
    a == *b
}

fn f_ctrl_start(kind: SceneKind) -> f64 {
    variables::by_name("f_ctrl")
        .and_then(|v| v.start[kind.index()])
        .unwrap_or(0.0)
}

#[repr(C)]
pub struct Instance {
    /// First field, so it can be checked through a raw pointer before anything else is read.
    magic: u64,
    pub log: Logger,
    kind: SceneKind,
    state: FmiState,
    resource_location: Option<String>,
    resource_dir: Option<PathBuf>,
    experiment: Experiment,
    /// The parameter values the host set (the simulation is built from them).
    params: SceneParams,
    f_ctrl: f64,
    /// From `fmi2ExitInitializationMode` on: the running simulation. Before: possibly the initial
    /// state built for an early output request, at `t = 0`, reused if the parameters still fit.
    sim: Option<Simulation>,
    /// The FMU states handed out to the host (freed with the instance).
    pub states: StateRegistry,
}

impl Instance {
    pub fn new(
        kind: SceneKind,
        log: Logger,
        resource_location: Option<String>,
        resource_dir: Option<PathBuf>,
    ) -> Instance {
        Instance {
            magic: INSTANCE_MAGIC,
            log,
            kind,
            state: FmiState::Instantiated,
            resource_location,
            resource_dir,
            experiment: Experiment::default(),
            params: SceneParams::defaults(kind),
            f_ctrl: f_ctrl_start(kind),
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

    pub fn kind(&self) -> SceneKind {
        self.kind
    }

    pub fn state(&self) -> FmiState {
        self.state
    }

    pub fn params(&self) -> &SceneParams {
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
        self.params = SceneParams::defaults(self.kind);
        self.f_ctrl = f_ctrl_start(self.kind);
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
    fn initial_simulation(&mut self) -> FmiResult<&mut Simulation> {
        let reusable = self
            .sim
            .as_ref()
            .is_some_and(|s| same_fixed(s.params(), &self.params));
        if !reusable {
            self.sim = None; // release the old mesh before building the new one
            self.params
                .validate()
                .map_err(|e| Failure::Error(e.to_string()))?;
            let sim =
                Simulation::new(self.params.clone()).map_err(|e| Failure::Error(e.to_string()))?;
            self.log
                .event(|| format!("initial state of the {} scene computed", self.kind));
            self.sim = Some(sim);
        }
        let (amplitude, frequency) = (self.params.forcing_amplitude, self.params.forcing_frequency);
        let sim = self.sim.as_mut().expect("just ensured");
        if sim.params().forcing_amplitude != amplitude
            || sim.params().forcing_frequency != frequency
        {
            sim.set_forcing(amplitude, frequency)
                .map_err(|e| Failure::Error(e.to_string()))?;
        }
        Ok(sim)
    }

    fn outputs(&mut self) -> FmiResult<Outputs> {
        match self.state {
            FmiState::Instantiated | FmiState::InitializationMode => {
                Ok(self.initial_simulation()?.outputs())
            }
            _ => match &self.sim {
                Some(sim) => Ok(sim.outputs()),
                None => error(
                    "no simulation state to read outputs from (initialization failed); call fmi2Reset",
                ),
            },
        }
    }

    // ----- values ------------------------------------------------------------------------------

    /// The variable of this scene with value reference `vr` and type `ty`.
    fn variable(&self, vr: u32, ty: VarType, func: &str) -> FmiResult<&'static Variable> {
        let Some(var) = variables::by_vr(vr) else {
            return error(format!("unknown value reference {vr}"));
        };
        if !var.scenes[self.kind.index()] {
            return error(format!(
                "{} is not a variable of the {} FMU",
                describe(var),
                self.kind
            ));
        }
        if type_name(var.var_type) != type_name(ty) {
            let actual = type_name(var.var_type);
            return error(format!(
                "{} is an {actual} variable, not {} (use {}{actual})",
                describe(var),
                type_name(ty),
                &func[..7] // "fmi2Get" or "fmi2Set"
            ));
        }
        Ok(var)
    }

    /// `fmi2GetBoolean` / `fmi2GetString` / the setters: this FMU has no such variables.
    pub fn no_variables_of_type(&self, func: &str, type_name: &str, vrs: &[u32]) -> FmiResult {
        self.require(if func.starts_with("fmi2Get") {
            mask::GET
        } else {
            mask::SET
        })?;
        let Some(&vr) = vrs.first() else {
            return Ok(());
        };
        match variables::by_vr(vr).filter(|v| v.scenes[self.kind.index()]) {
            Some(var) => error(format!(
                "{} is not a {type_name} variable: the {} FMU has no {type_name} variables",
                describe(var),
                self.kind
            )),
            None => error(format!(
                "unknown value reference {vr}: the {} FMU has no {type_name} variables",
                self.kind
            )),
        }
    }

    fn get_values(&mut self, func: &str, ty: VarType, vrs: &[u32]) -> FmiResult<Vec<f64>> {
        self.require(mask::GET)?;
        let vars = vrs
            .iter()
            .map(|&vr| self.variable(vr, ty, func))
            .collect::<FmiResult<Vec<_>>>()?;
        let needs_outputs = vars
            .iter()
            .any(|v| v.causality == Causality::Output && v.name != "newton_iterations");
        // Before initialization nothing has been simulated: no work done, no error yet.
        let outputs = if needs_outputs {
            Some(self.outputs()?)
        } else {
            None
        };
        let values = vars
            .iter()
            .map(|var| match var.causality {
                Causality::Parameter => self
                    .params
                    .get(var.name)
                    .expect("every parameter has a value"),
                Causality::Input => self.f_ctrl,
                Causality::Output => match var.name {
                    "newton_iterations" => self.newton_iterations(),
                    name => outputs
                        .as_ref()
                        .and_then(|o| o.by_name(name))
                        .unwrap_or_else(|| unreachable!("output `{name}` has no value")),
                },
            })
            .collect();
        self.log.trace(|| format!("{func}({vrs:?}) -> {values:?}"));
        Ok(values)
    }

    fn newton_iterations(&self) -> f64 {
        match self.state {
            FmiState::Instantiated | FmiState::InitializationMode => 0.0,
            _ => self
                .sim
                .as_ref()
                .map_or(0.0, |s| s.last_newton_iterations() as f64),
        }
    }

    pub fn get_real(&mut self, vrs: &[u32], out: &mut [f64]) -> FmiResult {
        let values = self.get_values("fmi2GetReal", VarType::Real, vrs)?;
        out.copy_from_slice(&values);
        Ok(())
    }

    pub fn get_integer(&mut self, vrs: &[u32], out: &mut [i32]) -> FmiResult {
        let values = self.get_values("fmi2GetInteger", VarType::Integer, vrs)?;
        for (o, v) in out.iter_mut().zip(values) {
            *o = v.clamp(i32::MIN as f64, i32::MAX as f64) as i32;
        }
        Ok(())
    }

    /// Checks every value first and applies them only if all are accepted.
    fn set_values(&mut self, func: &str, ty: VarType, vrs: &[u32], values: &[f64]) -> FmiResult {
        self.require(mask::SET)?;
        let mut params = self.params.clone();
        let mut f_ctrl = self.f_ctrl;
        for (&vr, &value) in vrs.iter().zip(values) {
            let var = self.variable(vr, ty, func)?;
            let allowed = match (var.causality, var.variability) {
                (Causality::Output, _) => {
                    return error(format!("{} is an output: it cannot be set", describe(var)));
                }
                (Causality::Parameter, Variability::Fixed) => mask::FIXED_PARAMETER,
                _ => mask::SET,
            };
            if allowed & self.state.bit() == 0 {
                return error(format!(
                    "{} is a {} {}: it can be set in {} only, not in {}",
                    describe(var),
                    format!("{:?}", var.variability).to_lowercase(),
                    format!("{:?}", var.causality).to_lowercase(),
                    state_list(allowed),
                    self.state.name()
                ));
            }
            match var.causality {
                Causality::Parameter => {
                    params
                        .set(var.name, value)
                        .map_err(|e| Failure::Error(format!("{e} (vr {vr})")))?;
                }
                _ => {
                    if !var.admits(value) {
                        let range = var.range_text().unwrap_or_else(|| "finite".to_string());
                        return error(format!(
                            "{}: {value} is out of range: must be {range}",
                            describe(var)
                        ));
                    }
                    f_ctrl = value;
                }
            }
        }
        let forcing_changed = params.forcing_amplitude != self.params.forcing_amplitude
            || params.forcing_frequency != self.params.forcing_frequency;
        if forcing_changed && self.state == FmiState::StepComplete {
            if let Some(sim) = &mut self.sim {
                sim.set_forcing(params.forcing_amplitude, params.forcing_frequency)
                    .map_err(|e| Failure::Error(e.to_string()))?;
            }
        }
        self.params = params;
        self.f_ctrl = f_ctrl;
        self.log.trace(|| format!("{func}({vrs:?}, {values:?})"));
        Ok(())
    }

    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> FmiResult {
        self.set_values("fmi2SetReal", VarType::Real, vrs, values)
    }

    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> FmiResult {
        let values: Vec<f64> = values.iter().map(|&v| v as f64).collect();
        self.set_values("fmi2SetInteger", VarType::Integer, vrs, &values)
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
        let f_ctrl = self.f_ctrl;
        let Some(sim) = self.sim.as_mut() else {
            return error("internal error: no simulation in state stepComplete");
        };
        match sim.advance(h, f_ctrl) {
            Ok(report) => {
                self.log.trace(|| {
                    format!(
                        "fmi2DoStep: t = {t:e} -> {:e}: {} sub-steps, {} Newton iterations, {} cuts",
                        t + h,
                        report.substeps,
                        report.newton_iterations,
                        report.cuts
                    )
                });
                // Sub-steps of half a forcing period or more sample the excitation at its
                // midpoints only: the step converges but cannot represent the load.
                let dt = h / report.substeps as f64;
                let omega = sim.params().forcing_frequency;
                if omega * dt >= std::f64::consts::PI && sim.params().forcing_amplitude != 0.0 {
                    self.log.warning(&format!(
                        "fmi2DoStep: sub-step {dt:e} s is at least half the forcing period \
                         (Omega dt = {:.3} >= pi): the excitation is aliased; lower dt_max",
                        omega * dt
                    ));
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
            kind: self.kind,
            fmi_state: self.state,
            experiment: self.experiment.clone(),
            params: self.params.clone(),
            f_ctrl: self.f_ctrl,
            snapshot,
        })
    }

    /// Checks that an FMU state fits this instance (scene and element count).
    pub fn check_compatible(&self, kind: SceneKind, elements: usize) -> FmiResult {
        if kind != self.kind {
            return error(format!(
                "the FMU state belongs to the {kind} scene, this instance is a {}",
                self.kind
            ));
        }
        if elements != self.params.elements {
            return error(format!(
                "the FMU state has {elements} elements, this instance has {} (set `elements` first)",
                self.params.elements
            ));
        }
        Ok(())
    }

    pub fn set_fmu_state(&mut self, data: &StateData) -> FmiResult {
        self.require(mask::ANY)?;
        self.check_compatible(data.kind, data.params.elements)?;
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
                let reusable = self
                    .sim
                    .as_ref()
                    .is_some_and(|s| same_fixed(s.params(), &data.params));
                if reusable {
                    let sim = self.sim.as_mut().expect("checked");
                    let backup = sim.snapshot();
                    if let Err(e) = sim.restore(snapshot) {
                        sim.restore(&backup)
                            .expect("a snapshot of this simulation restores");
                        return error(e.to_string());
                    }
                } else {
                    let mut sim = Simulation::new(data.params.clone())
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
        self.f_ctrl = data.f_ctrl;
        self.enter(data.fmi_state);
        self.log
            .event(|| format!("FMU state restored at t = {}", self.time()));
        Ok(())
    }
}
