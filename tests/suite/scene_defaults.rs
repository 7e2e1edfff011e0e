//! No value of the paper's reaches a user's scene that does not state it: without `nu` and `d`
//! in `[defaults]` the parameters start at `nu = 0.3` (a metal's) and `d = 0` (undamped), and a
//! rod set swinging keeps its energy (nothing damps it). The paper's scenes state their own
//! `nu = 0.2` and `d = 5e-4`.
//!
//! Run: `cargo test --profile quick --test suite scene_defaults::`
use crate::common;

use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

const USER: &str = r#"
name = "UserBar"
[geometry]
shape = "straight"
L = 2.0
[defaults]
E = 210e9
rho = 7850.0
b = 0.05
h = 0.01
elements = 8
dt_max = 1e-4
[[support]]
name = "root"
at = 0.0
fix = ["u1", "u2", "w"]
"#;

fn start(scene: &Scene, name: &str) -> f64 {
    let i = scene.param_index(name).expect("a parameter");
    scene.defaults().get(i)
}

#[test]
fn a_users_scene_gets_no_paper_value() {
    let scene = Arc::new(Scene::parse(USER, "user.toml").unwrap_or_else(|e| panic!("{e}")));
    assert_eq!(start(&scene, "nu"), 0.3);
    assert_eq!(start(&scene, "d"), 0.0);
    // Undamped: a cantilever released from a kick keeps its energy (midpoint rule: to the
    // Newton tolerance), where d = 5e-4 would remove some.
    let values = scene
        .values_with([("perturbation", 1e-3)])
        .unwrap_or_else(|e| panic!("{e}"));
    let mut sim = Simulation::new(scene.clone(), values).expect("initial state");
    for _ in 0..50 {
        sim.advance(1e-3).unwrap();
    }
    let damped = common::output(&sim, "E_damped");
    assert_eq!(damped, 0.0, "E_damped = {damped} without any damping");
    for paper in ["BuckledBeam", "PinnedArch", "ClampedArch"] {
        let scene = common::scene(paper);
        assert_eq!(start(&scene, "nu"), 0.2, "{paper}");
        assert_eq!(start(&scene, "d"), 5.0e-4, "{paper}");
    }
}
