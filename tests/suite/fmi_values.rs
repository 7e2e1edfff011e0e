//! Variables through the FMI 2.0 C API (the host is `fmi_host`): value references against the
//! scene files, unknown and mistyped references, bad values (the message names the variable and
//! its range), and NULL or garbage pointers in every argument.
#![cfg(any(
    target_arch = "x86_64",
    all(target_arch = "aarch64", not(target_vendor = "apple"))
))]
#![allow(non_upper_case_globals)]

use crate::fmi_host;

use fmi_host::*;
use georod::fmi::api::*;
use georod::fmi::types::*;
use std::ptr::{null, null_mut};

#[test]
fn value_references_match_the_scene_files() {
    for name in PAPER_SCENES {
        let scene = georod::scene::Scene::load(format!(
            "{}/scenes/{name}.toml",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        let vars = georod::scene::variables::variables(&scene);
        let vr_of = |n: &str| vars.iter().find(|v| v.name == n).map(|v| v.vr);
        for (n, vr) in [
            ("E", vr::E),
            ("nu", vr::nu),
            ("d", vr::d),
            ("L", vr::L),
            ("elements", vr::elements),
            ("dt_max", vr::dt_max),
            ("F", vr::F),
            ("Omega", vr::Omega),
            ("f_ctrl", vr::f_ctrl),
            ("E_kin", vr::E_kin),
            ("E_strain", vr::E_strain),
            ("newton_iterations", vr::newton_iterations),
            ("W_ext", vr::W_ext),
            ("W_ctrl", vr::W_ctrl),
            ("E_damped", vr::E_damped),
            ("energy_error", vr::energy_error),
            ("w_mid", vr::w_mid),
            ("v_mid", vr::v_mid),
        ] {
            assert_eq!(vr_of(n), Some(vr), "{name}: {n}");
        }
        let beam = name == "BuckledBeam";
        assert_eq!(vr_of("well"), beam.then_some(vr::well));
        assert_eq!(vr_of("pre_shortening"), beam.then_some(vr::pre_shortening));
        assert_eq!(vr_of("H"), (!beam).then_some(vr::H));
    }
}

// ----- values ---------------------------------------------------------------------------------

#[test]
fn unknown_and_mistyped_value_references() {
    let fmu = Fmu::new(BEAM);
    let c = fmu.c;
    let mut x = [0.0; 2];
    let mut i = [0; 2];
    unsafe {
        fmu.expect_error(
            fmi2GetReal(c, &999, 1, x.as_mut_ptr()),
            &["unknown value reference 999"],
        );
        fmu.expect_error(
            fmi2SetReal(c, &999, 1, x.as_ptr()),
            &["unknown value reference 999"],
        );
        fmu.expect_error(
            fmi2GetInteger(c, &vr::E, 1, i.as_mut_ptr()),
            &["`E` (vr 0)", "Real variable", "fmi2GetReal"],
        );
        fmu.expect_error(
            fmi2GetReal(c, &vr::elements, 1, x.as_mut_ptr()),
            &["`elements`", "Integer variable"],
        );
        fmu.expect_error(
            fmi2SetReal(c, &vr::well, 1, &1.0),
            &["`well`", "fmi2SetInteger"],
        );
        fmu.expect_error(
            fmi2SetReal(c, &vr::H, 1, &1.0),
            &["value reference 13", "not a variable of the BuckledBeam"],
        );
        fmu.expect_error(fmi2SetReal(c, &vr::w_mid, 1, &1.0), &["`w_mid`", "output"]);
        fmu.expect_error(
            fmi2SetInteger(c, &vr::newton_iterations, 1, &1),
            &["`newton_iterations`", "output"],
        );
        let mut b = 0;
        fmu.expect_error(
            fmi2GetBoolean(c, &vr::E, 1, &mut b),
            &["`E`", "no Boolean variables"],
        );
        fmu.expect_error(
            fmi2SetBoolean(c, &77, 1, &b),
            &["unknown value reference 77", "no Boolean"],
        );
        let mut s: fmi2String = null();
        fmu.expect_error(
            fmi2GetString(c, &vr::F, 1, &mut s),
            &["no String variables"],
        );
        fmu.expect_error(
            fmi2SetString(c, &vr::F, 1, &c"x".as_ptr()),
            &["no String variables"],
        );
        // Output arrays are left alone on error; arrays of several values work.
        x = [5.0, 5.0];
        fmu.expect_error(
            fmi2GetReal(c, [vr::E, 999].as_ptr(), 2, x.as_mut_ptr()),
            &["999"],
        );
        assert_eq!(x, [5.0, 5.0]);
        assert_eq!(
            fmi2GetReal(c, [vr::E, vr::nu].as_ptr(), 2, x.as_mut_ptr()),
            fmi2Status::OK
        );
        assert_eq!(x, [1.2e4, 0.2]);
        assert_eq!(
            fmi2GetInteger(c, [vr::elements, vr::well].as_ptr(), 2, i.as_mut_ptr()),
            fmi2Status::OK
        );
        assert_eq!(i, [10, 1]);
    }
}

/// `fmi2SetReal` with the single value reference of one input that is not the first (the 2nd
/// and the 5th of the BeamOnBase's six support inputs) sets that input and only it: the others
/// keep their values, and the support it moves is where the value says after the step (a
/// moving support reaches its input at the end of the step) while the others stay.
#[test]
fn one_input_set_by_its_value_reference_moves_only_its_support() {
    let path = format!("{}/examples/BeamOnBase.toml", env!("CARGO_MANIFEST_DIR"));
    let scene = georod::scene::Scene::load(path).unwrap();
    let vars = georod::scene::variables::variables(&scene);
    let vr_of = |n: &str| vars.iter().find(|v| v.name == n).unwrap().vr;
    let names = [
        "left_u1", "left_u2", "left_w", "right_u1", "right_u2", "right_w",
    ];
    let inputs: Vec<u32> = names.iter().map(|n| vr_of(n)).collect();
    assert_eq!(inputs, (1000..1006).collect::<Vec<u32>>());
    // The ends of the beam (21 shape points).
    let ends = [10_000, 10_020, 20_000, 20_020];
    let length = scene.defaults().std(georod::scene::Std::Span);
    let fmu = Fmu::new("BeamOnBase");
    fmu.init();
    assert_eq!(fmu.reals(&inputs), [0.0; 6]);
    let mut expected = [0.0; 6];
    // (input, value): right_u2 first, then left_u2 alone, which leaves right_u2 where it was.
    for (i, value) in [(4, 1e-3), (1, -2e-3)] {
        let status = unsafe { fmi2SetReal(fmu.c, &inputs[i], 1, &value) };
        assert_eq!(status, fmi2Status::OK, "{:?}", fmu.messages());
        expected[i] = value;
        assert_eq!(fmu.reals(&inputs), expected, "after setting {}", names[i]);
        assert_eq!(
            fmu.step(fmu.time(), H),
            fmi2Status::OK,
            "{:?}",
            fmu.messages()
        );
        assert_eq!(fmu.reals(&inputs), expected, "after the step");
        // x of both ends, then y: the held u1 stay 0, the u2 are the inputs (to round-off of
        // the interpolation at the ends).
        let want = [0.0, length, expected[1], expected[4]];
        for (got, want) in fmu.reals(&ends).iter().zip(want) {
            assert!(
                (got - want).abs() < 1e-15,
                "after setting {}: {got} instead of {want}",
                names[i]
            );
        }
    }
}

#[test]
fn bad_values_name_the_variable_and_the_range() {
    let fmu = Fmu::new(BEAM);
    fmu.expect_error(
        fmu.set_real(vr::E, f64::NAN),
        &["`E`", "NaN", "not a finite number"],
    );
    fmu.expect_error(fmu.set_real(vr::E, f64::INFINITY), &["`E`", "inf"]);
    fmu.expect_error(fmu.set_real(vr::E, -1.0), &["`E`", "out of range", "> 0"]);
    // nu: the open interval (-1, 0.5); its declared bounds are the doubles next to the ends.
    for nu in [0.51, 0.5, -1.0] {
        fmu.expect_error(fmu.set_real(vr::nu, nu), &["`nu`", "must be (-1, 0.5)"]);
    }
    // The declared bounds themselves are accepted (FMI 2.0 bounds are inclusive).
    assert_eq!(fmu.set_real(vr::nu, 0.49999999999999994), fmi2Status::OK);
    assert_eq!(fmu.set_real(vr::nu, -0.9999999999999999), fmi2Status::OK);
    assert_eq!(fmu.set_real(vr::E, f64::MIN_POSITIVE), fmi2Status::OK);
    assert_eq!(fmu.set_real(vr::E, 1.2e4), fmi2Status::OK);
    assert_eq!(fmu.set_real(vr::nu, 0.2), fmi2Status::OK);
    fmu.expect_error(fmu.set_real(vr::d, -1e-3), &["`d`", ">= 0"]);
    fmu.expect_error(fmu.set_real(vr::dt_max, 0.0), &["`dt_max`", "> 0"]);
    fmu.expect_error(
        fmu.set_integer(vr::elements, 1),
        &["`elements`", "[2, 100000]"],
    );
    fmu.expect_error(fmu.set_integer(vr::well, 2), &["`well`", "[-1, 1]"]);
    fmu.expect_error(fmu.set_integer(vr::well, 0), &["`well`", "+1 or -1"]);
    assert_eq!(fmu.set_integer(vr::well, -1), fmi2Status::OK);
    assert_eq!(fmu.set_integer(vr::well, 1), fmi2Status::OK);
    fmu.expect_error(
        fmu.set_real(vr::f_ctrl, f64::NEG_INFINITY),
        &["`f_ctrl`", "-inf"],
    );
    fmu.expect_error(fmu.set_real(vr::F, f64::NAN), &["`F`"]);
    // An array with one bad value changes nothing.
    let vrs = [vr::E, vr::nu, vr::L];
    let s = unsafe { fmi2SetReal(fmu.c, vrs.as_ptr(), 3, [2e4, 0.3, -10.0].as_ptr()) };
    fmu.expect_error(s, &["`L`"]);
    assert_eq!(fmu.reals(&vrs), [1.2e4, 0.2, 10.0]);
    let s = unsafe { fmi2SetReal(fmu.c, vrs.as_ptr(), 3, [2e4, 0.3, 12.0].as_ptr()) };
    assert_eq!(s, fmi2Status::OK);
    assert_eq!(fmu.reals(&vrs), [2e4, 0.3, 12.0]);
    // Bad experiment settings.
    unsafe {
        fmu.expect_error(
            fmi2SetupExperiment(fmu.c, 0, 0.0, f64::NAN, 0, 0.0),
            &["startTime = NaN"],
        );
        fmu.expect_error(
            fmi2SetupExperiment(fmu.c, 0, 0.0, 1.0, 1, 0.5),
            &["stopTime = 0.5"],
        );
        fmu.expect_error(
            fmi2SetupExperiment(fmu.c, 1, -1.0, 0.0, 0, 0.0),
            &["tolerance = -1"],
        );
    }
}

// ----- pointers -------------------------------------------------------------------------------

#[test]
fn null_and_garbage_pointers() {
    let fmu = Fmu::new(BEAM);
    let c = fmu.c;
    let mut x = 0.0;
    let i = 0;
    unsafe {
        // No instance: fmi2Error, nothing to log with.
        assert_eq!(
            fmi2GetReal(null_mut(), &vr::E, 1, &mut x),
            fmi2Status::Error
        );
        assert_eq!(fmi2EnterInitializationMode(null_mut()), fmi2Status::Error);
        assert_eq!(fmi2DoStep(null_mut(), 0.0, H, 0), fmi2Status::Error);
        fmi2FreeInstance(null_mut());
        let mut garbage = [0u64; 64];
        let g = garbage.as_mut_ptr() as fmi2Component;
        assert_eq!(fmi2Reset(g), fmi2Status::Error);
        assert_eq!(fmi2SetReal(g, &vr::E, 1, &1.0), fmi2Status::Error);
        fmi2FreeInstance(g);
        let misaligned = (garbage.as_mut_ptr() as *mut u8).add(1) as fmi2Component;
        assert_eq!(fmi2Terminate(misaligned), fmi2Status::Error);
        assert!(
            garbage.iter().all(|&w| w == 0),
            "nothing written through a bad instance"
        );

        fmu.expect_error(fmi2GetReal(c, null(), 1, &mut x), &["vr[] is NULL"]);
        fmu.expect_error(fmi2GetReal(c, &vr::E, 1, null_mut()), &["value[] is NULL"]);
        fmu.expect_error(fmi2SetReal(c, &vr::E, 1, null()), &["value[] is NULL"]);
        fmu.expect_error(
            fmi2GetInteger(c, &vr::elements, 1, null_mut()),
            &["value[]"],
        );
        fmu.expect_error(fmi2SetInteger(c, null(), 2, &i), &["vr[]"]);
        fmu.expect_error(fmi2GetBoolean(c, null(), 1, null_mut()), &["NULL"]);
        fmu.expect_error(fmi2SetString(c, &0, 1, null()), &["NULL"]);
        // nvr == 0 with NULL arrays is fine.
        assert_eq!(fmi2GetReal(c, null(), 0, null_mut()), fmi2Status::OK);
        assert_eq!(fmi2SetInteger(c, null(), 0, null()), fmi2Status::OK);
        assert_eq!(fmi2GetBoolean(c, null(), 0, null_mut()), fmi2Status::OK);
        assert_eq!(fmi2SetString(c, null(), 0, null()), fmi2Status::OK);
        fmu.expect_error(
            fmi2SetDebugLogging(c, fmi2True, 2, null()),
            &["categories[] is NULL"],
        );
        let cats = [c"logEvents".as_ptr(), null()];
        fmu.expect_error(
            fmi2SetDebugLogging(c, fmi2True, 2, cats.as_ptr()),
            &["categories[1] is NULL"],
        );
        fmu.expect_error(fmi2GetFMUstate(c, null_mut()), &["FMUstate"]);
        fmu.expect_error(fmi2SetFMUstate(c, null_mut()), &["FMUstate is NULL"]);
        let mut fake = [0u64; 8];
        fmu.expect_error(
            fmi2SetFMUstate(c, fake.as_mut_ptr() as fmi2FMUstate),
            &["not a live FMU state"],
        );
        let mut size = 0usize;
        fmu.expect_error(
            fmi2SerializedFMUstateSize(c, null_mut(), &mut size),
            &["FMUstate is NULL"],
        );
        assert_eq!(fmi2FreeFMUstate(c, null_mut()), fmi2Status::OK);
        let mut none: fmi2FMUstate = null_mut();
        assert_eq!(fmi2FreeFMUstate(c, &mut none), fmi2Status::OK);
        let mut fake_ptr = fake.as_mut_ptr() as fmi2FMUstate;
        fmu.expect_error(
            fmi2FreeFMUstate(c, &mut fake_ptr),
            &["not a live FMU state"],
        );
        fmu.expect_error(
            fmi2DeSerializeFMUstate(c, null(), 10, &mut none),
            &["serializedState is NULL"],
        );
        fmu.init();
        fmu.expect_error(
            fmi2GetRealStatus(c, fmi2LastSuccessfulTime, null_mut()),
            &["value is NULL"],
        );
        fmu.expect_error(
            fmi2GetBooleanStatus(c, fmi2Terminated, null_mut()),
            &["value is NULL"],
        );
        fmu.expect_error(
            fmi2GetStatus(c, fmi2DoStepStatus, null_mut()),
            &["value is NULL"],
        );
    }
    // Every refusal above left the instance usable.
    run(&fmu, 1);
}
