//! The exported FMI 2.0 Co-Simulation functions: thin C wrappers around [`Instance`].
//!
//! Every wrapper (1) checks the instance pointer (NULL, alignment, magic number), (2) runs the
//! call inside `catch_unwind` so that no panic crosses the C boundary (a panic puts the instance
//! in the `error` state and is reported as `fmi2Error`), (3) checks every other pointer and turns
//! C arrays into slices, (4) delegates to `Instance` and logs a refusal as `"<function>: why"`.
//!
//! The functions are `unsafe extern "C"`: their safety contract is the FMI 2.0 standard's (valid
//! pointers with the stated lengths); everything that can be checked cheaply is checked.
// Names follow the C headers (fmi2GetReal, loggingOn, fmi2Terminated, ...).
#![allow(clippy::missing_safety_doc, non_snake_case, non_upper_case_globals)]

use super::instance::{error, mask, Failure, FmiResult, Instance};
use super::logging::Logger;
use super::types::*;
use super::uri;
use std::ffi::CStr;
use std::os::raw::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};

// ----- helpers ------------------------------------------------------------------------------

fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic payload".to_string())
}

/// Runs `f` on the instance behind `c` and turns its result into an `fmi2Status`, logging
/// failures. A bad instance pointer is `fmi2Error` without a message (there is no logger).
fn with_instance(
    c: fmi2Component,
    func: &'static str,
    f: impl FnOnce(&mut Instance) -> FmiResult,
) -> fmi2Status {
    // SAFETY: best-effort check of the host's pointer (see Instance::from_raw).
    let Some(inst) = (unsafe { Instance::from_raw(c) }) else {
        return fmi2Status::Error;
    };
    let ptr: *mut Instance = inst;
    // SAFETY: `ptr` is the live instance; the closure holds the only reference while it runs.
    match catch_unwind(AssertUnwindSafe(|| f(unsafe { &mut *ptr }))) {
        Ok(Ok(())) => fmi2Status::OK,
        Ok(Err(failure)) => {
            // SAFETY: as above; the closure's reference is gone.
            let inst = unsafe { &*ptr };
            match failure {
                Failure::Error(why) => {
                    inst.log.error(&format!("{func}: {why}"));
                    fmi2Status::Error
                }
                Failure::Discard(why) => {
                    inst.log.discard(&format!("{func}: {why}"));
                    fmi2Status::Discard
                }
            }
        }
        Err(payload) => {
            // SAFETY: as above; the panic unwound out of the closure.
            let inst = unsafe { &mut *ptr };
            inst.poison();
            inst.log.error(&format!(
                "{func}: internal error (Rust panic: {}); the instance is now in the error state",
                panic_text(payload.as_ref())
            ));
            fmi2Status::Error
        }
    }
}

/// A C input array as a slice (`n == 0` allows NULL).
unsafe fn input<'a, T>(p: *const T, n: usize, what: &str) -> FmiResult<&'a [T]> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return error(format!("{what} is NULL but its length is {n}"));
    }
    if !p.is_aligned() || n > isize::MAX as usize / std::mem::size_of::<T>().max(1) {
        return error(format!(
            "{what}: misaligned pointer or impossible length {n}"
        ));
    }
    Ok(std::slice::from_raw_parts(p, n))
}

/// A C output array as a slice (`n == 0` allows NULL).
unsafe fn output<'a, T>(p: *mut T, n: usize, what: &str) -> FmiResult<&'a mut [T]> {
    if n == 0 {
        return Ok(&mut []);
    }
    input(p as *const T, n, what)?;
    Ok(std::slice::from_raw_parts_mut(p, n))
}

/// A single C output value.
unsafe fn out_ref<'a, T>(p: *mut T, what: &str) -> FmiResult<&'a mut T> {
    Ok(&mut output(p, 1, what)?[0])
}

/// A C string as UTF-8 (lossy); `None` for NULL.
unsafe fn string(p: *const c_char) -> Option<String> {
    (!p.is_null()).then(|| CStr::from_ptr(p).to_string_lossy().into_owned())
}

fn status_kind_arg(kind: fmi2StatusKind) -> FmiResult<&'static str> {
    match kind {
        fmi2DoStepStatus => Ok("fmi2DoStepStatus"),
        fmi2PendingStatus => Ok("fmi2PendingStatus"),
        fmi2LastSuccessfulTime => Ok("fmi2LastSuccessfulTime"),
        fmi2Terminated => Ok("fmi2Terminated"),
        other => error(format!(
            "{} is not a valid status kind",
            status_kind_name(other)
        )),
    }
}

// ----- inquiry, logging, life cycle ------------------------------------------------------------

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
        let mut names = Vec::with_capacity(nCategories);
        for (i, &p) in input(categories, nCategories, "categories[]")?
            .iter()
            .enumerate()
        {
            names
                .push(string(p).ok_or_else(|| Failure::Error(format!("categories[{i}] is NULL")))?);
        }
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
        let logger = callbacks.and_then(|f| f.logger);
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
        let interface = match super::interface::Interface::load(dir.as_deref(), &guid) {
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

// ----- values ---------------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetReal", |inst| {
        inst.require(mask::GET)?;
        inst.get_real(input(vr, nvr, "vr[]")?, output(value, nvr, "value[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    with_instance(c, "fmi2GetInteger", |inst| {
        inst.require(mask::GET)?;
        inst.get_integer(input(vr, nvr, "vr[]")?, output(value, nvr, "value[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2GetBoolean", |inst| {
        inst.require(mask::GET)?;
        output(value, nvr, "value[]")?;
        inst.no_variables_of_type("fmi2GetBoolean", "Boolean", input(vr, nvr, "vr[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2GetString", |inst| {
        inst.require(mask::GET)?;
        output(value, nvr, "value[]")?;
        inst.no_variables_of_type("fmi2GetString", "String", input(vr, nvr, "vr[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2SetReal", |inst| {
        inst.require(mask::SET)?;
        inst.set_real(input(vr, nvr, "vr[]")?, input(value, nvr, "value[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    with_instance(c, "fmi2SetInteger", |inst| {
        inst.require(mask::SET)?;
        inst.set_integer(input(vr, nvr, "vr[]")?, input(value, nvr, "value[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2SetBoolean", |inst| {
        inst.require(mask::SET)?;
        input(value, nvr, "value[]")?;
        inst.no_variables_of_type("fmi2SetBoolean", "Boolean", input(vr, nvr, "vr[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2SetString", |inst| {
        inst.require(mask::SET)?;
        input(value, nvr, "value[]")?;
        inst.no_variables_of_type("fmi2SetString", "String", input(vr, nvr, "vr[]")?)
    })
}

// ----- FMU state ------------------------------------------------------------------------------
//
// A state handle is an opaque token, looked up in the instance's registry (`inst.states`) before
// it is used: freed, foreign and garbage handles are refused, and never dereferenced.

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

// ----- not supported --------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    _vUnknown_ref: *const fmi2ValueReference,
    _nUnknown: usize,
    _vKnown_ref: *const fmi2ValueReference,
    _nKnown: usize,
    _dvKnown: *const fmi2Real,
    _dvUnknown: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetDirectionalDerivative", |inst| {
        inst.require(mask::DIRECTIONAL_DERIVATIVE)?;
        error("directional derivatives are not supported (providesDirectionalDerivative=false)")
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2SetRealInputDerivatives", |inst| {
        inst.require(mask::SET_INPUT_DERIVATIVES)?;
        inst.set_input_derivatives(
            input(vr, nvr, "vr[]")?,
            input(order, nvr, "order[]")?,
            input(value, nvr, "value[]")?,
        )
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetRealOutputDerivatives", |inst| {
        inst.require(mask::GET_OUTPUT_DERIVATIVES)?;
        error("output derivatives are not supported (MaxOutputDerivativeOrder=0)")
    })
}

// ----- stepping and status --------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2DoStep", |inst| {
        inst.do_step(currentCommunicationPoint, communicationStepSize)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    with_instance(c, "fmi2CancelStep", Instance::cancel_step)
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Status,
) -> fmi2Status {
    with_instance(c, "fmi2GetStatus", |inst| {
        inst.require(mask::STATUS)?;
        out_ref(value, "value")?;
        inst.status_unavailable("fmi2GetStatus", status_kind_arg(s)?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetRealStatus", |inst| {
        inst.require(mask::STATUS)?;
        let value = out_ref(value, "value")?;
        let kind = status_kind_arg(s)?;
        if s != fmi2LastSuccessfulTime {
            return inst.status_unavailable("fmi2GetRealStatus", kind);
        }
        *value = inst.last_successful_time()?;
        Ok(())
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Integer,
) -> fmi2Status {
    with_instance(c, "fmi2GetIntegerStatus", |inst| {
        inst.require(mask::STATUS)?;
        out_ref(value, "value")?;
        inst.status_unavailable("fmi2GetIntegerStatus", status_kind_arg(s)?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2GetBooleanStatus", |inst| {
        inst.require(mask::STATUS)?;
        let value = out_ref(value, "value")?;
        let kind = status_kind_arg(s)?;
        if s != fmi2Terminated {
            return inst.status_unavailable("fmi2GetBooleanStatus", kind);
        }
        *value = if inst.terminated()? {
            fmi2True
        } else {
            fmi2False
        };
        Ok(())
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2GetStringStatus", |inst| {
        inst.require(mask::STATUS)?;
        out_ref(value, "value")?;
        inst.status_unavailable("fmi2GetStringStatus", status_kind_arg(s)?)
    })
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
            assert_eq!(inst.state(), super::super::instance::FmiState::Error);
            // The error state allows a reset, after which the instance works again.
            assert_eq!(fmi2Reset(c), fmi2Status::OK);
            assert_eq!(fmi2EnterInitializationMode(c), fmi2Status::OK);
            fmi2FreeInstance(c);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
