//! What an FMU variable of a scene is: its causality and timing, the outputs every scene has,
//! what an output reports ([`OutputId`]), what a variable stands for ([`Role`]), and the blocks
//! of value references. A leaf of the scene module: `variables.rs` lists a scene's variables,
//! the FMI layer maps value references through these types.
use super::params::{Range, VarType, SCENE_PARAM_VR};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    Input,
    Output,
}

/// FMI variability of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Timing {
    Fixed,
    Tunable,
    Continuous,
    Discrete,
}

impl Timing {
    pub fn name(self) -> &'static str {
        match self {
            Timing::Fixed => "fixed",
            Timing::Tunable => "tunable",
            Timing::Continuous => "continuous",
            Timing::Discrete => "discrete",
        }
    }
}

/// The outputs every scene has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StandardOutput {
    KineticEnergy,
    StrainEnergy,
    NewtonIterations,
    ExternalWork,
    InputWork,
    SupportWork,
    Dissipated,
    EnergyError,
}

/// (output, name, vr, unit, description)
pub const STANDARD_OUTPUTS: [(StandardOutput, &str, u32, Option<&str>, &str); 8] = [
    (
        StandardOutput::KineticEnergy,
        "E_kin",
        32,
        Some("J"),
        "Kinetic energy of the whole rod",
    ),
    (
        StandardOutput::StrainEnergy,
        "E_strain",
        33,
        Some("J"),
        "Strain energy of the whole rod",
    ),
    (
        StandardOutput::NewtonIterations,
        "newton_iterations",
        34,
        None,
        "Newton corrections (with the exact Jacobian, or chord corrections with the last \
         factorization) summed over the sub-steps of the last communication step",
    ),
    (
        StandardOutput::ExternalWork,
        "W_ext",
        35,
        Some("J"),
        "Work done on the rod by the constant and harmonic loads since t = 0",
    ),
    (
        StandardOutput::InputWork,
        "W_ctrl",
        36,
        Some("J"),
        "Work done on the rod by the input loads since t = 0",
    ),
    (
        StandardOutput::SupportWork,
        "W_supports",
        39,
        Some("J"),
        "Work done on the rod by moving supports since t = 0 (0 when every support is fixed)",
    ),
    (
        StandardOutput::Dissipated,
        "E_damped",
        37,
        Some("J"),
        "Energy dissipated by the viscous damping since t = 0",
    ),
    (
        StandardOutput::EnergyError,
        "energy_error",
        38,
        Some("J"),
        "Energy balance error E_kin + E_strain - E(0) - W_ext - W_ctrl - W_supports + E_damped \
         (round-off for the energy-momentum scheme)",
    ),
];

/// What an output reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputId {
    Standard(StandardOutput),
    Sensor(usize),
    /// Component 0 (`Rx`), 1 (`Ry`) or 2 (`M`) of the reaction of a support on the rod.
    Reaction {
        support: usize,
        component: usize,
    },
    /// The force (moment on `w`) of spring `k` and its dashpot on the rod.
    SpringForce(usize),
    /// Component 0 (`R1`) or 1 (`R2`) of a support's reaction in its own frame.
    SupportFrame {
        support: usize,
        component: usize,
    },
    /// The normal force of truss member `member` (index in the frame) at its start (0) or
    /// end (1).
    BarForce {
        member: usize,
        end: usize,
    },
    /// The force of link `k`.
    LinkForce(usize),
    /// The force of stop `k` on the structure (along its dof).
    StopForce(usize),
    /// The fraction of the last communication step that stop `k` spent in contact.
    StopContact(usize),
    ShapeX(usize),
    ShapeY(usize),
    /// `[shape] fields` entry `field` at shape sample `point`.
    ShapeField {
        field: usize,
        point: usize,
    },
    /// Natural frequency `index` (0-based, ascending) of the initial state, in Hz.
    Frequency(usize),
    /// The running estimate of Lyapunov exponent `index` (0-based), per second or (with
    /// `per_period`) per forcing period.
    Lyapunov {
        index: usize,
        per_period: bool,
    },
    /// The time the Lyapunov exponents average over.
    LyapunovTime,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    Parameter(usize),
    Input(usize),
    Output(OutputId),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    pub name: String,
    pub vr: u32,
    pub var_type: VarType,
    pub causality: Causality,
    pub timing: Timing,
    pub description: String,
    pub unit: Option<String>,
    /// Parameters and inputs (at the scene's defaults).
    pub start: Option<f64>,
    pub range: Range,
    pub role: Role,
}

pub const LYAPUNOV_VR: u32 = 40;
pub const LYAPUNOV_PER_PERIOD_VR: u32 = 44;
pub const LYAPUNOV_TIME_VR: u32 = 48;
pub const INPUT_VR: u32 = 1_000;
pub const SENSOR_VR: u32 = 2_000;
pub const REACTION_VR: u32 = 3_000;
pub const SHAPE_X_VR: u32 = 10_000;
pub const SHAPE_Y_VR: u32 = 20_000;
/// Value reference of `shape_<field>[1]` of the `k`-th field: a block of [`MAX_SHAPE_POINTS`] per
/// field after `shape_y`.
pub const SHAPE_FIELD_VR: u32 = 30_000;
/// Value reference of `frequency[1]`.
pub const FREQUENCY_VR: u32 = 52;
/// Spring forces `<spring>_force`, after every other block.
pub const SPRING_FORCE_VR: u32 = 1_000_000;
/// A support's reactions in its own frame (`_R1`, `_R2`), two per support index.
pub const SUPPORT_FRAME_VR: u32 = 1_100_000;
/// Truss bar forces, two per member index of the frame.
pub const BAR_FORCE_VR: u32 = 1_200_000;
/// Link forces `<link>_force`.
pub const LINK_FORCE_VR: u32 = 1_300_000;
pub const REACTION_SUFFIXES: [&str; 3] = ["Rx", "Ry", "M"];

/// The most scene parameters, inputs, sensors, supports and shape samples whose value
/// references fit their blocks (each block ends where the next begins).
pub const MAX_SCENE_PARAMS: usize = (INPUT_VR - SCENE_PARAM_VR) as usize;
pub const MAX_INPUTS: usize = (SENSOR_VR - INPUT_VR) as usize;
pub const MAX_SENSORS: usize = (REACTION_VR - SENSOR_VR) as usize;
pub const MAX_SUPPORTS: usize = ((SHAPE_X_VR - REACTION_VR) / 3) as usize;
pub const MAX_SHAPE_POINTS: usize = (SHAPE_Y_VR - SHAPE_X_VR) as usize;

pub(crate) fn output(
    name: String,
    vr: u32,
    unit: Option<&str>,
    description: String,
    id: OutputId,
) -> Variable {
    Variable {
        name,
        vr,
        var_type: VarType::Real,
        causality: Causality::Output,
        timing: Timing::Continuous,
        description,
        unit: unit.map(str::to_string),
        start: None,
        range: Range::ANY,
        role: Role::Output(id),
    }
}
