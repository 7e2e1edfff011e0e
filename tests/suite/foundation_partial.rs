//! A Winkler foundation under part of a rod (`[[foundation]]` with `from`, `to`): every element
//! inside `[from, to]` carries it, and none outside.
//!
//! A free steel beam (only `u1` held, at one end) lies on a foundation of modulus `k` over
//! `[from, to]` and carries a uniform load `q` over exactly the same part. The load and the
//! foundation's reaction then cancel at every point of the part: the beam settles as a rigid body
//! by `w = q / k` everywhere, overhangs included (they carry nothing and stay straight), whatever
//! its bending stiffness, and the total foundation force `k * integral of w over [from, to]`
//! equals the load `q (to - from) L`. An element of the part without its foundation (or one
//! outside with it) bends the beam: the settlement is no longer uniform and the integral over
//! `[from, to]` no longer balances the load.
//!
//! Run: `cargo test --profile quick --test suite foundation_partial:: -- --nocapture`
use crate::common;

use common::Table;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

const LENGTH: f64 = 12.0;
const K: f64 = 2.0e6; // N/m2: a stiff soil under a 0.3 m wide beam
const Q: f64 = 3.0e4; // N/m

fn beam(from: f64, to: f64, elements: usize) -> Simulation {
    let text = format!(
        r#"
name = "PartFoundation"
[geometry]
shape = "straight"
L = {LENGTH}
[defaults]
E = 210e9
nu = 0.3
rho = 7850.0
d = 0.0
b = 0.3
h = 0.4
elements = {elements}
[[support]]
name = "axial"
at = 0.0
fix = ["u1"]
[[foundation]]
name = "soil"
k = {K}
from = {from}
to = {to}
[[load]]
name = "q"
kind = "distributed"
direction = "-e2"
value = {Q}
from = {from}
to = {to}
"#
    );
    let scene = Arc::new(Scene::parse(&text, "part.toml").unwrap_or_else(|e| panic!("{e}")));
    let values = scene.defaults();
    Simulation::new(scene, values).expect("static initial state")
}

#[test]
fn every_element_inside_the_part_carries_the_foundation() {
    let mut t = Table::new(&format!(
        "free steel beam {LENGTH} m, 300 x 400 mm, on k = {K:e} N/m2 over [from, to] under \
         q = {Q:e} N/m over the same part: settlement vs q / k, foundation force vs load"
    ));
    // Parts at the ends, inside, and one whose ends fall inside elements of an even mesh
    // (the mesh follows the scene: its ends become nodes).
    for (from, to, elements) in [
        (0.0, 0.4, 30),
        (0.3, 0.7, 40),
        (0.55, 1.0, 20),
        (0.13, 0.71, 25),
    ] {
        let sim = beam(from, to, elements);
        let (rod, u) = (sim.rod(), &sim.state().u);
        let settlement = Q / K;
        let mut s = 0.0;
        let (mut force, mut worst) = (0.0, 0.0f64);
        for (e, element) in rod.elements.iter().enumerate() {
            let (a, b) = (u[3 * e + 1], u[3 * e + 4]);
            worst = worst
                .max((a + settlement).abs())
                .max((b + settlement).abs());
            let middle = (s + 0.5 * element.length) / LENGTH;
            if middle > from && middle < to {
                // The consistent foundation k l/6 [[2, 1], [1, 2]] on the element's u2: its
                // resultant is the trapezoid k l (a + b) / 2, exactly.
                force -= K * element.length * 0.5 * (a + b);
            }
            s += element.length;
        }
        let load = Q * (to - from) * LENGTH;
        t.row(format_args!(
            "  [{from}, {to}], {elements} elements: settlement error {:.1e} of q/k, \
             foundation force {force:.6e} N vs load {load:.6e} N",
            worst / settlement
        ));
        // Exact in the continuum and in the discrete model (no bending at all): only the
        // static solver's tolerance remains (1e-10 of the residual's scale), far below the
        // percent-level bending that a missing element's load causes.
        assert!(
            worst < 1e-8 * settlement,
            "[{from}, {to}]: not a uniform settlement q/k = {settlement:e}: worst error {worst:e}"
        );
        assert!(
            (force - load).abs() < 1e-8 * load,
            "[{from}, {to}]: foundation force {force} vs load {load}"
        );
    }
}
