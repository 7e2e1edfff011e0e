//! The mesh follows the scene: every support is a node, the elements are spread over the
//! segments between the supports, every count from one per segment up works, and a scene whose
//! supports are nodes of the uniform mesh gets exactly that mesh.
//!
//! Run: `cargo test --profile quick --test suite scene_mesh:: -- --nocapture`
use crate::common;

use common::{output, Table};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

/// A two-span continuous beam (pin at 0, rollers at `at` and 1) under a constant uniform load
/// `q = 1e-6` along -e2: slender (L / h = 200) and loaded lightly, so linear beam theory holds.
fn two_spans(at: f64) -> Arc<Scene> {
    let text = format!(
        r#"
name = "TwoSpans"
[geometry]
shape = "straight"
L = 10.0
[defaults]
E = 1.2e4
rho = 1.0e-6
h = 0.05
elements = 10
[[support]]
name = "A"
at = 0.0
fix = ["u1", "u2"]
[[support]]
name = "B"
at = {at}
fix = ["u2"]
[[support]]
name = "C"
at = 1.0
fix = ["u2"]
[[load]]
name = "q"
kind = "distributed"
direction = "-e2"
value = 1e-6
"#
    );
    Arc::new(Scene::parse(&text, "two_spans.toml").expect("scene"))
}

/// Reactions of the two-span beam by the three-moment equation: the hogging moment over the
/// middle support is `q (a^3 + b^3) / (8 L)`.
fn two_span_reactions(q: f64, a: f64, b: f64) -> [f64; 3] {
    let moment = q * (a.powi(3) + b.powi(3)) / (8.0 * (a + b));
    let ra = 0.5 * q * a - moment / a;
    let rc = 0.5 * q * b - moment / b;
    [ra, q * (a + b) - ra - rc, rc]
}

#[test]
fn every_count_from_one_per_segment_up_puts_the_supports_on_nodes() {
    let scene = two_spans(0.37);
    assert_eq!(scene.element_range(), (2, 100_000));
    for n in 2..=40 {
        let values = scene.values_with([("elements", n as f64)]).unwrap();
        let sim = Simulation::new(scene.clone(), values).expect("static state");
        let rod = sim.rod();
        assert_eq!(rod.elements.len(), n);
        // The support is a node, exactly where the scene puts it.
        let b = rod.node_at(3.7);
        assert!(
            (rod.node_s[b] - 3.7).abs() < 1e-12,
            "{n}: {}",
            rod.node_s[b]
        );
        assert!(rod.fixed[3 * b + 1], "{n}: B's node not held");
        // Proportional: the segments hold 37 % and 63 % of the elements, to one element.
        let left = b as f64;
        assert!(
            (left - 0.37 * n as f64).abs() <= 1.0,
            "{n}: {b} elements left of B"
        );
        // Statics: the reactions balance the load (to the Newton tolerance).
        let total: f64 = ["A", "B", "C"]
            .iter()
            .map(|s| output(&sim, &format!("{s}_Ry")))
            .sum();
        assert!((total - 1e-5).abs() < 1e-9 * 1e-5, "{n}: {total}");
    }
    let e = scene.values_with([("elements", 1.0)]).unwrap_err();
    assert!(e.to_string().contains("[2, 100000]"), "{e}");
}

/// The reactions converge to beam theory on the spread meshes as on uniform ones: at second
/// order in the element length.
#[test]
fn spread_mesh_reactions_converge_to_beam_theory() {
    let scene = two_spans(0.37);
    let expected = two_span_reactions(1e-6, 3.7, 6.3);
    let mut t = Table::new(
        "two-span beam, spans 3.7 + 6.3, q = 1e-6, L/h = 200: reactions vs the three-moment \
         equation on spread meshes",
    );
    let mut errors = Vec::new();
    for n in [13, 26, 52] {
        let values = scene.values_with([("elements", n as f64)]).unwrap();
        let sim = Simulation::new(scene.clone(), values).expect("static state");
        let worst = ["A", "B", "C"]
            .iter()
            .zip(expected)
            .map(|(s, want)| (output(&sim, &format!("{s}_Ry")) - want).abs() / want)
            .fold(0.0f64, f64::max);
        t.row(format_args!(
            "  {n:>3} elements: worst relative error {worst:.3e}"
        ));
        errors.push(worst);
    }
    // Second order: halving the elements quarters the error (within 12 %; the shear flexibility,
    // O(EI / (GA a^2)) = 4e-5, stays below the mesh error here).
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((3.5..4.5).contains(&ratio), "{errors:?}");
    }
    assert!(errors[2] < 1.5e-3, "{errors:?}");
}

/// Supports on nodes of the uniform mesh: the mesh is the uniform one, bit for bit (nodes at
/// `i L / n`, elements of length `L / n`).
#[test]
fn supports_on_the_uniform_mesh_keep_it_bit_for_bit() {
    let scene = two_spans(0.3);
    for n in [10, 20, 30] {
        let values = scene.values_with([("elements", n as f64)]).unwrap();
        let sim = Simulation::new(scene.clone(), values).expect("static state");
        let rod = sim.rod();
        for (i, s) in rod.node_s.iter().enumerate() {
            assert_eq!(*s, 10.0 * i as f64 / n as f64, "{n}: node {i}");
        }
        for el in &rod.elements {
            assert_eq!(el.length, 10.0 / n as f64, "{n}");
        }
    }
    // 11 elements cannot be equal: 3 + 8 (0.3 of 11 is 3.3).
    let values = scene.values_with([("elements", 11.0)]).unwrap();
    let rod = Simulation::new(scene.clone(), values)
        .unwrap()
        .rod()
        .clone();
    assert_eq!(rod.node_at(3.0), 3);
    assert!((rod.node_s[3] - 3.0).abs() < 1e-12);
    assert!((rod.elements[0].length - 1.0).abs() < 1e-12);
    assert!((rod.elements[5].length - 7.0 / 8.0).abs() < 1e-12);
}
