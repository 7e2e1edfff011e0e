//! Inputs of moving supports set before the run (in FMI initialization mode) are part of the
//! static initial state: a settled middle support of a two-span beam changes its reactions as
//! beam theory says.
//!
//! Run: `cargo test --profile quick --test suite scene_initial_inputs:: -- --nocapture`
use crate::common;

use common::output;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

/// Two steel spans of 4 m, 100 x 200 mm, the middle support moved by an input.
const TWO_SPANS: &str = r#"
name = "TwoSpans"
[geometry]
shape = "straight"
L = 8.0
[defaults]
E = 210e9
nu = 0.3
rho = 7850.0
b = 0.1
h = 0.2
elements = 40
[[support]]
name = "A"
at = 0.0
fix = ["u1", "u2"]
[[support]]
name = "B"
at = 0.5
fix = ["u2"]
motion = "input"
[[support]]
name = "C"
at = 1.0
fix = ["u2"]
[[sensor]]
name = "w_B"
at = 0.5
quantity = "u2"
"#;

/// Settling the middle support by `delta` (up positive) adds `delta / ((2 L)^3 / (48 EI) +
/// 2 L / (4 G A))` to its reaction (the simply supported 2L beam's point-load flexibility at
/// midspan, bending and shear), and half of it, negated, to each end's.
#[test]
fn a_settlement_set_before_the_run_enters_the_static_state() {
    let scene = Arc::new(Scene::parse(TWO_SPANS, "two_spans.toml").unwrap());
    let (e, g, b, h, span): (f64, f64, f64, f64, f64) = (210e9, 210e9 / 2.6, 0.1, 0.2, 4.0);
    let (ei, ga) = (e * b * h * h * h / 12.0, g * b * h);
    let flexibility = (2.0 * span).powi(3) / (48.0 * ei) + 2.0 * span / (4.0 * ga);
    let run = |delta: f64| {
        let sim = Simulation::with_inputs(scene.clone(), scene.defaults(), vec![delta]).unwrap();
        ["A_Ry", "B_Ry", "C_Ry", "w_B"].map(|n| output(&sim, n))
    };
    let level = run(0.0);
    assert_eq!(level, [0.0; 4], "nothing loads the level beam");
    for delta in [-1e-3, 1e-3] {
        let r = run(delta);
        let want = delta / flexibility;
        println!(
            "delta {delta:+e}: R_B {:.6e} (theory {want:.6e}), R_A {:.6e}",
            r[1], r[0]
        );
        assert_eq!(r[3], delta, "the support is where the input put it");
        // The mesh's error, O(l^2): 6.2e-4 on 40 elements, 1.6e-4 on 80, 3.9e-5 on 160
        // (measured); a settlement left out of the static state gives 1.
        assert!((r[1] / want - 1.0).abs() < 1e-3, "{} vs {want}", r[1]);
        assert!((r[0] / (-0.5 * want) - 1.0).abs() < 1e-3, "{}", r[0]);
        assert!((r[0] + r[1] + r[2]).abs() < 1e-9 * want.abs());
    }
    let Err(e) = Simulation::with_inputs(scene.clone(), scene.defaults(), vec![]) else {
        panic!("no input values accepted");
    };
    assert!(e.to_string().contains("1 input values"), "{e}");
}
