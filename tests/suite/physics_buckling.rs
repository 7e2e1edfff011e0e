//! Buckling of the pinned-pinned straight rod under a prescribed end shortening: the shortening
//! at which the straight state loses stability (first negative pivot of the tangent) against the
//! closed-form critical load of the model (Euler's load with the shear and stretch corrections).
//!
//! Run: `cargo test --profile quick --test suite physics_buckling:: -- --nocapture`
use crate::common;

use common::{
    buckling_threshold, critical_axial_force, dense_tangent, free_dofs, lowest_eigenvalue, order,
    pinned_rod, straight_compressed_state, submatrix, Table,
};
use georod::model::element::Vector6;
use std::f64::consts::PI;

const LENGTH: f64 = 10.0;

#[test]
fn buckling_threshold_matches_critical_load() {
    let sec = common::section(1.0, 1.0);
    let euler = PI * PI * sec.ei / (LENGTH * LENGTH);
    let p_cr = critical_axial_force(&sec, LENGTH);
    let delta_cr = p_cr * LENGTH / sec.ea;
    let mut t = Table::new("buckling of the pinned-pinned rod L=10, b=h=1 by end shortening");
    t.row(format_args!(
        "  Euler load pi^2 EI/L^2 = {euler:.5}; critical axial force of the model P_cr = {p_cr:.5} \
         (root of P^2 + GA (1 - P/EA) P - GA EI (pi/L)^2 = 0; {:+.3}% vs Euler)",
        100.0 * (p_cr / euler - 1.0)
    ));
    t.row(format_args!(
        "  Delta_cr = P_cr L / EA = {delta_cr:.7} (Euler only: {:.7}; core's critical_strain P_E/(1+P_E/GA): {:.7})",
        euler * LENGTH / sec.ea,
        euler / (1.0 + euler / sec.ga) / sec.ea * LENGTH
    ));
    t.row(format_args!(
        "{:>5} {:>12} {:>11} {:>6} {:>11} {:>11} {:>13} {:>13}",
        "elem", "Delta_h", "rel.err", "order", "-S1", "-S1/P_E", "lam(0.999D)", "lam(1.001D)"
    ));
    let mut errors = Vec::new();
    for n in [10usize, 20, 40, 80] {
        let rod = pinned_rod(LENGTH, n);
        let delta = buckling_threshold(&rod, 2.0 * delta_cr);
        let err = (delta - delta_cr) / delta_cr;
        // Axial force at the threshold from the element (uniform along the rod).
        let u = straight_compressed_state(&rod, delta);
        let ue = Vector6::from_column_slice(&u[0..6]);
        let s = rod.elements[0].stress_resultants(&rod.section, &ue);
        // Cross-check with the lowest eigenvalue of the reduced dense tangent.
        let free = free_dofs(&rod);
        let lam = |d: f64| {
            lowest_eigenvalue(&submatrix(
                &dense_tangent(&rod, &straight_compressed_state(&rod, d)),
                &free,
            ))
        };
        let (below, above) = (lam(0.999 * delta), lam(1.001 * delta));
        let ord = errors.last().map_or(f64::NAN, |&prev| order(prev, err));
        t.row(format_args!(
            "{n:>5} {delta:>12.8} {err:>11.3e} {ord:>6.2} {:>11.5} {:>11.6} {below:>13.4e} {above:>13.4e}",
            -s[0],
            -s[0] / euler
        ));
        assert!(
            below > 0.0 && above < 0.0,
            "{n}: eigenvalue does not cross zero at the threshold"
        );
        assert!(
            s[1].abs() < 1e-12 * s[0].abs(),
            "shear force in the straight state"
        );
        // The axial force at the threshold is P_cr up to the discretization error.
        assert!(((-s[0]) - delta / LENGTH * sec.ea).abs() < 1e-10 * sec.ea * delta / LENGTH);
        errors.push(err);
    }
    // Tolerances: the FE buckling load of linear elements converges as O(h^2) from above (order
    // 2 +- 0.2 on every doubling); at 80 elements the error is below 1.5x the O(h^2)
    // extrapolation of the 10-element error, err_10 / 64 (margin for the O(h^4) remainder).
    for pair in 1..errors.len() {
        let o = order(errors[pair - 1], errors[pair]);
        assert!((o - 2.0).abs() < 0.2, "order {o}");
    }
    assert!(errors.iter().all(|&e| e > 0.0));
    assert!(
        *errors.last().unwrap() < 1.5 * errors[0] / 64.0,
        "{errors:?}"
    );
}
