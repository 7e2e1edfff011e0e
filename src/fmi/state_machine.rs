//! The FMI 2.0 Co-Simulation state machine of an instance: its states, the sets of states each
//! function may be called in (standard section 4.2.4), and how a call is refused. A leaf: it
//! names nothing else of `fmi`, so the instance, its FMU states and their registry all use it.
use serde::{Deserialize, Serialize};

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
    /// FMI 3.0 only (`fmi3EnterConfigurationMode`); last, so the serialized indices of the
    /// others stay as they were.
    ConfigurationMode,
}

impl FmiState {
    const ALL: [FmiState; 8] = [
        FmiState::Instantiated,
        FmiState::InitializationMode,
        FmiState::StepComplete,
        FmiState::StepFailed,
        FmiState::StepCanceled,
        FmiState::Terminated,
        FmiState::Error,
        FmiState::ConfigurationMode,
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
            FmiState::ConfigurationMode => "configurationMode",
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
    const CM: u16 = 1 << ConfigurationMode as u16;

    pub const ANY: u16 = I | IM | SC | SF | SCAN | T | E | CM;
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
    /// FMI 3.0: configuration mode is entered from `instantiated` and left back to it.
    pub const ENTER_CONFIGURATION: u16 = I;
    pub const EXIT_CONFIGURATION: u16 = CM;
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
