//! The C types of `fmi3PlatformTypes.h` and `fmi3FunctionTypes.h` this FMU uses.
//!
//! As in [`super::types`], what the host passes *in* by value is a plain integer: `fmi3Boolean`
//! is C's `bool`, received as a byte (any non-zero byte is true) so that a host passing 2 is not
//! undefined behaviour. `fmi3Status` is only passed *out*.
#![allow(non_camel_case_types, non_snake_case, non_upper_case_globals)]

use std::os::raw::{c_char, c_int, c_void};

pub type fmi3Instance = *mut c_void;
pub type fmi3InstanceEnvironment = *mut c_void;
pub type fmi3FMUState = *mut c_void;
pub type fmi3ValueReference = u32;
pub type fmi3Float32 = f32;
pub type fmi3Float64 = f64;
pub type fmi3Int8 = i8;
pub type fmi3UInt8 = u8;
pub type fmi3Int16 = i16;
pub type fmi3UInt16 = u16;
pub type fmi3Int32 = i32;
pub type fmi3UInt32 = u32;
pub type fmi3Int64 = i64;
pub type fmi3UInt64 = u64;
/// C `bool`, one byte.
pub type fmi3Boolean = u8;
pub type fmi3Char = c_char;
pub type fmi3String = *const fmi3Char;
pub type fmi3Byte = u8;
pub type fmi3Binary = *const fmi3Byte;
/// C `bool`, one byte.
pub type fmi3Clock = u8;
/// `fmi3DependencyKind` and `fmi3IntervalQualifier` (C enums): only passed to functions this
/// FMU refuses.
pub type fmi3DependencyKind = c_int;
pub type fmi3IntervalQualifier = c_int;

pub const fmi3True: fmi3Boolean = 1;
pub const fmi3False: fmi3Boolean = 0;

/// `fmi3Version`, returned by `fmi3GetVersion`.
pub const VERSION3: &std::ffi::CStr = c"3.0";

/// `fmi3Status` (C `int`-sized enum; the values of `fmi2Status` without `Pending`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
#[allow(clippy::upper_case_acronyms)]
pub enum fmi3Status {
    OK = 0,
    Warning = 1,
    Discard = 2,
    Error = 3,
    Fatal = 4,
}

/// `fmi3LogMessageCallback`: unlike FMI 2.0 the message is plain text, not a format.
pub type fmi3LogMessageCallback = unsafe extern "C" fn(
    instance_environment: fmi3InstanceEnvironment,
    status: fmi3Status,
    category: fmi3String,
    message: fmi3String,
);

/// `fmi3IntermediateUpdateCallback`: never called (providesIntermediateUpdate="false").
pub type fmi3IntermediateUpdateCallback = unsafe extern "C" fn(
    instance_environment: fmi3InstanceEnvironment,
    intermediate_update_time: fmi3Float64,
    intermediate_variable_set_requested: fmi3Boolean,
    intermediate_variable_get_allowed: fmi3Boolean,
    intermediate_step_finished: fmi3Boolean,
    can_return_early: fmi3Boolean,
    early_return_requested: *mut fmi3Boolean,
    early_return_time: *mut fmi3Float64,
);

/// Callbacks of Scheduled Execution (never called: that interface is refused).
pub type fmi3ClockUpdateCallback =
    unsafe extern "C" fn(instance_environment: fmi3InstanceEnvironment);
pub type fmi3LockPreemptionCallback = unsafe extern "C" fn();
pub type fmi3UnlockPreemptionCallback = unsafe extern "C" fn();
