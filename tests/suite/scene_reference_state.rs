//! `[initial] state = "reference"` with prescribed support displacements: the rod starts
//! undeformed and at rest, except that every held dof sits at its `displace` value (numbers,
//! fixed parameters as set by the host, `-name`), as docs/scenes.md says. Guards the branch of
//! `initial_displacements` that skips the static solution.
//!
//! Run: `cargo test --profile quick --test suite scene_reference_state::`
use crate::common;

use common::output;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

/// A straight rod, clamped at the left end with a lifted and turned clamp, a roller at 3/4
/// pushed down by the fixed parameter `drop` and a pin at the right end pulled along e1 by
/// `-drop`; no loads. Sensors at the supports and between them.
const LIFTED: &str = r#"
name = "Lifted"

[geometry]
shape = "straight"
L = 8.0

[defaults]
E = 1.2e4
rho = 1.0e-6
elements = 8

[[parameter]]
name = "drop"
start = 0.25

[[support]]
name = "clamp"
at = 0.0
fix = ["u1", "u2", "w"]
displace = { u1 = 0.125, u2 = 0.5, w = 0.0625 }

[[support]]
name = "roller"
at = 0.75
fix = ["u2"]
displace = { u2 = "drop" }

[[support]]
name = "pin"
at = 1.0
fix = ["u1", "u2"]
displace = { u1 = "-drop" }

[[sensor]]
name = "clamp_u2"
at = 0.0
quantity = "u2"

[[sensor]]
name = "roller_u2"
at = 0.75
quantity = "u2"

[[sensor]]
name = "pin_u1"
at = 1.0
quantity = "u1"

[[sensor]]
name = "mid_u2"
at = 0.5
quantity = "u2"

[shape]
points = 9

[initial]
state = "reference"
"#;

/// `(node, component, value)` of every held dof of [`LIFTED`] with `drop` set to `drop`.
fn held(drop: f64) -> Vec<(usize, usize, f64)> {
    vec![
        (0, 0, 0.125),
        (0, 1, 0.5),
        (0, 2, 0.0625),
        (6, 1, drop),
        (8, 0, -drop),
        (8, 1, 0.0),
    ]
}

#[test]
fn the_reference_state_puts_the_held_dofs_at_their_prescribed_values() {
    let scene = Arc::new(Scene::parse(LIFTED, "Lifted.toml").unwrap());
    // The host's value of the fixed parameter, not its start value, is what the slot reads.
    for drop in [0.25, -0.375] {
        let values = scene.values_with([("drop", drop)]).unwrap();
        let sim = Simulation::new(scene.clone(), values).unwrap();
        let state = sim.state();
        let mut expected = vec![0.0; state.u.len()];
        for (node, component, value) in held(drop) {
            expected[3 * node + component] = value;
        }
        // Exact: the values are assigned, not solved for, and every other dof is undeformed.
        assert_eq!(state.u, expected, "drop = {drop}");
        assert!(state.v.iter().all(|&v| v == 0.0), "at rest");
        // The same through the outputs a host reads.
        assert_eq!(output(&sim, "clamp_u2"), 0.5);
        assert_eq!(output(&sim, "roller_u2"), drop);
        assert_eq!(output(&sim, "pin_u1"), -drop);
        assert_eq!(output(&sim, "mid_u2"), 0.0);
        assert_eq!(output(&sim, "shape_x[1]"), 0.125);
        assert_eq!(output(&sim, "shape_y[1]"), 0.5);
        assert_eq!(output(&sim, "shape_y[7]"), drop); // s = 6 = 3/4 of L
        assert_eq!(output(&sim, "shape_x[9]"), 8.0 - drop);
    }
}
