//! Every item of a scene's vocabulary on a frame at once: supports fixed, prescribed
//! (`displace`) and moved by an input, at joints and inside members; point, distributed (a patch,
//! a trapezoid, along a member's normal), moment, gravity, harmonic, input and moving loads (along
//! a path of two members); point masses and springs at joints and inside members (a spring base
//! moved by an input); a foundation under part of a member; Rayleigh damping; sensors of every
//! quantity; shape fields; natural frequencies. The energy-momentum step closes the energy ledger
//! over all of it to round-off, and the prescribed displacement is where the scene puts it.
//!
//! Run: `cargo test --profile quick --test suite frames_vocabulary:: -- --nocapture`
use crate::common;

use common::{output, set_input, simulation_of};

const FRAME: &str = r#"
name = "Everything"
[defaults]
E = 210e9
rho = 7850.0
d = 1.0
elements = 40
integrator = 2
dt_max = 2e-4
F = 500.0
Omega = 50.0
[section]
shape = "general"
A = 5.38e-3
I = 8.356e-5
As = 2.57e-3
depth = 0.3
[damping]
alpha = 0.2
beta = 2e-5
[modes]
count = 3
[shape]
points = 5
fields = ["M", "N", "Q", "sigma_top", "kappa"]

[[joint]]
name = "A"
x = 0.0
y = 0.0
[[joint]]
name = "B"
x = 0.0
y = 4.0
[[joint]]
name = "M"
x = 3.0
y = 4.5
[[joint]]
name = "C"
x = 6.0
y = 4.0
[[joint]]
name = "D"
x = 6.0
y = 0.0

[[member]]
name = "left"
from = "A"
to = "B"
[[member]]
name = "roof1"
from = "B"
to = "M"
[[member]]
name = "roof2"
from = "M"
to = "C"
[[member]]
name = "right"
from = "D"
to = "C"
hinges = ["start"]
[[member]]
name = "tie"
from = "B"
to = "C"
kind = "truss"
section = { shape = "circle", D = 0.02 }

[[support]]
name = "footA"
joint = "A"
fix = ["u1", "u2", "w"]
motion = "input"
[[support]]
name = "footD"
joint = "D"
fix = ["u1", "u2"]
displace = { u2 = -0.001 }
[[support]]
name = "prop"
member = "left"
at = 0.5
fix = ["u1"]

[[mass]]
name = "crane"
joint = "M"
m = 300.0
J = 20.0
[[mass]]
name = "pump"
member = "right"
at = 0.4
m = 80.0

[[spring]]
name = "bumper"
joint = "C"
dof = "u1"
k = 2e5
c = 500.0
motion = "input"
[[spring]]
name = "rest"
member = "roof1"
at = 0.5
dof = "w"
k = 1e4

[[foundation]]
name = "soil"
member = "roof2"
from = 0.2
to = 0.8
k = 1e5
c = 100.0

[[load]]
name = "g"
kind = "gravity"
[[load]]
name = "snow"
kind = "distributed"
member = "roof1"
direction = "-e2"
value = 800.0
value_end = 200.0
from = 0.1
to = 0.9
[[load]]
name = "wind"
kind = "distributed"
member = "left"
direction = "-normal"
value = 300.0
[[load]]
name = "shake"
kind = "point"
joint = "B"
direction = "e1"
time = "harmonic"
[[load]]
name = "twist"
kind = "moment"
member = "roof2"
at = 0.3
value = 200.0
[[load]]
name = "push"
kind = "point"
joint = "M"
direction = "e1"
time = "input"
[[load]]
name = "trolley"
kind = "moving"
path = ["roof1", "roof2"]
direction = "-e2"
value = 1000.0
speed = 20.0
enter = 0.02

[[sensor]]
name = "sway"
joint = "B"
quantity = "u1"
[[sensor]]
name = "spin"
joint = "M"
quantity = "w"
[[sensor]]
name = "v_mid"
member = "roof2"
at = 0.5
quantity = "v2"
[[sensor]]
name = "a_mid"
member = "roof2"
at = 0.5
quantity = "a2"
[[sensor]]
name = "N_left"
joint = "A"
member = "left"
quantity = "N"
[[sensor]]
name = "M_right_top"
joint = "C"
member = "right"
quantity = "M"
[[sensor]]
name = "stress"
member = "roof1"
at = 0.25
quantity = "sigma_bottom"
[[sensor]]
name = "w_hinge"
joint = "D"
member = "right"
quantity = "w"
"#;

#[test]
fn every_item_on_a_frame_closes_the_energy_ledger() {
    let mut sim = simulation_of(FRAME, &[]);
    // The prescribed settlement is there.
    let dy = sim
        .structure()
        .interpolate(&sim.state().u, georod::model::Place::Joint(4), 1);
    assert!((dy + 0.001).abs() < 1e-15, "footD settles by {dy}");
    let f1 = sim.frequency(0);
    assert!(f1 > 0.0 && f1.is_finite(), "frequency[1] = {f1}");
    let mut worst = 0.0f64;
    let mut scale = 0.0f64;
    for k in 0..150 {
        let t = (k + 1) as f64 * 1e-3;
        set_input(&mut sim, "footA_u1", 2e-3 * (40.0 * t).sin());
        set_input(&mut sim, "bumper_base", -1e-3 * (30.0 * t).sin());
        set_input(&mut sim, "push", 100.0 * (20.0 * t).cos());
        sim.advance(1e-3).expect("a step");
        worst = worst.max(output(&sim, "energy_error").abs());
        for name in [
            "E_kin",
            "E_strain",
            "E_damped",
            "W_ext",
            "W_ctrl",
            "W_supports",
        ] {
            scale = scale.max(output(&sim, name).abs());
        }
    }
    for name in [
        "sway",
        "spin",
        "v_mid",
        "a_mid",
        "N_left",
        "M_right_top",
        "stress",
        "w_hinge",
        "tie_N_start",
        "bumper_force",
        "shape_M[7]",
        "shape_N[21]",
        "shape_kappa[3]",
    ] {
        let x = output(&sim, name);
        assert!(x.is_finite(), "{name} = {x}");
    }
    println!(
        "largest |energy_error| {worst:.2e} J over 0.15 s; energies and works up to {scale:.3e} J \
         (W_supports {:.3e}, W_ctrl {:.3e}, E_damped {:.3e})",
        output(&sim, "W_supports"),
        output(&sim, "W_ctrl"),
        output(&sim, "E_damped")
    );
    assert!(scale > 1.0, "the frame moves and works: {scale}");
    // Round-off of energies of this size over 750 sub-steps (the moving support's and spring
    // base's work booked from their paths, the link-free dashpots exactly).
    assert!(worst < 1e-10 * scale, "{worst} of {scale}");
}
