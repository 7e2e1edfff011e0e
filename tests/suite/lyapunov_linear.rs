//! Lyapunov exponents from the exact tangent map of the midpoint rule
//! (`georod::integrator::tangent`), checked against exact values: the tangent map against
//! central differences of the step, and the exponents of a linear rod against those of its
//! discrete modes (unresolved and resolved). The nonlinear checks are in `lyapunov_nonlinear.rs`.
use crate::common;

use common::{dense, dense_tangent, free_dofs, lyapunov_exponents, output, simulation, submatrix};
use georod::integrator::tangent::Lyapunov;
use georod::integrator::Midpoint;
use georod::scene::Scene;
use georod::simulation::Simulation;
use georod::solver::BlockTridiagonal;
use nalgebra::{Complex, DMatrix, DVector};
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
E = 1.2e4
nu = 0.2
rho = 1.0e-6
d = 5.0e-4
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
    midpoint.reserve_tangents(1, &rod);
    // tau = 1: the vector's norm is |du|^2 + |dv|^2.
    let mut tangent = Lyapunov::new(&rod, 1, 1.0, f64::INFINITY);
    let (du, dv) = {
        let (du, dv, ..) = tangent.parts();
        (du.to_vec(), dv.to_vec())
    };
    tangent.prepare(&rod, dt, midpoint.tangent_map_mut());
    let mut stepped = state.clone();
    midpoint
        .step(&rod, &loads, &mut stepped, 0.0, dt, &[])
        .unwrap();
    tangent.advance(&rod, midpoint.tangent_map(), 0.0, dt);
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

/// The tangent systems `J* y = b` that a step solves besides its own (refining the solve with
/// the Newton iteration's factorization, or where that does not contract, with the Jacobian
/// assembled at the last iterate), against a dense solve with the Jacobian at the converged
/// step, `2/dt^2 M + C/dt + K(u_n + du/2) / 2` over the free dofs. One system (refined where
/// that contracts) and two (factored once per step: `EXACT_FROM`). Steps from 1e-5 (the
/// sweeps' size) to 1e-2 and velocities from small to large exercise both paths of the one
/// system (each is required to occur). The solutions differ from the dense ones by the Jacobian's change over
/// the last correction (below the solver's tolerance, 1e-10 of the increment) and the
/// refinement's tolerance (1e-12, with a margin of 100): measured at most 5e-12 relative;
/// tolerance 1e-9.
#[test]
fn the_tangent_map_solves_with_the_converged_jacobian() {
    let sim = simulation("BuckledBeam", &[("elements", 6.0), ("F", 0.0)]);
    let rod = sim.rod().clone();
    let loads = sim.setup().loads.clone();
    let free = free_dofs(&rod);
    let n = rod.dofs();
    let (mut refined, mut factored, mut worst) = (0, 0, 0.0f64);
    for (count, amplitude) in [1, 2]
        .into_iter()
        .flat_map(|c| [(c, 0.3), (c, 3.0), (c, 30.0)])
    {
        let mut state = sim.state().clone();
        for (i, v) in state.v.iter_mut().enumerate() {
            *v = if rod.fixed[i] {
                0.0
            } else {
                amplitude * (0.7 * i as f64).sin()
            };
        }
        for dt in [1e-5, 1e-4, 1e-3, 1e-2] {
            let mut midpoint = Midpoint::new(&rod);
            midpoint.reserve_tangents(count, &rod);
            let map = midpoint.tangent_map_mut();
            map.set_count(count);
            for j in 0..count {
                for (i, b) in map.rhs_mut(j).iter_mut().enumerate() {
                    *b = if rod.fixed[i] {
                        0.0
                    } else {
                        ((1.3 + j as f64) * i as f64).cos()
                    };
                }
            }
            let rhs: Vec<Vec<f64>> = (0..count)
                .map(|j| midpoint.tangent_map_mut().rhs_mut(j).to_vec())
                .collect();
            let mut stepped = state.clone();
            let stats = midpoint
                .step(&rod, &loads, &mut stepped, 0.0, dt, &[])
                .unwrap();
            let u_mid: Vec<f64> = (0..n).map(|i| 0.5 * (state.u[i] + stepped.u[i])).collect();
            let mut a = BlockTridiagonal::new(rod.nodes());
            rod.add_mass(&mut a, 2.0 / (dt * dt));
            rod.add_damping(&mut a, 1.0 / dt);
            let lu = submatrix(&(dense(&a) + 0.5 * dense_tangent(&rod, &u_mid)), &free).lu();
            let mut off = 0.0f64;
            for (j, b) in rhs.iter().enumerate() {
                let b_free = DVector::from_iterator(free.len(), free.iter().map(|&i| b[i]));
                let y = lu.solve(&b_free).expect("nonsingular Jacobian");
                let got = midpoint.tangent_map().solution(j);
                for (k, &i) in free.iter().enumerate() {
                    off = off.max((got[i] - y[k]).abs() / y.amax());
                }
                assert!((0..n).filter(|&i| rod.fixed[i]).all(|i| got[i] == 0.0));
            }
            println!(
                "{count} system(s), v ~ {amplitude}, dt = {dt:e}: {} corrections, {} tangent \
                 factorizations, solutions off by {off:.1e}",
                stats.iterations, stats.tangent_factorizations
            );
            // One system is refined where that contracts (else factored); from two on
            // (EXACT_FROM) each step factors unless it ended on a Newton correction.
            if count == 1 && stats.tangent_factorizations == 0 {
                refined += 1;
            } else if count == 1 {
                factored += 1;
            }
            worst = worst.max(off);
        }
    }
    assert!(
        refined > 0 && factored > 0,
        "{refined} refined, {factored} factored"
    );
    assert!(worst < 1e-9, "{worst:e}");
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
    let estimate = lyapunov_exponents(&sim, 2);
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
    let estimate = lyapunov_exponents(&sim, 4);
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
