//! Each of the four `direction` values of a load (`e1`, `e2`, `-e1`, `-e2`) pushes the rod the
//! way it says with the magnitude it is given: the static reactions of a simply supported beam
//! (pin at the left end, roller at the right) under a constant point load `P` at midspan balance
//! it exactly, and the midspan moves along the load.
//!
//! Run: `cargo test --profile quick --test suite scene_load_directions::`
use crate::common;

use common::output;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

/// `P L^3 / (48 EI)` = 0.01 of the length 10 with `EI = 1000` (the default section).
const P: f64 = 0.48;

fn beam(direction: &str) -> Simulation {
    let text = format!(
        r#"
name = "Pushed"

[geometry]
shape = "straight"
L = 10.0

[defaults]
E = 1.2e4
rho = 1.0e-6
elements = 40

[[support]]
name = "pin"
at = 0.0
fix = ["u1", "u2"]

[[support]]
name = "roller"
at = 1.0
fix = ["u2"]

[[load]]
name = "push"
kind = "point"
at = 0.5
direction = "{direction}"
value = {P}

[[sensor]]
name = "mid_u1"
at = 0.5
quantity = "u1"

[[sensor]]
name = "mid_u2"
at = 0.5
quantity = "u2"
"#
    );
    let scene = Arc::new(Scene::parse(&text, "Pushed.toml").unwrap());
    Simulation::new(scene.clone(), scene.defaults()).unwrap()
}

#[test]
fn each_direction_is_balanced_by_the_reactions_it_should_be() {
    // (direction, unit vector)
    for (direction, d) in [
        ("e1", [1.0, 0.0]),
        ("e2", [0.0, 1.0]),
        ("-e1", [-1.0, 0.0]),
        ("-e2", [0.0, -1.0]),
    ] {
        let sim = beam(direction);
        let r = |name: &str| output(&sim, name);
        let (pin, roller) = ([r("pin_Rx"), r("pin_Ry")], [r("roller_Rx"), r("roller_Ry")]);
        // Global force balance: the static reactions of the equilibrium balance the load up to
        // the Newton tolerance (relative 1e-10 of the internal forces): 1e-8 P.
        for c in 0..2 {
            let total = pin[c] + roller[c] + P * d[c];
            assert!(
                total.abs() < 1e-8 * P,
                "{direction}: force balance {c}: {total:e}"
            );
        }
        assert_eq!(roller[0], 0.0, "{direction}: the roller holds no u1");
        if d[1] != 0.0 {
            // Transverse: half the load on each support. No support pushes along e1, so the
            // bent beam carries no axial force and is symmetric about midspan (it shortens
            // symmetrically): the moment balance gives exactly half, to the Newton tolerance.
            for (name, ry) in [("pin", pin[1]), ("roller", roller[1])] {
                let half = -0.5 * P * d[1];
                assert!(
                    (ry - half).abs() < 1e-8 * P,
                    "{direction}: {name}_Ry = {ry}, expected {half}"
                );
            }
            assert!(pin[0].abs() < 1e-8 * P, "{direction}: pin_Rx = {}", pin[0]);
        } else {
            // Axial: the pin takes all of it, no transverse reaction.
            assert!(
                (pin[0] + P * d[0]).abs() < 1e-8 * P,
                "{direction}: pin_Rx = {}",
                pin[0]
            );
            assert!(
                pin[1].abs() < 1e-8 * P && roller[1].abs() < 1e-8 * P,
                "{direction}: Ry = {} {}",
                pin[1],
                roller[1]
            );
        }
        // The midspan moves along the load, as much as linear beam theory says to 0.5 %: the
        // mesh error of the deflection falls as 1/n^2 (1 % with 10 elements, 0.06 % with the
        // 40 here), the geometric nonlinearity is of the order (deflection / L)^2 = 1e-6.
        // Across, bending
        // P L^3 / (48 EI) = 0.01 plus shear P L / (4 GA) = 2.4e-4 (GA = 5000); along,
        // P (L/2) / EA = 2e-4 (EA = 1.2e4).
        let moved = [r("mid_u1"), r("mid_u2")];
        let expected = [P * 5.0 / 1.2e4, 0.01 + P * 10.0 / (4.0 * 5000.0)];
        for c in 0..2 {
            if d[c] != 0.0 {
                let along = moved[c] * d[c];
                assert!(
                    (along / expected[c] - 1.0).abs() < 0.005,
                    "{direction}: midspan moved {along:e} along the load, expected {:e}",
                    expected[c]
                );
            }
        }
    }
}
