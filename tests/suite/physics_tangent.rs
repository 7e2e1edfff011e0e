//! Consistency of the core: the tangent is the derivative of the internal force (element and
//! assembled rod, straight and curved, large rotations), the force is the derivative of the
//! energy, Newton converges quadratically in statics and in a large midpoint step, and the
//! midpoint rule's chord corrections (factorization reused) reach Newton's solution.
//!
//! Run: `cargo test --profile quick --test suite physics_tangent:: -- --nocapture`
use crate::common;

use common::{dense_tangent, max_abs, Rng, Table};
use georod::integrator::{DynamicState, Midpoint, NewtonStats, StaticSolver};
use georod::model::element::Vector6;
use georod::model::rod::{ROTATION, U1, U2};
use georod::model::{Element, LoadSet, ReferenceCurve, Rod};
use nalgebra::DMatrix;

/// Central-difference step. The truncation error is `h^2 f''' / 6` relative (`f` is smooth on the
/// scale 1 of the rotations and of the displacements, which are of the size of the element),
/// about 1e-13, and the round-off `eps |f| / h` about 1e-10 relative: 1e-6 leaves four orders of
/// margin below the required 1e-6.
const FD_STEP: f64 = 1e-6;
/// Required relative error of the tangent against finite differences (brief: 1e-6).
const TANGENT_TOL: f64 = 1e-6;

/// Random element state: displacements of the size of the element, rotations up to 3 rad.
fn random_element_state(rng: &mut Rng, length: f64) -> Vector6 {
    Vector6::from_fn(|i, _| {
        if i % 3 == 2 {
            rng.uniform(-3.0, 3.0)
        } else {
            rng.uniform(-0.7, 0.7) * length
        }
    })
}

/// `max_j |K e_j - (f(u + h e_j) - f(u - h e_j)) / 2h| / |K|` (Frobenius norms).
fn element_tangent_error(el: &Element, sec: &georod::model::Section, ue: &Vector6) -> (f64, f64) {
    let (f, k) = el.force_and_tangent(sec, ue);
    let f_alone = el.internal_force(sec, ue);
    assert!((f - f_alone).norm() <= 1e-14 * f.norm().max(1.0));
    let mut worst = 0.0f64;
    let mut worst_energy = 0.0f64;
    for j in 0..6 {
        let (mut up, mut dn) = (*ue, *ue);
        up[j] += FD_STEP;
        dn[j] -= FD_STEP;
        let fd = (el.internal_force(sec, &up) - el.internal_force(sec, &dn)) / (2.0 * FD_STEP);
        worst = worst.max((fd - k.column(j)).norm() / k.norm());
        let de = (el.strain_energy(sec, &up) - el.strain_energy(sec, &dn)) / (2.0 * FD_STEP);
        worst_energy = worst_energy.max((de - f[j]).abs() / f.norm());
    }
    let asym = (k - k.transpose()).norm() / k.norm();
    assert!(asym < 1e-14, "element tangent not symmetric: {asym:e}");
    (worst, worst_energy)
}

#[test]
fn element_tangent_is_derivative_of_force() {
    let mut rng = Rng::new(0x5eed_0001);
    let mut t = Table::new("element tangent vs central differences (100 random states each)");
    t.row(format_args!(
        "{:<28} {:>14} {:>14}",
        "element", "max |dK|/|K|", "max |dE-f|/|f|"
    ));
    let sections = [
        ("b=h=1", common::section(1.0, 1.0)),
        ("h=0.01", common::section(1.0, 0.01)),
    ];
    for (sec_name, sec) in sections {
        for (name, alpha) in [("straight", [0.0, 0.0]), ("curved", [0.45, 0.12])] {
            let el = Element::new(0.8, alpha);
            let (mut worst, mut worst_e) = (0.0f64, 0.0f64);
            for _ in 0..100 {
                let ue = random_element_state(&mut rng, el.length);
                let (err, err_e) = element_tangent_error(&el, &sec, &ue);
                worst = worst.max(err);
                worst_e = worst_e.max(err_e);
            }
            t.row(format_args!(
                "{:<28} {worst:>14.3e} {worst_e:>14.3e}",
                format!("{name}, {sec_name}")
            ));
            assert!(
                worst < TANGENT_TOL,
                "{name} {sec_name}: tangent error {worst:e}"
            );
            assert!(
                worst_e < TANGENT_TOL,
                "{name} {sec_name}: force error {worst_e:e}"
            );
        }
    }
}

/// The assembled tangent (dense copy through `BlockTridiagonal::mul`) against central differences
/// of `Rod::internal_force`, and the assembled force against differences of `Rod::strain_energy`.
fn rod_tangent_error(rod: &Rod, u: &[f64]) -> (f64, f64, f64) {
    let n = rod.dofs();
    let k = dense_tangent(rod, u);
    let mut f = vec![0.0; n];
    rod.internal_force(u, &mut f);
    let mut fd = DMatrix::zeros(n, n);
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    let mut up = u.to_vec();
    let mut energy_err = 0.0f64;
    for j in 0..n {
        up[j] = u[j] + FD_STEP;
        rod.internal_force(&up, &mut fp);
        let ep = rod.strain_energy(&up);
        up[j] = u[j] - FD_STEP;
        rod.internal_force(&up, &mut fm);
        let em = rod.strain_energy(&up);
        up[j] = u[j];
        for i in 0..n {
            fd[(i, j)] = (fp[i] - fm[i]) / (2.0 * FD_STEP);
        }
        energy_err = energy_err.max(((ep - em) / (2.0 * FD_STEP) - f[j]).abs());
    }
    let tangent_err = (&k - &fd).norm() / k.norm();
    let asym = (&k - k.transpose()).norm() / k.norm();
    (tangent_err, energy_err / max_abs(&f), asym)
}

#[test]
fn assembled_tangent_is_derivative_of_force() {
    let mut rng = Rng::new(0x5eed_0002);
    let mut t = Table::new(
        "assembled rod tangent (dense via BlockTridiagonal::mul) vs central differences",
    );
    t.row(format_args!(
        "{:<34} {:>13} {:>13} {:>11}",
        "rod", "|dK|/|K|", "|dE-f|/|f|", "asym"
    ));
    let rods = [
        (
            "straight L=10, 12 el",
            Rod::new(
                ReferenceCurve::Straight { length: 10.0 },
                common::section(1.0, 1.0),
                0.0,
                12,
            ),
        ),
        (
            "arc L=32 H=8, 12 el",
            Rod::new(
                ReferenceCurve::arc(32.0, 8.0),
                common::section(1.0, 1.0),
                0.0,
                12,
            ),
        ),
        (
            "arc L=32 H=2, 9 el, h=0.05",
            Rod::new(
                ReferenceCurve::arc(32.0, 2.0),
                common::section(1.0, 0.05),
                0.0,
                9,
            ),
        ),
    ];
    for (name, rod) in &rods {
        for trial in 0..5 {
            // Smooth large-rotation field plus noise: a rod curled by up to several radians.
            let (a, b) = (rng.uniform(-4.0, 4.0), rng.uniform(-2.0, 2.0));
            let s_total = rod.curve.length();
            let mut u = vec![0.0; rod.dofs()];
            for i in 0..rod.nodes() {
                let t = rod.node_s[i] / s_total;
                u[3 * i + U1] = rng.uniform(-0.5, 0.5) + 0.3 * s_total * t * t;
                u[3 * i + U2] = rng.uniform(-0.5, 0.5) - 0.2 * s_total * t;
                u[3 * i + ROTATION] = a * t + b * t * t + rng.uniform(-0.3, 0.3);
            }
            let (err, err_e, asym) = rod_tangent_error(rod, &u);
            if trial == 0 || err > TANGENT_TOL {
                t.row(format_args!(
                    "{:<34} {err:>13.3e} {err_e:>13.3e} {asym:>11.1e}",
                    format!("{name} #{trial}")
                ));
            }
            assert!(err < TANGENT_TOL, "{name}: tangent error {err:e}");
            assert!(
                err_e < TANGENT_TOL,
                "{name}: force vs energy error {err_e:e}"
            );
            assert!(asym < 1e-14, "{name}: asymmetric tangent {asym:e}");
        }
    }
}

/// Prints a Newton history and checks quadratic convergence on the corrections: once a
/// correction `c_k` is below `reach = 1e-2 scale` (inside the basin) and `c_(k+1)` is above the
/// round-off floor `floor`, `c_(k+1) <= C c_k^2` with `C = 10 / reach` (i.e. from there on each
/// iteration contracts by at least 10 and the contraction improves in proportion to `c_k`).
/// Returns how many iterations were checked.
fn check_quadratic(
    t: &mut Table,
    label: &str,
    stats: &NewtonStats,
    scale: f64,
    floor: f64,
) -> usize {
    let r = stats.residual_history();
    let c = stats.correction_history();
    let reach = 1e-2 * scale;
    let constant = 10.0 / reach;
    t.row(format_args!(
        "  {label}: {} iterations (C = {constant:.0e})",
        stats.iterations
    ));
    t.row(format_args!(
        "    {:>3} {:>12} {:>12} {:>14}",
        "k", "residual", "correction", "c_k/c_(k-1)^2"
    ));
    let mut checked = 0;
    for k in 0..c.len() {
        let ratio = if k > 0 {
            c[k] / (c[k - 1] * c[k - 1])
        } else {
            f64::NAN
        };
        t.row(format_args!(
            "    {k:>3} {:>12.3e} {:>12.3e} {ratio:>14.3e}",
            r[k], c[k]
        ));
    }
    for k in 1..c.len() {
        if c[k - 1] < reach && c[k] > floor {
            checked += 1;
            assert!(
                c[k] <= constant * c[k - 1] * c[k - 1],
                "{label}: not quadratic at {k}: {:e} -> {:e}",
                c[k - 1],
                c[k]
            );
        }
    }
    checked
}

#[test]
fn newton_converges_quadratically() {
    // Static: a cantilever (L = 10, b = h = 1) under a tip load P L^2/EI = 3 along -e2, applied in
    // 3 load steps (the first steps start far away, the last ones show the asymptotic rate).
    let mut rod = common::straight_rod(10.0, 1.0, 1.0, 0.0, 20);
    for k in [U1, U2, ROTATION] {
        rod.fix(0, k);
    }
    let p = 3.0 * rod.section.ei / 100.0;
    let mut solver = StaticSolver::new(&rod);
    let mut u = vec![0.0; rod.dofs()];
    let mut f_ext = vec![0.0; rod.dofs()];
    let tip = 3 * rod.last_node() + U2;
    let mut t = Table::new("Newton, static cantilever P L^2/EI = 3 in 3 load steps (20 elements)");
    let mut checked = 0;
    for step in 1..=3 {
        f_ext[tip] = -p * step as f64 / 3.0;
        let stats = solver.solve(&rod, &mut u, &f_ext).expect("static solve");
        // Round-off floor of the corrections: about eps * cond(K) * |u| ~ 1e-12 here.
        checked += check_quadratic(&mut t, &format!("load step {step}"), &stats, 10.0, 1e-11);
    }
    t.row(format_args!("  tip deflection / L = {:.6}", -u[tip] / 10.0));
    assert!(
        checked >= 3,
        "too few static iterations in the quadratic regime"
    );

    // Dynamic: a free rod spinning at 2000 rad/s while bending, midpoint steps with dt = 2e-4
    // (20 x dt_max; the first bending period is ~2e-3): a rotation of 0.4 rad per step.
    let rod = common::straight_rod(10.0, 1.0, 1.0, 5e-4, 20);
    let loads = LoadSet::new(&rod, &[]);
    let mut state = DynamicState::at_rest(vec![0.0; rod.dofs()]);
    let omega = 2000.0;
    for i in 0..rod.nodes() {
        let s = rod.node_s[i];
        state.v[3 * i + U1] = 30.0;
        state.v[3 * i + U2] = omega * (s - 5.0) + 300.0 * (std::f64::consts::PI * s / 10.0).sin();
        state.v[3 * i + ROTATION] = omega;
    }
    let mut mid = Midpoint::new(&rod);
    // Plain Newton (one factorization per correction), to see the Jacobian's quadratic rate.
    mid.reuse_factorization = false;
    t.row(format_args!(
        "\nNewton, midpoint steps dt = 2e-4 of a free rod spinning at 2000 rad/s, bending"
    ));
    let mut checked = 0;
    for n in 0..3 {
        let stats = mid
            .step(&rod, &loads, &mut state, n as f64 * 2e-4, 2e-4, &[])
            .expect("midpoint step");
        checked += check_quadratic(&mut t, &format!("step {n}"), &stats, 10.0, 1e-11);
    }
    assert!(
        checked >= 3,
        "too few dynamic iterations in the quadratic regime"
    );
}

/// The midpoint rule reuses a factorization for chord corrections while they contract fast
/// (`Midpoint::reuse_factorization`, the default). Its steps must agree with plain Newton's to
/// the Newton tolerance (corrections below 1e-10 of the increment; the states here move by
/// increments of 1e-3 to 1e-1 per step, so agreement to 1e-11 absolute over a few steps, with
/// chaos-free large motion), with fewer factorizations.
#[test]
fn chord_corrections_reach_the_newton_solution() {
    let rod = common::straight_rod(10.0, 1.0, 1.0, 5e-4, 20);
    let loads = LoadSet::new(&rod, &[]);
    let mut start = DynamicState::at_rest(vec![0.0; rod.dofs()]);
    for i in 0..rod.nodes() {
        let s = rod.node_s[i];
        start.v[3 * i + U1] = 30.0;
        start.v[3 * i + U2] = 2000.0 * (s - 5.0) + 300.0 * (std::f64::consts::PI * s / 10.0).sin();
        start.v[3 * i + ROTATION] = 2000.0;
    }
    let mut t =
        Table::new("midpoint steps, plain Newton vs reused factorizations (free spinning rod)");
    t.row(format_args!(
        "{:>8} {:>6} {:>20} {:>20} {:>10} {:>10}",
        "dt", "steps", "Newton corr./fact.", "chord corr./fact.", "max |du|", "max gap"
    ));
    for dt in [1e-4, 1e-5, 1e-6] {
        let steps = 10;
        let (mut plain, mut reused) = (start.clone(), start.clone());
        let mut newton = Midpoint::new(&rod);
        newton.reuse_factorization = false;
        let mut chord = Midpoint::new(&rod);
        let (mut newton_work, mut chord_work) = ((0, 0), (0, 0));
        let (mut worst, mut widest) = (0.0f64, 0.0f64);
        for n in 0..steps {
            let t_n = n as f64 * dt;
            let a = newton
                .step(&rod, &loads, &mut plain, t_n, dt, &[])
                .expect("Newton");
            let b = chord
                .step(&rod, &loads, &mut reused, t_n, dt, &[])
                .expect("chord");
            newton_work = (
                newton_work.0 + a.iterations,
                newton_work.1 + a.factorizations,
            );
            chord_work = (chord_work.0 + b.iterations, chord_work.1 + b.factorizations);
            assert_eq!(a.iterations, a.factorizations);
            let increment = max_abs(newton.last_increment());
            let gap =
                (plain.u.iter().zip(&reused.u)).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            // Both stop when the error left after their last correction, estimated from the
            // contraction of the corrections, is a hundred times below the tolerance
            // 1e-10 |du| + 1e-12 (or the correction itself is below it). So both are within
            // 1e-12 |du| + 1e-14 of the exact step (plus round-off), and the errors add up over
            // steps: the bound below is twice that per step.
            assert!(
                gap <= (n + 1) as f64 * (2e-12 * increment + 2e-14),
                "dt = {dt:e}, step {n}: states differ by {gap:e} (increment {increment:e})"
            );
            worst = worst.max(increment);
            widest = widest.max(gap);
        }
        t.row(format_args!(
            "{dt:>8.0e} {steps:>6} {:>20} {:>20} {worst:>10.3e} {widest:>10.3e}",
            format!("{}/{}", newton_work.0, newton_work.1),
            format!("{}/{}", chord_work.0, chord_work.1)
        ));
        assert!(
            chord_work.1 <= newton_work.1,
            "reuse must not factor more often"
        );
        if dt <= 1e-5 {
            assert!(
                chord_work.1 < newton_work.1,
                "dt = {dt:e}: no factorization saved"
            );
        }
    }
}
