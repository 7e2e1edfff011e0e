//! FMU states (`fmi2GetFMUstate` & co.): everything needed to put an instance back exactly where
//! it was, and its versioned binary form (`fmi2SerializeFMUstate`).
//!
//! Serialized layout (bincode 1.3, fixed-width little-endian integers):
//! `Header { magic: 8 bytes, format_version: u32, scene: String, elements: u64 }` then `Body`.
//! The header is read first so that every mismatch gets its own clear message.
use super::instance::{Experiment, FmiState};
use crate::scene::{ParamValues, Scene};
use crate::simulation::Snapshot;
use serde::{Deserialize, Serialize};

/// First bytes of every serialized state.
pub const SERIAL_MAGIC: [u8; 8] = *b"GEOROD\x00S";
/// Layout version of [`Body`]; bump it when the fields change.
pub const SERIAL_VERSION: u32 = 3;
/// Marks a live `FmuState` allocation (detects garbage and freed pointers where cheap).
const STATE_MAGIC: u64 = 0x4745_4f52_4f44_5354; // "GEORODST"
const FREED_MAGIC: u64 = 0xdead_dead_dead_dead;

/// What an FMU state holds.
#[derive(Clone, Debug, PartialEq)]
pub struct StateData {
    /// The scene's name.
    pub scene: String,
    pub fmi_state: FmiState,
    pub experiment: Experiment,
    pub params: ParamValues,
    /// The inputs the host set (`None`: the start value).
    pub inputs: Vec<Option<f64>>,
    /// The simulation state; `None` before `fmi2ExitInitializationMode` (nothing simulated yet).
    pub snapshot: Option<Snapshot>,
}

/// The allocation behind an `fmi2FMUstate` pointer.
#[repr(C)]
pub struct FmuState {
    /// First field, so it can be checked through a raw pointer before anything else is read.
    magic: u64,
    pub data: StateData,
}

impl FmuState {
    pub fn into_raw(data: StateData) -> *mut FmuState {
        Box::into_raw(Box::new(FmuState {
            magic: STATE_MAGIC,
            data,
        }))
    }

    /// The state behind `p`, or `None` for NULL, misaligned or unmarked pointers.
    ///
    /// # Safety
    /// `p` must be NULL or readable for `size_of::<u64>()` bytes; it is then a live `FmuState`
    /// if its magic matches (a best-effort check, not a guarantee).
    pub unsafe fn from_raw<'a>(p: *mut std::ffi::c_void) -> Option<&'a mut FmuState> {
        let p = p as *mut FmuState;
        if p.is_null() || !p.is_aligned() || std::ptr::addr_of!((*p).magic).read() != STATE_MAGIC {
            return None;
        }
        Some(&mut *p)
    }

    /// Frees a state obtained from [`FmuState::into_raw`].
    ///
    /// # Safety
    /// `state` must come from `into_raw` and not have been freed.
    pub unsafe fn free(state: &mut FmuState) {
        state.magic = FREED_MAGIC;
        drop(Box::from_raw(state as *mut FmuState));
    }
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
    /// Every parameter of the scene by name; values are exact f64 bit patterns.
    params: Vec<(String, f64)>,
    inputs: Vec<Option<f64>>,
    snapshot: Option<Snapshot>,
}

fn header_of(data: &StateData) -> Header {
    Header {
        magic: SERIAL_MAGIC,
        format_version: SERIAL_VERSION,
        scene: data.scene.clone(),
        elements: data.params.elements() as u64,
    }
}

pub fn serialize(data: &StateData, scene: &Scene) -> Result<Vec<u8>, String> {
    let params = scene
        .params
        .iter()
        .zip(&data.params.0)
        .map(|(p, &x)| (p.name.clone(), x))
        .collect();
    let body = Body {
        fmi_state: data.fmi_state,
        experiment: data.experiment.clone(),
        params,
        inputs: data.inputs.clone(),
        snapshot: data.snapshot.clone(),
    };
    let mut bytes = bincode::serialize(&header_of(data)).map_err(|e| e.to_string())?;
    bytes.extend(bincode::serialize(&body).map_err(|e| e.to_string())?);
    Ok(bytes)
}

/// Reads a serialized state for an instance of `scene` with `elements` elements.
pub fn deserialize(bytes: &[u8], scene: &Scene, elements: usize) -> Result<StateData, String> {
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
    if header.scene != scene.name {
        return Err(format!(
            "the serialized state belongs to the {} scene, this instance is a {}",
            header.scene, scene.name
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
    let mut params = scene.defaults();
    if body.params.len() != scene.params.len() {
        return Err(format!(
            "corrupt serialized state: {} parameters, the scene has {}",
            body.params.len(),
            scene.params.len()
        ));
    }
    for (name, value) in &body.params {
        scene
            .set(&mut params, name, *value)
            .map_err(|e| format!("in the serialized state: {e}"))?;
    }
    if params.elements() != elements {
        return Err("corrupt serialized state: `elements` disagrees with its header".to_string());
    }
    if let Some(s) = &body.snapshot {
        if s.scene != scene.name || s.elements != elements {
            return Err(
                "corrupt serialized state: the simulation snapshot disagrees with its header"
                    .into(),
            );
        }
    }
    if body.inputs.len() != scene.inputs.len()
        || body.inputs.iter().flatten().any(|x| !x.is_finite())
    {
        return Err(
            "corrupt serialized state: wrong number of inputs or a non-finite input".to_string(),
        );
    }
    Ok(StateData {
        scene: scene.name.clone(),
        fmi_state: body.fmi_state,
        experiment: body.experiment,
        params,
        inputs: body.inputs,
        snapshot: body.snapshot,
    })
}
