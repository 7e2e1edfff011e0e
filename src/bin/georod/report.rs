//! What `georod simulate` writes and `georod check` lists: output columns by name (default: the
//! sensors, the support reactions and the energies), and a scene's variables with the shape
//! arrays on one line each, its static reactions and the initial state's key values.
use georod::scene::variables::{self, Causality, OutputId, Role, StandardOutput, Variable};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::fmt::Write as _;

/// The output columns: `names` (any outputs of the scene, by their FMU names), or by default
/// every sensor, every support reaction, `E_kin`, `E_strain` and `newton_iterations`.
pub fn columns(scene: &Scene, names: &[String]) -> Result<Vec<(String, OutputId)>, String> {
    let outputs: Vec<(String, OutputId)> = variables::variables(scene)
        .into_iter()
        .filter_map(|v| match v.role {
            Role::Output(id) => Some((v.name, id)),
            _ => None,
        })
        .collect();
    if names.is_empty() {
        let default = |id: &OutputId| matches!(id, OutputId::Sensor(_) | OutputId::Reaction { .. });
        let mut cols: Vec<_> = outputs
            .iter()
            .filter(|(_, id)| default(id))
            .cloned()
            .collect();
        for name in ["E_kin", "E_strain", "newton_iterations"] {
            cols.extend(outputs.iter().filter(|(n, _)| n == name).cloned());
        }
        return Ok(cols);
    }
    names
        .iter()
        .map(|name| {
            outputs
                .iter()
                .find(|(n, _)| n == name)
                .cloned()
                .ok_or_else(|| {
                    format!(
                        "--outputs: `{name}` is not an output of {} (its outputs: {})",
                        scene.name,
                        grouped_names(&outputs)
                    )
                })
        })
        .collect()
}

/// Output names with each shape array written once, as `shape_x[1..21]`.
fn grouped_names(outputs: &[(String, OutputId)]) -> String {
    let mut names: Vec<String> = Vec::new();
    for (name, _) in outputs {
        let array = array_name(name);
        match array {
            Some((base, _))
                if names
                    .last()
                    .is_some_and(|n| n.starts_with(&format!("{base}["))) => {}
            Some((base, _)) => names.push(format!("{base}[..]")),
            None => names.push(name.clone()),
        }
    }
    names.join(", ")
}

/// `("shape_x", 3)` for `shape_x[3]`; `None` for a name that is not an array entry.
fn array_name(name: &str) -> Option<(&str, usize)> {
    let (base, rest) = name.split_once('[')?;
    let index = rest.strip_suffix(']')?.parse().ok()?;
    Some((base, index))
}

/// The CSV header and one row per communication point: `time,<columns>`.
pub fn trajectory(
    sim: &mut Simulation,
    columns: &[(String, OutputId)],
    step: f64,
    stop: f64,
) -> Result<String, String> {
    let mut csv = String::from("time");
    for (name, _) in columns {
        let _ = write!(csv, ",{name}");
    }
    csv.push('\n');
    let row = |sim: &Simulation, t: f64, csv: &mut String| {
        let _ = write!(csv, "{t:e}");
        for (_, id) in columns {
            let x = sim.output(*id);
            let _ = match id {
                // An Integer output, written as one.
                OutputId::Standard(StandardOutput::NewtonIterations) => write!(csv, ",{x}"),
                _ => write!(csv, ",{x:e}"),
            };
        }
        csv.push('\n');
    };
    row(sim, 0.0, &mut csv);
    for _ in 0..(stop / step).round() as usize {
        sim.advance(step).map_err(|e| e.to_string())?;
        row(sim, sim.time(), &mut csv);
    }
    Ok(csv)
}

/// `georod check`'s listing: every variable (an array such as `shape_x[1..21]` on one line),
/// then the initial state's support reactions and sensor values, its strain energy and natural
/// frequencies, all with the scene's default parameters.
pub fn listing(scene: &Scene, sim: &Simulation) -> String {
    let vars = variables::variables(scene);
    let mut out = String::new();
    let mut i = 0;
    while i < vars.len() {
        let v = &vars[i];
        let run = match array_name(&v.name) {
            Some((base, 1)) => vars[i..]
                .iter()
                .take_while(|w| array_name(&w.name).is_some_and(|(b, _)| b == base))
                .count(),
            _ => 1,
        };
        let name = if run > 1 {
            format!("{}[1..{run}]", array_name(&v.name).map_or("", |(b, _)| b))
        } else {
            v.name.clone()
        };
        let description = match (run > 1, &scene.frame) {
            (true, Some(frame)) if v.name.starts_with("shape_") => {
                frame_samples(v, frame, scene.shape_points)
            }
            (true, _) => array_description(v, run),
            (false, _) => v.description.clone(),
        };
        let _ = writeln!(out, "  {:9} {name:24} {description}", kind(v));
        i += run;
    }
    let _ = writeln!(out, "initial state (default parameters):");
    for (k, s) in scene.supports.iter().enumerate() {
        let r = sim.reactions()[k];
        let _ = writeln!(
            out,
            "  support {:16} Rx = {:+.6e}  Ry = {:+.6e}  M = {:+.6e}",
            s.name, r[0], r[1], r[2]
        );
    }
    for (k, s) in scene.sensors.iter().enumerate() {
        let _ = writeln!(
            out,
            "  sensor  {:16} {:+.6e} {}",
            s.name,
            sim.output(OutputId::Sensor(k)),
            s.quantity.unit()
        );
    }
    let _ = writeln!(out, "  E_strain {:+.6e} J", sim.strain_energy());
    for k in 0..scene.modes {
        let _ = writeln!(
            out,
            "  frequency[{}] {:.6e} Hz",
            k + 1,
            sim.output(OutputId::Frequency(k))
        );
    }
    out
}

fn kind(v: &Variable) -> &'static str {
    match (v.causality, v.role) {
        (Causality::Parameter, _) => "parameter",
        (Causality::Input, _) => "input",
        (_, Role::Output(_)) => "output",
        _ => "",
    }
}

/// A frame's shape samples: which indices sample which member.
fn frame_samples(first: &Variable, frame: &georod::scene::frame::Frame, points: usize) -> String {
    let what = first.description.split(" of member").next().unwrap_or("");
    let ranges: Vec<String> = (frame.members.iter().enumerate())
        .map(|(m, member)| format!("[{}..{}] {}", m * points + 1, (m + 1) * points, member.name))
        .collect();
    format!(
        "{what}, at {points} equally spaced points along each member from its `from` joint: {}",
        ranges.join(", ")
    )
}

/// The description of an array's first entry, for the whole array: shape samples by the points
/// they sit at, other arrays (`lyapunov[1..4]`) by their entries.
fn array_description(first: &Variable, count: usize) -> String {
    match first.description.split_once(" at 0 of the arc length") {
        Some((what, _)) if first.name.starts_with("shape_") => {
            format!("{what}, at {count} equally spaced points along the arc length (s = 0 first)")
        }
        _ => format!("{} (entries 2..{count} alike)", first.description),
    }
}
