//! Angular-velocity sensors (`vw`) against rotation sensors (`w`) at the same station. The
//! midpoint rule advances every nodal dof by `(q_{n+1} - q_n) / dt = (v_n + v_{n+1}) / 2`, and a
//! sensor interpolates nodal values linearly, so with one sub-step per communication step the
//! two sensors obey that relation to round-off, on a node and between two nodes alike. The
//! energy-momentum scheme advances rotations by their Cayley increment instead,
//! `2 tan((w_{n+1} - w_n) / 2) / dt = (vw_n + vw_{n+1}) / 2` (docs/model.md, section 7): exact at
//! a node; between nodes the interpolation of that nonlinear relation is not, so only the node is
//! checked there.
use crate::common;

use common::output;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

/// A cantilever shaken at its tip (harmonic tip load) under a constant tip load, with rotation
/// and angular-velocity sensors at the tip (a node) and at 0.45 (between two nodes of 10).
const CANTILEVER: &str = r#"
name = "Spin"
[geometry]
shape = "straight"
L = 10.0
[defaults]
E = 1.2e4
rho = 1.0e-6
h = 0.1
elements = 10
dt_max = 1.0e-4
F = 0.005
Omega = 300.0
[[support]]
name = "root"
at = 0.0
fix = ["u1", "u2", "w"]
[[load]]
name = "tip"
kind = "point"
at = 1.0
direction = "-e2"
value = 0.01
[[load]]
name = "shake"
kind = "point"
at = 1.0
direction = "e2"
time = "harmonic"
[[sensor]]
name = "w_tip"
at = 1.0
quantity = "w"
[[sensor]]
name = "vw_tip"
at = 1.0
quantity = "vw"
[[sensor]]
name = "w_in"
at = 0.45
quantity = "w"
[[sensor]]
name = "vw_in"
at = 0.45
quantity = "vw"
"#;

#[test]
fn vw_is_the_midpoint_derivative_of_w() {
    let scene = Arc::new(Scene::parse(CANTILEVER, "spin.toml").unwrap_or_else(|e| panic!("{e}")));
    for integrator in [1.0, 2.0] {
        let values = scene
            .values_with([("integrator", integrator)])
            .unwrap_or_else(|e| panic!("{e}"));
        let mut sim = Simulation::new(Arc::clone(&scene), values).unwrap_or_else(|e| panic!("{e}"));
        let dt = 1.0e-4; // = dt_max: one sub-step per communication step
        assert_eq!(sim.substeps_for(dt), 1);
        for vw in ["vw_tip", "vw_in"] {
            assert_eq!(output(&sim, vw), 0.0, "{vw}: the static state is at rest");
        }
        let read = |sim: &Simulation| {
            [
                (output(sim, "w_tip"), output(sim, "vw_tip")),
                (output(sim, "w_in"), output(sim, "vw_in")),
            ]
        };
        let mut before = read(&sim);
        let (mut largest, mut worst) = ([0.0f64; 2], [0.0f64; 2]);
        let midpoint = integrator == 1.0;
        // The increment whose rate the velocities average over a step.
        let increment = |dw: f64| if midpoint { dw } else { 2.0 * (0.5 * dw).tan() };
        let checked = if midpoint { 2 } else { 1 };
        // 200 steps: about one period of the forcing (2 pi / 300 = 0.021 s).
        for _ in 0..200 {
            sim.advance(dt).unwrap_or_else(|e| panic!("{e}"));
            let after = read(&sim);
            for s in 0..2 {
                let ((w0, vw0), (w1, vw1)) = (before[s], after[s]);
                let difference = increment(w1 - w0) / dt;
                worst[s] = worst[s].max((difference - 0.5 * (vw0 + vw1)).abs());
                largest[s] = largest[s].max(vw1.abs());
            }
            before = after;
        }
        println!(
            "integrator {integrator}: max |vw| tip {:.3e}, at 0.45 {:.3e}; \
             max |increment(w1 - w0)/dt - (vw0 + vw1)/2| {:.3e}, {:.3e}",
            largest[0], largest[1], worst[0], worst[1]
        );
        for s in 0..checked {
            assert!(largest[s] > 1e-3, "the rod hardly turns: {largest:?}");
            assert!(
                worst[s] <= 1e-9 * largest[s],
                "integrator {integrator}, sensor {s}: {:.3e} against max |vw| {:.3e}",
                worst[s],
                largest[s]
            );
        }
    }
}
