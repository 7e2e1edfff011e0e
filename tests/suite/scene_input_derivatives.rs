//! Inputs with derivatives (`fmi2SetRealInputDerivatives`, `Simulation::set_input_derivative`):
//! over a communication step an input then follows the polynomial its derivatives define, a load
//! input from the value set, a support from where it is. Checked against motions the midpoint
//! rule reproduces exactly.
//!
//! Run: `cargo test --profile quick --test suite scene_input_derivatives:: -- --nocapture`
use crate::common;

use common::{output, set_input, Table};
use georod::model::rod::U2;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

fn input_index(sim: &Simulation, name: &str) -> usize {
    sim.scene()
        .inputs
        .iter()
        .position(|i| i.name == name)
        .unwrap()
}

/// A free rod at rest pushed by a distributed input load growing linearly, `f = c t`, given as
/// the value at each communication point and its first derivative: the loads the midpoint rule
/// samples at sub-step midpoints are exact, so the centre of mass moves exactly with
/// `v = c t^2 / (2 rho A)`. Held constant over each step instead, the same input lags by half a
/// step: `v` is off by `c t h / (2 rho A)`.
#[test]
fn a_load_input_follows_its_derivative() {
    let text = r#"
name = "FreeRod"
[geometry]
shape = "straight"
L = 10.0
[defaults]
E = 1.2e4
rho = 1.0e-6
d = 0.0
elements = 10
dt_max = 1.0e-4
[[load]]
name = "push"
kind = "distributed"
direction = "e2"
time = "input"
[[sensor]]
name = "v_mid"
at = 0.5
quantity = "v2"
[initial]
state = "reference"
"#;
    let scene = Arc::new(Scene::parse(text, "free rod").unwrap());
    let (c, h, steps) = (2.0, 1e-3, 50);
    let rho_a = 1e-6 * 1.0 * 1.0;
    let run = |derivatives: bool| {
        let mut sim = Simulation::new(scene.clone(), scene.defaults()).unwrap();
        let push = input_index(&sim, "push");
        for k in 0..steps {
            let t = k as f64 * h;
            sim.set_input(push, c * t).unwrap();
            if derivatives {
                sim.set_input_derivative(push, 1, c).unwrap();
            }
            sim.advance(h).unwrap();
        }
        output(&sim, "v_mid")
    };
    let t_end = steps as f64 * h;
    let exact = c * t_end * t_end / (2.0 * rho_a);
    let (with, held) = (run(true), run(false));
    let mut t = Table::new("free rod, distributed input load f = c t (c = 2), 50 steps of 1 ms");
    t.row(format_args!(
        "  v(t_end): with derivatives {with:.10e}, held {held:.10e}, exact {exact:.10e}"
    ));
    // Exact up to round-off: 500 sub-steps of sums (measured 2e-12).
    assert!((with - exact).abs() < 1e-10 * exact, "{with} vs {exact}");
    // Held: the half-step lag, c t h / (2 rho A), to round-off.
    let lag = c * t_end * h / (2.0 * rho_a);
    assert!(
        ((exact - held) - lag).abs() < 1e-9 * lag,
        "{held}: lag {}",
        exact - held
    );
}

/// Both ends of the clamped beam follow `g(t) = a t^2 / 2` given by its first and second
/// derivatives at each communication point (and nothing else): the supports move exactly on the
/// parabola and their speed is `a t`, without jumps. Once the start has died out (the base
/// accelerates at once at t = 0, which sets the beam ringing; the scene's damping, 2500 /s,
/// removes that in a few ms) the beam rides along quasi-statically: the reactions are the rod's
/// mass times `a` plus the drag on it, `d L (v - s')`, where `s' = d a L^4 / (720 EI)` is the
/// rate at which its mean sag under the growing drag `d v` grows (clamped-clamped beam: mean
/// deflection `q L^4 / (720 EI)` under a uniform load `q`).
#[test]
fn supports_follow_the_polynomial_of_their_derivatives() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/BeamOnBase.toml");
    let scene = Arc::new(Scene::load(path).unwrap());
    // The non-dimensional beam of the bounds below (the example itself is aluminium).
    let beam = [
        ("E", 1.2e4),
        ("rho", 1e-6),
        ("nu", 0.2),
        ("d", 5e-4),
        ("L", 10.0),
        ("b", 1.0),
        ("h", 0.2),
    ];
    let values = scene.values_with(beam).unwrap();
    let mut sim = Simulation::new(scene.clone(), values).unwrap();
    let (a, h) = (20.0, 1e-3);
    let rod = sim.rod().clone();
    let (mass, drag) = (rod.section.rho_a * 10.0, rod.damping * 10.0);
    let sag_rate = rod.damping * a * 1e4 / (720.0 * rod.section.ei);
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..100 {
        let t = k as f64 * h;
        for support in ["left", "right"] {
            let i = input_index(&sim, &format!("{support}_u2"));
            set_input(&mut sim, &format!("{support}_u2"), 0.0); // not used with derivatives
            sim.set_input_derivative(i, 1, a * t).unwrap();
            sim.set_input_derivative(i, 2, a).unwrap();
        }
        sim.advance(h).unwrap();
        let t1 = t + h;
        let g = 0.5 * a * t1 * t1;
        let node_u2 = sim.state().u[3 * rod.last_node() + U2];
        let node_v2 = sim.state().v[3 * rod.last_node() + U2];
        let reaction = output(&sim, "left_Ry") + output(&sim, "right_Ry");
        // Over the step the base's mean speed is a (t + h/2).
        let rigid = mass * a + drag * (a * (t + 0.5 * h) - sag_rate);
        worst.0 = worst.0.max((node_u2 - g).abs() / g);
        worst.1 = worst.1.max((node_v2 - a * t1).abs() / (a * t1));
        if k >= 20 {
            worst.2 = worst.2.max((reaction - rigid).abs() / rigid);
        }
    }
    let mut t = Table::new(
        "BeamOnBase, both ends on g = a t^2 / 2 (a = 20) by derivatives, 100 steps of 1 ms",
    );
    t.row(format_args!(
        "  position {:.1e}, speed {:.1e} (relative); reactions vs m a + c v {:.1e}",
        worst.0, worst.1, worst.2
    ));
    // The path is the polynomial itself (sums of sub-step increments: round-off).
    assert!(worst.0 < 1e-12 && worst.1 < 1e-9, "{worst:?}");
    // Quasi-static from 20 ms on (the start has decayed by exp(-50)); the sag correction is
    // first order in s'/v (4 % at 20 ms): the rest is of order (s'/v)^2, 2e-3.
    assert!(worst.2 < 3e-3, "reactions off by {:e}", worst.2);
}
