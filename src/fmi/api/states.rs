//! FMU states: `fmi2GetFMUstate`, `fmi2SetFMUstate`, `fmi2FreeFMUstate` and the serialized
//! form (`fmi2SerializedFMUstateSize`, `fmi2SerializeFMUstate`, `fmi2DeSerializeFMUstate`).
//!
//! A state handle is an opaque token, looked up in the instance's registry (`inst.states`) before
//! it is used: freed, foreign and garbage handles are refused, and never dereferenced.
use super::{input, out_ref, output, with_instance};
use crate::fmi::state_machine::{error, mask};
use crate::fmi::types::*;

/// Takes a copy of the instance's state. `*FMUstate` NULL: a new state. `*FMUstate` a live state
/// of this instance: updated in place (FMI 2.0 section 2.1.8). Anything else breaks the
/// standard's precondition; it is never dereferenced nor freed: a new state is written over it
/// and the call returns `fmi2Warning` (some hosts pass an uninitialized slot).
#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    let mut replaced_foreign = false;
    let status = with_instance(c, "fmi2GetFMUstate", |inst| {
        inst.require(mask::ANY)?;
        let slot = out_ref(FMUstate, "FMUstate")?;
        let data = inst.get_fmu_state()?;
        let old = *slot;
        if inst.states.owns(old) {
            return inst.states.replace(old, data, "*FMUstate");
        }
        if !old.is_null() {
            inst.log.warning_status(&format!(
                "fmi2GetFMUstate: *FMUstate = {old:p} is neither NULL nor a live state of this \
                 instance (FMI 2.0 allows only these); it was not used, a new state was \
                 allocated and written over it"
            ));
            replaced_foreign = true;
        }
        *slot = inst.states.add(data)?;
        Ok(())
    });
    if status == fmi2Status::OK && replaced_foreign {
        fmi2Status::Warning
    } else {
        status
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    with_instance(c, "fmi2SetFMUstate", |inst| {
        inst.require(mask::ANY)?;
        // A copy: the registry lives in the instance that set_fmu_state changes.
        let data = inst.states.get(FMUstate, "FMUstate")?.clone();
        inst.set_fmu_state(&data)
    })
}

/// Frees a state and sets `*FMUstate = NULL`; NULL (either level) is ignored (FMI 2.0). A handle
/// that is not a live state of this instance (freed already, another instance's, garbage) is
/// refused and left as it is.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    with_instance(c, "fmi2FreeFMUstate", |inst| {
        inst.require(mask::ANY)?;
        if FMUstate.is_null() {
            return Ok(());
        }
        let slot = out_ref(FMUstate, "FMUstate")?;
        if slot.is_null() {
            return Ok(());
        }
        inst.states.free(*slot, "*FMUstate")?;
        *slot = std::ptr::null_mut();
        Ok(())
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    with_instance(c, "fmi2SerializedFMUstateSize", |inst| {
        inst.require(mask::ANY)?;
        let bytes = inst.serialize_state(FMUstate)?;
        *out_ref(size, "size")? = bytes.len();
        Ok(())
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    serializedState: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    with_instance(c, "fmi2SerializeFMUstate", |inst| {
        inst.require(mask::ANY)?;
        let bytes = inst.serialize_state(FMUstate)?;
        if size != bytes.len() {
            return error(format!(
                "size = {size} differs from the serialized size {} (ask fmi2SerializedFMUstateSize)",
                bytes.len()
            ));
        }
        let out = output(serializedState as *mut u8, size, "serializedState")?;
        out.copy_from_slice(&bytes);
        inst.log
            .event(|| format!("FMU state serialized ({size} bytes)"));
        Ok(())
    })
}

/// Always allocates a new state and writes its handle to `*FMUstate`, which is an output only:
/// it is never read, and a state it held stays valid (free it separately). On a refusal
/// `*FMUstate` is left as it was.
#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    with_instance(c, "fmi2DeSerializeFMUstate", |inst| {
        inst.require(mask::ANY)?;
        let bytes = input(serializedState as *const u8, size, "serializedState")?;
        let slot = out_ref(FMUstate, "FMUstate")?;
        let data = inst.deserialize_state(bytes)?;
        *slot = inst.states.add(data)?;
        inst.log
            .event(|| format!("FMU state deserialized ({size} bytes)"));
        Ok(())
    })
}
