//! The energy ledger through impacts (`docs/model.md`, sections 10 and 14): the example
//! `ImpactingCantilever` (a steel strip shaken against a stop near its tip), undamped (`d = 0`),
//! with the energy-momentum integrator: the stop's force enters each step through its exact
//! discrete gradient, so `energy_error` stays at round-off through every impact; with a
//! contact dashpot `E_damped` books exactly the work the dashpot does and the ledger stays
//! closed.
//!
//! Run: `cargo test --profile quick --test suite contact_energy:: -- --nocapture`
use crate::common;

use common::contact::impacting_cantilever;
use common::output;
use georod::simulation::Simulation;

/// The example with `d = 0`, the energy-momentum scheme and the stop's dashpot `c`.
fn cantilever(c: f64) -> Simulation {
    impacting_cantilever(&[("d", 0.0), ("integrator", 2.0), ("F", 2.0)], c).unwrap()
}

/// Steps of 1 ms until ten impacts (a step that touches after one that did not): the largest
/// `|energy_error|`, the largest energy held (kinetic plus strain) and the impacts counted.
fn through_ten_impacts(sim: &mut Simulation) -> (f64, f64, usize) {
    let (mut worst, mut scale, mut impacts, mut touching) = (0.0f64, 0.0f64, 0, false);
    while impacts < 10 {
        sim.advance(1e-3).expect("a step");
        worst = worst.max(output(sim, "energy_error").abs());
        scale = scale.max(output(sim, "E_kin") + output(sim, "E_strain"));
        let now = output(sim, "stop_contact") > 0.0;
        impacts += usize::from(now && !touching);
        touching = now;
        assert!(sim.time() < 5.0, "ten impacts within 5 s");
    }
    (worst, scale, impacts)
}

/// Without a contact dashpot the ledger closes to round-off: 20 sub-steps per communication
/// step, each converged to Newton's tolerance (1e-10 of its increment), over thousands of
/// sub-steps; 1e-11 of the energy held leaves room over the measured 4e-13.
#[test]
fn the_ledger_closes_through_ten_impacts() {
    let mut sim = cantilever(0.0);
    let (worst, scale, impacts) = through_ten_impacts(&mut sim);
    println!(
        "{impacts} impacts in {:.3} s: largest |energy_error| {worst:.2e} J, energy up to \
         {scale:.3e} J ({:.1e} of it), W_ext {:.3e} J, E_damped {:.1e} J",
        sim.time(),
        worst / scale,
        output(&sim, "W_ext"),
        output(&sim, "E_damped")
    );
    assert_eq!(output(&sim, "E_damped"), 0.0);
    assert!(worst < 1e-11 * scale, "{worst}");
}

/// With a contact dashpot, `E_damped` is exactly the work the dashpot did (the ledger stays
/// closed to the same round-off) and it is not small: the impacts lose energy.
#[test]
fn the_contact_dashpot_work_is_e_damped() {
    let mut sim = cantilever(2.0);
    let (worst, scale, impacts) = through_ten_impacts(&mut sim);
    let damped = output(&sim, "E_damped");
    println!(
        "{impacts} impacts in {:.3} s: E_damped {damped:.6e} J, largest |energy_error| \
         {worst:.2e} J, energy up to {scale:.3e} J ({:.1e} of it)",
        sim.time(),
        worst / scale
    );
    assert!(damped > 1e-3 * scale, "{damped}");
    assert!(worst < 1e-11 * scale, "{worst}");
}
