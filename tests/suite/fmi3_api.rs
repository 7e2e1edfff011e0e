//! The FMI 3.0 Co-Simulation API: life cycle and state machine, `fmi3DoStep`'s out-arguments,
//! arrays (value references with element counts), and the same trajectories as the FMI 2.0 API
//! of the same scene, bit for bit, for every scene file.
#![cfg(not(all(target_vendor = "apple", target_arch = "aarch64")))]
use crate::fmi3_host;

use crate::fmi_host::{scene_files, Fmu, BEAM};
use fmi3_host::*;
use georod::fmi::api3::*;
use georod::fmi::types::*;
use georod::fmi::types3::*;
use georod::packaging::variables3::TIME_VR;
use georod::scene::variables::Causality;

#[test]
fn version_life_cycle_and_step_out_arguments() {
    let v = unsafe { std::ffi::CStr::from_ptr(fmi3GetVersion()) };
    assert_eq!(v.to_str().unwrap(), "3.0");
    let fmu = Fmu3::new(BEAM);
    unsafe {
        assert_eq!(fmi3EnterConfigurationMode(fmu.c), fmi3Status::OK);
        assert_eq!(fmi3ExitConfigurationMode(fmu.c), fmi3Status::OK);
        assert_eq!(
            fmi3EnterInitializationMode(fmu.c, fmi3True, 1e-6, 2.0, fmi3True, 2.01),
            fmi3Status::OK
        );
        assert_eq!(fmi3ExitInitializationMode(fmu.c), fmi3Status::OK);
    }
    let h = 1e-3;
    let (mut t, mut i) = (2.0, 0);
    while i < 5 {
        let (s, last, flags) = fmu.step(t, h);
        assert_eq!(s, fmi3Status::OK, "{:?}", fmu.messages());
        assert_eq!(
            flags, [fmi3False; 3],
            "no event, no termination, no early return"
        );
        assert!((last - (t + h)).abs() < 1e-12, "{last}");
        assert_eq!(
            fmu.floats(&[TIME_VR], 1),
            [last],
            "the time the FMU reached"
        );
        t = last;
        i += 1;
    }
    // Past stopTime: refused, nothing computed, the out-arguments untouched.
    let (s, last, flags) = fmu.step(t, 1.0);
    fmu.expect_error(s, &["fmi3DoStep", "stopTime"]);
    assert!(last.is_nan() && flags == [7; 3]);
    unsafe {
        assert_eq!(fmi3Terminate(fmu.c), fmi3Status::OK);
        assert_eq!(fmi3Reset(fmu.c), fmi3Status::OK);
    }
    fmu.init();
    assert_eq!(
        fmu.floats(&[TIME_VR], 1),
        [0.0],
        "reset: the start time is 0 again"
    );
}

#[test]
fn the_state_machine_is_enforced() {
    let fmu = Fmu3::new(BEAM);
    let (s, ..) = fmu.step(0.0, 1e-3);
    fmu.expect_error(s, &["fmi3DoStep", "not allowed in state instantiated"]);
    unsafe {
        fmu.expect_error(fmi3ExitConfigurationMode(fmu.c), &["instantiated"]);
        fmu.expect_error(fmi3ExitInitializationMode(fmu.c), &["instantiated"]);
        fmu.expect_error(fmi3Terminate(fmu.c), &["instantiated"]);
        assert_eq!(fmi3EnterConfigurationMode(fmu.c), fmi3Status::OK);
        // No structural parameters: nothing can be set in configuration mode.
        let x = 1.0;
        fmu.expect_error(fmi3SetFloat64(fmu.c, &0, 1, &x, 1), &["configurationMode"]);
        fmu.expect_error(
            fmi3EnterInitializationMode(fmu.c, fmi3False, 0.0, 0.0, fmi3False, 0.0),
            &["configurationMode"],
        );
        assert_eq!(fmi3ExitConfigurationMode(fmu.c), fmi3Status::OK);
        // A refused experiment changes no state.
        fmu.expect_error(
            fmi3EnterInitializationMode(fmu.c, fmi3False, 0.0, f64::NAN, fmi3False, 0.0),
            &["startTime"],
        );
        fmu.init();
        fmu.expect_error(fmi3EnterConfigurationMode(fmu.c), &["stepComplete"]);
        fmu.expect_error(
            fmi3EnterInitializationMode(fmu.c, fmi3False, 0.0, 0.0, fmi3False, 0.0),
            &["stepComplete"],
        );
        assert_eq!(fmi3Terminate(fmu.c), fmi3Status::OK);
        let (s, ..) = fmu.step(0.0, 1e-3);
        fmu.expect_error(s, &["terminated"]);
    }
}

#[test]
fn arrays_are_read_whole_with_element_counts() {
    let fmu = Fmu3::new(BEAM);
    fmu.init();
    let (vars, layout) = layout(BEAM);
    let x = layout
        .variables
        .iter()
        .find(|v| v.name == "shape_x")
        .unwrap();
    let y = layout
        .variables
        .iter()
        .find(|v| v.name == "shape_y")
        .unwrap();
    let e_kin = layout.variables.iter().find(|v| v.name == "E_kin").unwrap();
    let n = x.len;
    let mixed = fmu.floats(&[x.vr, e_kin.vr, y.vr], 2 * n + 1);
    assert_eq!(mixed[..n], fmu.floats(&[x.vr], n)[..]);
    assert_eq!(mixed[n + 1..], fmu.floats(&[y.vr], n)[..]);
    let fmi2 = Fmu::new(BEAM);
    fmi2.init();
    assert_eq!(mixed[..n], fmi2.reals(layout.element_vrs(x))[..]);
    let mut out = vec![0.0; 2 * n];
    unsafe {
        let s = fmi3GetFloat64(fmu.c, &x.vr, 1, out.as_mut_ptr(), n - 1);
        fmu.expect_error(s, &["nValues = 20", "21 elements"]);
        let s = fmi3GetFloat64(fmu.c, &x.vr, 1, out.as_mut_ptr(), n + 1);
        fmu.expect_error(s, &["nValues"]);
        let s = fmi3GetFloat64(fmu.c, &(x.vr + 1), 1, out.as_mut_ptr(), 1);
        fmu.expect_error(s, &["unknown value reference", "read the array"]);
        let mut i = 0;
        let s = fmi3GetInt32(fmu.c, &x.vr, 1, &mut i, 1);
        fmu.expect_error(
            s,
            &["`shape_x`", "Float64 variable, not Int32", "fmi3GetFloat64"],
        );
        let s = fmi3SetFloat64(fmu.c, &x.vr, 1, out.as_ptr(), n);
        fmu.expect_error(s, &["is an output"]);
        let s = fmi3SetFloat64(fmu.c, &TIME_VR, 1, out.as_ptr(), 1);
        fmu.expect_error(s, &["independent variable"]);
        let mut b = 0u8;
        let s = fmi3GetBoolean(fmu.c, &e_kin.vr, 1, &mut b, 1);
        fmu.expect_error(s, &["Float64 variable, not Boolean"]);
        assert_eq!(
            fmi3GetBoolean(fmu.c, std::ptr::null(), 0, std::ptr::null_mut(), 0),
            fmi3Status::OK
        );
        let s = fmi3GetFloat64(fmu.c, std::ptr::null(), 1, out.as_mut_ptr(), 1);
        fmu.expect_error(s, &["valueReferences is NULL"]);
        let s = fmi3GetFloat64(fmu.c, &x.vr, 1, std::ptr::null_mut(), n);
        fmu.expect_error(s, &["values is NULL"]);
    }
    // Integers and enumerations: newton_iterations (Int32), the integrator (Int64).
    let iterations = layout
        .variables
        .iter()
        .find(|v| vars[v.first].name == "newton_iterations");
    let mut k = -1;
    unsafe {
        assert_eq!(
            fmi3GetInt32(fmu.c, &iterations.unwrap().vr, 1, &mut k, 1),
            fmi3Status::OK
        );
    }
    assert_eq!(k, fmi2.integer(iterations.unwrap().vr));
}

#[test]
fn parameters_and_inputs_are_set_like_fmi2() {
    let (vars, layout) = layout(BEAM);
    let input = layout
        .variables
        .iter()
        .find(|v| vars[v.first].causality == Causality::Input)
        .expect("the beam has an input");
    let fmu = Fmu3::new(BEAM);
    fmu.init();
    unsafe {
        assert_eq!(
            fmi3SetFloat64(fmu.c, &input.vr, 1, &0.25, 1),
            fmi3Status::OK
        );
        let s = fmi3SetFloat64(fmu.c, &input.vr, 1, &f64::INFINITY, 1);
        fmu.expect_error(s, &["not a finite number"]);
    }
    assert_eq!(
        fmu.floats(&[input.vr], 1),
        [0.25],
        "a refused set changes nothing"
    );
    // The integrator choice is an Int32 (1 or 2): read as such, a value outside refused.
    let integrator = vars.iter().find(|v| v.name == "integrator").unwrap().vr;
    let mut value = 0i32;
    unsafe {
        assert_eq!(
            fmi3GetInt32(fmu.c, &integrator, 1, &mut value, 1),
            fmi3Status::OK
        );
        let s = fmi3SetInt32(fmu.c, &integrator, 1, &7, 1);
        fmu.expect_error(s, &["integrator"]);
    }
    assert_eq!(value, 1, "the midpoint rule by default");
}

/// Every output of the FMI 2.0 API, by value reference, as bits.
fn outputs2(fmu: &Fmu, vrs: &[u32], ints: &[u32]) -> Vec<u64> {
    let mut bits: Vec<u64> = fmu.reals(vrs).iter().map(|x| x.to_bits()).collect();
    bits.extend(ints.iter().map(|&vr| fmu.integer(vr) as u64));
    bits
}

#[test]
fn fmi3_and_fmi2_give_the_same_outputs_bit_for_bit_for_every_scene_file() {
    for (scene, _) in scene_files() {
        let (vars, layout) = layout(&scene);
        let outputs: Vec<_> = layout
            .variables
            .iter()
            .filter(|v| vars[v.first].causality == Causality::Output)
            .collect();
        let is_int = |v: &&&georod::packaging::variables3::Variable3| {
            vars[v.first].var_type == georod::scene::VarType::Integer
        };
        let reals: Vec<_> = outputs.iter().filter(|v| !is_int(v)).collect();
        let ints: Vec<u32> = outputs.iter().filter(is_int).map(|v| v.vr).collect();
        let vrs3: Vec<u32> = reals.iter().map(|v| v.vr).collect();
        let vrs2: Vec<u32> = reals
            .iter()
            .flat_map(|v| layout.element_vrs(v).to_vec())
            .collect();
        let (two, three) = (Fmu::new(&scene), Fmu3::new(&scene));
        two.init();
        three.init();
        let h = 2e-4;
        for step in 0..=10 {
            let mut bits: Vec<u64> = three
                .floats(&vrs3, vrs2.len())
                .iter()
                .map(|x| x.to_bits())
                .collect();
            for &vr in &ints {
                let mut k = 0;
                unsafe { assert_eq!(fmi3GetInt32(three.c, &vr, 1, &mut k, 1), fmi3Status::OK) };
                bits.push(k as u64);
            }
            assert_eq!(bits, outputs2(&two, &vrs2, &ints), "{scene}, step {step}");
            let t = step as f64 * h;
            assert_eq!(two.step(t, h), fmi2Status::OK, "{scene}");
            assert_eq!(three.step(t, h).0, fmi3Status::OK, "{scene}");
        }
    }
}
