//! FMU states (`fmi2GetFMUstate` & co.): everything needed to put an instance back exactly where
//! it was, and its versioned binary form (`fmi2SerializeFMUstate`).
//!
//! Serialized layout (bincode 1.3, fixed-width little-endian integers):
//! `Header { magic: 8 bytes, format_version: u32, scene: String, elements: u64 }` then `Body`.
//! The header is read first so that every mismatch gets its own clear message.
use super::instance::{Experiment, FmiState};
use crate::scene::{SceneKind, SceneParams};
use crate::simulation::Snapshot;
use crate::variables::{self, Causality};
use serde::{Deserialize, Serialize};

/// First bytes of every serialized state.
pub const SERIAL_MAGIC: [u8; 8] = *b"GEOROD\x00S";
/// Layout version of [`Body`]; bump it when the fields change.
pub const SERIAL_VERSION: u32 = 2;
/// What an FMU state holds.
#[derive(Clone, Debug, PartialEq)]
pub struct StateData {
    pub kind: SceneKind,
    pub fmi_state: FmiState,
    pub experiment: Experiment,
    pub params: SceneParams,
    pub f_ctrl: f64,
    /// The simulation state; `None` before `fmi2ExitInitializationMode` (nothing simulated yet).
    pub snapshot: Option<Snapshot>,
}

#[derive(Serialize, Deserialize)]
struct Header {
    magic: [u8; 8],
    format_version: u32,
    scene: String,
    elements: u64,
}

#[derive(Serialize, Deserialize)]
struct Body {
    fmi_state: FmiState,
    experiment: Experiment,
    /// Every parameter of the scene by name (SceneParams itself deserializes only from a scene
    /// file); values are exact f64 bit patterns.
    params: Vec<(String, f64)>,
    f_ctrl: f64,
    snapshot: Option<Snapshot>,
}

fn header_of(data: &StateData) -> Header {
    Header {
        magic: SERIAL_MAGIC,
        format_version: SERIAL_VERSION,
        scene: data.kind.name().to_string(),
        elements: data.params.elements as u64,
    }
}

pub fn serialize(data: &StateData) -> Result<Vec<u8>, String> {
    let params = variables::VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Parameter && v.scenes[data.kind.index()])
        .map(|v| {
            (
                v.name.to_string(),
                data.params.get(v.name).expect("a parameter"),
            )
        })
        .collect();
    let body = Body {
        fmi_state: data.fmi_state,
        experiment: data.experiment.clone(),
        params,
        f_ctrl: data.f_ctrl,
        snapshot: data.snapshot.clone(),
    };
    let mut bytes = bincode::serialize(&header_of(data)).map_err(|e| e.to_string())?;
    bytes.extend(bincode::serialize(&body).map_err(|e| e.to_string())?);
    Ok(bytes)
}

/// Reads a serialized state for an instance of scene `kind` with `elements` elements.
pub fn deserialize(bytes: &[u8], kind: SceneKind, elements: usize) -> Result<StateData, String> {
    if bytes.len() < SERIAL_MAGIC.len() + 4 {
        return Err(format!(
            "{} bytes is too short for a serialized georod FMU state",
            bytes.len()
        ));
    }
    if bytes[..SERIAL_MAGIC.len()] != SERIAL_MAGIC {
        return Err("not a serialized georod FMU state (wrong magic bytes)".to_string());
    }
    let header: Header = bincode::deserialize(bytes)
        .map_err(|e| format!("truncated or corrupt header of the serialized state ({e})"))?;
    if header.format_version != SERIAL_VERSION {
        return Err(format!(
            "serialized state format version {} (this FMU reads version {SERIAL_VERSION})",
            header.format_version
        ));
    }
    if header.scene != kind.name() {
        return Err(format!(
            "the serialized state belongs to the {} scene, this instance is a {kind}",
            header.scene
        ));
    }
    if header.elements != elements as u64 {
        return Err(format!(
            "the serialized state has {} elements, this instance has {elements} (set `elements` first)",
            header.elements
        ));
    }
    let header_len = bincode::serialized_size(&header).map_err(|e| e.to_string())? as usize;
    let body: Body = bincode::deserialize(&bytes[header_len..])
        .map_err(|e| format!("truncated or corrupt serialized state ({e})"))?;
    let used = header_len + bincode::serialized_size(&body).map_err(|e| e.to_string())? as usize;
    if used != bytes.len() {
        return Err(format!(
            "size {} does not match the serialized state ({used} bytes)",
            bytes.len()
        ));
    }
    let mut params = SceneParams::defaults(kind);
    for (name, value) in &body.params {
        params
            .set(name, *value)
            .map_err(|e| format!("in the serialized state: {e}"))?;
    }
    if params.elements != elements {
        return Err("corrupt serialized state: `elements` disagrees with its header".to_string());
    }
    if let Some(s) = &body.snapshot {
        if s.kind != kind || s.elements != elements {
            return Err(
                "corrupt serialized state: the simulation snapshot disagrees with its header"
                    .into(),
            );
        }
    }
    if !body.f_ctrl.is_finite() {
        return Err("corrupt serialized state: f_ctrl is not finite".to_string());
    }
    Ok(StateData {
        kind,
        fmi_state: body.fmi_state,
        experiment: body.experiment,
        params,
        f_ctrl: body.f_ctrl,
        snapshot: body.snapshot,
    })
}
