//! The FMU variables of a scene, in modelDescription order: its parameters, its inputs (input
//! loads, support motions), the standard outputs, then its sensors, support reactions and shape
//! samples. Each variable knows what it stands for ([`Role`]), so the FMI layer maps a value
//! reference to a parameter index, an input index or an [`OutputId`] without knowing any physics.
use super::params::{Range, VarType, Variability, SCENE_PARAM_VR};
use super::{Scene, Slot};

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

const LYAPUNOV_VR: u32 = 40;
const LYAPUNOV_PER_PERIOD_VR: u32 = 44;
const LYAPUNOV_TIME_VR: u32 = 48;
pub const INPUT_VR: u32 = 1_000;
pub const SENSOR_VR: u32 = 2_000;
pub const REACTION_VR: u32 = 3_000;
pub const SHAPE_X_VR: u32 = 10_000;
pub const SHAPE_Y_VR: u32 = 20_000;
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

pub(super) fn output(
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

/// Every FMU variable of `scene`, in modelDescription order.
pub fn variables(scene: &Scene) -> Vec<Variable> {
    let defaults = scene.defaults();
    let mut vars = Vec::new();
    for (i, p) in scene.params.iter().enumerate() {
        vars.push(Variable {
            name: p.name.clone(),
            vr: p.vr,
            var_type: p.var_type,
            causality: Causality::Parameter,
            timing: match p.variability {
                Variability::Fixed => Timing::Fixed,
                Variability::Tunable => Timing::Tunable,
            },
            description: p.description.clone(),
            unit: p.unit.clone(),
            start: Some(p.start),
            range: p.range,
            role: Role::Parameter(i),
        });
    }
    for (i, input) in scene.inputs.iter().enumerate() {
        vars.push(Variable {
            name: input.name.clone(),
            vr: INPUT_VR + i as u32,
            var_type: VarType::Real,
            causality: Causality::Input,
            timing: Timing::Continuous,
            description: input.description.clone(),
            unit: input.unit.clone(),
            start: Some(input.start.eval(&defaults)),
            range: Range::ANY,
            role: Role::Input(i),
        });
    }
    for (id, name, vr, unit, description) in STANDARD_OUTPUTS {
        let mut v = output(
            name.into(),
            vr,
            unit,
            description.into(),
            OutputId::Standard(id),
        );
        if id == StandardOutput::NewtonIterations {
            v.var_type = VarType::Integer;
            v.timing = Timing::Discrete;
        }
        vars.push(v);
    }
    vars.extend(lyapunov_outputs(scene));
    for (i, s) in scene.sensors.iter().enumerate() {
        let description = if s.description.is_empty() {
            match scene.frame {
                None => format!(
                    "{} at {} of the arc length",
                    s.quantity.what(),
                    s.at.fraction()
                ),
                Some(_) => format!("{} at {}", s.quantity.what(), scene.station_text(&s.at)),
            }
        } else {
            s.description.clone()
        };
        vars.push(output(
            s.name.clone(),
            SENSOR_VR + i as u32,
            Some(s.quantity.unit()),
            description,
            OutputId::Sensor(i),
        ));
    }
    for (k, s) in scene.supports.iter().enumerate() {
        for (c, suffix) in REACTION_SUFFIXES.iter().enumerate() {
            let (unit, what) = if c < 2 {
                (
                    "N",
                    format!(
                        "Reaction force of support {} on the rod along e{}",
                        s.name,
                        c + 1
                    ),
                )
            } else {
                (
                    "N.m",
                    format!(
                        "Reaction moment of support {} on the rod (counter-clockwise)",
                        s.name
                    ),
                )
            };
            let note = if s.fixed[c] {
                "; averaged over the last communication step (before the first step: the static reaction)"
            } else {
                "; 0: this dof is free"
            };
            vars.push(output(
                format!("{}_{suffix}", s.name),
                REACTION_VR + 3 * k as u32 + c as u32,
                Some(unit),
                format!("{what}{note}"),
                OutputId::Reaction {
                    support: k,
                    component: c,
                },
            ));
        }
    }
    for (k, s) in scene.springs.iter().enumerate() {
        vars.push(output(
            format!("{}_force", s.name),
            SPRING_FORCE_VR + k as u32,
            Some(if s.dof == 2 { "N.m" } else { "N" }),
            format!(
                "Force of spring {} and its dashpot on the rod along {}; averaged over the last \
                 communication step (before the first step: the static force)",
                s.name,
                ["e1", "e2", "the rotation (a moment)"][s.dof]
            ),
            OutputId::SpringForce(k),
        ));
    }
    for (axis, base, make) in [
        ("x", SHAPE_X_VR, OutputId::ShapeX as fn(usize) -> OutputId),
        ("y", SHAPE_Y_VR, OutputId::ShapeY as fn(usize) -> OutputId),
    ] {
        for i in 0..scene.shape_samples() {
            let description = match scene.frame {
                None => {
                    let at = i as f64 / (scene.shape_points - 1) as f64;
                    format!("Current {axis} position of the rod at {at} of its arc length")
                }
                Some(_) => format!("Current {axis} position {}", scene.shape_sample_text(i)),
            };
            vars.push(output(
                format!("shape_{axis}[{}]", i + 1),
                base + i as u32,
                Some("m"),
                description,
                make(i),
            ));
        }
    }
    vars.extend(super::readouts::outputs(scene));
    vars.extend(frame_outputs(scene));
    vars.extend(super::stops::outputs(scene));
    vars
}

/// A frame's own outputs: supports at an angle in their frame (`_R1`, `_R2`), truss bar forces
/// (`<member>_N_start`, `_N_end`) and link forces (`<link>_force`).
fn frame_outputs(scene: &Scene) -> Vec<Variable> {
    let mut vars = Vec::new();
    for (k, s) in scene
        .supports
        .iter()
        .enumerate()
        .filter(|(_, s)| s.angle != 0.0)
    {
        for c in 0..2 {
            vars.push(output(
                format!("{}_R{}", s.name, c + 1),
                SUPPORT_FRAME_VR + 2 * k as u32 + c as u32,
                Some("N"),
                format!(
                    "Reaction force of support {} on the structure along its own axis {} (turned \
                     by {} degrees from e{}); averaged like {0}_Rx",
                    s.name,
                    c + 1,
                    s.angle,
                    c + 1
                ),
                OutputId::SupportFrame {
                    support: k,
                    component: c,
                },
            ));
        }
    }
    let Some(frame) = &scene.frame else {
        return vars;
    };
    for (m, member) in frame.members.iter().enumerate() {
        if member.kind != super::frame::MemberKind::Truss {
            continue;
        }
        for (end, suffix) in ["start", "end"].iter().enumerate() {
            vars.push(output(
                format!("{}_N_{suffix}", member.name),
                BAR_FORCE_VR + 2 * m as u32 + end as u32,
                Some("N"),
                format!(
                    "Normal force of {} {} at its {suffix} (tension positive{})",
                    if member.cable {
                        "cable"
                    } else {
                        "truss member"
                    },
                    member.name,
                    if member.cable { "; 0 while slack" } else { "" }
                ),
                OutputId::BarForce { member: m, end },
            ));
        }
    }
    for (k, l) in frame.links.iter().enumerate() {
        vars.push(output(
            format!("{}_force", l.name),
            LINK_FORCE_VR + k as u32,
            Some("N"),
            format!(
                "Force of link {} along its current line (tension positive), spring and dashpot; \
                 averaged over the last communication step (before the first step: the static \
                 force)",
                l.name
            ),
            OutputId::LinkForce(k),
        ));
    }
    vars
}

/// `lyapunov[i]` (1/s), with a harmonic load `lyapunov_per_period[i]`, and `lyapunov_time`.
fn lyapunov_outputs(scene: &Scene) -> Vec<Variable> {
    let k = crate::integrator::tangent::MAX_EXPONENTS;
    let mut vars = Vec::new();
    for i in 0..k {
        vars.push(output(
            format!("lyapunov[{}]", i + 1),
            LYAPUNOV_VR + i as u32,
            Some("1/s"),
            format!(
                "Lyapunov exponent {} (in decreasing order) per second: the growth of the tangent \
                 vectors averaged after lyapunov_start + lyapunov_align (0 unless \
                 lyapunov_count >= {})",
                i + 1,
                i + 1
            ),
            OutputId::Lyapunov {
                index: i,
                per_period: false,
            },
        ));
    }
    if scene.param_index("Omega").is_some() {
        for i in 0..k {
            vars.push(output(
                format!("lyapunov_per_period[{}]", i + 1),
                LYAPUNOV_PER_PERIOD_VR + i as u32,
                Some("1"),
                format!(
                    "Lyapunov exponent {} per forcing period 2 pi / Omega (0 when Omega = 0)",
                    i + 1
                ),
                OutputId::Lyapunov {
                    index: i,
                    per_period: true,
                },
            ));
        }
    }
    vars.push(output(
        "lyapunov_time".to_string(),
        LYAPUNOV_TIME_VR,
        Some("s"),
        "Time the Lyapunov exponents average over (since lyapunov_start + lyapunov_align)"
            .to_string(),
        OutputId::LyapunovTime,
    ));
    vars
}

/// The start value of input `i` for the given parameter values.
pub fn input_start(scene: &Scene, i: usize, values: &super::ParamValues) -> f64 {
    match scene.inputs[i].start {
        Slot::Number(x) => x,
        slot => slot.eval(values),
    }
}
