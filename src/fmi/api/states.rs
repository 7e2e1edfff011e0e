//! FMU states: `fmi2GetFMUstate`, `fmi2SetFMUstate`, `fmi2FreeFMUstate` and the serialized
//! form (`fmi2SerializedFMUstateSize`, `fmi2SerializeFMUstate`, `fmi2DeSerializeFMUstate`).
//!
//! A state handle is an opaque token, looked up in the instance's registry (`inst.states`) before
//! it is used: freed, foreign and garbage handles are refused, and never dereferenced.
use super::{with_instance_warning as call, *};
use crate::fmi::ffi_states as states;

/// The handle's name in the FMI 2.0 header, for messages.
const ARG: &str = "FMUstate";

/// Takes a copy of the instance's state. `*FMUstate` NULL: a new state. `*FMUstate` a live state
/// of this instance: updated in place (FMI 2.0 section 2.1.8). Anything else breaks the
/// standard's precondition; it is never dereferenced nor freed: a new state is written over it
/// and the call returns `fmi2Warning` (some hosts pass an uninitialized slot).
#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    call(c, "fmi2GetFMUstate", |inst| {
        states::get(inst, FMUstate, "fmi2GetFMUstate", ARG)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    call(c, "fmi2SetFMUstate", |inst| {
        states::set(inst, FMUstate, ARG)
    })
}

/// Frees a state and sets `*FMUstate = NULL`; NULL (either level) is ignored (FMI 2.0). A handle
/// that is not a live state of this instance is refused and left as it is.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    call(c, "fmi2FreeFMUstate", |inst| {
        states::free(inst, FMUstate, ARG)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    call(c, "fmi2SerializedFMUstateSize", |inst| {
        states::serialized_size(inst, FMUstate, size)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    serializedState: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    call(c, "fmi2SerializeFMUstate", |inst| {
        let buffer = serializedState as *mut u8;
        states::serialize(inst, FMUstate, buffer, size, "fmi2SerializedFMUstateSize")
    })
}

/// Always allocates a new state and writes its handle to `*FMUstate`, an output only: it is
/// never read, and a state it held stays valid. On a refusal `*FMUstate` is left as it was.
#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    call(c, "fmi2DeSerializeFMUstate", |inst| {
        states::deserialize(inst, serializedState as *const u8, size, FMUstate, ARG)
    })
}
