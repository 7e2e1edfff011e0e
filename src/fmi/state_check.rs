//! Field checks of a deserialized FMU state: a state that passed its checksum can still be
//! crafted (or written by a buggy tool), so every number is checked to be finite and every size
//! to fit the instance before the state is handed out. The parameters go through the same
//! validation as `fmi2SetReal`.
use super::state_data::StateData;
use crate::scene::{ParamValues, Scene};
use crate::simulation::Snapshot;

/// The scene's parameters from the serialized list: each of the scene's parameters exactly once,
/// in order, each within its range.
pub fn params(scene: &Scene, list: &[(String, f64)]) -> Result<ParamValues, String> {
    let expected: Vec<&str> = scene.params.iter().map(|p| p.name.as_str()).collect();
    let names: Vec<&str> = list.iter().map(|(n, _)| n.as_str()).collect();
    if names != expected {
        return Err(format!(
            "corrupt serialized state: parameters {names:?}, the {} scene has {expected:?}",
            scene.name
        ));
    }
    let mut params = scene.defaults();
    for (name, value) in list {
        scene
            .set(&mut params, name, *value)
            .map_err(|e| format!("in the serialized state: {e}"))?;
    }
    Ok(params)
}

fn finite(what: &str, x: f64) -> Result<(), String> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(format!("{what} = {x} is not finite"))
    }
}

fn all_finite(what: &str, v: &[f64]) -> Result<(), String> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(format!("{what} {i} = {} is not finite", v[i])),
        None => Ok(()),
    }
}

/// Every field of `data` that the parameter validation does not already cover.
pub fn fields(data: &StateData, scene: &Scene) -> Result<(), String> {
    let e = &data.experiment;
    finite("startTime", e.start_time)?;
    if let Some(tol) = e.tolerance {
        if !(tol.is_finite() && tol > 0.0) {
            return Err(format!("tolerance = {tol} must be finite and > 0"));
        }
    }
    if let Some(stop) = e.stop_time {
        if !(stop.is_finite() && stop >= e.start_time) {
            return Err(format!(
                "stopTime = {stop} must be finite and >= startTime = {}",
                e.start_time
            ));
        }
    }
    if data.inputs.len() != scene.inputs.len() {
        return Err(format!(
            "{} inputs, the scene has {}",
            data.inputs.len(),
            scene.inputs.len()
        ));
    }
    for (input, value) in scene.inputs.iter().zip(&data.inputs) {
        if let Some(x) = value {
            finite(&input.name, *x)?;
        }
    }
    match &data.snapshot {
        Some(s) => snapshot(s, scene, data.params.elements()),
        None => Ok(()),
    }
}

fn snapshot(s: &Snapshot, scene: &Scene, elements: usize) -> Result<(), String> {
    if s.scene != scene.name || s.elements != elements {
        return Err(format!(
            "the simulation snapshot is of a {} with {} elements, the header says {} with \
             {elements}",
            s.scene, s.elements, scene.name
        ));
    }
    let dofs = scene.dofs(elements);
    if s.displacements.len() != dofs || s.velocities.len() != dofs {
        return Err(format!(
            "snapshot vectors of length {} and {}, {elements} elements need {dofs}",
            s.displacements.len(),
            s.velocities.len()
        ));
    }
    let sizes = [
        ("parameter values", s.values.len(), scene.params.len()),
        ("inputs", s.inputs.len(), scene.inputs.len()),
        // One per support, then one per spring (its force), then per link.
        ("reactions", s.reactions.len(), scene.reaction_slots()),
    ];
    for (what, got, want) in sizes {
        if got != want {
            return Err(format!("snapshot {what}: {got}, the scene has {want}"));
        }
    }
    finite("snapshot time", s.time)?;
    finite("clock origin", s.clock.origin)?;
    finite("clock step", s.clock.step)?;
    finite("clock time", s.clock.now())?;
    if s.time != s.clock.now() {
        return Err(format!(
            "snapshot time {} disagrees with its clock ({})",
            s.time,
            s.clock.now()
        ));
    }
    let e = &s.energy;
    let ledger = [
        ("external work", e.external_work),
        ("input work", e.input_work),
        ("support work", e.support_work),
        ("dissipated energy", e.dissipated),
        ("initial energy", e.initial_energy),
    ];
    for (what, x) in ledger {
        finite(what, x)?;
    }
    all_finite("displacement", &s.displacements)?;
    all_finite("velocity", &s.velocities)?;
    all_finite("parameter value", &s.values)?;
    all_finite("input", &s.inputs)?;
    let reactions: Vec<f64> = s.reactions.iter().flatten().copied().collect();
    all_finite("reaction", &reactions)?;
    lyapunov(s, scene, dofs)
}

/// The tangent vectors belong to `lyapunov` exponents of this rod; every number finite.
fn lyapunov(s: &Snapshot, scene: &Scene, dofs: usize) -> Result<(), String> {
    let k = scene
        .param_index(crate::scene::params::LYAPUNOV)
        .map_or(0.0, |i| s.values[i]) as usize;
    match &s.lyapunov {
        None if k == 0 => Ok(()),
        Some(l) if l.log_growth.len() == k && l.du.len() == k * dofs && l.dv.len() == k * dofs => {
            all_finite("tangent vector", &l.du)?;
            all_finite("tangent vector", &l.dv)?;
            all_finite("Lyapunov growth", &l.log_growth)?;
            finite("Lyapunov time", l.counted_time)?;
            if l.counted_time < 0.0 {
                return Err(format!("Lyapunov time {} < 0", l.counted_time));
            }
            Ok(())
        }
        _ => Err(format!(
            "the Lyapunov data does not match lyapunov_count = {k} exponents of {dofs} dofs"
        )),
    }
}
