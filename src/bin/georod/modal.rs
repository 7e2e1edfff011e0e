//! `georod modes SCENE.toml`: the natural frequencies of a scene's initial state (its static
//! equilibrium under the constant loads and prescribed displacements; harmonic and input loads
//! off), printed, and the mode shapes written as CSV.
use crate::args::Options;
use georod::model::modal_subspace::lowest_modes;
use georod::scene::Scene;
use georod::simulation::readouts::hertz;
use georod::simulation::Simulation;
use std::fmt::Write as _;
use std::sync::Arc;

/// The report printed and the mode-shape CSV: `node,s,x,y`, then `u1_k,u2_k,w_k` per mode
/// (each shape scaled so that its largest translation is +1).
pub fn modes_of_scene(file: &str, o: &Options) -> Result<(String, String), String> {
    let scene = Arc::new(Scene::load(file).map_err(|e| e.to_string())?);
    let values = scene
        .values_with(o.overrides.iter().map(|(k, v)| (k.as_str(), *v)))
        .map_err(|e| e.to_string())?;
    let sim = Simulation::new(scene.clone(), values).map_err(|e| format!("{file}: {e}"))?;
    let rod = sim.rod();
    let u = &sim.state().u;
    let free = rod.dofs() - rod.constrained().len();
    let count = o.count.min(free);
    let modes = lowest_modes(rod, u, count).map_err(|e| format!("{file}: {e}"))?;
    let mut report = format!(
        "{}: {} elements, natural frequencies of the initial state (undamped; constant loads on, \
         harmonic and input loads off)\n{:>5} {:>16} {:>16}\n",
        scene.name,
        sim.values().elements(),
        "mode",
        "frequency/Hz",
        "omega/(rad/s)"
    );
    let mut csv = String::from("node,s,x,y");
    for k in 1..=count {
        let _ = write!(csv, ",u1_{k},u2_{k},w_{k}");
    }
    csv.push('\n');
    let shapes: Vec<Vec<f64>> = modes.iter().map(|(_, shape)| scaled(shape)).collect();
    for (k, (lambda, _)) in modes.iter().enumerate() {
        let f = hertz(*lambda);
        let note = if *lambda < 0.0 {
            "  (unstable: -sqrt(-omega^2))"
        } else {
            ""
        };
        let _ = writeln!(
            report,
            "{:>5} {:>16.8e} {:>16.8e}{note}",
            k + 1,
            f,
            f * std::f64::consts::TAU
        );
    }
    for i in 0..rod.nodes() {
        let x = rod.node_position(u, i);
        let _ = write!(csv, "{i},{:e},{:e},{:e}", rod.node_s[i], x[0], x[1]);
        for shape in &shapes {
            let _ = write!(
                csv,
                ",{:e},{:e},{:e}",
                shape[3 * i],
                shape[3 * i + 1],
                shape[3 * i + 2]
            );
        }
        csv.push('\n');
    }
    Ok((report, csv))
}

/// A mode shape scaled so that its largest translation is +1 (a pure rotation: its largest
/// rotation).
fn scaled(shape: &[f64]) -> Vec<f64> {
    let translations = shape
        .chunks(3)
        .flat_map(|node| [node[0], node[1]])
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(0.0);
    let largest = if translations != 0.0 {
        translations
    } else {
        shape
            .iter()
            .copied()
            .max_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(1.0)
    };
    shape.iter().map(|x| x / largest).collect()
}
