//! The C types of `fmi2TypesPlatform.h` ("default" platform) and `fmi2FunctionTypes.h`.
//!
//! Enumerations that the host passes *in* (`fmi2Type`, `fmi2StatusKind`) are plain `c_int`
//! aliases with constants: a Rust `enum` receiving an out-of-range discriminant from C would be
//! undefined behaviour, an integer can simply be checked. `fmi2Status` is only passed *out* (and
//! to the logger), so it is a `#[repr(C)]` enum.
#![allow(non_camel_case_types, non_snake_case, non_upper_case_globals)]

use std::os::raw::{c_char, c_int, c_uint, c_void};

pub type fmi2Component = *mut c_void;
pub type fmi2ComponentEnvironment = *mut c_void;
pub type fmi2FMUstate = *mut c_void;
pub type fmi2ValueReference = c_uint;
pub type fmi2Real = f64;
pub type fmi2Integer = c_int;
pub type fmi2Boolean = c_int;
pub type fmi2Char = c_char;
pub type fmi2String = *const fmi2Char;
pub type fmi2Byte = c_char;

pub const fmi2True: fmi2Boolean = 1;
pub const fmi2False: fmi2Boolean = 0;

/// `fmi2TypesPlatform`, returned by `fmi2GetTypesPlatform`.
pub const TYPES_PLATFORM: &std::ffi::CStr = c"default";
/// `fmi2Version`, returned by `fmi2GetVersion`.
pub const VERSION: &std::ffi::CStr = c"2.0";

/// `fmi2Status` (C `int`-sized enum).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
#[allow(clippy::upper_case_acronyms)]
pub enum fmi2Status {
    OK = 0,
    Warning = 1,
    Discard = 2,
    Error = 3,
    Fatal = 4,
    Pending = 5,
}

impl fmi2Status {
    /// The enumerator name, for messages.
    pub fn name(self) -> &'static str {
        match self {
            fmi2Status::OK => "fmi2OK",
            fmi2Status::Warning => "fmi2Warning",
            fmi2Status::Discard => "fmi2Discard",
            fmi2Status::Error => "fmi2Error",
            fmi2Status::Fatal => "fmi2Fatal",
            fmi2Status::Pending => "fmi2Pending",
        }
    }
}

/// `fmi2Type`
pub type fmi2Type = c_int;
pub const fmi2ModelExchange: fmi2Type = 0;
pub const fmi2CoSimulation: fmi2Type = 1;

/// `fmi2StatusKind`
pub type fmi2StatusKind = c_int;
pub const fmi2DoStepStatus: fmi2StatusKind = 0;
pub const fmi2PendingStatus: fmi2StatusKind = 1;
pub const fmi2LastSuccessfulTime: fmi2StatusKind = 2;
pub const fmi2Terminated: fmi2StatusKind = 3;

/// The enumerator name of a status kind, for messages.
pub fn status_kind_name(kind: fmi2StatusKind) -> String {
    match kind {
        fmi2DoStepStatus => "fmi2DoStepStatus".to_string(),
        fmi2PendingStatus => "fmi2PendingStatus".to_string(),
        fmi2LastSuccessfulTime => "fmi2LastSuccessfulTime".to_string(),
        fmi2Terminated => "fmi2Terminated".to_string(),
        other => format!("unknown fmi2StatusKind {other}"),
    }
}

/// `fmi2CallbackLogger`: `message` is a printf format; we always pass `"%s"` and the text as the
/// single variadic argument, so a `%` in an instance name or message is never interpreted.
pub type fmi2CallbackLogger = unsafe extern "C" fn(
    component_environment: fmi2ComponentEnvironment,
    instance_name: fmi2String,
    status: fmi2Status,
    category: fmi2String,
    message: fmi2String,
    ...
);
pub type fmi2CallbackAllocateMemory = unsafe extern "C" fn(nobj: usize, size: usize) -> *mut c_void;
pub type fmi2CallbackFreeMemory = unsafe extern "C" fn(obj: *mut c_void);
pub type fmi2StepFinished =
    unsafe extern "C" fn(component_environment: fmi2ComponentEnvironment, status: fmi2Status);

/// `fmi2CallbackFunctions`. Function pointers are `Option`s: a NULL pointer is `None` (the
/// nullable-pointer layout guarantee makes this ABI-identical to the C struct).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct fmi2CallbackFunctions {
    pub logger: Option<fmi2CallbackLogger>,
    /// Never used: the FMU declares `canNotUseMemoryManagementFunctions="true"`.
    pub allocateMemory: Option<fmi2CallbackAllocateMemory>,
    /// Never used (see `allocateMemory`).
    pub freeMemory: Option<fmi2CallbackFreeMemory>,
    /// Never used: asynchronous `fmi2DoStep` is not supported.
    pub stepFinished: Option<fmi2StepFinished>,
    pub componentEnvironment: fmi2ComponentEnvironment,
}
