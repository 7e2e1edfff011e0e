//! Instantiation through the FMI 2.0 C API (the host is `fmi_host`): refused arguments, the GUID
//! of every scene, resource locations and altered resources; and the logger callback: a safe
//! format, the copied instance name, the component environment, debug logging categories.
#![cfg(any(
    target_arch = "x86_64",
    all(target_arch = "aarch64", not(target_vendor = "apple"))
))]
#![allow(non_upper_case_globals)]

use crate::fmi_host;

use fmi_host::*;
use georod::fmi::api::*;
use georod::fmi::types::*;
use std::cell::RefCell;
use std::ffi::{c_void, CString};
use std::os::raw::c_char;
use std::ptr::{null, null_mut};

// ----- instantiation --------------------------------------------------------------------------

/// Instantiates with the BuckledBeam's resources.
unsafe fn instantiate(
    name: *const c_char,
    ty: fmi2Type,
    guid: *const c_char,
    cb: *const fmi2CallbackFunctions,
) -> fmi2Component {
    let (_, uri) = resources(BEAM);
    fmi2Instantiate(name, ty, guid, uri.as_ptr(), cb, fmi2False, fmi2False)
}

#[test]
fn refused_instantiations() {
    let log: Box<Log> = Box::default();
    let cb = callbacks(&*log as *const Log as *mut c_void);
    let (guid, _) = resources(BEAM);
    let last = || log.borrow().last().unwrap().text.clone();
    unsafe {
        assert!(instantiate(
            c"x".as_ptr(),
            fmi2CoSimulation,
            c"{no-such-guid}".as_ptr(),
            &*cb
        )
        .is_null());
        assert!(
            last().contains("{no-such-guid}") && last().contains("does not match"),
            "{}",
            last()
        );
        // Another scene's GUID with these resources: refused the same way.
        let (other, _) = resources(PINNED);
        assert!(instantiate(c"x".as_ptr(), fmi2CoSimulation, other.as_ptr(), &*cb).is_null());
        assert!(last().contains("does not match"), "{}", last());
        assert!(instantiate(c"x".as_ptr(), fmi2ModelExchange, guid.as_ptr(), &*cb).is_null());
        assert!(last().contains("Co-Simulation"), "{}", last());
        assert!(instantiate(c"x".as_ptr(), 7, guid.as_ptr(), &*cb).is_null());
        assert!(instantiate(c"x".as_ptr(), fmi2CoSimulation, null(), &*cb).is_null());
        assert!(last().contains("fmuGUID is NULL"));
        assert!(instantiate(null(), fmi2CoSimulation, guid.as_ptr(), &*cb).is_null());
        assert!(last().contains("instanceName is NULL"));
        assert!(instantiate(c"  ".as_ptr(), fmi2CoSimulation, guid.as_ptr(), &*cb).is_null());
        assert!(last().contains("instanceName is empty"));
        assert!(log
            .borrow()
            .iter()
            .all(|m| m.status == fmi2Status::Error && m.category == "logStatusError"));
        // No callbacks at all, or no logger: allowed, silent.
        let c = instantiate(c"quiet".as_ptr(), fmi2CoSimulation, guid.as_ptr(), null());
        assert!(!c.is_null());
        assert_eq!(fmi2DoStep(c, 0.0, H, 0), fmi2Status::Error);
        fmi2FreeInstance(c);
        let silent = fmi2CallbackFunctions {
            logger: None,
            ..*cb
        };
        let c = instantiate(c"quiet".as_ptr(), fmi2CoSimulation, guid.as_ptr(), &silent);
        assert_eq!(fmi2DoStep(c, 0.0, H, 0), fmi2Status::Error);
        fmi2FreeInstance(c);
    }
}

#[test]
fn every_scene_has_its_guid() {
    for (scene, path) in scene_files() {
        let fmu = Fmu::new(&scene);
        let mut elements = 0;
        assert_eq!(
            unsafe { fmi2GetInteger(fmu.c, &vr::elements, 1, &mut elements) },
            fmi2Status::OK
        );
        let file = georod::scene::Scene::load(&path).unwrap();
        assert_eq!(elements as usize, file.defaults().elements(), "{scene}");
    }
}

#[test]
fn resource_locations() {
    let (guid, uri) = resources(BEAM);
    let uri = uri.to_str().unwrap();
    let path = uri.strip_prefix("file://").unwrap();
    let good = [
        uri.to_string(),
        format!("file:{path}"),
        format!("file://localhost{path}"),
        format!("{uri}/"),
    ];
    let empty = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("georod fmi_api empty {}", std::process::id()));
    std::fs::create_dir_all(&empty).unwrap();
    let bad = [
        ("http://h/x".to_string(), "not a file: URI"),
        ("file://remote/x".to_string(), "remote host"),
        (
            format!("file://{}", empty.display()).replace(' ', "%20"),
            "scene.toml",
        ),
    ];
    let instantiate = |loc: *const c_char, log: &Log| {
        let cb = callbacks(log as *const Log as *mut c_void);
        unsafe {
            fmi2Instantiate(
                c"r".as_ptr(),
                fmi2CoSimulation,
                guid.as_ptr(),
                loc,
                &*cb,
                0,
                0,
            )
        }
    };
    for loc in good {
        let log: Log = RefCell::default();
        let c = instantiate(CString::new(loc.clone()).unwrap().as_ptr(), &log);
        assert!(!c.is_null(), "{loc}: {:?}", log.borrow());
        unsafe { fmi2FreeInstance(c) };
    }
    for (loc, why) in bad {
        let log: Log = RefCell::default();
        let c = instantiate(CString::new(loc.clone()).unwrap().as_ptr(), &log);
        assert!(c.is_null(), "{loc} accepted");
        let text = log.borrow().last().unwrap().text.clone();
        assert!(text.contains(why), "{loc}: {text}");
    }
    let log: Log = RefCell::default();
    assert!(instantiate(null(), &log).is_null(), "no resources: refused");
    assert!(log
        .borrow()
        .last()
        .unwrap()
        .text
        .contains("fmuResourceLocation"));
}

#[test]
fn altered_resources_are_refused() {
    let (guid, uri) = resources(BEAM);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("georod fmi_api altered {}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let original = std::fs::read_to_string(
        uri.to_str()
            .unwrap()
            .strip_prefix("file://")
            .unwrap()
            .replace("%20", " ")
            + "/scene.toml",
    )
    .unwrap();
    let altered_uri =
        CString::new(format!("file://{}", dir.display()).replace(' ', "%20")).unwrap();
    for (what, text, why) in [
        (
            "a changed value",
            original.replace("L = 10.0", "L = 11.0"),
            "does not match the GUID",
        ),
        (
            "a broken file",
            original.replace("[geometry]", "[geometry"),
            "cannot be used",
        ),
    ] {
        std::fs::write(dir.join("scene.toml"), &text).unwrap();
        let log: Log = RefCell::default();
        let cb = callbacks(&log as *const Log as *mut c_void);
        let c = unsafe {
            fmi2Instantiate(
                c"a".as_ptr(),
                fmi2CoSimulation,
                guid.as_ptr(),
                altered_uri.as_ptr(),
                &*cb,
                0,
                0,
            )
        };
        assert!(c.is_null(), "{what}: accepted");
        let text = log.borrow().last().unwrap().text.clone();
        assert!(text.contains(why), "{what}: {text}");
    }
}

#[test]
fn logger_gets_a_safe_format_and_the_copied_name() {
    let fmu = Fmu::with(BEAM, "%s%n%s%d", false);
    fmu.expect_error(fmu.step(0.0, H), &["fmi2DoStep"]);
    let m = fmu.messages().pop().unwrap();
    assert_eq!((m.name.as_str(), m.format.as_str()), ("%s%n%s%d", "%s"));

    // The host frees its name right after instantiate.
    let log: Box<Log> = Box::default();
    let cb = callbacks(&*log as *const Log as *mut c_void);
    let (guid, _) = resources(BEAM);
    let name = CString::new("temporary-name").unwrap();
    let c = unsafe { instantiate(name.as_ptr(), fmi2CoSimulation, guid.as_ptr(), &*cb) };
    drop(name);
    // Reuse the freed memory for something else.
    let _other = CString::new("XXXXXXXXXXXXXXXXXXXXXXXXX").unwrap();
    assert_eq!(unsafe { fmi2Terminate(c) }, fmi2Status::Error);
    assert_eq!(log.borrow().last().unwrap().name, "temporary-name");
    // Interior NULs cannot reach the logger; a message with '%' is passed verbatim.
    let s = unsafe { fmi2SetDebugLogging(c, fmi2True, 1, [c"100%s".as_ptr()].as_ptr()) };
    assert_eq!(s, fmi2Status::Error);
    assert!(log.borrow().last().unwrap().text.contains("\"100%s\""));
    unsafe { fmi2FreeInstance(c) };
}

#[test]
fn component_environment_is_handed_back() {
    // Non-NULL: the same pointer in every call (the Fmu harness's log is reached through it).
    let fmu = Fmu::with(BEAM, "env", true);
    unsafe { fmi2EnterInitializationMode(fmu.c) };
    let env = &*fmu.log as *const Log as usize;
    assert!(!fmu.messages().is_empty());
    assert!(fmu.messages().iter().all(|m| m.env == env));

    // NULL: still handed back as NULL.
    NULL_ENV_LOG.with(|l| l.borrow_mut().clear());
    let cb = callbacks(null_mut());
    let (guid, _) = resources(BEAM);
    unsafe {
        let c = instantiate(c"null-env".as_ptr(), fmi2CoSimulation, guid.as_ptr(), &*cb);
        assert_eq!(fmi2Terminate(c), fmi2Status::Error);
        fmi2FreeInstance(c);
    }
    NULL_ENV_LOG.with(|l| {
        let l = l.borrow();
        assert_eq!(l.len(), 1);
        assert_eq!((l[0].env, l[0].name.as_str()), (0, "null-env"));
    });
}

#[test]
fn debug_logging_categories() {
    let fmu = Fmu::new(BEAM);
    unsafe {
        // Off: only errors.
        assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status::OK);
        assert!(fmu.messages().is_empty());
        fmu.expect_error(
            fmi2SetDebugLogging(fmu.c, fmi2True, 1, [c"logNope".as_ptr()].as_ptr()),
            &["unknown log category \"logNope\"", "logEvents"],
        );
        let cats = [c"logEvents".as_ptr()];
        assert_eq!(
            fmi2SetDebugLogging(fmu.c, fmi2True, 1, cats.as_ptr()),
            fmi2Status::OK
        );
        fmu.clear();
        assert_eq!(fmi2ExitInitializationMode(fmu.c), fmi2Status::OK);
        let msgs = fmu.messages();
        assert!(
            !msgs.is_empty() && msgs.iter().all(|m| m.category == "logEvents"),
            "{msgs:?}"
        );
        // logAll traces calls.
        assert_eq!(
            fmi2SetDebugLogging(fmu.c, fmi2True, 1, [c"logAll".as_ptr()].as_ptr()),
            fmi2Status::OK
        );
        fmu.clear();
        fmu.real(vr::E);
        assert!(fmu
            .messages()
            .iter()
            .any(|m| m.category == "logAll" && m.text.contains("fmi2GetReal")));
        // All off.
        assert_eq!(
            fmi2SetDebugLogging(fmu.c, fmi2False, 0, null()),
            fmi2Status::OK
        );
        fmu.clear();
        run(&fmu, 1);
        assert!(fmu.messages().is_empty());
    }
    assert_eq!(
        georod::fmi::logging::LOG_CATEGORIES
            .iter()
            .map(|c| c.0)
            .collect::<Vec<_>>(),
        ["logEvents", "logStatusWarning", "logStatusError", "logAll"]
    );
}
