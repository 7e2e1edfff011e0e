//! The scenes' initial states (symmetry and axial force of the buckled beam, equilibrium of the
//! preloaded arches) and the contract of `Simulation::advance` (a failed step changes nothing; a
//! communication step cut into sub-steps equals the same sub-steps taken one by one).
//!
//! Run: `cargo test --profile quick --test suite physics_scenes:: -- --nocapture`
use crate::common;

use common::{
    buckling_threshold, critical_axial_force, max_abs, max_abs_diff, output, param, pinned_rod,
    set_input, set_param, simulation, Table,
};
use georod::model::element::Vector6;
use georod::model::rod::{ROTATION, U1, U2};
use georod::model::Rod;
use georod::simulation::Snapshot;
use std::f64::consts::PI;

fn element_dofs(u: &[f64], e: usize) -> Vector6 {
    Vector6::from_column_slice(&u[3 * e..3 * e + 6])
}

/// Largest deviation from the mirror symmetry about `s = L/2` of the buckled beam: `u2`
/// symmetric, `u1 + Delta s / L` antisymmetric, `w` antisymmetric.
fn symmetry_defect(rod: &Rod, u: &[f64], shortening: f64, span: f64) -> (f64, f64, f64) {
    let n = rod.last_node();
    let (mut d1, mut d2, mut dw) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..=n {
        let j = n - i;
        let a1 = u[3 * i + U1] + shortening * rod.node_s[i] / span;
        let b1 = u[3 * j + U1] + shortening * rod.node_s[j] / span;
        d1 = d1.max((a1 + b1).abs());
        d2 = d2.max((u[3 * i + U2] - u[3 * j + U2]).abs());
        dw = dw.max((u[3 * i + ROTATION] + u[3 * j + ROTATION]).abs());
    }
    (d1, d2, dw)
}

#[test]
fn buckled_beam_initial_state() {
    let mut t = Table::new(
        "BuckledBeam initial static state (defaults: L=10, b=h=1, Delta=pre_shortening)",
    );
    t.row(format_args!(
        "{:>5} {:>5} {:>11} {:>10} {:>10} {:>10} {:>11} {:>10} {:>10} {:>9}",
        "elem", "well", "w_mid", "sym u1", "sym u2", "sym w", "H=-N1", "|N2|", "max S1", "P_cr^h"
    ));
    let euler = PI * PI * common::section(1.0, 1.0).ei / 100.0;
    let p_cr = critical_axial_force(&common::section(1.0, 1.0), 10.0);
    for elements in [10.0, 40.0] {
        let mut w_mids = Vec::new();
        let mut states = Vec::new();
        for well in [1.0, -1.0] {
            let sim = simulation("BuckledBeam", &[("well", well), ("elements", elements)]);
            let (shortening, span) = (param(&sim, "pre_shortening"), param(&sim, "L"));
            let rod = sim.rod();
            let u = &sim.state().u;
            let (d1, d2, dw) = symmetry_defect(rod, u, shortening, span);
            // Element forces in the global frame: the translational part of each element's
            // internal force at its end node b, N_e = mean over the Gauss points of
            // S1 t + S2 n. With no load between the ends, N_e is the same in every element.
            let mut n_e = Vec::new();
            let mut s1 = Vec::new();
            for (e, el) in rod.elements.iter().enumerate() {
                let ue = element_dofs(u, e);
                let f = el.internal_force(&rod.section, &ue);
                n_e.push((f[3], f[4]));
                s1.push(el.stress_resultants(&rod.section, &ue)[0]);
            }
            let thrust = -n_e[0].0;
            let spread = n_e
                .iter()
                .map(|&(x, y)| ((x + thrust).abs()).max(y.abs()))
                .fold(0.0, f64::max);
            let max_s1 = s1.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x));
            let min_s1 = s1.iter().fold(f64::INFINITY, |m, &x| m.min(x));
            // The discrete buckling load of the same mesh (the bisection of physics_buckling).
            let rod_lin = pinned_rod(span, elements as usize);
            let delta_h = buckling_threshold(&rod_lin, 0.2);
            let p_h = delta_h / span * rod.section.ea;
            let w_mid = output(&sim, "w_mid");
            t.row(format_args!(
                "{elements:>5} {well:>5} {w_mid:>11.7} {d1:>10.2e} {d2:>10.2e} {dw:>10.2e} {thrust:>11.5} {spread:>10.2e} {max_s1:>10.4} {p_h:>9.4}",
            ));
            // Tolerances: the discrete problem is left-right symmetric and Newton keeps the
            // symmetry of its (symmetric) starting point up to round-off: measured <= 5.6e-17
            // on |u| ~ 0.3; bound 1e-14 (~50 ulps).
            assert!(
                d1 < 1e-14 && d2 < 1e-14 && dw < 1e-14,
                "asymmetric: {d1:e} {d2:e} {dw:e}"
            );
            assert!(w_mid * well > 0.1, "w_mid = {w_mid} not in well {well}");
            // Nodal equilibrium: N_e equal in all elements, vertical part zero, to the Newton
            // residual: the last correction (< 1e-10 of the motion) is followed by quadratic
            // convergence, so what remains is round-off of forces ~EA |e| ~ 1e2: measured
            // 1.6e-12 (1.6e-14 of the thrust); bound 1e-12 of the thrust.
            assert!(spread < 1e-12 * thrust, "element forces differ: {spread:e}");
            // Compression everywhere; the thrust exceeds the buckling load of the same mesh
            // (post-buckling stiffening of the pinned elastica, H / P_cr ~ 1 + theta0^2 / 8).
            assert!(max_s1 < 0.0, "tension in a buckled element");
            assert!((-min_s1 - thrust).abs() < 1e-3 * thrust);
            assert!(
                thrust > p_h,
                "thrust {thrust} below the discrete buckling load {p_h}"
            );
            if elements == 10.0 {
                // The scene as shipped (10 elements): above the Euler load, as the issue states.
                assert!(
                    thrust > euler,
                    "thrust {thrust} below the Euler load {euler}"
                );
            }
            w_mids.push(w_mid);
            states.push(u.clone());
        }
        // The two wells are mirror images (u2, w -> -u2, -w; u1 unchanged).
        let (up, down) = (&states[0], &states[1]);
        let mut mirror = 0.0f64;
        for i in 0..up.len() {
            let sign = if i % 3 == U1 { 1.0 } else { -1.0 };
            mirror = mirror.max((up[i] - sign * down[i]).abs());
        }
        t.row(format_args!(
            "  {elements} elements: w_mid(+1) + w_mid(-1) = {:.2e}, mirror defect of the states {mirror:.2e}",
            w_mids[0] + w_mids[1]
        ));
        // Exact: every operation of the model and of Newton is odd or even in (u2, w), and so
        // are IEEE arithmetic and libm's sin/cos (python/tests/test_analysis_fmu.py finds the
        // whole chaotic trajectories mirrored bit for bit).
        assert_eq!(w_mids[0], -w_mids[1]);
        assert_eq!(mirror, 0.0);
    }
    t.row(format_args!(
        "  Euler load pi^2 EI/L^2 = {euler:.4}; continuum critical force with shear and stretch \
         P_cr = {p_cr:.4}. The thrust exceeds the Euler load on 10 elements only because the \
         10-element buckling load is 1.3% stiff; on 40 elements it lies between P_cr and P_E."
    ));
}

#[test]
fn preloaded_arches_start_in_equilibrium() {
    let mut t = Table::new("arches with crown preload P0: initial state residual and rest");
    t.row(format_args!(
        "{:<12} {:>6} {:>12} {:>13} {:>14} {:>14}",
        "scene", "P0", "w_mid", "|r|_inf/P0", "|du| 1 step", "|v| 1 step"
    ));
    for (kind, preloads) in [
        ("PinnedArch", [20.0, -20.0]),
        ("ClampedArch", [20.0, -20.0]),
    ] {
        for p0 in preloads {
            let mut sim = simulation(kind, &[("P0", p0)]);
            let rod = sim.rod().clone();
            let u = sim.state().u.clone();
            let mut r = vec![0.0; rod.dofs()];
            rod.internal_force(&u, &mut r);
            let mut f_ext = vec![0.0; rod.dofs()];
            rod.add_point_transverse_load(&mut f_ext, rod.midspan(), p0);
            for ((ri, fi), &fixed) in r.iter_mut().zip(&f_ext).zip(&rod.fixed) {
                *ri = if fixed { 0.0 } else { *ri - fi };
            }
            let residual = max_abs(&r) / p0.abs();
            let w_mid = output(&sim, "w_mid");
            // Released with F = 0 (default) and f_ctrl = 0, the preload P0 keeps acting: it
            // must stay at rest.
            sim.advance(1e-4).expect("advance");
            let moved = max_abs_diff(&sim.state().u, &u);
            let speed = max_abs(&sim.state().v);
            t.row(format_args!(
                "{kind:<12} {p0:>6} {w_mid:>12.6} {residual:>13.3e} {moved:>14.3e} {speed:>14.3e}",
            ));
            // Tolerances: the static Newton stops with corrections below 1e-10 of the motion and
            // converges quadratically, so the residual is round-off of the internal forces:
            // measured <= 1.4e-13 of the load; bound 1e-11. At rest over one step it then moves
            // by round-off (measured 1.8e-15) at speeds of 2 du / dt (5.5e-11); bounds 1e-13
            // and 1e-9.
            assert!(residual < 1e-11, "{kind}: residual {residual:e}");
            assert!(
                w_mid * p0 < 0.0,
                "{kind}: crown does not move with the load"
            );
            assert!(
                moved < 1e-13 && speed < 1e-9,
                "{kind}: not at rest ({moved:e}, {speed:e})"
            );
        }
    }
}

/// Bit patterns of everything in a snapshot (f64 equality would accept -0.0 == 0.0).
fn bits(s: &Snapshot) -> Vec<u64> {
    let mut b: Vec<u64> = s
        .displacements
        .iter()
        .chain(&s.velocities)
        .map(|x| x.to_bits())
        .collect();
    b.extend(s.values.iter().chain(&s.inputs).map(|x| x.to_bits()));
    b.extend([s.time.to_bits(), s.last_newton_iterations as u64]);
    b
}

#[test]
fn failed_advance_leaves_state_unchanged() {
    let mut t = Table::new("Simulation::advance failure: state unchanged");
    // First a few good steps (so the state is a moving one, not the initial one), then a load of
    // 1e9 per unit length with steps of up to 1 s: Newton fails on every sub-step size down to
    // h / 2^5.
    let overrides = [("dt_max", 1e-5)];
    let mut sim = simulation("BuckledBeam", &overrides);
    let outputs = |sim: &georod::simulation::Simulation| {
        [
            "w_mid",
            "v_mid",
            "E_kin",
            "E_strain",
            "W_ext",
            "energy_error",
            "left_Rx",
            "right_Ry",
        ]
        .map(|name| output(sim, name).to_bits())
    };
    set_input(&mut sim, "f_ctrl", 0.5);
    for _ in 0..3 {
        sim.advance(1e-4).unwrap();
    }
    set_param(&mut sim, "F", 1e9);
    set_param(&mut sim, "Omega", 0.0);
    set_input(&mut sim, "f_ctrl", 3.0);
    let before = sim.snapshot();
    let outputs_before = outputs(&sim);
    let result = sim.advance(0.5);
    t.row(format_args!(
        "  after 3 steps: advance(0.5) with F = 1e9 (50000 sub-steps of dt_max would be needed; \
         it fails on the first): {result:?}"
    ));
    assert!(result.is_err(), "expected a failing step");
    let after = sim.snapshot();
    assert_eq!(
        bits(&before),
        bits(&after),
        "state changed by a failed step"
    );
    assert_eq!(sim.time().to_bits(), before.time.to_bits());
    assert_eq!(outputs_before, outputs(&sim), "outputs changed");
    // The failure leaves no trace in the integrator either: continuing with a sane load gives
    // bit for bit what a simulation restored from the same snapshot gives.
    let mut twin = simulation("BuckledBeam", &overrides);
    twin.restore(&before).unwrap();
    for s in [&mut sim, &mut twin] {
        set_param(s, "F", 0.7);
        set_param(s, "Omega", 3500.0);
        set_input(s, "f_ctrl", 0.0);
    }
    for _ in 0..5 {
        sim.advance(1e-5).unwrap();
        twin.advance(1e-5).unwrap();
    }
    t.row(format_args!(
        "  bit-identical before/after the failure: yes; continuation equals a restored twin: {}",
        bits(&sim.snapshot()) == bits(&twin.snapshot())
    ));
    assert_eq!(bits(&sim.snapshot()), bits(&twin.snapshot()));
}

#[test]
fn substeps_equal_separate_communication_steps() {
    let mut t = Table::new(
        "communication step of 1e-4 (10 sub-steps of dt_max = 1e-5) vs 10 steps of 1e-5",
    );
    t.row(format_args!(
        "{:<12} {:>5} {:>14} {:>14} {:>14} {:>8}",
        "scene", "step", "max |du|", "max |dv|", "|u| scale", "bitwise"
    ));
    for (kind, f, f_ctrl) in [("BuckledBeam", 0.7, 0.0), ("PinnedArch", 50.0, 5.0)] {
        let mut a = simulation(kind, &[("F", f)]);
        let mut b = simulation(kind, &[("F", f)]);
        set_input(&mut a, "f_ctrl", f_ctrl);
        set_input(&mut b, "f_ctrl", f_ctrl);
        let mut worst = 0.0f64;
        for k in 1..=5 {
            let report = a.advance(1e-4).unwrap();
            assert_eq!(report.substeps, 10);
            for _ in 0..10 {
                let r = b.advance(1e-5).unwrap();
                assert_eq!(r.substeps, 1);
            }
            let (sa, sb) = (a.state(), b.state());
            let du = max_abs_diff(&sa.u, &sb.u);
            let dv = max_abs_diff(&sa.v, &sb.v);
            let scale = max_abs(&sa.u);
            let bitwise =
                sa.u.iter()
                    .chain(&sa.v)
                    .zip(sb.u.iter().chain(&sb.v))
                    .all(|(x, y)| x.to_bits() == y.to_bits());
            t.row(format_args!(
                "{kind:<12} {k:>5} {du:>14.3e} {dv:>14.3e} {scale:>14.3e} {bitwise:>8}",
            ));
            // Velocity scale of round-off: v_(n+1) = 2 du / dt - v_n turns an ulp of u into
            // 2 eps |u| / dt, so velocities are compared relative to |v| + |u| / dt.
            let v_scale = max_abs(&sa.v) + scale / 1e-5;
            worst = worst.max(du / scale).max(dv / v_scale);
            // The two differ only in how t_k and dt are rounded (t0 + k h/10 with h/10 vs a
            // running sum of 1e-5 with dt = 1e-5): the states agree to 1e-12 relative.
            assert!(
                du <= 1e-12 * scale,
                "{kind}: displacements differ by {du:e}"
            );
            assert!(dv <= 1e-12 * v_scale, "{kind}: velocities differ by {dv:e}");
        }
        assert!((a.time() - b.time()).abs() < 1e-15);
        t.row(format_args!(
            "  {kind}: worst relative difference {worst:.2e}"
        ));
    }
}

/// The branch choice with a constant load that breaks the symmetry: the BuckledBeam scene with a
/// downward dead load q. Below the snap-through load both wells hold a stable equilibrium, the
/// upper one pushed down (0 < w_mid < the unloaded 0.330), the lower one deeper; past it only the
/// lower well holds one, and asking for the upper well is refused with a message.
#[test]
fn branch_choice_under_a_constant_load() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/BuckledBeam.toml"
    ))
    .unwrap()
    .replace(
        "[shape]",
        "[[parameter]]\nname = \"q0\"\nstart = 0.0\n\n[[load]]\nname = \"dead\"\nkind = \
             \"distributed\"\ndirection = \"-e2\"\nvalue = \"q0\"\n\n[shape]",
    );
    let scene = std::sync::Arc::new(georod::scene::Scene::parse(&text, "dead load").unwrap());
    let build = |q: f64, well: f64| {
        let values = scene
            .values_with([("q0", q), ("well", well), ("F", 0.0)])
            .unwrap();
        georod::simulation::Simulation::new(scene.clone(), values)
    };
    let mut t = Table::new("BuckledBeam with a downward dead load q: the two wells");
    for q in [0.1, 0.2] {
        let (up, down) = (build(q, 1.0).unwrap(), build(q, -1.0).unwrap());
        let (wu, wd) = (output(&up, "w_mid"), output(&down, "w_mid"));
        let lift = output(&up, "left_Ry") + output(&up, "right_Ry");
        t.row(format_args!(
            "  q = {q}: w_mid up {wu:.6}, down {wd:.6}; reactions {lift:.12} = q L {}",
            q * 10.0
        ));
        assert!(0.0 < wu && wu < 0.330, "q = {q}: upper well at {wu}");
        assert!(wd < -0.330, "q = {q}: lower well at {wd}");
        assert!((lift - q * 10.0).abs() < 1e-8 * q * 10.0);
    }
    let e = build(1.0, 1.0)
        .err()
        .expect("no upper equilibrium at q = 1");
    t.row(format_args!("  q = 1, well = +1: {e}"));
    assert!(e.to_string().contains("no equilibrium found"), "{e}");
    assert!(build(1.0, -1.0).is_ok());
}
