//! FMU states (`fmi2GetFMUstate` & co.): everything needed to put an instance back exactly where
//! it was, and its versioned, self-checking binary form (`fmi2SerializeFMUstate`).
//!
//! Serialized layout, version 5 (all integers little-endian):
//!
//! | offset | size | field |
//! |---:|---:|---|
//! | 0 | 8 | magic `GEOROD\0S` |
//! | 8 | 4 | format version (`u32`, [`SERIAL_VERSION`]) |
//! | 12 | 4 | CRC-32 (IEEE, as zlib's `crc32`) of the whole buffer with these 4 bytes taken as 0 |
//! | 16 | 8 | total length of the buffer in bytes (`u64`) |
//! | 24 | .. | bincode 1.3 (fixed-width integers): `Header { guid, scene, elements }`, then `Body` |
//!
//! Reading checks, in this order, and refuses with a message at the first failure: length,
//! magic, version, recorded length, checksum, the bincode payload (with no trailing bytes), the
//! GUID / scene / element count against the instance, then every field
//! ([`super::state_check`]). The CRC-32 detects every corruption of up to 32 consecutive bits
//! (so every changed byte) and all but 2^-32 of random ones; it is a guard against accidents, the
//! field checks against crafted states.
use super::experiment::Experiment;
use super::state_check;
pub use super::state_data::StateData;
use super::state_machine::FmiState;
use crate::scene::Scene;
use crate::simulation::Snapshot;
use bincode::Options;
use serde::{Deserialize, Serialize};

/// First bytes of every serialized state.
pub const SERIAL_MAGIC: [u8; 8] = *b"GEOROD\x00S";
/// Layout version; bump it when the layout or the fields change.
pub const SERIAL_VERSION: u32 = 5;
/// Where the CRC-32 sits, and the length of the fixed prefix.
const CRC_AT: usize = 12;
const LENGTH_AT: usize = 16;
pub const PREFIX_LEN: usize = 24;

#[derive(Serialize, Deserialize)]
struct Header {
    /// The GUID of the FMU that wrote the state: the same scene and the same variables.
    guid: String,
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

/// bincode 1.3's legacy encoding (fixed-width little-endian integers), reading at most `limit`
/// bytes and nothing after the value.
fn codec(limit: u64) -> impl Options {
    bincode::DefaultOptions::new()
        .with_fixint_encoding()
        .with_limit(limit)
}

/// The CRC-32 of `bytes` with its checksum field taken as zero.
pub fn checksum(bytes: &[u8]) -> u32 {
    let mut h = crc32fast::Hasher::new();
    h.update(&bytes[..CRC_AT]);
    h.update(&[0; 4]);
    h.update(&bytes[CRC_AT + 4..]);
    h.finalize()
}

/// The bytes of a state of `scene` taken by an FMU with this `guid`.
pub fn serialize(data: &StateData, scene: &Scene, guid: &str) -> Result<Vec<u8>, String> {
    let params = scene
        .params
        .iter()
        .zip(&data.params.0)
        .map(|(p, &x)| (p.name.clone(), x))
        .collect();
    let header = Header {
        guid: guid.to_string(),
        scene: data.scene.clone(),
        elements: data.params.elements() as u64,
    };
    let body = Body {
        fmi_state: data.fmi_state,
        experiment: data.experiment.clone(),
        params,
        inputs: data.inputs.clone(),
        snapshot: data.snapshot.clone(),
    };
    let mut bytes = Vec::with_capacity(PREFIX_LEN + 1024);
    bytes.extend_from_slice(&SERIAL_MAGIC);
    bytes.extend_from_slice(&SERIAL_VERSION.to_le_bytes());
    bytes.extend_from_slice(&[0; 4 + 8]); // CRC and length, filled in below
    codec(u64::MAX)
        .serialize_into(&mut bytes, &(&header, &body))
        .map_err(|e| e.to_string())?;
    let len = bytes.len() as u64;
    bytes[LENGTH_AT..PREFIX_LEN].copy_from_slice(&len.to_le_bytes());
    let crc = checksum(&bytes);
    bytes[CRC_AT..CRC_AT + 4].copy_from_slice(&crc.to_le_bytes());
    Ok(bytes)
}

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"))
}

/// The prefix checks: everything up to and including the checksum.
fn check_prefix(bytes: &[u8]) -> Result<(), String> {
    if bytes.len() < PREFIX_LEN {
        return Err(format!(
            "{} bytes is too short for a serialized georod FMU state (at least {PREFIX_LEN})",
            bytes.len()
        ));
    }
    if bytes[..SERIAL_MAGIC.len()] != SERIAL_MAGIC {
        return Err("not a serialized georod FMU state (wrong magic bytes)".to_string());
    }
    let version = u32_at(bytes, SERIAL_MAGIC.len());
    if version != SERIAL_VERSION {
        return Err(format!(
            "serialized state format version {version} (this FMU reads version {SERIAL_VERSION})"
        ));
    }
    let recorded = u64::from_le_bytes(bytes[LENGTH_AT..PREFIX_LEN].try_into().expect("8 bytes"));
    if recorded != bytes.len() as u64 {
        return Err(format!(
            "size = {} does not match the length recorded in the serialized state ({recorded} \
             bytes): truncated, extended or corrupt",
            bytes.len()
        ));
    }
    let (stored, computed) = (u32_at(bytes, CRC_AT), checksum(bytes));
    if stored != computed {
        return Err(format!(
            "checksum mismatch (stored CRC-32 {stored:#010x}, computed {computed:#010x}): the \
             serialized state is corrupt"
        ));
    }
    Ok(())
}

/// Reads a serialized state for an instance of `scene` (its FMU's `guid`) with `elements`
/// elements.
pub fn deserialize(
    bytes: &[u8],
    scene: &Scene,
    guid: &str,
    elements: usize,
) -> Result<StateData, String> {
    check_prefix(bytes)?;
    let payload = &bytes[PREFIX_LEN..];
    let (header, body): (Header, Body) = codec(payload.len() as u64)
        .deserialize(payload)
        .map_err(|e| format!("corrupt serialized state ({e})"))?;
    if header.scene != scene.name {
        return Err(format!(
            "the serialized state belongs to the {} scene, this instance is a {}",
            header.scene, scene.name
        ));
    }
    if header.guid != guid {
        return Err(format!(
            "the serialized state was written by another build of the {} FMU (GUID {}, \
             this FMU has {guid})",
            scene.name, header.guid
        ));
    }
    if header.elements != elements as u64 {
        return Err(format!(
            "the serialized state has {} elements, this instance has {elements} (set `elements` first)",
            header.elements
        ));
    }
    let params = state_check::params(scene, &body.params)?;
    if params.elements() != elements {
        return Err("corrupt serialized state: `elements` disagrees with its header".to_string());
    }
    let data = StateData {
        scene: scene.name.clone(),
        fmi_state: body.fmi_state,
        experiment: body.experiment,
        params,
        inputs: body.inputs,
        snapshot: body.snapshot,
    };
    state_check::fields(&data, scene).map_err(|e| format!("corrupt serialized state: {e}"))?;
    Ok(data)
}
