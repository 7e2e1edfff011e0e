//! Linear natural frequencies of the simply supported straight rod against the Timoshenko beam
//! (shear coefficient 1, rotary inertia included) and the axial bar.
//!
//! Run: `cargo test --profile quick --test suite physics_frequencies:: -- --nocapture`
use crate::common;

use common::{
    axial_omega, dense_mass, dense_tangent, free_dofs, generalized_eigen, order, submatrix,
    timoshenko_bending_omega, Table,
};
use georod::model::rod::{ROTATION, U1, U2};
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// The paper's straight rod: `L = 10`, `b = h = 1`, `E = 1.2e4`, `nu = 0.2`, `rho = 1e-6`.
const LENGTH: f64 = 10.0;

struct Mode {
    omega: f64,
    /// Share of the kinetic energy `x^T M x` in the axial dofs.
    axial_share: f64,
    /// Number of the half sine wave that best matches the mode (of `u2` or `u1`).
    wave: usize,
}

/// The modes of the rod with `n` elements, pinned-pinned: `u1 = u2 = 0` at `s = 0`, `u2 = 0` and
/// (also) `u1 = 0` at `s = L`, rotations free. With `u1` fixed at both ends the axial modes are
/// those of a fixed-fixed bar, `n pi / L sqrt(E / rho)`.
fn modes(n: usize) -> Vec<Mode> {
    let mut rod = common::straight_rod(LENGTH, 1.0, 1.0, 0.0, n);
    let last = rod.last_node();
    rod.fix(0, U1);
    rod.fix(0, U2);
    rod.fix(last, U1);
    rod.fix(last, U2);
    let free = free_dofs(&rod);
    let u0 = vec![0.0; rod.dofs()];
    let k = submatrix(&dense_tangent(&rod, &u0), &free);
    let m = submatrix(&dense_mass(&rod), &free);
    let (values, vectors) = generalized_eigen(&k, &m);
    let mass = dense_mass(&rod);
    let mut x_full = vec![0.0; rod.dofs()];
    let mut out = Vec::new();
    for (j, &lambda) in values.iter().enumerate() {
        x_full.fill(0.0);
        for (r, &dof) in free.iter().enumerate() {
            x_full[dof] = vectors[(r, j)];
        }
        let x = DMatrix::from_column_slice(rod.dofs(), 1, &x_full);
        let total = (x.transpose() * &mass * &x)[(0, 0)];
        let mut xa = x.clone();
        for i in 0..rod.nodes() {
            xa[3 * i + U2] = 0.0;
            xa[3 * i + ROTATION] = 0.0;
        }
        let axial = (xa.transpose() * &mass * &xa)[(0, 0)];
        let axial_share = axial / total;
        let kind = if axial_share > 0.5 { U1 } else { U2 };
        // Best-matching half sine: largest |projection| on sin(q pi s / L), q = 1..n.
        let wave = (1..=n)
            .max_by(|&p, &q| {
                let proj = |q: usize| {
                    (0..rod.nodes())
                        .map(|i| {
                            x_full[3 * i + kind] * (q as f64 * PI * rod.node_s[i] / LENGTH).sin()
                        })
                        .sum::<f64>()
                        .abs()
                };
                proj(p).total_cmp(&proj(q))
            })
            .unwrap();
        out.push(Mode {
            omega: lambda.max(0.0).sqrt(),
            axial_share,
            wave,
        });
        if out.len() >= 12 {
            break;
        }
    }
    out
}

#[test]
fn simply_supported_frequencies_converge_to_timoshenko() {
    let sec = common::section(1.0, 1.0);
    let meshes = [10usize, 20, 40, 80];
    let exact: Vec<f64> = (1..=3)
        .map(|n| timoshenko_bending_omega(&sec, LENGTH, n))
        .collect();
    let euler: Vec<f64> = (1..=3)
        .map(|n| (n as f64 * PI / LENGTH).powi(2) * (sec.ei / sec.rho_a).sqrt())
        .collect();
    let mut t = Table::new(
        "simply supported rod L=10, b=h=1: bending frequencies (rad/s) vs Timoshenko (k_s = 1)",
    );
    t.row(format_args!(
        "  Timoshenko: {:.3} {:.3} {:.3}   (Euler-Bernoulli: {:.1} {:.1} {:.1})",
        exact[0], exact[1], exact[2], euler[0], euler[1], euler[2]
    ));
    t.row(format_args!(
        "{:>5} {:>12} {:>10} {:>6} {:>12} {:>10} {:>6} {:>12} {:>10} {:>6}",
        "elem",
        "omega1",
        "rel.err",
        "order",
        "omega2",
        "rel.err",
        "order",
        "omega3",
        "rel.err",
        "order"
    ));
    let mut errors: Vec<[f64; 3]> = Vec::new();
    let mut axial_rows = Vec::new();
    for &n in &meshes {
        let all = modes(n);
        let bending: Vec<&Mode> = all.iter().filter(|m| m.axial_share < 1e-8).collect();
        let axial: Vec<&Mode> = all.iter().filter(|m| m.axial_share > 1.0 - 1e-8).collect();
        // The linearized straight rod decouples exactly: every mode is purely axial or bending.
        assert_eq!(bending.len() + axial.len(), all.len(), "{n}: coupled modes");
        let mut err = [0.0; 3];
        for q in 0..3 {
            assert_eq!(
                bending[q].wave,
                q + 1,
                "{n} elements: bending mode {q} misidentified"
            );
            err[q] = (bending[q].omega - exact[q]) / exact[q];
        }
        let ord = |q: usize| {
            errors
                .last()
                .map_or(f64::NAN, |prev: &[f64; 3]| order(prev[q], err[q]))
        };
        t.row(format_args!(
            "{n:>5} {:>12.4} {:>10.3e} {:>6.2} {:>12.4} {:>10.3e} {:>6.2} {:>12.4} {:>10.3e} {:>6.2}",
            bending[0].omega,
            err[0],
            ord(0),
            bending[1].omega,
            err[1],
            ord(1),
            bending[2].omega,
            err[2],
            ord(2)
        ));
        let a1 = axial_omega(&sec, LENGTH, axial[0].wave);
        axial_rows.push((
            n,
            axial[0].omega,
            axial[0].wave,
            a1,
            all.iter().position(|m| m.axial_share > 0.5),
        ));
        errors.push(err);
    }
    t.row(format_args!(
        "  axial modes (identified by their kinetic energy share, exactly 0 or 1):"
    ));
    for (n, w, wave, exact_axial, position) in &axial_rows {
        t.row(format_args!(
            "  {n:>3} elements: first axial mode #{} in the spectrum, half-waves {wave}, omega {w:.1} vs n pi/L sqrt(E/rho) = {exact_axial:.1} (rel {:.2e})",
            position.unwrap() + 1,
            (w - exact_axial) / exact_axial
        ));
    }
    // Tolerances: linear elements with a consistent mass converge as O(h^2); the errors must
    // fall by 4 (order 2 +- 0.25) per doubling on the two finest pairs, be positive (stiff and
    // consistent mass: an upper bound), and at 80 elements be below 1.5x the O(h^2) extrapolation
    // of the 10-element error (err_10 / 64 = 1.9e-4, 7.5e-4, 1.6e-3): 3e-4, 1e-3, 2.5e-3.
    for q in 0..3 {
        for pair in 1..errors.len() {
            let o = order(errors[pair - 1][q], errors[pair][q]);
            if pair >= 2 {
                assert!((o - 2.0).abs() < 0.25, "mode {}: order {o:.3}", q + 1);
            }
        }
        assert!(
            errors.iter().all(|e| e[q] > 0.0),
            "mode {} below the exact",
            q + 1
        );
    }
    let finest = errors.last().unwrap();
    assert!(
        finest[0] < 3e-4 && finest[1] < 1e-3 && finest[2] < 2.5e-3,
        "{finest:?}"
    );
    for (_, w, wave, exact_axial, _) in &axial_rows {
        assert_eq!(*wave, 1);
        assert!((w - exact_axial).abs() / exact_axial < 1e-2);
    }
}
