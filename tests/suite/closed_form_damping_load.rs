//! The magnitudes of the damping `d` and of the excitation `F cos(Omega t)` against closed forms,
//! on a free straight rod (no supports) integrated by `Midpoint` directly.
//!
//! Why these motions: a rigid translation and a purely axial motion of a straight rod leave
//! `u2 = w = 0` exactly (the shear strain and the bending curvature stay zero, so nothing couples
//! into the transverse and rotational dofs), and on them the discrete equations are linear with
//! the damping matrix equal to `d / (rho A)` times the translational mass matrix (both are the
//! consistent `integral N^T N ds`, model.md). Each check therefore has a closed form in which `d`
//! and `F` enter by their values, not through the rod's own matrices:
//! - rigid translation: `v' = -c v`, `c = d / (rho A)`: `v(t) = v0 exp(-c t)`; the midpoint rule
//!   multiplies `v` by exactly `(1 - c dt/2) / (1 + c dt/2)` per step;
//! - free axial vibration in the first free-free mode: every axial mode obeys
//!   `q'' + c q' + omega^2 q = 0`, so its amplitude decays like `exp(-c t / 2)`, i.e. at
//!   `d / (2 rho A)` whatever its frequency; the discrete mode shape `cos(pi i / n)` and frequency
//!   `omega_h^2 = 6 E / (rho l^2) (1 - cos(pi/n)) / (2 + cos(pi/n))` of linear elements with
//!   consistent mass are closed forms too, so the step map is known exactly;
//! - uniform load `F cos(Omega t)` along `-e2` from rest: its nodal forces are `F / (rho A)`
//!   times the mass matrix applied to a uniform vector, so the rod translates rigidly with
//!   `v' + c v = -(F / rho A) cos(Omega t)`.
//!
//! Run: `cargo test --profile quick --test suite closed_form_damping_load:: -- --nocapture`
use crate::common;

use common::{loads, max_abs, Table};
use georod::integrator::{DynamicState, Midpoint};
use georod::model::rod::{ROTATION, U1, U2};
use georod::model::{ReferenceCurve, Rod, Section};
use std::f64::consts::PI;

/// The paper's material and section (`b = h = 1`), so `rho A = 1e-6`, `c = d / (rho A) = 500/s`.
const E: f64 = 1.2e4;
const NU: f64 = 0.2;
const RHO: f64 = 1.0e-6;
const AREA: f64 = 1.0;
const D: f64 = 5.0e-4;
const LENGTH: f64 = 10.0;
const ELEMENTS: usize = 10;
/// Time step: `omega_h dt = 0.035` for the first axial mode, `c dt = 5e-4`.
const DT: f64 = 1e-6;
/// 0.01 s: `c t = 5`, the amplitudes fall by `exp(-2.5)` (axial) and `exp(-5)` (translation).
const STEPS: usize = 10_000;

fn c() -> f64 {
    D / (RHO * AREA)
}

/// A free straight rod along `e1` (no dof constrained).
fn free_rod(damping: f64) -> Rod {
    let section = Section::rectangular(E, NU, RHO, 1.0, 1.0);
    Rod::new(
        ReferenceCurve::Straight { length: LENGTH },
        section,
        damping,
        ELEMENTS,
    )
}

/// `max_i |x[3 i + k]|` over the nodes.
fn max_dof(x: &[f64], k: usize) -> f64 {
    x.iter()
        .skip(k)
        .step_by(3)
        .fold(0.0f64, |m, v| m.max(v.abs()))
}

/// The implicit midpoint map of `q'' + c q' + w2 q = 0` on `(q, q')` for one step `dt`:
/// `(I - dt/2 A)^-1 (I + dt/2 A)`, `A = [[0, 1], [-w2, -c]]`.
fn midpoint_map(w2: f64, c: f64, dt: f64) -> [[f64; 2]; 2] {
    let s = 0.5 * dt;
    let det = 1.0 + s * c + s * s * w2;
    [
        [(1.0 + s * c - s * s * w2) / det, 2.0 * s / det],
        [-2.0 * s * w2 / det, (1.0 - s * c - s * s * w2) / det],
    ]
}

#[test]
fn rigid_translation_loses_velocity_as_exp_minus_d_t_over_rho_a() {
    let rod = free_rod(D);
    let none = loads(&rod, true, 0.0, 0.0, 0.0);
    let v0 = [30.0, -20.0];
    let mut state = DynamicState::at_rest(vec![0.0; rod.dofs()]);
    for i in 0..rod.nodes() {
        state.v[3 * i + U1] = v0[0];
        state.v[3 * i + U2] = v0[1];
    }
    let factor = (1.0 - 0.5 * c() * DT) / (1.0 + 0.5 * c() * DT);
    let mut mid = Midpoint::new(&rod);
    let (mut worst_step, mut worst_rigid, mut worst_rotation) = (0.0f64, 0.0f64, 0.0f64);
    for n in 0..STEPS {
        let before = state.v.clone();
        mid.step(&rod, &none, &mut state, n as f64 * DT, DT, &[])
            .expect("step");
        for i in 0..rod.nodes() {
            for k in [U1, U2] {
                let expected = factor * before[3 * i + k];
                worst_step = worst_step.max((state.v[3 * i + k] - expected).abs() / expected.abs());
                worst_rigid = worst_rigid.max((state.v[3 * i + k] - state.v[k]).abs());
            }
        }
        worst_rotation = worst_rotation.max(max_dof(&state.u, ROTATION));
    }
    let t = STEPS as f64 * DT;
    let exact = (-c() * t).exp();
    let got = state.v[U1] / v0[0];
    let continuous = (got - exact).abs() / exact;
    // The midpoint factor against exp(-c dt): per step ln((1 - x) / (1 + x)) = -2 (x + x^3 / 3
    // + ...), x = c dt / 2, so after t the relative gap is c t (c dt)^2 / 12 = 1.04e-7.
    let predicted = c() * t * (c() * DT).powi(2) / 12.0;
    let mut table = Table::new("free rod, rigid translation (30, -20), d = 5e-4, dt = 1e-6");
    table.row(format_args!(
        "  per step: max |v_(n+1) - (1 - c dt/2)/(1 + c dt/2) v_n| / |v| = {worst_step:.2e}; \
         nodes differ by {worst_rigid:.1e} m/s, rotate by {worst_rotation:.1e} rad"
    ));
    table.row(format_args!(
        "  t = {t}: v/v0 = {got:.12e}, exp(-d t / (rho A)) = {exact:.12e}, rel. gap {continuous:.3e} \
         (predicted c t (c dt)^2 / 12 = {predicted:.3e})"
    ));
    // Per step and node: round-off. Positions (|u| up to 0.3) carry ulps of 5.5e-17, i.e.
    // strains of ~1e-16, whose elastic forces (EA = 1.2e4 on rho A = 1e-6) move the nodal
    // velocities apart by ~1e-12 m/s per step as a random walk: measured 4.5e-11 m/s after
    // 1e4 steps, 4.5e-11 of |v| at the end. Bounds 20x that; a 1 % error in d shows as 5e-6.
    assert!(worst_step < 1e-9, "per-step factor off by {worst_step:e}");
    assert!(worst_rigid < 1e-9, "the translation is not rigid");
    assert!(
        worst_rotation < 1e-14,
        "a translation rotated by {worst_rotation:e}"
    );
    // Against the continuous decay: the predicted O(dt^2) gap within 1 %.
    assert!(
        (continuous - predicted).abs() < 1e-2 * predicted,
        "v/v0 = {got}, exp(-ct) = {exact}"
    );
}

#[test]
fn free_axial_vibration_decays_at_d_over_2_rho_a() {
    let rod = free_rod(D);
    let none = loads(&rod, true, 0.0, 0.0, 0.0);
    let n = ELEMENTS as f64;
    let (l, theta) = (LENGTH / n, PI / n);
    let w2 = 6.0 * E / (RHO * l * l) * (1.0 - theta.cos()) / (2.0 + theta.cos());
    let shape: Vec<f64> = (0..rod.nodes()).map(|i| (i as f64 * theta).cos()).collect();
    let v_amp = 10.0;
    let mut state = DynamicState::at_rest(vec![0.0; rod.dofs()]);
    for (i, phi) in shape.iter().enumerate() {
        state.v[3 * i + U1] = v_amp * phi;
    }
    let map = midpoint_map(w2, c(), DT);
    let (mut q, mut p) = (0.0, v_amp);
    let mut mid = Midpoint::new(&rod);
    // W_k = u_k . v_(k+1) - u_(k+1) . v_k: the phase-plane area spanned by two successive states
    // of the mode, which the step map multiplies by det(map) exactly (continuous time:
    // exp(-c dt), Liouville), whatever the phase of the oscillation.
    let area = |a: &DynamicState, b: &DynamicState| -> f64 {
        (0..rod.nodes())
            .map(|i| a.u[3 * i] * b.v[3 * i] - b.u[3 * i] * a.v[3 * i])
            .sum()
    };
    let (mut w_first, mut w_last) = (f64::NAN, f64::NAN);
    let mut worst_mode = 0.0f64;
    let omega = w2.sqrt();
    for step in 0..STEPS {
        let before = state.clone();
        mid.step(&rod, &none, &mut state, step as f64 * DT, DT, &[])
            .expect("step");
        (q, p) = (map[0][0] * q + map[0][1] * p, map[1][0] * q + map[1][1] * p);
        for (i, phi) in shape.iter().enumerate() {
            let du = (state.u[3 * i] - q * phi).abs() * omega / v_amp;
            let dv = (state.v[3 * i] - p * phi).abs() / v_amp;
            worst_mode = worst_mode.max(du).max(dv);
        }
        assert_eq!(
            max_dof(&state.u, U2).max(max_dof(&state.u, ROTATION)),
            0.0,
            "an axial motion moved u2 or w"
        );
        w_last = area(&before, &state);
        if step == 0 {
            w_first = w_last;
        }
    }
    let span = (STEPS - 1) as f64 * DT;
    let rate = -(w_last / w_first).ln() / (2.0 * span);
    let closed_form = D / (2.0 * RHO * AREA);
    let det = map[0][0] * map[1][1] - map[0][1] * map[1][0];
    let discrete = -det.ln() / (2.0 * DT);
    let gap = (rate - closed_form).abs() / closed_form;
    let mut table = Table::new(
        "free rod, first axial mode (10 elements, omega_h = 34.5e3 rad/s), d = 5e-4, dt = 1e-6",
    );
    table.row(format_args!(
        "  nodal u1, v1 vs the exact step map of the mode: max error {worst_mode:.2e} \
         (of the amplitude)"
    ));
    table.row(format_args!(
        "  decay rate {rate:.9} 1/s; d/(2 rho A) = {closed_form}; rel. gap {gap:.3e}; \
         step map predicts {discrete:.9} (gap (omega dt/2)^2 = {:.3e})",
        (omega * DT / 2.0).powi(2)
    ));
    // The step is linear in the mode (one Newton correction, then a round-off chord
    // correction): the state follows the 2x2 map to round-off accumulated over 1e4 steps.
    // Measured 2.5e-11: ulp-level differences between the map's coefficients and the solver's
    // accumulate linearly over the 1e4 steps.
    assert!(
        worst_mode < 1e-10,
        "mode off the exact step map: {worst_mode:e}"
    );
    assert!((rate - discrete).abs() < 1e-9 * closed_form);
    // The midpoint rule damps a mode of frequency omega at (c/2) / (1 + (omega dt / 2)^2)
    // (from det = (1 - c dt/2 + (omega dt/2)^2) / (1 + c dt/2 + (omega dt/2)^2)): a gap of
    // 2.98e-4 here; 1e-3 bounds it with margin and is 200x below a 20 % error in d.
    assert!(
        gap < 1e-3,
        "decay rate {rate} vs d/(2 rho A) = {closed_form}"
    );
    assert!(max_abs(&state.v) < v_amp * (-closed_form * STEPS as f64 * DT).exp() * 1.01);
}

/// The rigid response to the uniform load `F cos(Omega t)` along `-e2` from rest: the velocity of
/// every node against the closed form of `v' + c v = -(F / rho A) cos(Omega t)`, `v(0) = 0`, and
/// against the same equation stepped by the midpoint rule (load at the step midpoint).
fn harmonic_response(damping: f64) -> (f64, f64) {
    let (f, omega) = (0.9, 3500.0);
    let rod = free_rod(damping);
    let load = loads(&rod, true, f, omega, 0.0);
    let (a, c) = (f / (RHO * AREA), damping / (RHO * AREA));
    let exact = |t: f64| {
        let (s, co) = (omega * t).sin_cos();
        -a * (c * co + omega * s - c * (-c * t).exp()) / (c * c + omega * omega)
    };
    let mut state = DynamicState::at_rest(vec![0.0; rod.dofs()]);
    let mut mid = Midpoint::new(&rod);
    let mut v_discrete = 0.0;
    let (mut worst_exact, mut worst_discrete) = (0.0f64, 0.0f64);
    for n in 0..STEPS {
        let t_mid = (n as f64 + 0.5) * DT;
        mid.step(&rod, &load, &mut state, n as f64 * DT, DT, &[])
            .expect("step");
        v_discrete = ((1.0 - 0.5 * c * DT) * v_discrete - DT * a * (omega * t_mid).cos())
            / (1.0 + 0.5 * c * DT);
        // Centre-of-mass velocity: the mean of the linearly interpolated velocity over the rod.
        let l = LENGTH / ELEMENTS as f64;
        let v_cm: f64 = (0..ELEMENTS)
            .map(|e| 0.5 * l * (state.v[3 * e + U2] + state.v[3 * e + 3 + U2]))
            .sum::<f64>()
            / LENGTH;
        let t = (n + 1) as f64 * DT;
        worst_exact = worst_exact.max((v_cm - exact(t)).abs());
        for i in 0..rod.nodes() {
            worst_discrete = worst_discrete.max((state.v[3 * i + U2] - v_discrete).abs());
        }
    }
    assert!(max_dof(&state.u, U1).max(max_dof(&state.u, ROTATION)) < 1e-12);
    let scale = a / omega;
    (worst_exact / scale, worst_discrete / scale)
}

#[test]
fn free_rod_under_uniform_harmonic_load_translates_at_f_over_rho_a_omega() {
    let mut table = Table::new(
        "free rod from rest, uniform load 0.9 cos(3500 t) along -e2: centre-of-mass velocity \
         vs closed form (errors relative to F / (rho A Omega) = 257 m/s)",
    );
    for damping in [0.0, D] {
        let (exact, discrete) = harmonic_response(damping);
        table.row(format_args!(
            "  d = {damping:.0e}: vs v(t) = {}: {exact:.2e}; nodes vs the stepped scalar \
             equation: {discrete:.2e}",
            if damping == 0.0 {
                "-F/(rho A Omega) sin(Omega t)"
            } else {
                "-F/(rho A) (c cos + Omega sin - c e^(-ct)) / (c^2 + Omega^2)"
            },
        ));
        // The midpoint rule samples the load at step midpoints: for d = 0 the stepped velocity
        // is exactly (Omega dt / 2) / sin(Omega dt / 2) = 1 + (Omega dt)^2 / 24 = 1 + 5.10e-7
        // times the exact one (measured: 5.10e-7); damping adds O((c dt)^2) = 2.5e-7 terms.
        // 1e-6 bounds both and is 1e5 below a 10 % error in F.
        assert!(exact < 1e-6, "d = {damping}: {exact:e}");
        // Node by node against the scalar recurrence: round-off (10^4 steps of a linear solve).
        assert!(discrete < 1e-11, "d = {damping}: {discrete:e}");
    }
}
