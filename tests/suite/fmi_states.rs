//! FMU states through the FMI 2.0 C API (the host is `fmi_host`): bit-for-bit round trips in
//! memory and serialized, the restored state machine, refused serialized states; and a
//! discarded step, which must leave the state exactly as it was.
#![cfg(any(
    target_arch = "x86_64",
    all(target_arch = "aarch64", not(target_vendor = "apple"))
))]
#![allow(non_upper_case_globals)]

use crate::fmi_host;

use fmi_host::*;
use georod::fmi::api::*;
use georod::fmi::types::*;
use std::ptr::null_mut;

// ----- FMU state ------------------------------------------------------------------------------

#[test]
fn fmu_state_round_trips_bit_for_bit() {
    let fmu = Fmu::new(BEAM);
    fmu.init();
    assert_eq!(fmu.set_real(vr::F, 0.9), fmi2Status::OK);
    run(&fmu, 3);
    let mut state: fmi2FMUstate = null_mut();
    unsafe { assert_eq!(fmi2GetFMUstate(fmu.c, &mut state), fmi2Status::OK) };
    let t0 = fmu.time();
    let reference = run(&fmu, 6);
    // Change everything the state must restore.
    assert_eq!(fmu.set_real(vr::F, 0.1), fmi2Status::OK);
    assert_eq!(fmu.set_real(vr::f_ctrl, 3.0), fmi2Status::OK);
    unsafe { assert_eq!(fmi2SetFMUstate(fmu.c, state), fmi2Status::OK) };
    assert_eq!(fmu.time(), t0);
    assert_eq!(fmu.real(vr::F), 0.9);
    assert_eq!(fmu.real(vr::f_ctrl), 0.0);
    assert_eq!(run(&fmu, 6), reference);

    // Serialized, then restored in a fresh instance of the same scene.
    let mut size = 0;
    unsafe {
        assert_eq!(
            fmi2SerializedFMUstateSize(fmu.c, state, &mut size),
            fmi2Status::OK
        )
    };
    let mut bytes = vec![0 as fmi2Byte; size];
    unsafe {
        fmu.expect_error(
            fmi2SerializeFMUstate(fmu.c, state, bytes.as_mut_ptr(), size - 1),
            &["size"],
        );
        assert_eq!(
            fmi2SerializeFMUstate(fmu.c, state, bytes.as_mut_ptr(), size),
            fmi2Status::OK
        );
    }
    let other = Fmu::new(BEAM);
    let mut copy: fmi2FMUstate = null_mut();
    unsafe {
        assert_eq!(
            fmi2DeSerializeFMUstate(other.c, bytes.as_ptr(), size, &mut copy),
            fmi2Status::OK
        );
        assert_eq!(
            fmi2SetFMUstate(other.c, copy),
            fmi2Status::OK,
            "{:?}",
            other.messages()
        );
    }
    assert_eq!(other.time(), t0);
    assert_eq!(run(&other, 6), reference);

    // A state re-taken into an existing allocation, then freed (pointer set to NULL).
    unsafe {
        let before = copy;
        assert_eq!(fmi2GetFMUstate(other.c, &mut copy), fmi2Status::OK);
        assert_eq!(copy, before, "updated in place");
        assert_eq!(fmi2FreeFMUstate(other.c, &mut copy), fmi2Status::OK);
        assert!(copy.is_null());
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), fmi2Status::OK);
        assert!(state.is_null());
    }
}

#[test]
fn fmu_state_restores_the_state_machine() {
    let fmu = Fmu::new(BEAM);
    let mut early: fmi2FMUstate = null_mut();
    unsafe {
        assert_eq!(fmu.set_real(vr::F, 0.25), fmi2Status::OK);
        assert_eq!(fmi2GetFMUstate(fmu.c, &mut early), fmi2Status::OK);
        fmu.init();
        run(&fmu, 2);
        assert_eq!(fmi2Terminate(fmu.c), fmi2Status::OK);
        assert_eq!(fmi2SetFMUstate(fmu.c, early), fmi2Status::OK);
        // Back in instantiated, with the parameters of then.
        fmu.expect_error(fmi2DoStep(fmu.c, 0.0, H, 0), &["instantiated"]);
        assert_eq!(fmu.real(vr::F), 0.25);
        fmu.init();
        assert_eq!(fmu.time(), 0.0);
        run(&fmu, 1);
        fmi2FreeFMUstate(fmu.c, &mut early);
    }
}

#[test]
fn bad_serialized_states_are_refused() {
    let fmu = Fmu::new(BEAM);
    fmu.init();
    run(&fmu, 1);
    let mut state: fmi2FMUstate = null_mut();
    let mut size = 0;
    let bytes = unsafe {
        assert_eq!(fmi2GetFMUstate(fmu.c, &mut state), fmi2Status::OK);
        assert_eq!(
            fmi2SerializedFMUstateSize(fmu.c, state, &mut size),
            fmi2Status::OK
        );
        let mut bytes = vec![0 as fmi2Byte; size];
        assert_eq!(
            fmi2SerializeFMUstate(fmu.c, state, bytes.as_mut_ptr(), size),
            fmi2Status::OK
        );
        fmi2FreeFMUstate(fmu.c, &mut state);
        bytes
    };
    let deser = |f: &Fmu, b: &[fmi2Byte]| {
        let mut out: fmi2FMUstate = null_mut();
        let s = unsafe { fmi2DeSerializeFMUstate(f.c, b.as_ptr(), b.len(), &mut out) };
        assert!(out.is_null() || s == fmi2Status::OK);
        if !out.is_null() {
            unsafe { fmi2FreeFMUstate(f.c, &mut out) };
        }
        s
    };
    assert_eq!(deser(&fmu, &bytes), fmi2Status::OK);
    fmu.expect_error(
        deser(&fmu, &bytes[..size - 1]),
        &["does not match the length"],
    );
    fmu.expect_error(deser(&fmu, &bytes[..20]), &["too short"]);
    fmu.expect_error(deser(&fmu, &bytes[..5]), &["too short"]);
    fmu.expect_error(deser(&fmu, &[]), &["too short"]);
    let mut longer = bytes.clone();
    longer.push(0);
    fmu.expect_error(deser(&fmu, &longer), &["does not match the length"]);
    let mut wrong_magic = bytes.clone();
    wrong_magic[0] ^= 1;
    fmu.expect_error(deser(&fmu, &wrong_magic), &["wrong magic"]);
    let mut wrong_version = bytes.clone();
    wrong_version[8] = 99;
    fmu.expect_error(deser(&fmu, &wrong_version), &["format version 99"]);
    let arch = Fmu::new(PINNED);
    arch.expect_error(deser(&arch, &bytes), &["BuckledBeam scene", "PinnedArch"]);
    let finer = Fmu::new(BEAM);
    assert_eq!(finer.set_integer(vr::elements, 12), fmi2Status::OK);
    finer.expect_error(deser(&finer, &bytes), &["10 elements", "has 12"]);
    // In-memory states belong to their instance: another instance refuses them.
    unsafe {
        assert_eq!(fmi2GetFMUstate(fmu.c, &mut state), fmi2Status::OK);
        arch.expect_error(fmi2SetFMUstate(arch.c, state), &["not a live FMU state"]);
        finer.expect_error(fmi2SetFMUstate(finer.c, state), &["not a live FMU state"]);
        fmi2FreeFMUstate(fmu.c, &mut state);
    }
}

// ----- discarded steps ------------------------------------------------------------------------

#[test]
fn a_step_that_cannot_converge_is_discarded_and_changes_nothing() {
    // The PinnedArch moving in its chaotic regime (F = 20, Omega = 1000, 10 ms), then a crown
    // force f_ctrl = 1000 over 5 ms with dt_max = 0.5 ms: every attempt (10, 20, ... 320
    // sub-steps) fails after converged sub-steps (tests/suite/step_retry.rs checks that premise on the
    // core), so a discard that kept any of the partly advanced state would show here.
    let fmu = Fmu::new(PINNED);
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status::OK);
        assert_eq!(fmu.set_real(vr::dt_max, 5e-4), fmi2Status::OK);
        assert_eq!(fmu.set_real(vr::F, 20.0), fmi2Status::OK);
        assert_eq!(fmu.set_real(vr::Omega, 1000.0), fmi2Status::OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), fmi2Status::OK);
    }
    for k in 0..10 {
        assert_eq!(fmu.step(k as f64 * 1e-3, 1e-3), fmi2Status::OK);
    }
    assert_eq!(fmu.set_real(vr::f_ctrl, 1000.0), fmi2Status::OK);
    let state = |f: &Fmu| {
        let mut bits = f.outputs();
        let ledger = [vr::W_ext, vr::W_ctrl, vr::E_damped, vr::energy_error];
        bits.extend(f.reals(&ledger).iter().map(|x| x.to_bits()));
        bits
    };
    let before = state(&fmu);
    assert!(
        f64::from_bits(before[1]).abs() > 1.0,
        "the arch should be moving"
    );
    fmu.clear();
    let t = fmu.time();
    let s = fmu.step(t, 5e-3);
    assert_eq!(s, fmi2Status::Discard, "{:?}", fmu.messages());
    let msg = fmu.messages().pop().unwrap();
    assert_eq!(
        (msg.status, msg.category.as_str()),
        (fmi2Status::Discard, "logStatusWarning")
    );
    assert!(msg.text.contains("did not converge"), "{}", msg.text);
    assert_eq!(
        state(&fmu),
        before,
        "the state (w_mid, v_mid, E_kin, E_strain of the whole rod, energy ledger) is exactly \
         the one before the step"
    );
    assert_eq!(fmu.time(), t);
    let mut terminated = fmi2True;
    unsafe {
        assert_eq!(
            fmi2GetBooleanStatus(fmu.c, fmi2Terminated, &mut terminated),
            fmi2Status::OK
        );
        assert_eq!(terminated, fmi2False);
        // stepFailed: no more steps or inputs, but terminate/reset are fine.
        fmu.expect_error(fmi2DoStep(fmu.c, 0.0, 1e-2, 0), &["stepFailed"]);
        fmu.expect_error(fmu.set_real(vr::F, 1.0), &["stepFailed"]);
        assert_eq!(fmi2Terminate(fmu.c), fmi2Status::OK);
    }
}
