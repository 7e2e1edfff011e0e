//! One FMU instance: the FMI 2.0 Co-Simulation state machine, parameter and value handling, and
//! the simulation it drives. Pure Rust (slices, `&str`); [`crate::fmi::api`] does the C side.
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
//!
//! This file holds the instance itself (fields, pointer checks, accessors, the state check
//! every call makes); its methods are grouped by concern:
//! - `lifecycle`: experiment setup, initialization mode, terminate, reset, the initial state;
//! - `inputs`: what the value functions of [`crate::fmi::values`] read and write (inputs, their
//!   derivatives, the simulation outputs come from);
//! - `stepping`: `fmi2DoStep` and the status queries;
//! - `fmu_states`: taking, restoring and (de)serializing FMU states.
//!
//! The FMI states, the states each call is allowed in and how a call is refused are the leaf
//! [`crate::fmi::state_machine`]; what an FMU state holds is [`crate::fmi::state_data`]. The
//! instance uses them, the FMU state format and the state registry; none of those uses the
//! instance.
mod fmu_states;
mod inputs;
mod lifecycle;
mod stepping;

use super::experiment::Experiment;
use super::interface::Interface;
use super::logging::Logger;
use super::state_machine::{error, state_list, FmiResult, FmiState};
use super::state_registry::StateRegistry;
use crate::scene::{ParamValues, Scene};
use crate::simulation::Simulation;
use std::path::PathBuf;
use std::sync::Arc;

/// Marks a live `Instance` allocation (detects garbage and freed pointers where cheap).
pub const INSTANCE_MAGIC: u64 = 0x4745_4f52_4f44_4649; // "GEORODFI"
pub const FREED_MAGIC: u64 = 0xdead_beef_dead_beef;

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

    /// Moves to `state` (logged as an event).
    fn enter(&mut self, state: FmiState) {
        let from = self.state;
        self.state = state;
        self.log
            .event(|| format!("state {} -> {}", from.name(), state.name()));
    }
}
