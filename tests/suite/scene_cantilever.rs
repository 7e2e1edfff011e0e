//! The cantilever of `examples/Cantilever.toml` (a scene file: clamped root, dead tip load `P`)
//! made slender (L/h = 500), for P L^2/EI = 1, 2, 5, 10: the initial static state against the
//! inextensible elastica (computed here by shooting), the root reactions against the load and
//! its moment, and the shape samples against the rod's root and length.
//!
//! Run: `cargo test --profile quick --test suite scene_cantilever:: -- --nocapture`
use crate::common;

use common::{output, Table};
use georod::scene::{Scene, Std};
use georod::simulation::Simulation;
use std::sync::Arc;

/// The inextensible elastica of a cantilever under a dead tip load: with `s` in [0, 1] and
/// `theta` the tangent angle, `theta'' = alpha cos(theta)`, `theta(0) = 0`, `theta'(1) = 0`
/// (moment `EI theta' = -P (x_tip - x)`). Shooting on `theta'(0)` by bisection with RK4 steps.
/// Returns the tip position `(x, y) / L`.
fn elastica_tip(alpha: f64) -> (f64, f64) {
    const STEPS: usize = 4000;
    let integrate = |slope0: f64| {
        // State (theta, theta', x, y); RK4 with a fixed step.
        let f = |z: [f64; 4]| [z[1], alpha * z[0].cos(), z[0].cos(), z[0].sin()];
        let h = 1.0 / STEPS as f64;
        let mut z = [0.0, slope0, 0.0, 0.0];
        for _ in 0..STEPS {
            let add = |a: [f64; 4], b: [f64; 4], c: f64| std::array::from_fn(|i| a[i] + c * b[i]);
            let k1 = f(z);
            let k2 = f(add(z, k1, 0.5 * h));
            let k3 = f(add(z, k2, 0.5 * h));
            let k4 = f(add(z, k3, h));
            z = std::array::from_fn(|i| {
                z[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
            });
        }
        z
    };
    // theta'(1) grows monotonically with theta'(0) in [-alpha, 0].
    let (mut lo, mut hi) = (-alpha, 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if integrate(mid)[1] > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let z = integrate(0.5 * (lo + hi));
    (z[2], z[3])
}

fn cantilever() -> Arc<Scene> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/Cantilever.toml");
    Arc::new(Scene::load(path).expect("example scene"))
}

#[test]
fn cantilever_scene_matches_the_elastica() {
    let scene = cantilever();
    let (length, height) = (10.0, 0.02); // L/h = 500
    let mut t = Table::new(
        "examples/Cantilever.toml, L/h = 500, 40 elements: static tip deflection vs the \
         inextensible elastica (shooting), root reactions vs the tip load, shape samples",
    );
    t.row(format_args!(
        "{:>5} {:>11} {:>11} {:>9} {:>10} {:>10} {:>10} {:>11}",
        "PL2/EI", "w_tip/L", "elastica", "rel.err", "Ry/P-1", "Rx/P", "M/(P x)-1", "polyline/L"
    ));
    for alpha in [1.0, 2.0, 5.0, 10.0] {
        let mut values = scene.defaults();
        scene.set(&mut values, "h", height).unwrap();
        scene.set(&mut values, "L", length).unwrap();
        scene.set(&mut values, "elements", 40.0).unwrap();
        let width = values.get(scene.param_index("b").unwrap());
        let ei = values.std(Std::E) * width * height.powi(3) / 12.0;
        let load = alpha * ei / (length * length);
        scene.set(&mut values, "P", load).unwrap();
        let sim = Simulation::new(scene.clone(), values).expect("static state");
        let (x_ref, y_ref) = elastica_tip(alpha);
        let w_tip = output(&sim, "w_tip") / length;
        let error = (w_tip - y_ref).abs() / y_ref.abs();
        // Reactions of the root on the rod: they balance the tip load -P e2 and its moment about
        // the root, P x_tip (counter-clockwise), x_tip the tip's current abscissa.
        let x_tip = length + output(&sim, "u_tip");
        let (rx, ry, m) = (
            output(&sim, "root_Rx"),
            output(&sim, "root_Ry"),
            output(&sim, "root_M"),
        );
        let (ry_err, rx_err, m_err) = (ry / load - 1.0, rx / load, m / (load * x_tip) - 1.0);
        // Shape samples: from the root, a polyline as long as the rod up to the chord error of
        // 40 straight pieces on a curve of curvature up to alpha / L, (kappa ds)^2 / 24. (The
        // samples fall on the nodes here; the element kinematics, linear displacements with an
        // interpolated rotation, put the nodes of a bent element at a chord of
        // l (1 + O((kappa l)^2)): the same order, of either sign.)
        let points = scene.shape_points;
        let p: Vec<[f64; 2]> = (0..points).map(|i| sim.shape_point(i)).collect();
        let polyline: f64 = p
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum();
        let chord = (alpha / (points - 1) as f64).powi(2) / 24.0;
        t.row(format_args!(
            "{alpha:>5} {w_tip:>11.6} {y_ref:>11.6} {error:>9.2e} {ry_err:>10.1e} {rx_err:>10.1e} \
             {m_err:>10.1e} {:>11.7}",
            polyline / length
        ));
        // 0.5 %: the bound; the 40-element hybrid mesh is second order (the elastica
        // test in physics_elastica.rs), and shear and stretch change the deflection by
        // O((h/L)^2) = 4e-6 only.
        assert!(
            error < 5e-3,
            "alpha {alpha}: tip deflection off by {error:.2e}"
        );
        let x_err = ((x_tip / length) - x_ref).abs();
        assert!(
            x_err < 5e-3 * (1.0 - x_ref).max(1e-2),
            "alpha {alpha}: tip abscissa off by {x_err:.2e}"
        );
        // The static reactions are f_int - f_ext on the held dofs of an equilibrium converged to
        // round-off: their balance with the load is exact up to the Newton residual.
        for (what, err) in [("Ry", ry_err), ("Rx", rx_err), ("M", m_err)] {
            assert!(err.abs() < 1e-8, "alpha {alpha}: {what} off by {err:.2e}");
        }
        assert_eq!(p[0], [0.0, 0.0], "the shape starts at the root");
        assert!(
            (polyline - length).abs() <= length * (chord + 1e-6),
            "alpha {alpha}: polyline {polyline} vs length {length} (chord error {chord:.1e})"
        );
    }
}
