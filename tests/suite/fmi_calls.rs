//! The FMI 2.0 Co-Simulation C API, called the way a host calls it (raw pointers, C strings,
//! a logger callback), straight from Rust; the host and its logger are in `fmi_host`. Here: runs
//! from instantiation to termination, and the state machine (call orders the standard forbids
//! are refused and change nothing; reset; a failed initialization).
#![cfg(any(
    target_arch = "x86_64",
    all(target_arch = "aarch64", not(target_vendor = "apple"))
))]
#![allow(non_upper_case_globals)]

use crate::fmi_host;

use fmi_host::*;
use georod::fmi::api::*;
use georod::fmi::types::*;
use std::ffi::CStr;
use std::ptr::{null, null_mut};

// ----- basics ---------------------------------------------------------------------------------

#[test]
fn version_and_platform() {
    unsafe {
        assert_eq!(CStr::from_ptr(fmi2GetVersion()).to_str().unwrap(), "2.0");
        assert_eq!(
            CStr::from_ptr(fmi2GetTypesPlatform()).to_str().unwrap(),
            "default"
        );
    }
}

#[test]
fn happy_path_buckled_beam() {
    let fmu = Fmu::with(BEAM, "beam", true);
    unsafe {
        assert_eq!(
            fmi2SetupExperiment(fmu.c, fmi2True, 1e-6, 0.0, fmi2True, 1.0),
            fmi2Status::OK
        );
        assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status::OK);
        assert_eq!(fmu.set_real(vr::F, 0.8), fmi2Status::OK);
        assert_eq!(fmu.set_integer(vr::elements, 10), fmi2Status::OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), fmi2Status::OK);
    }
    assert!(fmu.real(vr::w_mid) > 0.0, "well +1: midspan up");
    assert_eq!(fmu.real(vr::F), 0.8);
    assert_eq!(fmu.integer(vr::elements), 10);
    assert_eq!(fmu.integer(vr::newton_iterations), 0);
    let first = run(&fmu, 10);
    assert!(fmu.integer(vr::newton_iterations) > 0);
    assert!((fmu.time() - 10.0 * H).abs() < 1e-15);
    // Tunable parameters and inputs in stepComplete.
    assert_eq!(fmu.set_real(vr::Omega, 3000.0), fmi2Status::OK);
    assert_eq!(fmu.set_real(vr::F, 0.5), fmi2Status::OK);
    assert_eq!(fmu.set_real(vr::f_ctrl, 0.1), fmi2Status::OK);
    run(&fmu, 5);
    let [w, v, ek, es] = fmu.reals(&[vr::w_mid, vr::v_mid, vr::E_kin, vr::E_strain])[..] else {
        unreachable!()
    };
    assert!(w.is_finite() && v.is_finite() && ek >= 0.0 && es > 0.0);
    assert_ne!(first[9], fmu.outputs());
    let mut terminated = fmi2True;
    unsafe {
        assert_eq!(
            fmi2GetBooleanStatus(fmu.c, fmi2Terminated, &mut terminated),
            fmi2Status::OK
        );
        assert_eq!(terminated, fmi2False);
        assert_eq!(fmi2Terminate(fmu.c), fmi2Status::OK);
    }
    // Values and the time stay readable after termination.
    assert_eq!(fmu.real(vr::w_mid), w);
    assert!((fmu.time() - 15.0 * H).abs() < 1e-15);
    let events: Vec<_> = fmu
        .messages()
        .into_iter()
        .filter(|m| m.category == "logEvents")
        .collect();
    assert!(
        events
            .iter()
            .any(|m| m.text.contains("initializationMode -> stepComplete")),
        "{events:?}"
    );
    assert!(fmu
        .messages()
        .iter()
        .all(|m| m.format == "%s" && m.name == "beam"));
}

#[test]
fn arch_scenes_run() {
    let fmu = Fmu::new(PINNED);
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status::OK);
        assert_eq!(fmu.set_real(vr::H, 2.5), fmi2Status::OK);
        assert_eq!(fmu.set_real(vr::F, 10.0), fmi2Status::OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), fmi2Status::OK);
    }
    assert_eq!(fmu.real(vr::H), 2.5);
    run(&fmu, 3);
    // The beam's parameters do not exist here.
    let mut i = 0;
    let s = unsafe { fmi2GetInteger(fmu.c, &vr::well, 1, &mut i) };
    fmu.expect_error(
        s,
        &["value reference 12", "not a variable of the PinnedArch"],
    );
}

#[test]
fn start_time_offsets_the_clock() {
    let fmu = Fmu::new(BEAM);
    unsafe {
        assert_eq!(
            fmi2SetupExperiment(fmu.c, fmi2False, 0.0, 2.0, fmi2False, 0.0),
            fmi2Status::OK
        );
        assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status::OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), fmi2Status::OK);
    }
    assert_eq!(fmu.time(), 2.0);
    let s = fmu.step(0.0, H);
    fmu.expect_error(s, &["currentCommunicationPoint", "0e0", "2e0"]);
    assert_eq!(fmu.step(2.0, H), fmi2Status::OK);
    assert_eq!(fmu.step(2.0 + H, H), fmi2Status::OK);
    assert!((fmu.time() - (2.0 + 2.0 * H)).abs() < 1e-12);
}

#[test]
fn outputs_before_initialization_are_the_initial_state() {
    let fmu = Fmu::new(BEAM);
    let before = fmu.real(vr::w_mid);
    assert!(before > 0.0);
    assert_eq!(fmu.integer(vr::newton_iterations), 0);
    unsafe { assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status::OK) };
    assert_eq!(fmu.set_integer(vr::well, -1), fmi2Status::OK);
    let down = fmu.real(vr::w_mid);
    assert!(
        down < 0.0,
        "a changed fixed parameter gives a new initial state"
    );
    unsafe { assert_eq!(fmi2ExitInitializationMode(fmu.c), fmi2Status::OK) };
    assert_eq!(fmu.real(vr::w_mid), down);
    assert_eq!(fmu.real(vr::f_ctrl), 0.0);
}

// ----- state machine --------------------------------------------------------------------------

#[test]
fn forbidden_call_orders() {
    let fmu = Fmu::new(BEAM);
    let c = fmu.c;
    let mut x = 0.0;
    let mut st = fmi2Status::OK;
    unsafe {
        // instantiated
        fmu.expect_error(
            fmi2DoStep(c, 0.0, H, fmi2True),
            &["fmi2DoStep", "not allowed in state instantiated"],
        );
        fmu.expect_error(
            fmi2ExitInitializationMode(c),
            &["fmi2ExitInitializationMode", "instantiated"],
        );
        fmu.expect_error(fmi2Terminate(c), &["fmi2Terminate", "instantiated"]);
        fmu.expect_error(
            fmi2GetStatus(c, fmi2DoStepStatus, &mut st),
            &["fmi2GetStatus", "instantiated"],
        );
        fmu.expect_error(
            fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &mut x),
            &["fmi2GetRealStatus"],
        );
        fmu.expect_error(
            fmi2CancelStep(c),
            &["fmi2CancelStep", "no asynchronous step in progress"],
        );
        fmu.expect_error(
            fmi2GetDirectionalDerivative(c, null(), 0, null(), 0, null(), null_mut()),
            &["fmi2GetDirectionalDerivative", "instantiated"],
        );
        // initializationMode
        assert_eq!(fmi2EnterInitializationMode(c), fmi2Status::OK);
        fmu.expect_error(
            fmi2EnterInitializationMode(c),
            &["fmi2EnterInitializationMode", "initializationMode"],
        );
        fmu.expect_error(
            fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0),
            &["fmi2SetupExperiment", "initializationMode"],
        );
        fmu.expect_error(
            fmi2DoStep(c, 0.0, H, fmi2True),
            &["fmi2DoStep", "initializationMode"],
        );
        fmu.expect_error(fmi2Terminate(c), &["fmi2Terminate", "initializationMode"]);
        assert_eq!(fmi2ExitInitializationMode(c), fmi2Status::OK);
        // stepComplete
        fmu.expect_error(
            fmi2ExitInitializationMode(c),
            &["fmi2ExitInitializationMode", "stepComplete"],
        );
        fmu.expect_error(
            fmi2EnterInitializationMode(c),
            &["fmi2EnterInitializationMode", "stepComplete"],
        );
        fmu.expect_error(
            fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0),
            &["stepComplete"],
        );
        fmu.expect_error(
            fmu.set_real(vr::E, 1e4),
            &["`E`", "fixed parameter", "stepComplete"],
        );
        fmu.expect_error(
            fmu.set_integer(vr::elements, 4),
            &["`elements`", "fixed parameter"],
        );
        fmu.expect_error(fmi2CancelStep(c), &["no asynchronous step in progress"]);
        fmu.expect_error(
            fmi2DoStep(c, 0.0, 0.0, fmi2True),
            &["communicationStepSize = 0"],
        );
        fmu.expect_error(fmi2DoStep(c, 0.0, -H, fmi2True), &["communicationStepSize"]);
        fmu.expect_error(
            fmi2DoStep(c, 0.0, f64::NAN, fmi2True),
            &["communicationStepSize = NaN"],
        );
        fmu.expect_error(
            fmi2DoStep(c, 0.0, f64::INFINITY, fmi2True),
            &["communicationStepSize = inf"],
        );
        fmu.expect_error(
            fmi2DoStep(c, f64::NAN, H, fmi2True),
            &["currentCommunicationPoint"],
        );
        fmu.expect_error(
            fmi2DoStep(c, 1e-3, H, fmi2True),
            &["currentCommunicationPoint = 1e-3"],
        );
        assert_eq!(
            fmi2DoStep(c, 0.0, H, fmi2True),
            fmi2Status::OK,
            "refused calls changed nothing"
        );
        // A gap or an overlap in communication points is refused.
        fmu.expect_error(
            fmi2DoStep(c, 0.0, H, fmi2True),
            &["currentCommunicationPoint"],
        );
        assert_eq!(
            fmi2GetStatus(c, fmi2DoStepStatus, &mut st),
            fmi2Status::Discard
        );
        fmu.expect_error(
            fmi2GetStatus(c, 42, &mut st),
            &["unknown fmi2StatusKind 42"],
        );
        let mut i = 0;
        assert_eq!(
            fmi2GetIntegerStatus(c, fmi2DoStepStatus, &mut i),
            fmi2Status::Discard
        );
        let mut s: fmi2String = null();
        assert_eq!(
            fmi2GetStringStatus(c, fmi2PendingStatus, &mut s),
            fmi2Status::Discard
        );
        assert_eq!(
            fmi2GetRealStatus(c, fmi2DoStepStatus, &mut x),
            fmi2Status::Discard
        );
        fmu.expect_error(
            fmi2GetDirectionalDerivative(c, null(), 0, null(), 0, null(), null_mut()),
            &["not supported"],
        );
        // Input derivatives (canInterpolateInputs="true"): orders 1 and 2 of an input only.
        fmu.expect_error(
            fmi2SetRealInputDerivatives(c, &vr::f_ctrl, 1, &3, &1.0),
            &["`f_ctrl`", "derivative order 3"],
        );
        fmu.expect_error(
            fmi2SetRealInputDerivatives(c, &vr::w_mid, 1, &1, &1.0),
            &["`w_mid`", "not an input"],
        );
        fmu.expect_error(
            fmi2SetRealInputDerivatives(c, &vr::f_ctrl, 1, &1, &f64::NAN),
            &["`f_ctrl`", "not finite"],
        );
        assert_eq!(
            fmi2SetRealInputDerivatives(c, &vr::f_ctrl, 1, &1, &0.0),
            fmi2Status::OK
        );
        fmu.expect_error(
            fmi2GetRealOutputDerivatives(c, &vr::w_mid, 1, &1, &mut x),
            &["MaxOutputDerivativeOrder=0"],
        );
        // terminated
        assert_eq!(fmi2Terminate(c), fmi2Status::OK);
        fmu.expect_error(fmi2Terminate(c), &["fmi2Terminate", "terminated"]);
        fmu.expect_error(fmi2DoStep(c, H, H, fmi2True), &["fmi2DoStep", "terminated"]);
        fmu.expect_error(fmu.set_real(vr::F, 1.0), &["fmi2SetReal", "terminated"]);
        fmu.expect_error(
            fmu.set_real(vr::f_ctrl, 1.0),
            &["fmi2SetReal", "terminated"],
        );
        fmu.expect_error(fmi2EnterInitializationMode(c), &["terminated"]);
        fmu.expect_error(
            fmi2SetRealInputDerivatives(c, null(), 0, null(), null()),
            &["terminated"],
        );
        // reset -> instantiated, start values
        assert_eq!(fmi2Reset(c), fmi2Status::OK);
        fmu.expect_error(fmi2DoStep(c, 0.0, H, fmi2True), &["instantiated"]);
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), fmi2Status::OK);
    }
}

#[test]
fn reset_restores_start_values_and_reproduces_the_run() {
    let fmu = Fmu::new(BEAM);
    fmu.init();
    let first = run(&fmu, 5);
    assert_eq!(fmu.set_real(vr::F, 2.0), fmi2Status::OK);
    assert_eq!(fmu.set_real(vr::f_ctrl, 1.0), fmi2Status::OK);
    unsafe { assert_eq!(fmi2Reset(fmu.c), fmi2Status::OK) };
    assert_eq!(fmu.real(vr::F), 0.7);
    assert_eq!(fmu.real(vr::f_ctrl), 0.0);
    assert_eq!(fmu.integer(vr::newton_iterations), 0);
    fmu.init();
    assert_eq!(fmu.time(), 0.0);
    assert_eq!(run(&fmu, 5), first);
}

#[test]
fn exit_initialization_failure_enters_the_error_state() {
    let fmu = Fmu::new(BEAM);
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status::OK);
        // In range on its own, but far more than the rod's length: no buckled equilibrium in
        // the well, found at exit.
        assert_eq!(fmu.set_real(vr::pre_shortening, 1000.0), fmi2Status::OK);
        let s = fmi2ExitInitializationMode(fmu.c);
        fmu.expect_error(
            s,
            &["initial static state not found", "well", "error state"],
        );
        fmu.expect_error(
            fmi2DoStep(fmu.c, 0.0, H, fmi2True),
            &["fmi2DoStep", "state error"],
        );
        let mut x = 0.0;
        fmu.expect_error(
            fmi2GetReal(fmu.c, &vr::w_mid, 1, &mut x),
            &["no simulation state"],
        );
        assert_eq!(
            fmu.real(vr::pre_shortening),
            1000.0,
            "parameters stay readable"
        );
        assert_eq!(fmi2Reset(fmu.c), fmi2Status::OK);
    }
    fmu.init();
}
