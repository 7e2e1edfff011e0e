//! The exported FMI 3.0 Co-Simulation functions: thin C wrappers around the same
//! [`Instance`] as the FMI 2.0 API ([`super::api`]), with the same guarantees: the handle is
//! checked, every call runs inside `catch_unwind` (`fmi::ffi::call`), every pointer is
//! checked, and a refusal is logged as `"<function>: why"`.
//!
//! What FMI 3.0 changes is done here: arrays (a value reference names a whole `shape_*` array,
//! `nValues` counts elements; `values` maps them to the instance's scalars), the start time
//! given to `fmi3EnterInitializationMode`, `fmi3DoStep`'s out-arguments, configuration mode,
//! and the plain-text logger. The functions a Co-Simulation FMU without events, clocks or
//! derivatives does not support are exported too and answer `fmi3Error` with a logged message
//! (`unsupported`).
//! - `lifecycle`: version, debug logging, instantiate and free, configuration and
//!   initialization modes, terminate, reset;
//! - `values`: get and set of every variable type;
//! - `states`: get, set, free, serialize and deserialize FMU states;
//! - `stepping`: `fmi3DoStep`;
//! - `unsupported`: Model Exchange, Scheduled Execution, events, clocks, derivatives.
// Names follow the C headers (fmi3GetFloat64, loggingOn, ...).
#![allow(clippy::missing_safety_doc, non_snake_case, non_upper_case_globals)]

mod lifecycle;
mod states;
mod stepping;
mod unsupported;
mod values;

pub use lifecycle::*;
pub use states::*;
pub use stepping::*;
pub use unsupported::*;
pub use values::*;

use super::ffi::{self, Outcome};
use super::instance::Instance;
use super::state_machine::FmiResult;
use super::types3::*;

impl From<Outcome> for fmi3Status {
    fn from(outcome: Outcome) -> fmi3Status {
        match outcome {
            Outcome::Ok => fmi3Status::OK,
            Outcome::Warning => fmi3Status::Warning,
            Outcome::Discard => fmi3Status::Discard,
            Outcome::Error => fmi3Status::Error,
        }
    }
}

/// Runs `f` on the instance behind `instance` and turns its result into an `fmi3Status`.
fn with_instance(
    instance: fmi3Instance,
    func: &'static str,
    f: impl FnOnce(&mut Instance) -> FmiResult,
) -> fmi3Status {
    ffi::call(instance, func, |inst| f(inst).map(|()| false)).into()
}

/// As [`with_instance`], for calls that may answer `fmi3Warning` (`f` returns `true`).
fn with_instance_warning(
    instance: fmi3Instance,
    func: &'static str,
    f: impl FnOnce(&mut Instance) -> FmiResult<bool>,
) -> fmi3Status {
    ffi::call(instance, func, f).into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_is_caught_and_answered_with_fmi3_error() {
        let dir = std::env::temp_dir().join(format!("georod-api3-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let source = std::fs::read_to_string("scenes/BuckledBeam.toml").unwrap();
        std::fs::write(dir.join(crate::packaging::SCENE_RESOURCE), &source).unwrap();
        let scene = crate::scene::Scene::parse(&source, "BuckledBeam.toml").unwrap();
        let token = crate::packaging::model_description3::model_description3(&scene).token;
        let token = std::ffi::CString::new(token).unwrap();
        let path = std::ffi::CString::new(format!("{}/", dir.display())).unwrap();
        unsafe {
            let c = fmi3InstantiateCoSimulation(
                c"p".as_ptr(),
                token.as_ptr(),
                path.as_ptr(),
                fmi3False,
                fmi3False,
                fmi3False,
                fmi3False,
                std::ptr::null(),
                0,
                std::ptr::null_mut(),
                None,
                None,
            );
            assert!(!c.is_null());
            let status = with_instance(c, "fmi3Test", |_| panic!("boom"));
            assert_eq!(status, fmi3Status::Error);
            let inst = Instance::from_raw(c).unwrap();
            assert_eq!(inst.state(), crate::fmi::state_machine::FmiState::Error);
            assert_eq!(
                fmi3Reset(c),
                fmi3Status::OK,
                "the error state allows a reset"
            );
            assert_eq!(
                fmi3EnterInitializationMode(c, fmi3False, 0.0, 0.0, fmi3False, 0.0),
                fmi3Status::OK
            );
            fmi3FreeInstance(c);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
