//! Rayleigh damping `alpha M + beta K0` (`[damping]`): the measured logarithmic decrement of
//! the first two bending modes is `alpha / (2 omega) + beta omega / 2`, `ratio` gives the
//! requested ratio at both frequencies, the energy ledger books the dissipation, and bad
//! `[damping]` tables are refused.
//!
//! Run: `cargo test --profile quick --test suite rayleigh_damping:: -- --nocapture`
use crate::common;

use common::{loads, output, Table};
use georod::integrator::{DynamicState, Midpoint};
use georod::model::modal::{dense_tangent_and_mass, free_dofs, modes};
use georod::model::rod::{U1, U2};
use georod::model::{ReferenceCurve, Rod, Section};
use georod::scene::damping::Rayleigh;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::f64::consts::PI;
use std::sync::Arc;

/// A simply supported steel beam, 4 m, 50 x 100 mm, 20 elements, no other damping.
fn beam() -> Rod {
    let section = Section::rectangular(210e9, 0.3, 7850.0, 0.05, 0.1);
    let mut rod = Rod::new(ReferenceCurve::Straight { length: 4.0 }, section, 0.0, 20);
    rod.fix(0, U1);
    rod.fix(0, U2);
    rod.fix(rod.last_node(), U2);
    rod
}

/// The damping ratio measured from the free decay of `mode` (of `rod`, about the straight
/// state) by the logarithmic decrement over `cycles` periods: the rod starts displaced along
/// the mode (by 1e-6 of its length: linear) and at rest; the modal coordinate
/// `q = phi^T M u` is sampled 400 times per period and its maxima located by parabolas.
fn measured_ratio(rod: &Rod, mode: usize, cycles: usize) -> (f64, f64) {
    let zero = vec![0.0; rod.dofs()];
    let modes = modes(rod, &zero);
    let (phi, omega) = (&modes[mode].shape, modes[mode].omega());
    let peak = phi.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let scale = 4e-6 / peak;
    let mut state = DynamicState::at_rest(phi.iter().map(|x| scale * x).collect());
    let dt = 2.0 * PI / omega / 400.0;
    let none = loads(rod, true, 0.0, 0.0, 0.0);
    let mut mid = Midpoint::new(rod);
    let modal = |u: &[f64]| {
        let mut mu = vec![0.0; u.len()];
        rod.add_mass_times(u, &mut mu, 1.0);
        mu.iter().zip(phi).map(|(a, b)| a * b).sum::<f64>()
    };
    let mut q = vec![modal(&state.u)];
    for n in 0..400 * cycles + 10 {
        mid.step(rod, &none, &mut state, n as f64 * dt, dt, &[])
            .expect("step");
        q.push(modal(&state.u));
    }
    // Maxima of q (the first is the start), each refined by the parabola through three samples.
    let mut maxima = vec![q[0]];
    for k in 1..q.len() - 1 {
        if q[k] > q[k - 1] && q[k] >= q[k + 1] {
            let (a, b, c) = (q[k - 1], q[k], q[k + 1]);
            maxima.push(b + (a - c).powi(2) / (8.0 * (2.0 * b - a - c)));
        }
    }
    let n = cycles.min(maxima.len() - 1);
    let delta = (maxima[0] / maxima[n]).ln() / n as f64;
    (delta / (4.0 * PI * PI + delta * delta).sqrt(), omega)
}

#[test]
fn logarithmic_decrement_of_the_first_two_modes_is_rayleighs() {
    let (alpha, beta) = (2.0, 4e-5);
    let mut rod = beam();
    rod.with_rayleigh(alpha, beta, &vec![0.0; rod.dofs()]);
    let mut t = Table::new(
        "simply supported steel beam, 4 m, 20 elements, alpha = 2 /s, beta = 4e-5 s: damping \
         ratio from the logarithmic decrement vs alpha / (2 omega) + beta omega / 2",
    );
    for mode in [0, 1] {
        let (measured, omega) = measured_ratio(&rod, mode, 4);
        let expected = Rayleigh { alpha, beta }.ratio_at(omega);
        let error = (measured - expected).abs() / expected;
        t.row(format_args!(
            "  mode {}: omega {omega:.2} rad/s, ratio {measured:.6e} vs {expected:.6e}, error {error:.1e}",
            mode + 1
        ));
        // The midpoint rule damps a mode of omega dt = 2 pi / 400 with the continuous ratio to
        // O((omega dt)^2) = 2.5e-4 (measured 4e-5); 5e-4 catches a missing term (the alpha and
        // beta parts are each a fifth of the ratio or more here).
        assert!(error < 5e-4, "mode {}: {measured} vs {expected}", mode + 1);
    }
}

#[test]
fn ratio_gives_that_damping_at_both_frequencies() {
    let undamped = beam();
    let zero = vec![0.0; undamped.dofs()];
    let frequencies: Vec<f64> = modes(&undamped, &zero)[..2]
        .iter()
        .map(|m| m.hertz())
        .collect();
    let ratio = 0.02;
    let rayleigh = Rayleigh::from_ratio(ratio, frequencies[0], frequencies[1]);
    let mut rod = beam();
    rod.with_rayleigh(rayleigh.alpha, rayleigh.beta, &zero);
    for (mode, f) in frequencies.iter().enumerate() {
        assert!((rayleigh.ratio_at(2.0 * PI * f) - ratio).abs() < 1e-15);
        let (measured, _) = measured_ratio(&rod, mode, 4);
        println!("mode {}: {f:.3} Hz, measured ratio {measured:.6}", mode + 1);
        assert!(
            (measured / ratio - 1.0).abs() < 2e-3,
            "mode {mode}: {measured}"
        );
    }
}

/// The paper's buckled beam with `[damping]` added.
fn buckled(damping: &str, integrator: f64, dt_max: f64) -> Simulation {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/BuckledBeam.toml"
    ))
    .unwrap()
        + damping;
    let scene = Arc::new(Scene::parse(&text, "buckled with [damping]").expect("scene"));
    let values = scene
        .values_with([("integrator", integrator), ("F", 1.0), ("dt_max", dt_max)])
        .unwrap();
    Simulation::new(scene, values).expect("initial state")
}

/// The Simulation's damping matrix is `d`'s plus `alpha M + beta K0`, with K0 the tangent of
/// the buckled initial state: its dissipation rate `v^T C v` against the dense matrices.
#[test]
fn the_damping_matrix_is_alpha_m_plus_beta_k0_of_the_initial_state() {
    let (alpha, beta) = (30.0, 2e-6);
    let plain = buckled("", 1.0, 1e-5);
    let damped = buckled(
        &format!("\n[damping]\nalpha = {alpha}\nbeta = {beta}\n"),
        1.0,
        1e-5,
    );
    let rod = damped.rod();
    let u0 = &damped.state().u;
    let (k, m) = dense_tangent_and_mass(rod, u0);
    let free = free_dofs(rod);
    let v: Vec<f64> = (0..rod.dofs())
        .map(|i| {
            if rod.fixed[i] {
                0.0
            } else {
                (0.37 * i as f64).sin()
            }
        })
        .collect();
    let vf = nalgebra::DVector::from_iterator(free.len(), free.iter().map(|&i| v[i]));
    let rayleigh = vf.dot(&((alpha * &m + beta * &k) * &vf));
    let expected = plain.rod().dissipation_rate(&v) + rayleigh;
    let got = rod.dissipation_rate(&v);
    assert!(
        (got - expected).abs() < 1e-12 * expected,
        "{got} vs {expected}"
    );
}

/// The energy ledger books the Rayleigh dissipation: `energy_error` stays at the level it has
/// without it, while `E_damped` grows. Midpoint rule: its own O(dt^2) energy error, which the
/// added damping does not raise. Energy-momentum scheme: exact for translational damping; the
/// Rayleigh terms act on the rotations too, which the scheme advances by their Cayley increment
/// while the damping acts on `dw`, a mismatch of O(dw^3) per step (as with `[model]
/// rotational_damping`): the error falls by 4 when the step is halved.
#[test]
fn the_energy_ledger_books_rayleigh_damping() {
    let mut t = Table::new("buckled beam, F = 1, 0.02 s: energy ledger with Rayleigh");
    let run = |damping: &str, integrator: f64, dt_max: f64| {
        let mut sim = buckled(damping, integrator, dt_max);
        for _ in 0..200 {
            sim.advance(1e-4).unwrap();
        }
        let get = |name| output(&sim, name);
        (get("energy_error"), get("E_damped"), get("W_ext"))
    };
    let rayleigh = "\n[damping]\nratio = 0.2\nfrequencies = [100.0, 1000.0]\n";
    for integrator in [1.0, 2.0] {
        let (error0, damped0, work0) = run("", integrator, 1e-5);
        let (error1, damped1, work1) = run(rayleigh, integrator, 1e-5);
        t.row(format_args!(
            "  integrator {integrator}: E_damped {damped0:.4e} -> {damped1:.4e}, energy_error \
             {error0:.1e} -> {error1:.1e} (W_ext {work0:.3e}, {work1:.3e})"
        ));
        assert!(
            damped1 > 1.1 * damped0,
            "Rayleigh dissipated little: {damped1}"
        );
        let bound = match integrator {
            // The midpoint rule's own error (4e-5 of the work here), not raised.
            1.0 => 2.0 * error0.abs(),
            // 5e-9 of the work measured; a missing term would be 2 J.
            _ => 2e-8 * work1.abs(),
        };
        assert!(
            error1.abs() < bound,
            "integrator {integrator}: {error1:e} vs {error0:e} without Rayleigh"
        );
    }
    let (coarse, _, _) = run(rayleigh, 2.0, 1e-5);
    let (fine, _, _) = run(rayleigh, 2.0, 5e-6);
    t.row(format_args!(
        "  energy-momentum, dt_max 1e-5 -> 5e-6: energy_error {coarse:.2e} -> {fine:.2e}"
    ));
    assert!((3.0..5.0).contains(&(coarse / fine)), "{coarse} -> {fine}");
}

#[test]
fn bad_damping_tables_are_refused() {
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/BuckledBeam.toml"
    ))
    .unwrap();
    for (table, parts) in [
        (
            "ratio = 0.05\nfrequencies = [5.0, 5.0]",
            vec!["damping.frequencies", "different"],
        ),
        (
            "ratio = 0.05\nfrequencies = [5.0]",
            vec!["damping.frequencies", "two"],
        ),
        ("ratio = 0.05", vec!["damping.frequencies", "missing"]),
        ("frequencies = [1.0, 2.0]", vec!["damping.ratio", "missing"]),
        (
            "ratio = 0.05\nfrequencies = [1.0, 2.0]\nalpha = 1.0",
            vec!["damping.ratio", "not both"],
        ),
        ("alpha = -1.0", vec!["damping.alpha", ">= 0"]),
        ("beta = -1e-3", vec!["damping.beta", ">= 0"]),
        (
            "ratio = -0.1\nfrequencies = [1.0, 2.0]",
            vec!["damping.ratio", ">= 0"],
        ),
        (
            "ratio = 0.1\nfrequencies = [0.0, 2.0]",
            vec!["damping.frequencies", "> 0"],
        ),
        ("gamma = 1.0", vec!["damping.gamma", "unknown field"]),
        ("", vec!["[damping]", "empty"]),
    ] {
        let text = format!("{base}\n[damping]\n{table}\n");
        common::assert_refused(table, &text, &parts);
    }
}
