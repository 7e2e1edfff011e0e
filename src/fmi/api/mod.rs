//! The exported FMI 2.0 Co-Simulation functions: thin C wrappers around [`Instance`].
//!
//! Every wrapper (1) checks the instance pointer (NULL, alignment, magic number), (2) runs the
//! call inside `catch_unwind` so that no panic crosses the C boundary (a panic puts the instance
//! in the `error` state and is reported as `fmi2Error`), (3) checks every other pointer and turns
//! C arrays into slices, (4) delegates to `Instance` and logs a refusal as `"<function>: why"`.
//!
//! The functions are `unsafe extern "C"`: their safety contract is the FMI 2.0 standard's (valid
//! pointers with the stated lengths); everything that can be checked cheaply is checked.
//!
//! The call wrapper and pointer checks are shared with the FMI 3.0 API ([`super::ffi`]); this
//! file turns their outcome into an `fmi2Status`. The wrappers are grouped by concern and re-exported here, so each keeps its `fmi::api::` path:
//! - `lifecycle`: version and platform, debug logging, instantiate and free, experiment setup,
//!   initialization mode, terminate, reset;
//! - `values`: get and set Real/Integer/Boolean/String, input and output derivatives;
//! - `states`: get, set, free, serialize and deserialize FMU states;
//! - `stepping`: doStep, cancelStep and the status queries.
// Names follow the C headers (fmi2GetReal, loggingOn, fmi2Terminated, ...); the allowance holds
// for the submodules too.
#![allow(clippy::missing_safety_doc, non_snake_case, non_upper_case_globals)]

mod lifecycle;
mod states;
mod stepping;
mod values;

pub use lifecycle::*;
pub use states::*;
pub use stepping::*;
pub use values::*;

use super::ffi::{self, Outcome};
use super::instance::Instance;
use super::state_machine::FmiResult;
use super::types::*;

pub(crate) use super::ffi::{input, out_ref, output, string};

impl From<Outcome> for fmi2Status {
    fn from(outcome: Outcome) -> fmi2Status {
        match outcome {
            Outcome::Ok => fmi2Status::OK,
            Outcome::Warning => fmi2Status::Warning,
            Outcome::Discard => fmi2Status::Discard,
            Outcome::Error => fmi2Status::Error,
        }
    }
}

/// Runs `f` on the instance behind `c` and turns its result into an `fmi2Status`, logging
/// failures. A bad instance pointer is `fmi2Error` without a message (there is no logger).
fn with_instance(
    c: fmi2Component,
    func: &'static str,
    f: impl FnOnce(&mut Instance) -> FmiResult,
) -> fmi2Status {
    ffi::call(c, func, |inst| f(inst).map(|()| false)).into()
}

/// As [`with_instance`], for calls that may answer `fmi2Warning` (`f` returns `true`).
fn with_instance_warning(
    c: fmi2Component,
    func: &'static str,
    f: impl FnOnce(&mut Instance) -> FmiResult<bool>,
) -> fmi2Status {
    ffi::call(c, func, f).into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_is_caught_and_poisons_only_its_instance() {
        let dir = std::env::temp_dir().join(format!("georod-api-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let source = std::fs::read_to_string("scenes/BuckledBeam.toml").unwrap();
        std::fs::write(dir.join(crate::packaging::SCENE_RESOURCE), &source).unwrap();
        let scene = crate::scene::Scene::parse(&source, "BuckledBeam.toml").unwrap();
        let guid = crate::packaging::model_description::model_description(&scene).guid;
        let guid = std::ffi::CString::new(guid).unwrap();
        let uri = std::ffi::CString::new(format!("file://{}", dir.display())).unwrap();
        unsafe {
            let c = fmi2Instantiate(
                c"p".as_ptr(),
                fmi2CoSimulation,
                guid.as_ptr(),
                uri.as_ptr(),
                std::ptr::null(),
                fmi2False,
                fmi2False,
            );
            assert!(!c.is_null());
            let status = with_instance(c, "fmi2Test", |_| panic!("boom"));
            assert_eq!(status, fmi2Status::Error);
            let inst = Instance::from_raw(c).unwrap();
            assert_eq!(inst.state(), crate::fmi::state_machine::FmiState::Error);
            // The error state allows a reset, after which the instance works again.
            assert_eq!(fmi2Reset(c), fmi2Status::OK);
            assert_eq!(fmi2EnterInitializationMode(c), fmi2Status::OK);
            fmi2FreeInstance(c);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
