//! Inquiry, logging and life cycle: `fmi2GetTypesPlatform`, `fmi2GetVersion`,
//! `fmi2SetDebugLogging`, `fmi2Instantiate`, `fmi2FreeInstance`, `fmi2SetupExperiment`, the
//! initialization mode, `fmi2Terminate` and `fmi2Reset`.
use super::{string, with_instance};
use crate::fmi::ffi::strings;
use crate::fmi::instance::Instance;
use crate::fmi::logging::{Callback, Logger};
use crate::fmi::state_machine::mask;
use crate::fmi::types::*;
use crate::fmi::uri;
use std::os::raw::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    TYPES_PLATFORM.as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    VERSION.as_ptr()
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2SetDebugLogging", |inst| {
        inst.require(mask::ANY)?;
        let names = strings(categories, nCategories, "categories[]")?;
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        inst.set_debug_logging(loggingOn != fmi2False, &names)
    })
}

/// Creates an instance of the scene in `<fmuResourceLocation>/scene.toml`. Returns NULL (with a
/// message when a logger was given) for a NULL or empty instance name, Model Exchange, missing
/// or unusable resources, or a scene file whose modelDescription GUID is not `fmuGUID`.
#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instanceName: fmi2String,
    fmuType: fmi2Type,
    fmuGUID: fmi2String,
    fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    loggingOn: fmi2Boolean,
) -> fmi2Component {
    let result = catch_unwind(AssertUnwindSafe(|| {
        // A NULL callbacks struct is taken as "no callbacks" (nothing is ever logged).
        let callbacks = if functions.is_null() || !functions.is_aligned() {
            None
        } else {
            Some(*functions)
        };
        let logger = callbacks.and_then(|f| f.logger).map(Callback::Fmi2);
        let env = callbacks.map_or(std::ptr::null_mut(), |f| f.componentEnvironment);
        let name = string(instanceName);
        let log = Logger::new(
            logger,
            env,
            name.as_deref().unwrap_or(""),
            loggingOn != fmi2False,
        );
        let refuse = |why: String| {
            log.error(&format!("fmi2Instantiate: {why}"));
            std::ptr::null_mut()
        };
        let Some(name) = name else {
            return refuse("instanceName is NULL".to_string());
        };
        if name.trim().is_empty() {
            return refuse("instanceName is empty".to_string());
        }
        if fmuType != fmi2CoSimulation {
            return refuse(format!(
                "fmuType = {fmuType}: this FMU supports Co-Simulation (fmi2CoSimulation = 1) only"
            ));
        }
        let Some(guid) = string(fmuGUID) else {
            return refuse("fmuGUID is NULL".to_string());
        };
        let location = string(fmuResourceLocation);
        let dir = match location.as_deref().map(uri::file_uri_to_path) {
            Some(Ok(dir)) => Some(dir),
            Some(Err(why)) => return refuse(format!("fmuResourceLocation is not usable: {why}")),
            None => None,
        };
        let interface = match crate::fmi::interface::Interface::load(dir.as_deref(), &guid) {
            Ok(i) => i,
            Err(why) => return refuse(why),
        };
        log.event(|| {
            format!(
                "instantiated the {} scene (GUID {guid}), resources: {location:?}",
                interface.scene.name
            )
        });
        let inst = Box::new(Instance::new(interface, log, location, dir));
        Box::into_raw(inst) as fmi2Component
    }));
    result.unwrap_or(std::ptr::null_mut())
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    // SAFETY: best-effort pointer check; the instance was made by Box::into_raw in Instantiate.
    if let Some(inst) = Instance::from_raw(c) {
        let _ = catch_unwind(AssertUnwindSafe(|| {
            // The states the host did not free go with the instance (its registry owns them).
            let unfreed = inst.states.len();
            inst.log.event(|| {
                format!("instance freed, with {unfreed} FMU states not freed by the host")
            });
            Instance::free(inst);
        }));
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    toleranceDefined: fmi2Boolean,
    tolerance: fmi2Real,
    startTime: fmi2Real,
    stopTimeDefined: fmi2Boolean,
    stopTime: fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2SetupExperiment", |inst| {
        inst.setup_experiment(
            (toleranceDefined != fmi2False).then_some(tolerance),
            startTime,
            (stopTimeDefined != fmi2False).then_some(stopTime),
        )
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    with_instance(
        c,
        "fmi2EnterInitializationMode",
        Instance::enter_initialization_mode,
    )
}

#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    with_instance(
        c,
        "fmi2ExitInitializationMode",
        Instance::exit_initialization_mode,
    )
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    with_instance(c, "fmi2Terminate", Instance::terminate)
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    with_instance(c, "fmi2Reset", Instance::reset)
}
