//! Acceleration sensors and fields (`a1`, `a2`, `aw`: the change of velocity over the last
//! sub-step divided by it): a free rod under a harmonic point load, whose centre of mass
//! accelerates as `F cos(Omega t) / (rho A L)` (the midpoint rule takes the load at the
//! sub-step's middle); a clamped rod on a base moved with a given acceleration; and the
//! accelerations kept by a snapshot.
//!
//! Run: `cargo test --profile quick --test suite readouts_accelerations:: -- --nocapture`
use crate::common;

use common::{output, Table};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

fn parse(text: &str) -> Arc<Scene> {
    Arc::new(Scene::parse(text, "accelerations.toml").expect("scene"))
}

/// A free rod (no support, from the reference state, no damping), `F cos(Omega t)` along e2 at
/// 0.3 of its length, acceleration fields at the 11 nodes.
const FREE_ROD: &str = r#"
name = "FreeRod"
[geometry]
shape = "straight"
L = 10.0
[defaults]
E = 2.0e5
rho = 2.0
d = 0.0
b = 1.0
h = 0.1
elements = 10
dt_max = 1.0e-4
F = 3.0
Omega = 20.0
[[load]]
name = "shake"
kind = "point"
at = 0.3
direction = "e2"
time = "harmonic"
[[sensor]]
name = "a_tip"
at = 1.0
quantity = "a2"
[initial]
state = "reference"
[shape]
points = 11
fields = ["a1", "a2", "aw"]
"#;

/// The consistent mass makes the rod's momentum change `rho A` times the integral of the
/// interpolated acceleration (the trapezoidal rule on the nodes, exact for the linear
/// interpolation), and the internal forces sum to zero: so the mean of `a2` over the rod is
/// `F cos(Omega (t - dt/2)) / (rho A L)` to the solver's tolerance (1e-9 of the amplitude), and
/// differs from `F cos(Omega t) / (rho A L)` by at most `Omega dt / 2` of the amplitude (the
/// midpoint rule's load at the sub-step's middle). `a1` sums to zero (no load along e1).
#[test]
fn free_rod_centre_of_mass_accelerates_with_the_load() {
    let scene = parse(FREE_ROD);
    let mut sim = Simulation::new(scene.clone(), scene.defaults()).expect("reference state");
    let (force, omega, mass, dt) = (3.0, 20.0, 2.0 * 0.1 * 10.0, 1e-4);
    let amplitude = force / mass;
    let h = 1e-3;
    let (mut exact, mut midpoint_rule, mut along_e1) = (0.0f64, 0.0f64, 0.0f64);
    for step in 1..=400 {
        sim.advance(h).expect("step");
        let t = step as f64 * h;
        let mean = |name: &str| {
            let a: Vec<f64> = (1..=11)
                .map(|i| output(&sim, &format!("shape_{name}[{i}]")))
                .collect();
            (a.iter().sum::<f64>() - 0.5 * (a[0] + a[10])) / 10.0
        };
        let a2 = mean("a2");
        exact = exact.max((a2 - amplitude * (omega * (t - 0.5 * dt)).cos()).abs());
        midpoint_rule = midpoint_rule.max((a2 - amplitude * (omega * t).cos()).abs());
        along_e1 = along_e1.max(mean("a1").abs());
    }
    let mut t = Table::new("Free rod, F cos(Omega t) at 0.3 L: centre-of-mass acceleration");
    t.row(format_args!(
        "max |a_cm - F cos(Omega (t - dt/2)) / m| / (F/m) = {:.2e}; against cos(Omega t): \
         {:.2e} (Omega dt / 2 = {:.2e}); |a1 mean| / (F/m) = {:.2e}; tip a2 at t = 0.4: {:.4e}",
        exact / amplitude,
        midpoint_rule / amplitude,
        0.5 * omega * dt,
        along_e1 / amplitude,
        output(&sim, "a_tip"),
    ));
    assert!(exact < 1e-9 * amplitude, "{exact}");
    assert!(midpoint_rule <= (0.5 * omega * dt + 1e-9) * amplitude);
    assert!(
        midpoint_rule > 0.1 * 0.5 * omega * dt * amplitude,
        "the half step shows"
    );
    assert!(along_e1 < 1e-9 * amplitude, "{along_e1}");
}

/// A cantilever whose clamped root follows an input with given velocity and acceleration
/// (`fmi2SetRealInputDerivatives`): the root moves along `x0 + v t + a t^2 / 2` over each step,
/// so the acceleration read at the root is `a` (to the round-off of position increments); a snapshot restores the
/// accelerations with the state.
#[test]
fn base_acceleration_is_read_at_the_base_and_kept_by_snapshots() {
    let scene = parse(
        r#"
name = "Shaken"
[geometry]
shape = "straight"
L = 2.0
[defaults]
E = 2.0e5
rho = 2.0
b = 1.0
h = 0.1
elements = 4
[[support]]
name = "base"
at = 0.0
fix = ["u1", "u2", "w"]
motion = "input"
[[sensor]]
name = "a_base"
at = 0.0
quantity = "a2"
[[sensor]]
name = "a_tip"
at = 1.0
quantity = "a2"
[[sensor]]
name = "aw_tip"
at = 1.0
quantity = "aw"
"#,
    );
    let mut sim = Simulation::new(scene.clone(), scene.defaults()).expect("static state");
    let input = scene
        .inputs
        .iter()
        .position(|i| i.name == "base_u2")
        .unwrap();
    assert_eq!(output(&sim, "a_base"), 0.0, "before the first step");
    let accel = 0.7;
    let h = 1e-3;
    let mut velocity = 0.0;
    for _ in 0..20 {
        sim.set_input_derivative(input, 1, velocity).unwrap();
        sim.set_input_derivative(input, 2, accel).unwrap();
        sim.advance(h).unwrap();
        velocity += accel * h;
        let a = output(&sim, "a_base");
        // The held dof's velocity comes from its position increments (`2 du / dt - v`), whose
        // round-off `1e-16 |x| / dt` the acceleration divides by `dt` again: 1e-9 here.
        assert!((a - accel).abs() < 1e-7 * accel, "{a}");
    }
    let snapshot = sim.snapshot();
    let kept = (output(&sim, "a_tip"), output(&sim, "aw_tip"));
    assert!(kept.0 != 0.0 && kept.1 != 0.0);
    sim.set_input_derivative(input, 2, -accel).unwrap();
    sim.advance(h).unwrap();
    assert!(output(&sim, "a_tip") != kept.0);
    sim.restore(&snapshot).unwrap();
    assert_eq!((output(&sim, "a_tip"), output(&sim, "aw_tip")), kept);
    sim.reset();
    assert_eq!(output(&sim, "a_tip"), 0.0, "reset: at rest");
}
