//! A moving force that enters late, at a road vehicle's speed: 30 m/s over a 10 m steel beam
//! (a third of the critical speed), entering at `enter = 0.1 s`. Nothing moves before it enters
//! (the state stays exactly the static one, zero), and afterwards the midspan deflection follows
//! the modal series of the force at its true position `s = v (t - enter)`.
//!
//! The sensitivity is the point: with communication steps of 0.5 ms the force travels 15 mm a
//! step, and a force three steps early or late changes the midspan deflection by about
//! `pi v / L * 3 dt = 1.4 %` of its peak where the deflection changes fastest; the tolerance
//! below is a quarter of that.
//!
//! Run: `cargo test --profile quick --test suite moving_load_late_entry:: -- --nocapture`
use crate::common;

use common::moving::Crossing;
use common::{output, Table};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

/// Steel, 200 x 200 mm, span 10 m (L/h = 50), no damping; P = 10 kN at 30 m/s.
const E: f64 = 210e9;
const RHO: f64 = 7850.0;
const LENGTH: f64 = 10.0;
const FORCE: f64 = 1e4;
const SPEED: f64 = 30.0;
const ENTER: f64 = 0.1;
const DT: f64 = 5e-4;

fn ei() -> f64 {
    E * 0.2 * 0.2f64.powi(3) / 12.0
}

fn mass_per_length() -> f64 {
    RHO * 0.04
}

fn bridge() -> Simulation {
    let text = format!(
        r#"
name = "LateTruck"
[geometry]
shape = "straight"
L = {LENGTH}
[defaults]
E = {E}
nu = 0.3
rho = {RHO}
d = 0.0
b = 0.2
h = 0.2
elements = 40
dt_max = {DT}
[[support]]
name = "A"
at = 0.0
fix = ["u1", "u2"]
[[support]]
name = "B"
at = 1.0
fix = ["u2"]
[[load]]
name = "truck"
kind = "moving"
direction = "-e2"
value = {FORCE}
speed = {SPEED}
enter = {ENTER}
[[sensor]]
name = "w_mid"
at = 0.5
quantity = "u2"
[[sensor]]
name = "w_quarter"
at = 0.25
quantity = "u2"
[[sensor]]
name = "v_mid"
at = 0.5
quantity = "v2"
"#
    );
    let scene = Arc::new(Scene::parse(&text, "late.toml").unwrap_or_else(|e| panic!("{e}")));
    Simulation::new(scene.clone(), scene.defaults()).expect("initial state")
}

/// The modal series of the Euler-Bernoulli beam (tests/common/moving.rs).
fn series(x: f64, t: f64) -> f64 {
    let crossing = Crossing {
        length: LENGTH,
        ei: ei(),
        mu: mass_per_length(),
        force: FORCE,
        speed: SPEED,
    };
    crossing.deflection(x, t)
}

#[test]
fn a_late_fast_force_moves_nothing_before_it_enters_then_follows_its_position() {
    let mut sim = bridge();
    let before = (ENTER / DT).round() as usize;
    for k in 0..before {
        sim.advance(DT).unwrap();
        for name in ["w_mid", "w_quarter", "v_mid"] {
            assert_eq!(
                output(&sim, name),
                0.0,
                "{name} moved at t = {} s, before the force entered at {ENTER} s",
                (k + 1) as f64 * DT
            );
        }
    }
    let crossing = (LENGTH / SPEED / DT).floor() as usize;
    let peak = FORCE * LENGTH.powi(3) / (48.0 * ei());
    let (mut worst, mut largest) = (0.0f64, 0.0f64);
    for k in 1..=crossing {
        sim.advance(DT).unwrap();
        let since = k as f64 * DT;
        for (name, x) in [("w_mid", 0.5 * LENGTH), ("w_quarter", 0.25 * LENGTH)] {
            let got = output(&sim, name);
            worst = worst.max((got - series(x, since)).abs());
            largest = largest.max(got.abs());
        }
    }
    let mut t = Table::new(&format!(
        "simply supported steel beam {LENGTH} m, P = 10 kN entering at {ENTER} s at {SPEED} m/s, \
         steps {DT} s: deflection vs the modal series at the force's true position"
    ));
    t.row(format_args!(
        "  largest deflection {largest:.4e} m (static peak {peak:.4e}), worst difference {:.2e} \
         of the static peak",
        worst / peak
    ));
    // The series is the Euler-Bernoulli beam: the rod's shear and rotary inertia (O((pi h /
    // L)^2) = 4e-3 on the first frequency) and the 40-element mesh leave well under 1e-3 of the
    // peak (scene_moving_load.rs measures 6e-4 at half the critical speed); a force three steps
    // early or late leaves 1.4e-2.
    assert!(worst < 3.5e-3 * peak, "worst {worst:e} vs peak {peak:e}");
    assert!(largest > 0.5 * peak, "the force never bent the beam");
}
