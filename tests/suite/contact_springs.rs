//! Hardening and softening springs (`[[spring]] k3`): force `k u + k3 u^3` from the base.
//! - a stiff beam heaving on two such springs, released at rest: its period against the exact
//!   Duffing period at the amplitude it reaches (a complete elliptic integral), and at small
//!   amplitudes the linear period;
//! - the same beam with the springs' bases shaken through their inputs, energy-momentum
//!   integrator: the energy ledger (the cubic parts' energy in `E_strain`, the bases' work in
//!   `W_supports`) closes to round-off, and `<spring>_force` is the spring's force.
//!
//! Run: `cargo test --profile quick --test suite contact_springs:: -- --nocapture`
use crate::common;

use common::contact::release;
use common::{output, set_input, simulation_of};
use georod::simulation::Simulation;
use std::f64::consts::PI;

const K: f64 = 1e5;
const MASS: f64 = 7850.0 * 0.01;
const DT: f64 = 1e-5;

/// A 1 m beam, 1e5 times as stiff as steel (it heaves as a rigid body: see
/// tests/suite/contact_stops.rs), on two springs `k = K`, `k3` at its ends, guided along e2.
fn duffing(k3: f64, integrator: f64, motion: &str) -> String {
    let head = common::contact::guided_block("Duffing", DT, integrator);
    format!(
        r#"{head}[[spring]]
name = "left"
at = 0.0
dof = "u2"
k = {K}
k3 = {k3}
motion = "{motion}"
[[spring]]
name = "right"
at = 1.0
dof = "u2"
k = {K}
k3 = {k3}
motion = "{motion}"
[[sensor]]
name = "mid"
at = 0.5
quantity = "u2"
[[sensor]]
name = "end"
at = 0.0
quantity = "u2"
"#
    )
}

/// The complete elliptic integral of the first kind `K(m) = int_0^(pi/2) (1 - m sin^2)^(-1/2)`
/// (parameter `m < 1`, negative too) by the arithmetic-geometric mean.
fn elliptic_k(m: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    // Quadratic convergence: a few iterations reach round-off (where a and b may stay an ulp
    // apart).
    for _ in 0..30 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// The period of `x'' + w0^2 x + eps x^3 = 0` at the amplitude `a`:
/// `4 K(m) / sqrt(w0^2 + eps a^2)`, `m = eps a^2 / (2 (w0^2 + eps a^2))`.
fn duffing_period(w0: f64, eps: f64, a: f64) -> f64 {
    let s = w0 * w0 + eps * a * a;
    4.0 * elliptic_k(eps * a * a / (2.0 * s)) / s.sqrt()
}

/// Period from the upward zero crossings (linearly interpolated) over about five periods, and
/// the largest displacement reached.
fn period_and_amplitude(sim: &mut Simulation, periods: f64, guess: f64) -> (f64, f64) {
    let steps = (periods * guess / DT) as usize;
    let (mut crossings, mut top) = (Vec::new(), f64::MIN);
    let (mut t0, mut x0) = (0.0, output(sim, "mid"));
    for _ in 0..steps {
        sim.advance(DT).expect("a step");
        let (t, x) = (sim.time(), output(sim, "mid"));
        if x0 < 0.0 && x >= 0.0 {
            crossings.push(t0 + (t - t0) * x0 / (x0 - x));
        }
        top = top.max(x);
        (t0, x0) = (t, x);
    }
    let n = crossings.len() - 1;
    ((crossings[n] - crossings[0]) / n as f64, top)
}

/// Hardening (k3 > 0) and softening (k3 < 0, below the peak at |u| = sqrt(k / (3 |k3|)) = 18 mm)
/// at amplitudes where the cubic part matters (eps a^2 / w0^2 from -0.2 to 4) and a small one.
/// Error budget: the schemes' period error `(w dt)^2 / 12` at the Duffing's own frequency,
/// below 2e-7 here, and the amplitude measured at a sample (a step of 1e-5 s around the top:
/// second order in the amplitude's error, which enters the period to first order: 1e-8):
/// 1e-6 leaves room.
#[test]
fn the_duffing_period_at_the_measured_amplitude() {
    let w0 = (2.0 * K / MASS).sqrt();
    for integrator in [1.0, 2.0] {
        for (k3, a) in [(1e9, 2e-2), (1e9, 5e-3), (-1e8, 1.5e-2), (1e9, 1e-5)] {
            let eps = 2.0 * k3 / MASS;
            let guess = duffing_period(w0, eps, a);
            let mut sim = simulation_of(&duffing(k3, integrator, "none"), &[]);
            release(&mut sim, a, 0.0);
            let (period, top) = period_and_amplitude(&mut sim, 5.3, guess);
            let exact = duffing_period(w0, eps, top);
            let error = (period - exact).abs() / exact;
            println!(
                "integrator {integrator}, k3 {k3:e}, released at {a:e}: amplitude {top:.9e}, \
                 eps a^2 / w0^2 = {:.3}, period {period:.9} s, Duffing {exact:.9} s (linear \
                 {:.9} s), relative error {error:.2e}",
                eps * top * top / (w0 * w0),
                2.0 * PI / w0
            );
            assert!(error < 1e-6, "{error}");
            if a < 1e-4 {
                let linear = 2.0 * PI / w0;
                assert!((period - linear).abs() < 1e-6 * linear);
            }
        }
    }
}

/// Both springs' bases shaken (1 mm at 30 Hz, through `left_base`, `right_base`), the
/// energy-momentum scheme: the ledger closes to round-off (Newton's tolerance over 20000
/// sub-steps: 1e-11 of the energy held, against the measured 2e-13) and each spring's force
/// output is the force the step applied (one sub-step per communication step):
/// `-(k (a + b) / 2 + k3 (a + b) (a^2 + b^2) / 4)`, `a`, `b` the stretches at its ends (the
/// cubic part's discrete gradient), to round-off (1e-12 of the force or of 1 N).
#[test]
fn shaken_bases_keep_the_ledger_closed() {
    let mut sim = simulation_of(&duffing(1e9, 2.0, "input"), &[]);
    let (mut worst, mut scale, mut force_error) = (0.0f64, 0.0f64, 0.0f64);
    let (mut u0, mut b0) = (0.0, 0.0);
    for i in 1..=20000 {
        let b = 1e-3 * (2.0 * PI * 30.0 * i as f64 * DT).sin();
        set_input(&mut sim, "left_base", b);
        set_input(&mut sim, "right_base", b);
        sim.advance(DT).expect("a step");
        worst = worst.max(output(&sim, "energy_error").abs());
        scale = scale.max(output(&sim, "E_kin") + output(&sim, "E_strain"));
        let u = output(&sim, "end");
        // The stretches at the step's ends; the linear part at the midpoint, the cubic part's
        // discrete gradient.
        let (ra, rb) = (u0 - b0, u - b);
        let force = -(K * 0.5 * (ra + rb) + 0.25 * 1e9 * (ra + rb) * (ra * ra + rb * rb));
        let reported = output(&sim, "left_force");
        force_error = force_error.max((reported - force).abs() / force.abs().max(1.0));
        (u0, b0) = (u, b);
    }
    println!(
        "largest |energy_error| {worst:.2e} J, energy up to {scale:.3e} J ({:.1e} of it), \
         W_supports {:.3e} J; left_force against the force applied: {force_error:.1e}",
        worst / scale,
        output(&sim, "W_supports")
    );
    assert!(worst < 1e-11 * scale, "{worst}");
    assert!(
        output(&sim, "W_supports").abs() > 1e-3 * scale,
        "the bases work"
    );
    assert!(force_error < 1e-12, "{force_error}");
}
