//! Field checks of a deserialized FMU state: a state that passed its checksum can still be
//! crafted (or written by a buggy tool), so every number is checked to be finite and every size
//! to fit the instance before the state is handed out. The parameters go through the same
//! validation as `fmi2SetReal`.
use super::fmu_state::StateData;
use crate::scene::{SceneKind, SceneParams};
use crate::simulation::Snapshot;
use crate::variables::{self, Causality};

/// Degrees of freedom per node in the snapshot's vectors (u1, u2, w; `model::rod::Rod::dofs`).
const DOFS_PER_NODE: usize = 3;

/// The scene's parameters from the serialized list: each of the scene's parameters exactly once,
/// each within its range.
pub fn params(kind: SceneKind, list: &[(String, f64)]) -> Result<SceneParams, String> {
    let expected: Vec<&str> = variables::VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Parameter && v.scenes[kind.index()])
        .map(|v| v.name)
        .collect();
    let names: Vec<&str> = list.iter().map(|(n, _)| n.as_str()).collect();
    if names != expected {
        return Err(format!(
            "corrupt serialized state: parameters {names:?}, the {kind} scene has {expected:?}"
        ));
    }
    let mut params = SceneParams::defaults(kind);
    for (name, value) in list {
        params
            .set(name, *value)
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

/// Every field of `data` that the parameter validation does not already cover.
pub fn fields(data: &StateData) -> Result<(), String> {
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
    let f_ctrl = variables::by_name("f_ctrl").expect("f_ctrl is a variable");
    if !f_ctrl.admits(data.f_ctrl) {
        return Err(format!("f_ctrl = {} is out of range", data.f_ctrl));
    }
    match &data.snapshot {
        Some(s) => snapshot(s, data.kind, data.params.elements),
        None => Ok(()),
    }
}

fn snapshot(s: &Snapshot, kind: SceneKind, elements: usize) -> Result<(), String> {
    if s.kind != kind || s.elements != elements {
        return Err(format!(
            "the simulation snapshot is of a {} with {} elements, the header says {kind} with \
             {elements}",
            s.kind, s.elements
        ));
    }
    let dofs = DOFS_PER_NODE * (elements + 1);
    if s.displacements.len() != dofs || s.velocities.len() != dofs {
        return Err(format!(
            "snapshot vectors of length {} and {}, {elements} elements need {dofs}",
            s.displacements.len(),
            s.velocities.len()
        ));
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
    finite("forcing amplitude", s.forcing_amplitude)?;
    finite("forcing frequency", s.forcing_frequency)?;
    let ledger = [
        ("external work", s.energy.external_work),
        ("control work", s.energy.control_work),
        ("dissipated energy", s.energy.dissipated),
        ("initial energy", s.energy.initial_energy),
    ];
    for (what, x) in ledger {
        finite(what, x)?;
    }
    for (what, v) in [
        ("displacement", &s.displacements),
        ("velocity", &s.velocities),
    ] {
        if let Some(i) = v.iter().position(|x| !x.is_finite()) {
            return Err(format!("{what} {i} = {} is not finite", v[i]));
        }
    }
    Ok(())
}
