//! The FMI 3.0 API against bad input, as the FMI 2.0 tests do: refused instantiations, bad
//! handles and pointers, FMU states (round trips, the same serialized format as FMI 2.0, freed
//! and foreign handles), and the functions a Co-Simulation FMU need not support.
#![cfg(not(all(target_vendor = "apple", target_arch = "aarch64")))]
use crate::fmi3_host;

use crate::fmi_host::{self, Fmu, BEAM, PINNED};
use fmi3_host::*;
use georod::fmi::api::*;
use georod::fmi::api3::*;
use georod::fmi::types::*;
use georod::fmi::types3::*;
use std::ffi::{c_void, CString};

#[test]
fn refused_instantiations_return_null_with_a_message() {
    let (token, path) = resources3(BEAM);
    let log: Log3 = Log3::default();
    let env = &log as *const Log3 as *mut c_void;
    let bad_token = CString::new("{not-the-token}").unwrap();
    assert!(instantiate("a", &bad_token, &path, &log).is_null());
    let missing = CString::new("/nonexistent/georod/").unwrap();
    assert!(instantiate("a", &token, &missing, &log).is_null());
    assert!(instantiate(" ", &token, &path, &log).is_null());
    let name = CString::new("a").unwrap();
    let vr = 0u32;
    let with = |event: u8, n: usize| unsafe {
        fmi3InstantiateCoSimulation(
            name.as_ptr(),
            token.as_ptr(),
            path.as_ptr(),
            0,
            0,
            event,
            0,
            &vr,
            n,
            env,
            Some(capture3),
            None,
        )
    };
    assert!(with(fmi3True, 0).is_null());
    assert!(with(fmi3False, 1).is_null());
    unsafe {
        let me = fmi3InstantiateModelExchange(
            name.as_ptr(),
            token.as_ptr(),
            path.as_ptr(),
            0,
            0,
            env,
            Some(capture3),
        );
        assert!(me.is_null());
        let se = fmi3InstantiateScheduledExecution(
            name.as_ptr(),
            token.as_ptr(),
            path.as_ptr(),
            0,
            0,
            env,
            Some(capture3),
            None,
            None,
            None,
        );
        assert!(se.is_null());
        let c = fmi3InstantiateCoSimulation(
            std::ptr::null(),
            token.as_ptr(),
            path.as_ptr(),
            0,
            0,
            0,
            0,
            std::ptr::null(),
            0,
            env,
            None,
            None,
        );
        assert!(c.is_null(), "no name, and no logger: refused silently");
    }
    let texts: Vec<String> = log.borrow().iter().map(|m| m.text.clone()).collect();
    let expected = [
        "does not match the GUID",
        "cannot be used",
        "instanceName is empty",
        "eventModeUsed",
        "intermediate variables",
        "fmi3InstantiateModelExchange: this FMU supports Co-Simulation only",
        "fmi3InstantiateScheduledExecution: this FMU supports Co-Simulation only",
    ];
    assert_eq!(texts.len(), expected.len(), "{texts:?}");
    for (text, part) in texts.iter().zip(expected) {
        assert!(text.contains(part), "`{text}` lacks `{part}`");
    }
    assert!(log.borrow().iter().all(|m| m.status == fmi3Status::Error));
}

#[test]
fn null_and_garbage_handles_and_pointers_are_refused() {
    let garbage = Box::new([0x1234_5678_u64; 8]);
    let g = garbage.as_ptr() as fmi3Instance;
    unsafe {
        for c in [std::ptr::null_mut(), g] {
            assert_eq!(fmi3ExitInitializationMode(c), fmi3Status::Error);
            assert_eq!(fmi3EnterEventMode(c), fmi3Status::Error);
            let mut x = 0.0;
            assert_eq!(fmi3GetFloat64(c, &0, 1, &mut x, 1), fmi3Status::Error);
            fmi3FreeInstance(c);
        }
    }
    let fmu = Fmu3::new(BEAM);
    fmu.init();
    let (mut flag, mut last) = (0u8, 0.0);
    unsafe {
        let s = fmi3DoStep(
            fmu.c,
            0.0,
            1e-4,
            0,
            std::ptr::null_mut(),
            &mut flag,
            &mut flag,
            &mut last,
        );
        fmu.expect_error(s, &["eventHandlingNeeded is NULL"]);
        let s = fmi3DoStep(
            fmu.c,
            0.0,
            1e-4,
            0,
            &mut flag,
            &mut flag,
            &mut flag,
            std::ptr::null_mut(),
        );
        fmu.expect_error(s, &["lastSuccessfulTime is NULL"]);
        let categories = [std::ptr::null::<std::os::raw::c_char>()];
        let s = fmi3SetDebugLogging(fmu.c, fmi3True, 1, categories.as_ptr());
        fmu.expect_error(s, &["categories[0] is NULL"]);
        let bad = CString::new("logNothing").unwrap();
        let s = fmi3SetDebugLogging(fmu.c, fmi3True, 1, &bad.as_ptr());
        fmu.expect_error(s, &["unknown log category"]);
    }
    let (s, last, _) = fmu.step(0.0, 1e-4);
    assert_eq!(
        (s, last),
        (fmi3Status::OK, 1e-4),
        "the refused steps computed nothing"
    );
}

#[test]
fn fmu_states_round_trip_and_share_the_fmi2_format() {
    let fmu = Fmu3::new(BEAM);
    fmu.init();
    let t = run(&fmu, 0.0, 3);
    let mut state: fmi3FMUState = std::ptr::null_mut();
    unsafe { assert_eq!(fmi3GetFMUState(fmu.c, &mut state), fmi3Status::OK) };
    run(&fmu, t, 4);
    let after = bits(&fmu);
    unsafe { assert_eq!(fmi3SetFMUState(fmu.c, state), fmi3Status::OK) };
    run(&fmu, t, 4);
    assert_eq!(
        bits(&fmu),
        after,
        "restored, the same steps give the same outputs"
    );
    // Serialized through FMI 3.0, read back through FMI 2.0 (the same format), and back.
    let mut size = 0;
    let mut bytes;
    unsafe {
        assert_eq!(
            fmi3SerializedFMUStateSize(fmu.c, state, &mut size),
            fmi3Status::OK
        );
        bytes = vec![0u8; size];
        let s = fmi3SerializeFMUState(fmu.c, state, bytes.as_mut_ptr(), size - 1);
        fmu.expect_error(s, &["fmi3SerializedFMUStateSize"]);
        assert_eq!(
            fmi3SerializeFMUState(fmu.c, state, bytes.as_mut_ptr(), size),
            fmi3Status::OK
        );
    }
    let two = Fmu::new(BEAM);
    two.init();
    let restored = fmi_host::deserialize(
        &two,
        &bytes.iter().map(|&b| b as fmi2Byte).collect::<Vec<_>>(),
        std::ptr::null_mut(),
    );
    assert_eq!(restored.0, fmi2Status::OK);
    unsafe {
        assert_eq!(fmi2SetFMUstate(two.c, restored.1), fmi2Status::OK);
        assert_eq!(fmi2DoStep(two.c, t, 1e-4, fmi2True), fmi2Status::OK);
    }
    let mut copy: fmi3FMUState = std::ptr::null_mut();
    unsafe {
        assert_eq!(
            fmi3DeserializeFMUState(fmu.c, bytes.as_ptr(), size, &mut copy),
            fmi3Status::OK
        );
        assert_eq!(fmi3SetFMUState(fmu.c, copy), fmi3Status::OK);
    }
    run(&fmu, t, 1);
    let (_, layout) = layout(BEAM);
    let e_kin = layout
        .variables
        .iter()
        .find(|v| v.name == "E_kin")
        .unwrap()
        .vr;
    assert_eq!(
        fmu.floats(&[e_kin], 1)[0].to_bits(),
        two.real(e_kin).to_bits()
    );
    // Corrupt bytes, freed and foreign handles are refused.
    bytes[size / 2] ^= 0x40;
    let mut other: fmi3FMUState = std::ptr::null_mut();
    unsafe {
        let s = fmi3DeserializeFMUState(fmu.c, bytes.as_ptr(), size, &mut other);
        assert_eq!(s, fmi3Status::Error);
        assert!(other.is_null(), "a refusal leaves *FMUState as it was");
        assert_eq!(fmi3FreeFMUState(fmu.c, &mut state), fmi3Status::OK);
        assert!(state.is_null());
        assert_eq!(
            fmi3FreeFMUState(fmu.c, &mut state),
            fmi3Status::OK,
            "NULL is ignored"
        );
        let freed = copy;
        assert_eq!(fmi3FreeFMUState(fmu.c, &mut copy), fmi3Status::OK);
        fmu.expect_error(
            fmi3SetFMUState(fmu.c, freed),
            &["fmi3SetFMUState", "FMUState"],
        );
        let arch = Fmu3::new(PINNED);
        let mut foreign: fmi3FMUState = std::ptr::null_mut();
        assert_eq!(fmi3GetFMUState(arch.c, &mut foreign), fmi3Status::OK);
        fmu.expect_error(fmi3SetFMUState(fmu.c, foreign), &["FMUState"]);
        // A slot holding something else is never used: a new state is written over it.
        let mut junk = 0x10 as fmi3FMUState;
        assert_eq!(fmi3GetFMUState(fmu.c, &mut junk), fmi3Status::Warning);
        assert_eq!(fmi3FreeFMUState(fmu.c, &mut junk), fmi3Status::OK);
    }
}

#[test]
fn unsupported_functions_answer_error_with_a_message_naming_them() {
    let fmu = Fmu3::new(BEAM);
    fmu.init();
    let (mut x, mut n, mut b) = (0.0, 0usize, 0u8);
    let vr = 0u32;
    unsafe {
        let calls: Vec<(fmi3Status, &str)> = vec![
            (fmi3EnterEventMode(fmu.c), "fmi3EnterEventMode"),
            (fmi3EnterStepMode(fmu.c), "fmi3EnterStepMode"),
            (
                fmi3EvaluateDiscreteStates(fmu.c),
                "fmi3EvaluateDiscreteStates",
            ),
            (
                fmi3UpdateDiscreteStates(fmu.c, &mut b, &mut b, &mut b, &mut b, &mut b, &mut x),
                "fmi3UpdateDiscreteStates",
            ),
            (
                fmi3GetNumberOfVariableDependencies(fmu.c, vr, &mut n),
                "fmi3GetNumberOfVariableDependencies",
            ),
            (
                fmi3GetDirectionalDerivative(fmu.c, &vr, 1, &vr, 1, &x, 1, &mut x, 1),
                "fmi3GetDirectionalDerivative",
            ),
            (
                fmi3GetAdjointDerivative(fmu.c, &vr, 1, &vr, 1, &x, 1, &mut x, 1),
                "fmi3GetAdjointDerivative",
            ),
            (
                fmi3GetOutputDerivatives(fmu.c, &vr, 1, &1, &mut x, 1),
                "fmi3GetOutputDerivatives",
            ),
            (
                fmi3GetShiftDecimal(fmu.c, &vr, 1, &mut x),
                "fmi3GetShiftDecimal",
            ),
            (fmi3SetTime(fmu.c, 0.0), "fmi3SetTime"),
            (
                fmi3GetNumberOfContinuousStates(fmu.c, &mut n),
                "fmi3GetNumberOfContinuousStates",
            ),
            (
                fmi3ActivateModelPartition(fmu.c, vr, 0.0),
                "fmi3ActivateModelPartition",
            ),
            (fmi3GetClock(fmu.c, &vr, 1, &mut b), "fmi3GetClock"),
            (
                fmi3GetFloat32(fmu.c, &vr, 1, &mut 0.0f32, 1),
                "fmi3GetFloat32",
            ),
            (fmi3SetUInt64(fmu.c, &vr, 1, &0u64, 1), "fmi3SetUInt64"),
        ];
        let log = fmu.messages();
        assert_eq!(log.len(), calls.len());
        for ((status, name), msg) in calls.into_iter().zip(log) {
            assert_eq!(status, fmi3Status::Error, "{name}");
            assert!(msg.text.starts_with(&format!("{name}: ")), "{}", msg.text);
        }
        let mut sizes = [0usize];
        let mut values = [std::ptr::null::<u8>()];
        let s = fmi3GetBinary(fmu.c, &vr, 1, sizes.as_mut_ptr(), values.as_mut_ptr(), 1);
        fmu.expect_error(s, &["fmi3GetBinary", "not Binary"]);
    }
    let (s, ..) = fmu.step(0.0, 1e-4);
    assert_eq!(s, fmi3Status::OK, "refused calls change nothing");
}

#[test]
fn the_logger_gets_plain_text_and_the_environment() {
    let fmu = Fmu3::new(BEAM);
    let on = CString::new("logEvents").unwrap();
    unsafe {
        assert_eq!(
            fmi3SetDebugLogging(fmu.c, fmi3True, 1, &on.as_ptr()),
            fmi3Status::OK
        );
    }
    fmu.init();
    let log = fmu.messages();
    assert!(
        log.iter()
            .any(|m| m.category == "logEvents" && m.text.contains("state")),
        "{log:?}"
    );
    // A `%` is text, never a format (FMI 3.0 messages are plain strings).
    let pct = CString::new("log%s%n").unwrap();
    unsafe { fmi3SetDebugLogging(fmu.c, fmi3True, 1, &pct.as_ptr()) };
    assert!(fmu.messages().last().unwrap().text.contains("log%s%n"));
}
