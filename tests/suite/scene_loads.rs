//! The loads of an engineer's beam: partial and linearly varying distributed loads, point
//! moments and gravity, against beam theory with shear (static deflections and reactions), and
//! the tip moment `2 pi EI / L` that rolls a cantilever into a full circle.
//!
//! Run: `cargo test --profile quick --test suite scene_loads:: -- --nocapture`
use crate::common;

use common::{output, Table};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::f64::consts::PI;
use std::sync::Arc;

/// Steel, 50 x 100 mm, L = 2 m (L/h = 20: the shear part of the deflection is 1e-2 of it).
const E: f64 = 210e9;
const G: f64 = 210e9 / 2.6;
const RHO: f64 = 7850.0;
const AREA: f64 = 0.005;
const INERTIA: f64 = 0.05 * 1e-3 / 12.0;
const LENGTH: f64 = 2.0;

/// A beam with the given supports and loads (TOML), sensors `w_tip` at 1 and `w_mid` at 0.5.
fn beam(supports: &str, loads: &str) -> Arc<Scene> {
    let text = format!(
        r#"
name = "Beam"
[geometry]
shape = "straight"
L = {LENGTH}
[defaults]
E = {E}
nu = 0.3
rho = {RHO}
b = 0.05
h = 0.1
elements = 40
{supports}
{loads}
[[sensor]]
name = "w_tip"
at = 1.0
quantity = "u2"
[[sensor]]
name = "u_tip"
at = 1.0
quantity = "u1"
[[sensor]]
name = "w_mid"
at = 0.5
quantity = "u2"
[[sensor]]
name = "rotation_tip"
at = 1.0
quantity = "w"
"#
    );
    Arc::new(Scene::parse(&text, "beam.toml").unwrap_or_else(|e| panic!("{e}")))
}

const CLAMPED: &str = "[[support]]\nname = \"root\"\nat = 0.0\nfix = [\"u1\", \"u2\", \"w\"]";
const SIMPLE: &str = "[[support]]\nname = \"A\"\nat = 0.0\nfix = [\"u1\", \"u2\"]\n\
                      [[support]]\nname = \"B\"\nat = 1.0\nfix = [\"u2\"]";

/// `name` in the static state on `n` elements.
fn statics(scene: &Arc<Scene>, n: f64, names: &[&str]) -> Vec<f64> {
    let values = scene.values_with([("elements", n)]).unwrap();
    let sim = Simulation::new(scene.clone(), values).expect("static state");
    names.iter().map(|name| output(&sim, name)).collect()
}

/// A sensor Richardson-extrapolated from 40 and 80 elements (the mesh error is O(l^2)).
fn extrapolated(scene: &Arc<Scene>, name: &str) -> f64 {
    let (coarse, fine) = (
        statics(scene, 40.0, &[name])[0],
        statics(scene, 80.0, &[name])[0],
    );
    (4.0 * fine - coarse) / 3.0
}

/// Static deflections under the new distributed loads against Timoshenko beam theory (bending
/// part plus shear part):
/// - tip of a cantilever under a partial uniform load over [a, L]:
///   `q (3 L^4 - 4 a^3 L + a^4) / (24 EI)` and `q (L^2 - a^2) / (2 G A)`;
/// - under triangular loads falling from `q0` at the root to 0: `q0 L^4 / (30 EI)` and
///   `q0 L^2 / (6 G A)`; rising to `q0` at the tip: `11 q0 L^4 / (120 EI)` and
///   `q0 L^2 / (3 G A)`;
/// - midspan of a simply supported beam under its own weight, `q = rho A g`:
///   `5 q L^4 / (384 EI)` and `q L^2 / (8 G A)`.
///
/// The reactions balance the load.
#[test]
fn distributed_loads_and_gravity_deflect_as_timoshenko_beams() {
    let (ei, ga, l) = (E * INERTIA, G * AREA, LENGTH);
    let q = 1000.0;
    let a = 0.37 * l; // inside an element of every mesh here: the patch ends mid-element
    let weight = RHO * AREA * 9.81;
    let cases = [
        (
            "partial uniform load over [0.37, 1]",
            CLAMPED,
            format!("from = 0.37\nvalue = {q}"),
            "w_tip",
            q * (3.0 * l.powi(4) - 4.0 * a.powi(3) * l + a.powi(4)) / (24.0 * ei)
                + q * (l * l - a * a) / (2.0 * ga),
            q * (l - a),
        ),
        (
            "triangular load, q0 at the root",
            CLAMPED,
            format!("value = {q}\nvalue_end = 0.0"),
            "w_tip",
            q * l.powi(4) / (30.0 * ei) + q * l * l / (6.0 * ga),
            0.5 * q * l,
        ),
        (
            "triangular load, q0 at the tip",
            CLAMPED,
            format!("value = 0.0\nvalue_end = {q}"),
            "w_tip",
            11.0 * q * l.powi(4) / (120.0 * ei) + q * l * l / (3.0 * ga),
            0.5 * q * l,
        ),
        (
            "gravity on a simply supported beam",
            SIMPLE,
            String::new(),
            "w_mid",
            5.0 * weight * l.powi(4) / (384.0 * ei) + weight * l * l / (8.0 * ga),
            weight * l,
        ),
    ];
    let mut t = Table::new(
        "steel beam 2 m, 50 x 100 mm: static deflection vs Timoshenko beam theory (40/80 \
         elements extrapolated), reactions vs the load",
    );
    for (what, supports, keys, sensor, deflection, total) in cases {
        let kind = if what.starts_with("gravity") {
            "gravity"
        } else {
            "distributed"
        };
        let load =
            format!("[[load]]\nname = \"q\"\nkind = \"{kind}\"\ndirection = \"-e2\"\n{keys}\n");
        let scene = beam(supports, &load);
        let got = -extrapolated(&scene, sensor);
        let error = (got - deflection).abs() / deflection;
        let reactions = if supports == CLAMPED {
            statics(&scene, 40.0, &["root_Ry"])[0]
        } else {
            statics(&scene, 40.0, &["A_Ry", "B_Ry"]).iter().sum()
        };
        let balance = (reactions - total).abs() / total;
        t.row(format_args!(
            "  {what}: {got:.8e} vs {deflection:.8e}, error {error:.1e}; reactions - load {balance:.1e}"
        ));
        // 1e-5: below the shear part (1e-2 of the deflection) by 1000, above the extrapolated
        // mesh error and the geometric nonlinearity ((w/L)^2 < 1e-8).
        assert!(error < 1e-5, "{what}: {got} vs {deflection}");
        // Statics: the reactions are the residual on the held dofs of a converged equilibrium.
        assert!(balance < 1e-9, "{what}: reactions {reactions} vs {total}");
    }
}

/// A linearly varying load over a part of a simply supported beam: the reactions are its
/// resultant's lever rule, `R_B = integral q(s) s ds / L` (exact for any mesh: the nodal loads
/// are the consistent ones, integrated exactly).
#[test]
fn trapezoidal_patch_reactions_follow_the_lever_rule() {
    let (q1, q2, from, to) = (800.0, 2000.0, 0.2, 0.65);
    let load = format!(
        "[[load]]\nname = \"q\"\nkind = \"distributed\"\ndirection = \"-e2\"\nfrom = {from}\n\
         to = {to}\nvalue = {q1}\nvalue_end = {q2}\n"
    );
    let scene = beam(SIMPLE, &load);
    let (a, b) = (from * LENGTH, to * LENGTH);
    // q(s) = q1 + (q2 - q1) (s - a) / (b - a): resultant and first moment about s = 0.
    let total = 0.5 * (q1 + q2) * (b - a);
    let moment = (b - a) * (q1 * (2.0 * a + b) + q2 * (a + 2.0 * b)) / 6.0;
    for n in [7.0, 40.0] {
        let r = statics(&scene, n, &["A_Ry", "B_Ry"]);
        let want = [total - moment / LENGTH, moment / LENGTH];
        for (got, want) in r.iter().zip(want) {
            // The moment balance holds about the deformed geometry: off by O(w/L) = 1e-5.
            assert!((got - want).abs() < 1e-4 * want, "{n}: {got} vs {want}");
        }
    }
}

/// A tip moment `M = 2 pi EI / L` bends a cantilever at the constant curvature `M / EI`:
/// into a full circle, its tip back at the root, turned by 2 pi.
#[test]
fn tip_moment_rolls_a_cantilever_into_a_full_circle() {
    let ei = E * INERTIA;
    let moment = 2.0 * PI * ei / LENGTH;
    let load = format!("[[load]]\nname = \"m\"\nkind = \"moment\"\nat = 1.0\nvalue = {moment}\n");
    let scene = beam(CLAMPED, &load);
    let mut t = Table::new("cantilever, tip moment 2 pi EI / L: tip position and rotation");
    for n in [20.0, 40.0] {
        let r = statics(&scene, n, &["u_tip", "w_tip", "rotation_tip", "root_M"]);
        let gap = (LENGTH + r[0]).hypot(r[1]) / LENGTH;
        t.row(format_args!(
            "  {n} elements: tip at ({:.3e}, {:.3e}) from the root (gap {gap:.2e} L), rotation \
             {:.12} = 2 pi {:+.1e}, root moment {:.6e}",
            LENGTH + r[0],
            r[1],
            r[2],
            r[2] / (2.0 * PI) - 1.0,
            r[3]
        ));
        // Constant curvature is what the hybrid element represents exactly (the rotation
        // linear, each element's chord the rotated chord of its arc): the nodes lie on the
        // circle and the tip is back at the root to round-off; the root holds -M.
        assert!(
            (r[2] / (2.0 * PI) - 1.0).abs() < 1e-12,
            "{n}: rotation {}",
            r[2]
        );
        assert!(
            (r[3] / moment + 1.0).abs() < 1e-9,
            "{n}: root moment {}",
            r[3]
        );
        assert!(gap < 1e-12, "{n}: the tip misses the root by {gap:e} L");
    }
}

#[test]
fn bad_loads_are_refused() {
    let cases = [
        (
            "kind = \"distributed\"\ndirection = \"-e2\"\nvalue = 1.0\nfrom = 0.6\nto = 0.4",
            vec!["key `to`", "`from` must be below `to`"],
        ),
        (
            "kind = \"point\"\nat = 0.5\ndirection = \"-e2\"\nvalue = 1.0\nvalue_end = 2.0",
            vec!["key `value_end`", "only a distributed load"],
        ),
        (
            "kind = \"moment\"\nat = 0.5\ndirection = \"e2\"\nvalue = 1.0",
            vec!["key `direction`", "about e3"],
        ),
        (
            "kind = \"gravity\"\ntime = \"harmonic\"",
            vec!["key `time`", "constant"],
        ),
        (
            "kind = \"gravity\"\nat = 0.5",
            vec!["key `at`", "acts along the rod"],
        ),
        (
            "kind = \"distributed\"\ndirection = \"-e2\"\ntime = \"input\"\nvalue_end = 2.0",
            vec!["key `value_end`", "input"],
        ),
        ("kind = \"torque\"", vec!["key `kind`", "gravity"]),
    ];
    for (keys, parts) in cases {
        let load = format!("[[load]]\nname = \"q\"\n{keys}\n");
        let text = format!(
            "name = \"B\"\n[geometry]\nshape = \"straight\"\nL = 2.0\n[defaults]\nE = 1.0\nrho = 1.0\n{CLAMPED}\n{load}"
        );
        common::assert_refused(keys, &text, &parts);
    }
}

/// A harmonic tip moment and an input moment do work through the rotation dof: the energy
/// ledger books it (`W_ext`, `W_ctrl`) as exactly as for forces (energy-momentum scheme: to
/// round-off).
#[test]
fn moments_do_work_in_the_energy_ledger() {
    let load = "[[load]]\nname = \"m\"\nkind = \"moment\"\nat = 1.0\ntime = \"harmonic\"\n\
                [[load]]\nname = \"m_ctrl\"\nkind = \"moment\"\nat = 0.5\ntime = \"input\"\n";
    let scene = beam(CLAMPED, load);
    let values = scene
        .values_with([
            ("F", 2000.0),
            ("Omega", 300.0),
            ("integrator", 2.0),
            ("d", 0.0),
        ])
        .unwrap();
    let mut sim = Simulation::new(scene.clone(), values).unwrap();
    common::set_input(&mut sim, "m_ctrl", 500.0);
    for _ in 0..100 {
        sim.advance(1e-4).unwrap();
    }
    let (work, control, error) = (
        output(&sim, "W_ext"),
        output(&sim, "W_ctrl"),
        output(&sim, "energy_error"),
    );
    println!("W_ext {work:.6e}, W_ctrl {control:.6e}, energy_error {error:.1e}");
    assert!(work.abs() > 0.0 && control.abs() > 0.0);
    assert!(
        error.abs() < 1e-9 * (work.abs() + control.abs()),
        "{error:e}"
    );
}
