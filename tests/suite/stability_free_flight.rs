//! Stability study (issue 7), part 3: a free-flying rod with large rigid rotations.
//!
//! A straight rod (L = 10, b = h = 1, scenes' material, 20 elements, no support, no load,
//! d = 0) is bent into a half circle (initial curvature pi / L, strain energy ~4.9e3) and
//! released spinning at 300 rad/s about its centre of mass while translating at (30, -20): it
//! turns by about 30 rad (5 revolutions) in 10^4 steps while it vibrates elastically (first
//! free-free bending period ~9e-4 s; dt = 1e-5 s ~ T/90). Both schemes, with the same adaptive
//! step (halving on Newton failure, reported). Conserved: linear momentum (both schemes: exact),
//! angular momentum (midpoint: exact; energy-momentum: second order in dt), energy
//! (energy-momentum: exact).
//!
//! Run: `cargo test --profile quick --test suite stability_free_flight:: -- --nocapture`
use crate::common;
use crate::stability_driver as driver;

use common::Table;
use georod::integrator::{DynamicState, Midpoint, Scheme};
use georod::model::rod::{ROTATION, U1, U2};
use georod::model::{LoadSet, Rod};
use std::f64::consts::PI;
use std::io::Write;

const LENGTH: f64 = 10.0;
const SPIN: f64 = 300.0;

/// The rod bent into a half circle (centre of the arc at the origin of its chord's middle),
/// spinning about its centre of mass and translating.
fn bent_spinning_rod() -> (Rod, DynamicState) {
    let rod = common::straight_rod(LENGTH, 1.0, 1.0, 0.0, 20);
    let mut state = DynamicState::at_rest(vec![0.0; rod.dofs()]);
    let kappa = PI / LENGTH;
    let radius = 1.0 / kappa;
    let mut x = Vec::new();
    for i in 0..rod.nodes() {
        let s = rod.node_s[i];
        // The circle of curvature kappa tangent to e1 at the origin: tangent angle kappa s.
        let p = (
            radius * (kappa * s).sin(),
            radius * (1.0 - (kappa * s).cos()),
        );
        x.push(p);
        state.u[3 * i + U1] = p.0 - s;
        state.u[3 * i + U2] = p.1;
        state.u[3 * i + ROTATION] = kappa * s;
    }
    // Centre of mass (equal node weights are exact enough for the spin axis; momenta are
    // measured, not assumed).
    let n = x.len() as f64;
    let c = x
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p.0 / n, a.1 + p.1 / n));
    for (i, p) in x.iter().enumerate() {
        state.v[3 * i + U1] = -SPIN * (p.1 - c.1) + 30.0;
        state.v[3 * i + U2] = SPIN * (p.0 - c.0) - 20.0;
        state.v[3 * i + ROTATION] = SPIN;
    }
    (rod, state)
}

struct Run {
    completed: usize,
    failure: Option<String>,
    energy: f64,
    linear: f64,
    angular: f64,
    rotation: f64,
    cut_steps: usize,
    mean_iterations: f64,
}

fn run(scheme: Scheme, dt: f64, steps: usize) -> Run {
    let (rod, mut state) = bent_spinning_rod();
    let loads = LoadSet::new(&rod, &[]);
    let mut integrator = Midpoint::new(&rod);
    integrator.scheme = scheme;
    let energy = |s: &DynamicState| rod.kinetic_energy(&s.v) + rod.strain_energy(&s.u);
    let (e0, p0, l0) = (
        energy(&state),
        rod.linear_momentum(&state.v),
        rod.angular_momentum(&state.u, &state.v),
    );
    let mut csv = driver::csv(
        &format!("stability_free_flight_{scheme:?}"),
        &format!("free rod L=10 b=h=1 20 el bent to a half circle, spin {SPIN} rad/s; dt={dt:e}; {scheme:?}"),
        "step,time,rel_energy_error,rel_linear_momentum_error,rel_angular_momentum_error,rotation",
    );
    let every = (steps / 5000).max(1);
    let mut r = Run {
        completed: 0,
        failure: None,
        energy: 0.0,
        linear: 0.0,
        angular: 0.0,
        rotation: 0.0,
        cut_steps: 0,
        mean_iterations: 0.0,
    };
    let mut iterations = 0u64;
    for n in 0..steps {
        match driver::step_adaptive(
            &mut integrator,
            &rod,
            &loads,
            &mut state,
            n as f64 * dt,
            dt,
            5,
        ) {
            Ok(s) => {
                iterations += s.iterations as u64;
                if s.cuts > 0 {
                    r.cut_steps += 1;
                }
            }
            Err(e) => {
                r.failure = Some(format!("step {n}: {e}"));
                break;
            }
        }
        r.completed = n + 1;
        let de = (energy(&state) - e0) / e0;
        let dp = (rod.linear_momentum(&state.v) - p0).norm() / p0.norm();
        let dl = (rod.angular_momentum(&state.u, &state.v) - l0) / l0;
        assert!(de.is_finite() && dp.is_finite() && dl.is_finite());
        r.energy = r.energy.max(de.abs());
        r.linear = r.linear.max(dp);
        r.angular = r.angular.max(dl.abs());
        // Rotation of the body: the mean rotation dof (continuous, not wrapped).
        r.rotation = (0..rod.nodes())
            .map(|i| state.u[3 * i + ROTATION] - rod.node_s[i] * PI / LENGTH)
            .sum::<f64>()
            / rod.nodes() as f64;
        if let Some(f) = csv.as_mut() {
            if (n + 1) % every == 0 {
                writeln!(
                    f,
                    "{},{:e},{de:.6e},{dp:.6e},{dl:.6e},{:.6}",
                    n + 1,
                    (n + 1) as f64 * dt,
                    r.rotation
                )
                .unwrap();
            }
        }
    }
    r.mean_iterations = iterations as f64 / r.completed.max(1) as f64;
    r
}

#[test]
fn free_flight_momenta_and_energy() {
    let steps = driver::steps_from_env(10_000);
    let dt = 1e-5;
    let mut t = Table::new(&format!(
        "free rod L = 10, b = h = 1, 20 el., d = 0, bent to a half circle, spinning at {SPIN} \
         rad/s: {steps} steps of dt = {dt:e} s; Newton tolerance 1e-10 of the increment; max \
         relative changes"
    ));
    t.row(format_args!(
        "{:<16} {:>7} {:>6} {:>10} {:>12} {:>12} {:>12} {:>10}",
        "scheme", "steps", "cut", "rotation", "energy", "lin. mom.", "ang. mom.", "iter/step"
    ));
    let mut runs = Vec::new();
    for scheme in [Scheme::Midpoint, Scheme::EnergyMomentum] {
        let r = run(scheme, dt, steps);
        t.row(format_args!(
            "{:<16} {:>7} {:>6} {:>10.2} {:>12.3e} {:>12.3e} {:>12.3e} {:>10.2}  {}",
            format!("{scheme:?}"),
            r.completed,
            r.cut_steps,
            r.rotation,
            r.energy,
            r.linear,
            r.angular,
            r.mean_iterations,
            r.failure.as_deref().unwrap_or("")
        ));
        runs.push(r);
    }
    // Angular momentum of the energy-momentum scheme against the step, over the same time
    // (1000 steps of dt): at solver tolerance for every step size.
    let short = steps / 10;
    let mut errors = Vec::new();
    for k in 0..4u32 {
        let n = 1usize << k;
        errors.push(run(Scheme::EnergyMomentum, dt / n as f64, short * n).angular);
    }
    t.row(format_args!(
        "energy-momentum, max |dJ|/J0 over {:.3} s with dt, dt/2, dt/4, dt/8: {:.3e} {:.3e} {:.3e} {:.3e}",
        short as f64 * dt,
        errors[0], errors[1], errors[2], errors[3],
    ));
    let (mid, em) = (&runs[0], &runs[1]);
    // Energy-momentum: completes; energy, linear and angular momentum to solver tolerance
    // (1e-10 relative corrections accumulated over 10^4 steps: 1e-8).
    assert_eq!(em.completed, steps, "{:?}", em.failure);
    assert!(em.energy < 1e-8, "energy {}", em.energy);
    assert!(em.linear < 1e-9, "linear momentum {}", em.linear);
    assert!(em.angular < 1e-9, "angular momentum {}", em.angular);
    assert!(
        errors.iter().all(|&e| e < 1e-9),
        "angular momentum {errors:?}"
    );
    assert!(em.rotation.abs() > 25.0, "rotation {}", em.rotation);
    // Midpoint: both momenta to solver tolerance for as long as it runs (its energy is reported).
    assert!(mid.completed > 0);
    assert!(
        mid.linear < 1e-9 && mid.angular < 1e-9,
        "{} {}",
        mid.linear,
        mid.angular
    );
}
