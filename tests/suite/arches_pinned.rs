//! Issue 5: the bistable PinnedArch (defaults: L = 32, H = 2, 10 elements). Its zero-load
//! equilibria come from the static path (traced both ways, located by bisection): z1 (the
//! unloaded arch) and z3 (inverted) are stable, z2 between them is unstable. Dynamically, with
//! the scene's damping and no excitation, a small disturbance of z1 or z3 dies out (the run
//! returns to the same equilibrium), while the same disturbance of z2 sends the arch to z1 or z3.
//! The natural frequencies about z1 and z3 are real, z2 has negative `omega^2`.
//!
//! Run: `cargo test --profile quick --test suite arches_pinned:: -- --nocapture`
use crate::common;
use georod::integrator::continuation::{
    equilibria_at_load, follow_both_ways, ContinuationSettings, Equilibrium,
};
use georod::model::modal::modes;
use georod::model::rod::U2;

use common::{output, simulation};

/// z1, z2, z3 in order of decreasing midspan deflection.
fn zero_load_equilibria() -> (georod::model::Rod, Vec<(f64, Equilibrium)>) {
    let sim = simulation("PinnedArch", &[]);
    let rise = common::param(&sim, "H");
    let rod = sim.rod().clone();
    let mut q = vec![0.0; rod.dofs()];
    rod.add_point_transverse_load(&mut q, rod.midspan(), 1.0);
    let mut settings = ContinuationSettings::for_rod(&rod, 50.0);
    settings.max_displacement = 4.0 * rise;
    let (path, _) = follow_both_ways(&rod, &vec![0.0; rod.dofs()], 0.0, &q, &settings);
    let mid = rod.midspan();
    let mut eq: Vec<(f64, Equilibrium)> = equilibria_at_load(&rod, &q, &path, 0.0, &settings)
        .into_iter()
        .map(|e| (rod.interpolate(&e.u, mid, U2), e))
        .collect();
    eq.sort_by(|a, b| b.0.total_cmp(&a.0));
    eq.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-8);
    (rod, eq)
}

/// Damped free motion from `u` with a disturbance velocity `v_mid0` (the crown node's `u2`
/// velocity and, to break the symmetry, a quarter of it at the quarter-span node); returns
/// `w_mid` after `duration`.
fn release(u: &[f64], v_crown: f64, duration: f64) -> f64 {
    let mut sim = simulation("PinnedArch", &[]);
    let mut s = sim.snapshot();
    s.displacements.copy_from_slice(u);
    let nodes = s.velocities.len() / 3;
    s.velocities[3 * (nodes / 2) + U2] = -v_crown;
    s.velocities[3 * (nodes / 4) + U2] = -0.25 * v_crown;
    sim.restore(&s).expect("restore");
    let h = 1e-3;
    for _ in 0..(duration / h).round() as usize {
        sim.advance(h).expect("step");
    }
    output(&sim, "w_mid")
}

/// w_mid of z2 and z3 as this code computed them (regression guard, see below).
const REGRESSION_Z2: f64 = -2.6675217316931263;
const REGRESSION_Z3: f64 = -3.99334691540843;

/// The stability pattern (z1, z3 stable, z2 unstable; modal and dynamic checks agree) is the
/// physics checked here; the positions of z2 and z3 are regression guards.
#[test]
fn pinned_arch_equilibria_stability_and_return() {
    let (rod, eq) = zero_load_equilibria();
    let ws: Vec<f64> = eq.iter().map(|e| e.0).collect();
    let negative: Vec<usize> = eq.iter().map(|e| e.1.negative_eigenvalues).collect();
    println!("PinnedArch zero-load equilibria: w_mid = {ws:?}, negative eigenvalues {negative:?}");
    assert_eq!(eq.len(), 3, "expected z1, z2, z3");
    assert!(ws[0].abs() < 1e-12);
    // Regression guard, not an independent reference: z2 and z3 are this code's own values
    // (docs/arches.md, first found in issue 5; no closed form exists for the inverted circular
    // arch). They pin the static model and the continuation against unintended change: located
    // by bisection to ~1e-12, so 1e-8 leaves room for round-off only.
    assert!((ws[1] - REGRESSION_Z2).abs() < 1e-8, "z2 moved: {}", ws[1]);
    assert!((ws[2] - REGRESSION_Z3).abs() < 1e-8, "z3 moved: {}", ws[2]);
    assert_eq!(negative[0], 0);
    assert!(negative[1] > 0);
    assert_eq!(negative[2], 0);
    for (name, (w, e)) in ["z1", "z2", "z3"].iter().zip(&eq) {
        let m = modes(&rod, &e.u);
        println!(
            "  {name} (w_mid = {w:.4}): omega^2 = {:.4e}, {:.4e}, {:.4e}",
            m[0].omega_squared, m[1].omega_squared, m[2].omega_squared
        );
        let unstable = m.iter().filter(|m| m.omega_squared < 0.0).count();
        assert_eq!(unstable, e.negative_eigenvalues, "{name}");
    }
    // A disturbance of 20 (crown velocity; the static deflection scale is 1, the lowest
    // frequency ~1.2e3 rad/s, so the crown moves by about 0.02) and 0.1 s of free damped motion
    // (the translational damping decays like exp(-250 t)).
    let disturbance = 20.0;
    for (k, sign) in [(0, 1.0), (0, -1.0), (2, 1.0), (2, -1.0)] {
        let (w0, e) = &eq[k];
        let w = release(&e.u, sign * disturbance, 0.1);
        println!(
            "  from z{} ({w0:.4}) disturbed by {:+}: w_mid = {w:.6} after 0.1 s ({:.1e} off)",
            k + 1,
            sign * disturbance,
            w - w0
        );
        assert!((w - w0).abs() < 1e-4, "z{} did not return: {w}", k + 1);
    }
    for sign in [1.0, -1.0] {
        let (w0, e) = &eq[1];
        let w = release(&e.u, sign * disturbance, 0.1);
        println!(
            "  from z2 ({w0:.4}) disturbed by {:+}: w_mid = {w:.6} after 0.1 s ({:.1e} from z1, \
             {:.1e} from z3)",
            sign * disturbance,
            w - ws[0],
            w - ws[2]
        );
        let near = |z: f64| (w - z).abs() < 1e-3;
        assert!(near(ws[0]) || near(ws[2]), "z2 disturbed ended at {w}");
    }
}
