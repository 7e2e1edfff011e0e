//! Lyapunov exponents from the exact tangent map of the midpoint rule
//! (`georod::integrator::tangent`), checked against exact values and a second method.
mod common;

use common::{dense, dense_tangent, free_dofs, output, simulation, submatrix};
use georod::integrator::tangent::{Lyapunov, TangentScratch};
use georod::integrator::Midpoint;
use georod::scene::Scene;
use georod::simulation::Simulation;
use georod::solver::BlockTridiagonal;
use nalgebra::{Complex, DMatrix};
use std::sync::Arc;

/// The exponents of the midpoint map of the linearized rod about its state (at rest): with
/// `s` the roots of `det(s^2 M + s C + K) = 0` over the free dofs, the midpoint rule maps a
/// mode by `mu = (1 + s dt/2) / (1 - s dt/2)` per step, so its exponent is `ln|mu| / dt`.
/// Sorted from the largest.
fn exact_exponents(sim: &Simulation, dt: f64) -> Vec<f64> {
    let rod = sim.rod();
    let free = free_dofs(rod);
    let n = free.len();
    let matrix = |add: &dyn Fn(&mut BlockTridiagonal)| {
        let mut m = BlockTridiagonal::new(rod.nodes());
        add(&mut m);
        submatrix(&dense(&m), &free)
    };
    let m = matrix(&|a| rod.add_mass(a, 1.0));
    let c = matrix(&|a| rod.add_damping(a, 1.0));
    let k = submatrix(&dense_tangent(rod, &sim.state().u), &free);
    let m_inv = m.try_inverse().expect("mass is invertible");
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    a.view_mut((0, n), (n, n)).fill_with_identity();
    a.view_mut((n, 0), (n, n)).copy_from(&(-&m_inv * k));
    a.view_mut((n, n), (n, n)).copy_from(&(-&m_inv * c));
    let mut exponents: Vec<f64> = a
        .complex_eigenvalues()
        .iter()
        .map(|s| {
            let half = Complex::new(0.5 * dt, 0.0) * s;
            let mu = (Complex::new(1.0, 0.0) + half) / (Complex::new(1.0, 0.0) - half);
            mu.norm().ln() / dt
        })
        .collect();
    exponents.sort_by(|x, y| y.partial_cmp(x).unwrap());
    exponents
}

/// A clamped-clamped beam from the undeformed state at rest, no loads: it stays at rest, so
/// its midpoint map is linear with the constant tangent at the reference state. The rotations
/// are damped too, so that every mode decays.
const LINEAR_BEAM: &str = r#"
name = "LinearBeam"
description = "Clamped-clamped beam at rest, rotations damped too"

[geometry]
shape = "straight"
L = 10.0

[defaults]
elements = 4
dt_max = 1.0e-4

[[support]]
name = "left"
at = 0.0
fix = ["u1", "u2", "w"]

[[support]]
name = "right"
at = 1.0
fix = ["u1", "u2", "w"]

[model]
rotational_damping = 1.0e-4

[initial]
state = "reference"
"#;

fn linear_beam(overrides: &[(&str, f64)]) -> Simulation {
    let scene = Arc::new(Scene::parse(LINEAR_BEAM, "LinearBeam").unwrap());
    let values = scene.values_with(overrides.iter().copied()).unwrap();
    Simulation::new(scene, values).unwrap()
}

fn exponents(sim: &Simulation, k: usize) -> Vec<f64> {
    (1..=k)
        .map(|j| output(sim, &format!("lyapunov[{j}]")))
        .collect()
}

#[test]
fn the_tangent_map_is_the_derivative_of_the_step() {
    // A moving buckled beam (not at rest: the tangent is at a general state), one step, against
    // central differences of the step itself along the same direction. With eps = 1e-6 the
    // difference quotient is accurate to about eps^2 |d3 step| ~ 1e-12 and to round-off
    // 1e-16 / eps ~ 1e-10 (times the Newton tolerance's noise, 1e-10 |du| / eps ~ 1e-9 of a
    // step's increment): 1e-7 holds with a margin.
    let sim = simulation("BuckledBeam", &[("elements", 4.0), ("F", 0.0)]);
    let rod = sim.rod().clone();
    let loads = sim.setup().loads.clone();
    let dt = 1e-5;
    let mut state = sim.state().clone();
    for (i, v) in state.v.iter_mut().enumerate() {
        *v = if rod.fixed[i] {
            0.0
        } else {
            0.3 * (0.7 * i as f64).sin()
        };
    }
    let mut midpoint = Midpoint::new(&rod);
    midpoint.linearize = true;
    let mut stepped = state.clone();
    midpoint
        .step(&rod, &loads, &mut stepped, 0.0, dt, &[])
        .unwrap();
    // tau = 1: the vector's norm is |du|^2 + |dv|^2.
    let mut tangent = Lyapunov::new(&rod, 1, 1.0, f64::INFINITY);
    let (du, dv) = {
        let (du, dv, ..) = tangent.parts();
        (du.to_vec(), dv.to_vec())
    };
    let mut scratch = TangentScratch::new(rod.dofs());
    tangent.advance(&rod, &midpoint, &mut scratch, 0.0, dt);
    let (tu, tv, ..) = tangent.parts();
    let eps = 1e-6;
    let step_from = |sign: f64| {
        let mut z = state.clone();
        for i in 0..rod.dofs() {
            z.u[i] += sign * eps * du[i];
            z.v[i] += sign * eps * dv[i];
        }
        Midpoint::new(&rod)
            .step(&rod, &loads, &mut z, 0.0, dt, &[])
            .unwrap();
        z
    };
    let (plus, minus) = (step_from(1.0), step_from(-1.0));
    let fd_u: Vec<f64> = (0..rod.dofs())
        .map(|i| (plus.u[i] - minus.u[i]) / (2.0 * eps))
        .collect();
    let fd_v: Vec<f64> = (0..rod.dofs())
        .map(|i| (plus.v[i] - minus.v[i]) / (2.0 * eps))
        .collect();
    let norm = (fd_u.iter().chain(&fd_v).map(|x| x * x).sum::<f64>()).sqrt();
    let error = (0..rod.dofs())
        .map(|i| {
            (tu[i] - fd_u[i] / norm)
                .abs()
                .max((tv[i] - fd_v[i] / norm).abs())
        })
        .fold(0.0, f64::max);
    println!("tangent map vs central differences: {error:.2e} (unit vectors)");
    assert!(error < 1e-7, "{error:e}");
}

#[test]
fn exponents_of_a_linear_rod_are_those_of_its_discrete_modes() {
    // Exact: the linear midpoint map's exponents ln|mu| / dt (see `exact_exponents`). At
    // dt = 1e-4 the leading modes are the unresolved high-frequency ones, which the midpoint
    // rule damps little (ln|mu|/dt ~ -4 ζ / (omega dt^2)): two complex pairs at -4.068 and
    // -4.503 /s. The vectors align with the leading pair within a few 1/(4.503 - 4.068) s;
    // averaging from 20 s to 60 s, the estimate's error is the log of how much a vector's
    // norm varies along its orbit in the pair's plane (about 1) over 40 s: 0.025 /s;
    // measured 0.02-0.06 /s. Tolerance 0.1 /s, a quarter of the gap to the next pair.
    let dt = 1.0e-4;
    let mut sim = linear_beam(&[
        ("lyapunov_count", 2.0),
        ("lyapunov_align", 20.0),
        ("dt_max", dt),
    ]);
    let exact = exact_exponents(&sim, dt);
    for _ in 0..600 {
        sim.advance(1000.0 * dt).unwrap();
    }
    let estimate = exponents(&sim, 2);
    println!(
        "unresolved modes: exact {:?}, estimate {estimate:?}",
        &exact[..4]
    );
    assert!((output(&sim, "lyapunov_time") - 40.0).abs() < 1e-6);
    for (e, x) in estimate.iter().zip(&exact) {
        assert!((e - x).abs() < 0.1, "{e} vs {x}");
    }
}

#[test]
fn exponents_of_a_resolved_linear_rod_are_its_modal_decay_rates() {
    // At dt = 1e-6 every mode is resolved and the exponents are the modal decay rates
    // (-250 /s: d / (2 rho A) for bending modes, which carry little rotational energy). The
    // leading four (two pairs, -249.05 and -249.64) sit 0.3-4 /s from the next ones, so the
    // individual estimates over [0.05 s, 0.3 s] mix; their sum, the growth of the volume
    // they span, converges at the gap to the third pair. Error: the log of the volume's norm
    // variation (a few units) over 0.25 s, about 10 /s of -998 /s: tolerance 2 %, measured
    // 1.3 % (each exponent within 1.9 % of the leading one; tolerance 5 %).
    let dt = 1.0e-6;
    let mut sim = linear_beam(&[
        ("lyapunov_count", 4.0),
        ("lyapunov_align", 0.05),
        ("dt_max", dt),
    ]);
    let exact = exact_exponents(&sim, dt);
    for _ in 0..300 {
        sim.advance(1000.0 * dt).unwrap();
    }
    let estimate = exponents(&sim, 4);
    let (sum, sum_exact) = (estimate.iter().sum::<f64>(), exact[..4].iter().sum::<f64>());
    println!(
        "resolved modes: exact {:?}, estimate {estimate:?}",
        &exact[..6]
    );
    assert!(
        (sum - sum_exact).abs() < 0.02 * sum_exact.abs(),
        "{sum} vs {sum_exact}"
    );
    for e in &estimate {
        assert!(
            (e - exact[0]).abs() < 0.05 * exact[0].abs(),
            "{e} vs {}",
            exact[0]
        );
    }
}

/// The paper's buckled beam at `F`, `Omega` (10 elements, T/64 sub-steps) with `k` exponents.
fn buckled(f: f64, omega: f64, k: f64, align: f64) -> Simulation {
    let period = 2.0 * std::f64::consts::PI / omega;
    simulation(
        "BuckledBeam",
        &[
            ("F", f),
            ("Omega", omega),
            ("lyapunov_count", k),
            ("lyapunov_align", align),
            ("dt_max", period / 64.0),
        ],
    )
}

#[test]
fn the_tangent_vectors_leave_the_trajectory_alone() {
    // The extra factorization at the converged step happens after the step's result is fixed.
    let (f, omega) = (1.5, 3500.0);
    let period = 2.0 * std::f64::consts::PI / omega;
    let mut plain = buckled(f, omega, 0.0, 0.0);
    let mut with = buckled(f, omega, 2.0, 0.0);
    for _ in 0..50 {
        plain.advance(period).unwrap();
        with.advance(period).unwrap();
    }
    assert_eq!(plain.state(), with.state(), "bit for bit");
    assert_eq!(plain.reactions(), with.reactions());
    assert!(output(&with, "lyapunov[1]") > 0.0);
    assert_eq!(output(&plain, "lyapunov[1]"), 0.0);
}

#[test]
fn exponents_do_not_depend_on_the_communication_step() {
    // Same sub-steps (dt = 2^-20 s, exact in binary), grouped 1 or 16 to a communication step:
    // the tangent vectors are renormalized after every sub-step, so the estimates agree bit for
    // bit.
    let dt = 1.0 / 1_048_576.0;
    let values = |sim: &Simulation| -> Vec<f64> {
        let mut v = exponents(sim, 2);
        v.push(output(sim, "lyapunov_per_period[1]"));
        v.push(output(sim, "lyapunov_time"));
        v
    };
    let mut one = buckled(1.5, 3500.0, 2.0, 0.002);
    let mut sixteen = buckled(1.5, 3500.0, 2.0, 0.002);
    for sim in [&mut one, &mut sixteen] {
        let i = sim.scene().param_index("dt_max").unwrap();
        assert_eq!(
            sim.values().get(i),
            2.0 * std::f64::consts::PI / 3500.0 / 64.0
        );
    }
    let (mut one, mut sixteen) = (rebuild_with_dt(&one, dt), rebuild_with_dt(&sixteen, dt));
    for _ in 0..16 * 400 {
        one.advance(dt).unwrap();
    }
    for _ in 0..400 {
        sixteen.advance(16.0 * dt).unwrap();
    }
    assert_eq!(one.time(), sixteen.time());
    assert_eq!(values(&one), values(&sixteen));
    assert!(values(&one)[0] != 0.0);
}

fn rebuild_with_dt(sim: &Simulation, dt: f64) -> Simulation {
    let scene = sim.scene().clone();
    let mut values = sim.values().clone();
    scene.set(&mut values, "dt_max", dt).unwrap();
    Simulation::new(scene, values).unwrap()
}

#[test]
fn snapshots_carry_the_tangent_vectors() {
    let period = 2.0 * std::f64::consts::PI / 3500.0;
    let mut sim = buckled(1.5, 3500.0, 3.0, 5.0 * period);
    for _ in 0..10 {
        sim.advance(period).unwrap();
    }
    let snapshot = sim.snapshot();
    for _ in 0..10 {
        sim.advance(period).unwrap();
    }
    let first = exponents(&sim, 3);
    sim.restore(&snapshot).unwrap();
    for _ in 0..10 {
        sim.advance(period).unwrap();
    }
    assert_eq!(exponents(&sim, 3), first);
    // A snapshot whose Lyapunov data does not fit is refused, and changes nothing.
    let mut bad = snapshot.clone();
    bad.lyapunov.as_mut().unwrap().log_growth.pop();
    assert!(sim
        .restore(&bad)
        .unwrap_err()
        .to_string()
        .contains("Lyapunov"));
    let mut bad = snapshot.clone();
    bad.lyapunov.as_mut().unwrap().du[5] = f64::NAN;
    assert!(sim.restore(&bad).is_err());
    assert_eq!(exponents(&sim, 3), first);
    // Reset starts the estimate again.
    sim.reset();
    assert_eq!(output(&sim, "lyapunov_time"), 0.0);
    for _ in 0..20 {
        sim.advance(period).unwrap();
    }
    assert_eq!(exponents(&sim, 3), first);
}

/// The largest exponent per forcing period by two trajectories (Benettin): the twin starts
/// `d0` away along the tangent vector's initial direction and is pulled back to `d0` every
/// period along its separation (through snapshots), in the same norm `|du|^2 + |dv/Omega|^2`
/// over the free dofs.
fn twin_exponent(f: f64, omega: f64, periods: usize, skip: usize) -> (f64, f64) {
    let period = 2.0 * std::f64::consts::PI / omega;
    let d0 = 1e-8;
    let mut reference = buckled(f, omega, 1.0, skip as f64 * period);
    let mut twin = buckled(f, omega, 1.0, skip as f64 * period);
    let free: Vec<usize> = free_dofs(reference.rod());
    let start = reference.snapshot();
    let direction = start.lyapunov.clone().unwrap();
    let place = |twin: &mut Simulation, reference: &Simulation, du: &[f64], dv: &[f64], scale| {
        let mut s = reference.snapshot();
        for &i in &free {
            s.displacements[i] += scale * du[i];
            s.velocities[i] += scale * dv[i];
        }
        twin.restore(&s).unwrap();
    };
    place(&mut twin, &reference, &direction.du, &direction.dv, d0);
    let mut growth = 0.0;
    for p in 0..periods {
        reference.advance(period).unwrap();
        twin.advance(period).unwrap();
        let (r, t) = (reference.state(), twin.state());
        let du: Vec<f64> = (0..r.u.len()).map(|i| t.u[i] - r.u[i]).collect();
        let dv: Vec<f64> = (0..r.v.len()).map(|i| t.v[i] - r.v[i]).collect();
        let d = free
            .iter()
            .map(|&i| du[i] * du[i] + (dv[i] / omega).powi(2))
            .sum::<f64>()
            .sqrt();
        if p >= skip {
            growth += (d / d0).ln();
        }
        place(&mut twin, &reference, &du, &dv, d0 / d);
    }
    let twin_estimate = growth / (periods - skip) as f64;
    (twin_estimate, output(&reference, "lyapunov_per_period[1]"))
}

#[test]
fn the_tangent_agrees_with_two_nearby_trajectories() {
    // Same trajectory, same start direction, same norm and window: the twin's separation
    // (d0 = 1e-8 of a state of size ~1) follows the tangent map up to its own nonlinearity
    // O(d0) and the Newton tolerance's noise (1e-10 of a step's increment, ~1e-13 absolute:
    // 1e-5 of d0, per period), so the two estimates agree to about 1e-5 per period (measured
    // 1e-6): tolerance 1e-5, far below the exponents themselves (0.97 chaotic, -0.0012
    // periodic). Chaotic (F = 1.5) and periodic (F = 2.0, period-1 orbit) cases at
    // Omega = 3500, 100 periods averaged after 50.
    for (f, chaotic) in [(1.5, true), (2.0, false)] {
        let (twin, tangent) = twin_exponent(f, 3500.0, 150, 50);
        println!("F = {f}: twin {twin:.6}, tangent {tangent:.6} per period");
        assert!(
            (twin - tangent).abs() < 1e-5,
            "F = {f}: {twin} vs {tangent}"
        );
        assert_eq!(tangent > 0.05, chaotic, "F = {f}: {tangent}");
        if !chaotic {
            assert!(tangent < 0.0);
        }
    }
}

#[test]
fn tangent_vectors_start_at_lyapunov_start() {
    // Before lyapunov_start the vectors rest and cost nothing (no extra factorization); they
    // count after lyapunov_align more.
    let period = 2.0 * std::f64::consts::PI / 3500.0;
    let mut plain = buckled(1.5, 3500.0, 0.0, 0.0);
    let scene = plain.scene().clone();
    let values = scene
        .values_with([
            ("F", 1.5),
            ("Omega", 3500.0),
            ("dt_max", period / 64.0),
            ("lyapunov_count", 1.0),
            ("lyapunov_start", 10.0 * period),
            ("lyapunov_align", 5.0 * period),
        ])
        .unwrap();
    let mut late = Simulation::new(scene, values).unwrap();
    let initial = late.snapshot().lyapunov.unwrap();
    for _ in 0..10 {
        let (a, b) = (
            plain.advance(period).unwrap(),
            late.advance(period).unwrap(),
        );
        assert_eq!(a.factorizations, b.factorizations);
    }
    assert_eq!(late.snapshot().lyapunov.unwrap(), initial);
    for _ in 0..5 {
        let (a, b) = (
            plain.advance(period).unwrap(),
            late.advance(period).unwrap(),
        );
        let extra = b.factorizations - a.factorizations;
        assert!(extra >= 1 && extra <= b.substeps as u32, "{extra}");
    }
    assert_ne!(late.snapshot().lyapunov.unwrap().du, initial.du);
    assert_eq!(output(&late, "lyapunov_time"), 0.0);
    late.advance(period).unwrap();
    assert!((output(&late, "lyapunov_time") / period - 1.0).abs() < 1e-9);
}

#[test]
fn lyapunov_refusals() {
    let scene = common::scene("BuckledBeam");
    let em = scene
        .values_with([("lyapunov_count", 1.0), ("integrator", 2.0)])
        .unwrap();
    let e = Simulation::new(scene.clone(), em)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("lyapunov_count") && e.contains("integrator = 1"),
        "{e}"
    );
    let e = scene
        .values_with([("lyapunov_count", 5.0)])
        .unwrap_err()
        .to_string();
    assert!(e.contains("lyapunov_count") && e.contains("[0, 4]"), "{e}");
    assert!(scene.values_with([("lyapunov_start", -1.0)]).is_err());
}

#[test]
fn the_perturbation_kicks_the_state_by_its_change() {
    // The start value kicks the initial state; a later change kicks the state at the next
    // step by the change only; a restored snapshot is not kicked again. The kick is a unit
    // vector in |du|^2 + |dv / Omega|^2 over the free dofs.
    let omega = 3500.0;
    let norm = |a: &Simulation, b: &Simulation| -> f64 {
        let (x, y) = (a.state(), b.state());
        (0..x.u.len())
            .map(|i| (x.u[i] - y.u[i]).powi(2) + ((x.v[i] - y.v[i]) / omega).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let plain = simulation("BuckledBeam", &[("F", 0.0)]);
    let kicked = simulation("BuckledBeam", &[("F", 0.0), ("perturbation", 1e-6)]);
    let ratio = norm(&plain, &kicked) / 1e-6;
    assert!((ratio - 1.0).abs() < 1e-9, "{ratio}");
    let fixed = (0..plain.rod().dofs()).filter(|&i| plain.rod().fixed[i]);
    for i in fixed {
        assert_eq!(plain.state().u[i], kicked.state().u[i], "held dofs stay");
    }
    // A change of the tunable value by 2e-6 before a step kicks the state at the start of the
    // step exactly as the start value 2e-6 kicks the initial state.
    let h = 1e-5;
    let mut b = simulation("BuckledBeam", &[("F", 0.0)]);
    let mut d = simulation("BuckledBeam", &[("F", 0.0), ("perturbation", 2e-6)]);
    common::set_param(&mut b, "perturbation", 2e-6);
    let before = b.snapshot();
    b.advance(h).unwrap();
    d.advance(h).unwrap();
    assert_eq!(b.state(), d.state());
    b.advance(h).unwrap();
    d.advance(h).unwrap();
    assert_eq!(b.state(), d.state(), "kicked once only");
    // Restoring the snapshot taken after the change but before the step: the snapshot's state
    // is unkicked, and its perturbation value counts as applied (no kick at the next step).
    b.restore(&before).unwrap();
    let mut c = simulation("BuckledBeam", &[("F", 0.0)]);
    b.advance(h).unwrap();
    c.advance(h).unwrap();
    assert_eq!(b.state(), c.state());
}
