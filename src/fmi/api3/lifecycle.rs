//! Inquiry, logging and life cycle: `fmi3GetVersion`, `fmi3SetDebugLogging`,
//! `fmi3InstantiateCoSimulation`, `fmi3FreeInstance`, configuration and initialization modes,
//! `fmi3Terminate` and `fmi3Reset`.
use super::with_instance;
use crate::fmi::ffi::{string, strings};
use crate::fmi::instance::Instance;
use crate::fmi::interface::Interface;
use crate::fmi::logging::{Callback, Logger};
use crate::fmi::state_machine::mask;
use crate::fmi::types3::*;
use std::os::raw::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

#[no_mangle]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    VERSION3.as_ptr()
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    instance: fmi3Instance,
    loggingOn: fmi3Boolean,
    nCategories: usize,
    categories: *const fmi3String,
) -> fmi3Status {
    with_instance(instance, "fmi3SetDebugLogging", |inst| {
        inst.require(mask::ANY)?;
        let names = strings(categories, nCategories, "categories[]")?;
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        inst.set_debug_logging(loggingOn != fmi3False, &names)
    })
}

/// Creates an instance of the scene in `<resourcePath>/scene.toml` (FMI 3.0 passes a native
/// path, not a URI). Returns NULL, with a logged message, for a NULL or empty instance name, an
/// asked-for feature this FMU lacks (event mode, early return, intermediate variables), missing
/// or unusable resources, or a scene file whose token is not `instantiationToken`.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    resourcePath: fmi3String,
    _visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    eventModeUsed: fmi3Boolean,
    _earlyReturnAllowed: fmi3Boolean,
    _requiredIntermediateVariables: *const fmi3ValueReference,
    nRequiredIntermediateVariables: usize,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: Option<fmi3LogMessageCallback>,
    _intermediateUpdate: Option<fmi3IntermediateUpdateCallback>,
) -> fmi3Instance {
    let result = catch_unwind(AssertUnwindSafe(|| {
        let name = string(instanceName);
        let log = Logger::new(
            logMessage.map(Callback::Fmi3),
            instanceEnvironment,
            name.as_deref().unwrap_or(""),
            loggingOn != fmi3False,
        );
        let refuse = |why: String| {
            log.error(&format!("fmi3InstantiateCoSimulation: {why}"));
            std::ptr::null_mut()
        };
        let Some(name) = name else {
            return refuse("instanceName is NULL".to_string());
        };
        if name.trim().is_empty() {
            return refuse("instanceName is empty".to_string());
        }
        if eventModeUsed != fmi3False {
            return refuse(
                "eventModeUsed = true: this FMU has no event mode (hasEventMode=\"false\")"
                    .to_string(),
            );
        }
        if nRequiredIntermediateVariables != 0 {
            return refuse(format!(
                "{nRequiredIntermediateVariables} intermediate variables required: this FMU \
                 provides no intermediate update (providesIntermediateUpdate=\"false\")"
            ));
        }
        // earlyReturnAllowed is harmless: fmi3DoStep never returns early.
        let Some(token) = string(instantiationToken) else {
            return refuse("instantiationToken is NULL".to_string());
        };
        let location = string(resourcePath).filter(|p| !p.is_empty());
        let dir = location.as_deref().map(PathBuf::from);
        let interface = match Interface::load(dir.as_deref(), &token) {
            Ok(i) => i,
            Err(why) => return refuse(why),
        };
        log.event(|| {
            format!(
                "instantiated the {} scene (token {token}), resources: {location:?}",
                interface.scene.name
            )
        });
        Box::into_raw(Box::new(Instance::new(interface, log, location, dir))) as fmi3Instance
    }));
    result.unwrap_or(std::ptr::null_mut())
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeInstance(instance: fmi3Instance) {
    crate::fmi::api::fmi2FreeInstance(instance)
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterConfigurationMode(instance: fmi3Instance) -> fmi3Status {
    with_instance(
        instance,
        "fmi3EnterConfigurationMode",
        Instance::enter_configuration_mode,
    )
}

#[no_mangle]
pub unsafe extern "C" fn fmi3ExitConfigurationMode(instance: fmi3Instance) -> fmi3Status {
    with_instance(
        instance,
        "fmi3ExitConfigurationMode",
        Instance::exit_configuration_mode,
    )
}

/// The experiment (FMI 2.0's `fmi2SetupExperiment`) and the mode change in one call: both are
/// allowed in `instantiated` only, so either both happen or neither.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    instance: fmi3Instance,
    toleranceDefined: fmi3Boolean,
    tolerance: fmi3Float64,
    startTime: fmi3Float64,
    stopTimeDefined: fmi3Boolean,
    stopTime: fmi3Float64,
) -> fmi3Status {
    with_instance(instance, "fmi3EnterInitializationMode", |inst| {
        inst.require(mask::ENTER_INITIALIZATION)?;
        inst.setup_experiment(
            (toleranceDefined != fmi3False).then_some(tolerance),
            startTime,
            (stopTimeDefined != fmi3False).then_some(stopTime),
        )?;
        inst.enter_initialization_mode()
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3ExitInitializationMode(instance: fmi3Instance) -> fmi3Status {
    with_instance(
        instance,
        "fmi3ExitInitializationMode",
        Instance::exit_initialization_mode,
    )
}

#[no_mangle]
pub unsafe extern "C" fn fmi3Terminate(instance: fmi3Instance) -> fmi3Status {
    with_instance(instance, "fmi3Terminate", Instance::terminate)
}

#[no_mangle]
pub unsafe extern "C" fn fmi3Reset(instance: fmi3Instance) -> fmi3Status {
    with_instance(instance, "fmi3Reset", Instance::reset)
}
