//! FMU states: `fmi3GetFMUState`, `fmi3SetFMUState`, `fmi3FreeFMUState` and the serialized form,
//! the same code as FMI 2.0's ([`crate::fmi::ffi_states`]): the same opaque handles and the
//! same self-checking format, so a state serialized through either API restores through the
//! other.
use super::with_instance_warning as call;
use crate::fmi::ffi_states as states;
use crate::fmi::types3::*;

/// The handle's name in the FMI 3.0 header, for messages.
const ARG: &str = "FMUState";

#[no_mangle]
pub unsafe extern "C" fn fmi3GetFMUState(
    instance: fmi3Instance,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    call(instance, "fmi3GetFMUState", |inst| {
        states::get(inst, FMUState, "fmi3GetFMUState", ARG)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetFMUState(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
) -> fmi3Status {
    call(instance, "fmi3SetFMUState", |inst| {
        states::set(inst, FMUState, ARG)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeFMUState(
    instance: fmi3Instance,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    call(instance, "fmi3FreeFMUState", |inst| {
        states::free(inst, FMUState, ARG)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
    size: *mut usize,
) -> fmi3Status {
    call(instance, "fmi3SerializedFMUStateSize", |inst| {
        states::serialized_size(inst, FMUState, size)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SerializeFMUState(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
    serializedState: *mut fmi3Byte,
    size: usize,
) -> fmi3Status {
    call(instance, "fmi3SerializeFMUState", |inst| {
        states::serialize(
            inst,
            FMUState,
            serializedState,
            size,
            "fmi3SerializedFMUStateSize",
        )
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    instance: fmi3Instance,
    serializedState: *const fmi3Byte,
    size: usize,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    call(instance, "fmi3DeserializeFMUState", |inst| {
        states::deserialize(inst, serializedState, size, FMUState, ARG)
    })
}
