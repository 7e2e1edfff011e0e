//! The FMU variables of a scene, in modelDescription order: its parameters, its inputs (input
//! loads, support motions), the standard outputs, then its sensors, support reactions and shape
//! samples, the shape fields and frequencies, and a frame's own outputs. Each variable knows what
//! it stands for ([`Role`]), so the FMI layer maps a value reference to a parameter index, an
//! input index or an [`OutputId`] without knowing any physics.
use super::params::{Range, VarType, Variability};
pub use super::variable_kinds::*;
use super::{Scene, Slot};

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
    // What the supports and springs act on, in their descriptions.
    let body = if scene.frame.is_some() {
        "structure"
    } else {
        "rod"
    };
    for (k, s) in scene.supports.iter().enumerate() {
        for (c, suffix) in REACTION_SUFFIXES.iter().enumerate() {
            let (unit, what) = if c < 2 {
                (
                    "N",
                    format!(
                        "Reaction force of support {} on the {body} along e{}",
                        s.name,
                        c + 1
                    ),
                )
            } else {
                (
                    "N.m",
                    format!(
                        "Reaction moment of support {} on the {body} (counter-clockwise)",
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
                "Force of spring {} and its dashpot on the {body} along {}; averaged over the last \
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
    vars.extend(field_outputs(scene));
    vars.extend(super::frame_outputs::frame_outputs(scene));
    vars.extend(super::stops::outputs(scene));
    vars
}

/// The outputs `shape_<field>[i]` and `frequency[k]`.
fn field_outputs(scene: &Scene) -> Vec<Variable> {
    let mut vars = Vec::new();
    for (field, q) in scene.shape_fields.iter().enumerate() {
        let base = SHAPE_FIELD_VR + (field * MAX_SHAPE_POINTS) as u32;
        for point in 0..scene.shape_samples() {
            vars.push(output(
                format!("shape_{}[{}]", q.name(), point + 1),
                base + point as u32,
                Some(q.unit()),
                format!("{} {}", q.what(), scene.shape_sample_text(point)),
                OutputId::ShapeField { field, point },
            ));
        }
    }
    for k in 0..scene.modes {
        let mut v = output(
            format!("frequency[{}]", k + 1),
            FREQUENCY_VR + k as u32,
            Some("Hz"),
            format!(
                "Natural frequency {} (ascending) of the initial state: undamped, about the \
                 static equilibrium under the constant loads and prescribed displacements, \
                 computed at fmi2ExitInitializationMode (negative, -sqrt(-omega^2) / (2 pi), for an \
                 unstable direction)",
                k + 1
            ),
            OutputId::Frequency(k),
        );
        v.timing = Timing::Discrete;
        vars.push(v);
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
