//! The FMU variables of a scene, in modelDescription order: its parameters, its inputs (input
//! loads, support motions), the standard outputs, then its sensors, support reactions and shape
//! samples. Each variable knows what it stands for ([`Role`]), so the FMI layer maps a value
//! reference to a parameter index, an input index or an [`OutputId`] without knowing any physics.
use super::params::{Range, VarType, Variability};
use super::{Scene, Slot, DOF_NAMES};
use std::collections::BTreeMap;

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
    ShapeX(usize),
    ShapeY(usize),
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
    /// For an Enumeration: the name of its declared type.
    pub declared_type: Option<&'static str>,
}

const INPUT_VR: u32 = 1_000;
const SENSOR_VR: u32 = 2_000;
const REACTION_VR: u32 = 3_000;
const SHAPE_X_VR: u32 = 10_000;
const SHAPE_Y_VR: u32 = 20_000;
pub const REACTION_SUFFIXES: [&str; 3] = ["Rx", "Ry", "M"];

fn output(
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
        declared_type: None,
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
            declared_type: (p.var_type == VarType::Enumeration).then_some("Integrator"),
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
            declared_type: None,
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
    for (i, s) in scene.sensors.iter().enumerate() {
        let (dof, velocity) = s.quantity.dof();
        let unit = match (dof, velocity) {
            (2, false) => "rad",
            (2, true) => "rad/s",
            (_, false) => "m",
            (_, true) => "m/s",
        };
        let description = if s.description.is_empty() {
            let what = [
                "Displacement u1",
                "Displacement u2",
                "Rotation w",
                "Velocity v1",
                "Velocity v2",
                "Angular velocity vw",
            ];
            format!(
                "{} at {} of the arc length",
                what[velocity as usize * 3 + dof],
                s.at
            )
        } else {
            s.description.clone()
        };
        vars.push(output(
            s.name.clone(),
            SENSOR_VR + i as u32,
            Some(unit),
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
    for (axis, base, make) in [
        ("x", SHAPE_X_VR, OutputId::ShapeX as fn(usize) -> OutputId),
        ("y", SHAPE_Y_VR, OutputId::ShapeY as fn(usize) -> OutputId),
    ] {
        for i in 0..scene.shape_points {
            let at = i as f64 / (scene.shape_points - 1) as f64;
            vars.push(output(
                format!("shape_{axis}[{}]", i + 1),
                base + i as u32,
                Some("m"),
                format!("Current {axis} position of the rod at {at} of its arc length"),
                make(i),
            ));
        }
    }
    vars
}

/// Every name an FMU variable of this scene would get must be unique; a clash is reported with
/// the scene key that makes it.
pub fn check_names(scene: &Scene) -> Result<(), (String, String)> {
    let mut seen: BTreeMap<String, String> = BTreeMap::new();
    let mut claim = |name: String, by: String| -> Result<(), (String, String)> {
        match seen.get(&name) {
            Some(first) => Err((
                by.clone(),
                format!("the name `{name}` is used twice: by {first} and by {by}"),
            )),
            None => {
                seen.insert(name, by);
                Ok(())
            }
        }
    };
    for p in &scene.params {
        claim(p.name.clone(), format!("parameter {}", p.name))?;
    }
    for (_, name, ..) in STANDARD_OUTPUTS {
        claim(name.to_string(), format!("the standard output {name}"))?;
    }
    for i in &scene.inputs {
        claim(i.name.clone(), format!("the input {}", i.name))?;
    }
    for s in &scene.sensors {
        claim(s.name.clone(), format!("[[sensor]] {}", s.name))?;
    }
    for s in &scene.supports {
        for suffix in REACTION_SUFFIXES {
            claim(
                format!("{}_{suffix}", s.name),
                format!("the reactions of [[support]] {}", s.name),
            )?;
        }
    }
    for l in &scene.loads {
        if !matches!(l.time, super::TimeLaw::Input(_)) {
            // Only input loads become variables, but a load name is still one name.
            claim(l.name.clone(), format!("[[load]] {}", l.name))?;
        }
    }
    for n in ["shape_x", "shape_y"] {
        claim(n.to_string(), "the shape outputs".to_string())?;
    }
    let _ = DOF_NAMES;
    Ok(())
}

/// The start value of input `i` for the given parameter values.
pub fn input_start(scene: &Scene, i: usize, values: &super::ParamValues) -> f64 {
    match scene.inputs[i].start {
        Slot::Number(x) => x,
        slot => slot.eval(values),
    }
}
