//! A scene brought to its initial static state and advanced in time by midpoint sub-steps:
//! everything an FMU instance computes, without any FMI concern.
use crate::scene::{ParamError, SceneKind, SceneParams};
use serde::{Deserialize, Serialize};
use std::fmt;

/// Why a simulation could not be built or advanced.
#[derive(Clone, Debug, PartialEq)]
pub enum SimError {
    /// A parameter out of range (names the variable and the allowed range).
    Param(ParamError),
    /// The initial static equilibrium could not be found.
    InitialState(String),
    /// A time step did not converge even after cutting it; the state is unchanged.
    StepFailed { time: f64, reason: String },
    /// A snapshot that does not belong to this simulation.
    BadSnapshot(String),
    /// A bad argument (non-finite or negative step size, ...).
    BadArgument(String),
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Param(e) => e.fmt(f),
            SimError::InitialState(why) => write!(f, "initial static state not found: {why}"),
            SimError::StepFailed { time, reason } => {
                write!(f, "step from t = {time} failed: {reason}; state left unchanged")
            }
            SimError::BadSnapshot(why) => write!(f, "state snapshot refused: {why}"),
            SimError::BadArgument(why) => f.write_str(why),
        }
    }
}

impl std::error::Error for SimError {}

impl From<ParamError> for SimError {
    fn from(e: ParamError) -> Self {
        SimError::Param(e)
    }
}

/// The outputs of the FMU at the current time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outputs {
    pub w_mid: f64,
    pub v_mid: f64,
    pub kinetic_energy: f64,
    pub strain_energy: f64,
}

/// What one [`Simulation::advance`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AdvanceReport {
    pub substeps: usize,
    pub newton_iterations: u32,
    /// How many times the sub-step was halved after a Newton failure.
    pub cuts: u32,
}

/// Everything needed to continue a simulation exactly: self-contained, versioned.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    pub version: u32,
    pub kind: SceneKind,
    pub elements: usize,
    pub time: f64,
    pub displacements: Vec<f64>,
    pub velocities: Vec<f64>,
    pub forcing_amplitude: f64,
    pub forcing_frequency: f64,
    pub last_newton_iterations: u32,
}

pub struct Simulation {
    _todo: (),
}

impl Simulation {
    pub fn new(_params: SceneParams) -> Result<Simulation, SimError> {
        todo!()
    }
    pub fn params(&self) -> &SceneParams {
        todo!()
    }
    pub fn time(&self) -> f64 {
        todo!()
    }
    pub fn set_forcing(&mut self, _amplitude: f64, _frequency: f64) -> Result<(), ParamError> {
        todo!()
    }
    pub fn advance(&mut self, _h: f64, _f_ctrl: f64) -> Result<AdvanceReport, SimError> {
        todo!()
    }
    pub fn outputs(&self) -> Outputs {
        todo!()
    }
    pub fn last_newton_iterations(&self) -> u32 {
        todo!()
    }
    pub fn snapshot(&self) -> Snapshot {
        todo!()
    }
    pub fn restore(&mut self, _s: &Snapshot) -> Result<(), SimError> {
        todo!()
    }
    pub fn reset(&mut self) {
        todo!()
    }
}
