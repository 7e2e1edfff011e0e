//! Stability study (issue 7), part 4: very large steps, very large excitation, the number of
//! elements from 2 to 10,000 and parameters at the edges of their ranges, through `Simulation`
//! (what an FMU runs). The contract: every communication step either converges to finite,
//! bounded outputs or fails with `SimError::StepFailed` leaving the state exactly as it was
//! (the FMU's fmi2Discard); nothing panics, nothing is NaN; a refused value names its variable.
//!
//! Run: `cargo test --profile quick --test suite stability_extremes:: -- --nocapture`
use crate::common;

use common::{output, scene, Table};
use georod::scene::variables::{variables, Role};
use georod::simulation::{SimError, Simulation};
use std::f64::consts::PI;
use std::sync::Arc;

/// The paper's scenes, deliberately by name: the forcing levels of this study (beam 7, arches
/// 1000, ...) and the `w_mid` it reports are theirs.
const SCENES: [&str; 3] = ["BuckledBeam", "PinnedArch", "ClampedArch"];

/// Every output of the simulation's scene (sensors, reactions, shape, energies), by name.
fn outputs(sim: &Simulation) -> Vec<(String, f64)> {
    variables(sim.scene())
        .into_iter()
        .filter_map(|v| match v.role {
            Role::Output(id) => Some((v.name, sim.output(id))),
            _ => None,
        })
        .collect()
}

/// Output values as bit patterns (NaN-safe equality).
fn output_bits(sim: &Simulation) -> Vec<u64> {
    outputs(sim).iter().map(|(_, x)| x.to_bits()).collect()
}

/// Tally of a run of communication steps.
#[derive(Default, Debug)]
struct Tally {
    ok: usize,
    discarded: usize,
    max_w: f64,
    iterations: u32,
    /// Most halvings of the sub-step in one communication step.
    cuts: u32,
    first_failure: Option<String>,
}

/// `steps` communication steps of `h`; after a discarded step the run continues from the same
/// (unchanged) state with the next step, like a host that retries. Checks the contract.
fn drive(sim: &mut Simulation, h: f64, steps: usize) -> Tally {
    let mut tally = Tally::default();
    for _ in 0..steps {
        let before = sim.snapshot();
        let outputs_before = output_bits(sim);
        match sim.advance(h) {
            Ok(report) => {
                tally.ok += 1;
                tally.iterations = tally.iterations.max(report.newton_iterations);
                tally.cuts = tally.cuts.max(report.cuts);
                for (name, v) in outputs(sim) {
                    assert!(v.is_finite(), "{name} = {v} after a converged step");
                }
                tally.max_w = tally.max_w.max(output(sim, "w_mid").abs());
            }
            Err(SimError::StepFailed { reason, .. }) => {
                tally.discarded += 1;
                tally.first_failure.get_or_insert(reason);
                assert_eq!(sim.snapshot(), before, "state changed by a failed step");
                assert_eq!(output_bits(sim), outputs_before);
                // A host would now give up or change something; retrying is pointless (the
                // core is deterministic), so stop.
                break;
            }
            Err(e) => panic!("unexpected error {e}"),
        }
    }
    tally
}

/// The simulation of a scene with overridden parameters, or why it could not be built.
fn build(kind: &str, overrides: &[(&str, f64)]) -> Result<Simulation, SimError> {
    let scene = scene(kind);
    let values = scene.values_with(overrides.iter().copied())?;
    Simulation::new(Arc::clone(&scene), values)
}

#[test]
fn huge_excitation_and_huge_steps() {
    let mut t = Table::new(
        "very large excitation with 1 to 2.2 communication steps per forcing period and \
         dt_max = h (one sub-step each, halved up to 5 times on Newton failure): 20 periods. \
         NB with exactly 1 or 2 steps per period a halved sub-step samples the excitation at \
         cos(Omega t_mid) = 0: the step converges without ever seeing the load",
    );
    t.row(format_args!(
        "{:<12} {:>6} {:>7} {:>6} {:>4} {:>6} {:>6} {:>9} {:>6} {:>5}  first failure",
        "scene", "F", "Omega", "h/T", "int", "ok", "disc.", "max|w|", "iter", "cuts"
    ));
    let cases: Vec<(&str, f64, f64)> = vec![
        ("PinnedArch", 500.0, 1000.0),
        ("PinnedArch", 1000.0, 1000.0),
        ("PinnedArch", 3000.0, 1000.0),
        ("ClampedArch", 3000.0, 1000.0),
        ("BuckledBeam", 20.0, 3500.0),
    ];
    let mut converged_any = false;
    for (kind, f, omega) in cases {
        for per_period in [1.0, 1.1, 2.0, 2.2] {
            for integrator in [1.0, 2.0] {
                let period = 2.0 * PI / omega;
                let h = period / per_period;
                let mut sim = build(
                    kind,
                    &[
                        ("F", f),
                        ("Omega", omega),
                        ("dt_max", h),
                        ("integrator", integrator),
                    ],
                )
                .expect("initial state");
                let tally = drive(&mut sim, h, (20.0 * per_period) as usize);
                converged_any |= tally.discarded == 0;
                t.row(format_args!(
                    "{kind:<12} {f:>6} {omega:>7} {:>6} {integrator:>4} {:>6} {:>6} {:>9.3} {:>6} {:>5}  {}",
                    format!("1/{per_period}"),
                    tally.ok,
                    tally.discarded,
                    tally.max_w,
                    tally.iterations,
                    tally.cuts,
                    tally.first_failure.as_deref().unwrap_or("")
                ));
                // Bounded (finite is checked in `drive`): a coarse midpoint step may overshoot
                // (u_(n+1) = u_n + 2 (u_mid - u_n)), so the bound is generous: 10 rod lengths.
                assert!(tally.max_w < 10.0 * sim.rod().curve.length(), "{tally:?}");
            }
        }
    }
    assert!(converged_any);
}

#[test]
fn elements_from_2_to_10000() {
    let mut t = Table::new(
        "number of elements: initial state, then 10 communication steps of 1e-4 s (dt_max = 1e-5), \
         F = 10 x default (beam 7, arches 1000), both integrators",
    );
    t.row(format_args!(
        "{:<12} {:>8} {:>4} {:>6} {:>6} {:>11} {:>6}",
        "scene", "elements", "int", "ok", "disc.", "w_mid", "iter"
    ));
    for kind in SCENES {
        let f = if kind == "BuckledBeam" { 7.0 } else { 1000.0 };
        for elements in [2usize, 3, 4, 10, 100, 1000, 10_000] {
            for integrator in [1.0, 2.0] {
                if elements == 10_000 && integrator == 2.0 {
                    continue; // the same path; keeps the test short
                }
                let overrides = [
                    ("elements", elements as f64),
                    ("F", f),
                    ("integrator", integrator),
                ];
                let mut sim = match build(kind, &overrides) {
                    Ok(s) => s,
                    Err(e) => {
                        t.row(format_args!("{kind:<12} {elements:>8} refused: {e}"));
                        assert!(matches!(e, SimError::InitialState(_)), "{e}");
                        continue;
                    }
                };
                let tally = drive(&mut sim, 1e-4, 10);
                t.row(format_args!(
                    "{kind:<12} {elements:>8} {integrator:>4} {:>6} {:>6} {:>11.4e} {:>6}  {}",
                    tally.ok,
                    tally.discarded,
                    output(&sim, "w_mid"),
                    tally.iterations,
                    tally.first_failure.as_deref().unwrap_or("")
                ));
                if elements >= 4 {
                    assert_eq!(tally.discarded, 0, "{kind} {elements}");
                }
            }
        }
    }
}

#[test]
fn parameters_at_the_edges() {
    let mut t = Table::new(
        "parameters at the edges of their ranges (each alone, other values default; arches \
         with F = 300): initial state, then 20 communication steps of 1e-4 s",
    );
    let edges: Vec<(&str, f64)> = vec![
        ("E", 1e-6),
        ("E", 1e12),
        ("E", 1e100),
        ("nu", -0.9999999999999999), // the declared bounds of (-1, 0.5)
        ("nu", 0.49999999999999994),
        ("rho", 1e-30),
        ("rho", 1e10),
        ("d", 0.0),
        ("d", 1e3),
        ("d", 1e12),
        ("h", 1e-3),
        ("h", 4.0),
        ("b", 1e-6),
        ("dt_max", 1e-8),
        ("dt_max", 1e3),
        ("elements", 2.0),
        ("F", 1e6),
        ("F", -1e6),
        ("Omega", 0.0),
        ("Omega", 1e9),
        ("P0", 50.0),
        ("P0", 1e4),
        ("pre_shortening", 0.0),
        ("pre_shortening", 4.9),
        ("H", 1e-6),
        ("H", 16.0),
    ];
    for kind in SCENES {
        let scene = scene(kind);
        for &(name, value) in &edges {
            let mut params = scene.defaults();
            if scene.param_index(name).is_none() {
                continue; // not a parameter of this scene
            }
            if kind != "BuckledBeam" {
                scene.set(&mut params, "F", 300.0).expect("F"); // the arches' default F is 0
            }
            scene
                .set(&mut params, name, value)
                .expect("inside the range");
            let label = format!("{kind:<12} {name:>14} = {value:<10e}");
            if let Err(e) = scene.check(&params) {
                t.row(format_args!("{label} refused by check: {e}"));
                assert_eq!(e.name, name);
                continue;
            }
            let mut sim = match Simulation::new(Arc::clone(&scene), params) {
                Ok(s) => s,
                Err(e) => {
                    t.row(format_args!("{label} no initial state: {e}"));
                    assert!(matches!(e, SimError::InitialState(_)), "{e}");
                    continue;
                }
            };
            let o = outputs(&sim);
            assert!(
                o.iter().all(|(_, x)| x.is_finite()),
                "{label}: non-finite initial outputs {o:?}"
            );
            let tally = drive(&mut sim, 1e-4, 20);
            t.row(format_args!(
                "{label} ok {:>3}, discarded {}, w_mid {:>11.4e}, E_strain {:>10.3e}, max iter {:>4} {}",
                tally.ok,
                tally.discarded,
                output(&sim, "w_mid"),
                sim.strain_energy(),
                tally.iterations,
                tally.first_failure.as_deref().unwrap_or("")
            ));
        }
    }
}

#[test]
fn refused_values_name_the_variable() {
    let mut t = Table::new("values out of range: refused by Scene::set, naming the variable");
    let bad: Vec<(&str, f64)> = vec![
        ("E", 0.0),
        ("E", -1.0),
        ("E", f64::INFINITY),
        ("nu", -1.0),
        ("nu", 0.5),
        ("nu", 0.51),
        ("rho", 0.0),
        ("d", -1e-9),
        ("b", 0.0),
        ("h", -1.0),
        ("L", 0.0),
        ("elements", 1.0),
        ("elements", 2.5),
        ("elements", 100_001.0),
        ("dt_max", 0.0),
        ("dt_max", f64::NAN),
        ("F", f64::NAN),
        ("Omega", -1.0),
        ("integrator", 3.0),
    ];
    for kind in SCENES {
        let scene = scene(kind);
        for &(name, value) in &bad {
            let mut p = scene.defaults();
            let before = p.clone();
            let e = scene.set(&mut p, name, value).expect_err("must be refused");
            assert_eq!(e.name, name);
            assert!(e.to_string().contains(name), "{e}");
            assert_eq!(p, before, "a refused value changed the parameters");
            if kind == "BuckledBeam" {
                t.row(format_args!("  {name} = {value}: {e}"));
            }
        }
    }
    // Conditions between parameters are checked by Scene::check (and Simulation::new), also
    // naming the variable.
    let e = build("PinnedArch", &[("H", 17.0)]).err().expect("H > L/2");
    assert!(matches!(&e, SimError::Param(p) if p.name == "H"), "{e}");
    // A support off the mesh: the message says which element counts work.
    let e = build("BuckledBeam", &[("elements", 11.0)]);
    assert!(e.is_ok(), "supports at both ends are on every mesh");
}

/// dt_max far below h: one communication step would need h / dt_max sub-steps (here about
/// 1e297): `advance` refuses it at once with a message that says what to change, instead of
/// running for ever, and the state is untouched.
#[test]
fn tiny_dt_max_is_refused() {
    let mut sim = build("BuckledBeam", &[("dt_max", 1e-300)]).expect("initial state");
    let n = sim.substeps_for(1e-3);
    let before = sim.snapshot();
    let start = std::time::Instant::now();
    let e = sim.advance(1e-3).expect_err("too many sub-steps");
    println!("dt_max = 1e-300, h = 1e-3: {n} sub-steps -> {e}");
    assert!(n > georod::simulation::MAX_SUBSTEPS);
    assert!(e.to_string().contains("dt_max"), "{e}");
    assert!(start.elapsed().as_secs_f64() < 1.0);
    assert_eq!(sim.snapshot(), before);
}
