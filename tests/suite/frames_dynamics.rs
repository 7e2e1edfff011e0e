//! Frames in motion, against conservation laws:
//! - a free L-shaped frame (no support, no damping) struck at a joint by a force pulse (an input
//!   load held over one communication step): after the pulse its linear and angular momentum
//!   stay constant (the midpoint rule conserves both exactly: to the solver's tolerance);
//! - a swaying portal frame with a truss brace, a link, a joint mass and a joint spring, under
//!   a harmonic load: with the energy-momentum integrator its energy ledger closes to round-off
//!   without damping, and with every kind of damping (the material's, Rayleigh, a joint dashpot,
//!   a link's dashpot along its current line) `E_damped` keeps it closed.
//!
//! Run: `cargo test --profile quick --test suite frames_dynamics:: -- --nocapture`
use crate::common;

use common::{output, set_input, simulation_of};

const L_FRAME: &str = r#"
name = "LFrame"
[defaults]
E = 70e9
nu = 0.3
rho = 2700.0
d = 0.0
elements = 24
[section]
b = 0.04
h = 0.02
[initial]
state = "reference"
[[joint]]
name = "A"
x = 0.0
y = 0.0
[[joint]]
name = "B"
x = 1.0
y = 0.0
[[joint]]
name = "C"
x = 1.0
y = 0.6
[[member]]
name = "long"
from = "A"
to = "B"
[[member]]
name = "short"
from = "B"
to = "C"
[[mass]]
name = "tip"
joint = "C"
m = 0.5
J = 1e-4
[[load]]
name = "kick"
kind = "point"
joint = "C"
direction = "e2"
time = "input"
"#;

#[test]
fn a_free_frame_keeps_its_momenta_after_a_pulse() {
    let mut sim = simulation_of(L_FRAME, &[("dt_max", 1e-4)]);
    set_input(&mut sim, "kick", 200.0);
    sim.advance(1e-3).expect("the pulse");
    set_input(&mut sim, "kick", 0.0);
    let s = sim.structure().clone();
    let momenta = |sim: &georod::simulation::Simulation| {
        let (u, v) = (&sim.state().u, &sim.state().v);
        (s.linear_momentum(v), s.angular_momentum(u, v))
    };
    let (p0, l0) = momenta(&sim);
    // The pulse's impulse, 200 N for 1 ms, all along e2.
    println!("after the pulse: p = {p0:?} (impulse 0.2 N s), L = {l0:.6e}");
    assert!((p0[1] - 0.2).abs() < 1e-12 && p0[0].abs() < 1e-12, "{p0:?}");
    // At x = 1 from the origin (it moved by 1e-4 during the pulse).
    assert!((l0 - 0.2).abs() < 1e-3, "{l0}");
    let (mut dp, mut dl) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        sim.advance(1e-3).expect("a free step");
        let (p, l) = momenta(&sim);
        dp = dp.max((p - p0).norm());
        dl = dl.max((l - l0).abs());
    }
    println!("over 0.2 s: largest change of p {dp:.2e} N s, of L {dl:.2e} N m s");
    // The solver's tolerance (1e-10 of the increments) and round-off.
    assert!(dp < 1e-12 * 0.2 / 1e-3, "{dp}");
    // 2000 sub-steps, each converged to 1e-10 of its increment.
    assert!(dl < 5e-10 * l0.abs(), "{dl}");
}

/// A portal frame with a diagonal truss brace, a link from the beam's middle to a column's
/// middle, a mass and a spring on a corner, shaken at its beam level; `damped`: with the
/// material's damping, Rayleigh damping and dashpots on the link and the spring.
fn braced_portal(damped: bool) -> String {
    let (d, rayleigh) = if damped {
        ("d = 2.0", "[damping]\nalpha = 0.5\nbeta = 1e-5")
    } else {
        ("", "")
    };
    format!(
        r#"
name = "Braced"
[defaults]
E = 210e9
rho = 7850.0
elements = 30
integrator = 2
dt_max = 1e-4
F = 2000.0
Omega = 60.0
{d}
{rayleigh}
[section]
shape = "general"
A = 5.38e-3
I = 8.356e-5
As = 2.5e-3
[[joint]]
name = "A"
x = 0.0
y = 0.0
[[joint]]
name = "B"
x = 0.0
y = 4.0
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
name = "beam"
from = "B"
to = "C"
[[member]]
name = "right"
from = "D"
to = "C"
hinges = ["end"]
[[member]]
name = "brace"
from = "A"
to = "C"
kind = "truss"
section = {{ shape = "circle", D = 0.02 }}
[[link]]
name = "strut"
from = {{ member = "beam", at = 0.5 }}
to = {{ member = "right", at = 0.5 }}
k = 5e5
{link_damping}
[[mass]]
name = "machine"
joint = "B"
m = 200.0
J = 5.0
[[spring]]
name = "bearing"
joint = "C"
dof = "u1"
k = 1e6
{spring_damping}
[[support]]
name = "a"
joint = "A"
fix = ["u1", "u2", "w"]
[[support]]
name = "d"
joint = "D"
fix = ["u1", "u2"]
[[load]]
name = "wind"
kind = "point"
joint = "B"
direction = "e1"
time = "harmonic"
[[load]]
name = "weight"
kind = "gravity"
"#,
        link_damping = if damped { "c = 2e3" } else { "" },
        spring_damping = if damped { "c = 1e3" } else { "" },
    )
}

#[test]
fn the_energy_ledger_of_a_swaying_frame_closes() {
    for (what, damped) in [("undamped", false), ("damped", true)] {
        let mut sim = simulation_of(&braced_portal(damped), &[]);
        let mut worst = 0.0f64;
        let mut scale = 0.0f64;
        for _ in 0..100 {
            sim.advance(2e-3).expect("a step");
            worst = worst.max(output(&sim, "energy_error").abs());
            scale = scale
                .max(output(&sim, "E_kin"))
                .max(output(&sim, "E_damped"));
        }
        println!(
            "{what}: largest |energy_error| {worst:.2e} J over 0.2 s (E_kin, E_damped up to {scale:.3e} J, W_ext {:.3e} J)",
            output(&sim, "W_ext")
        );
        assert!(scale > 1e-3, "the frame moves: {scale}");
        // Round-off of energies of this size over 1000 sub-steps, and the link dashpot's
        // direction taken one iteration before the converged step (to the solver's tolerance).
        assert!(
            worst < 1e-9 * scale.max(output(&sim, "E_strain")),
            "{what}: {worst}"
        );
    }
}

/// A link's dashpot acts along the link's current line at the step's rate: the tangent map of the
/// Lyapunov exponents does not include it, so exponents are refused, naming the link (as a stop's
/// contact dashpot is); without the dashpot they run.
#[test]
fn exponents_are_refused_with_a_link_dashpot() {
    let with = |damped: bool| -> Result<(), String> {
        let scene = georod::scene::Scene::parse(&braced_portal(damped), "braced.toml").unwrap();
        let values = scene
            .values_with([("integrator", 1.0), ("lyapunov_count", 1.0)])
            .map_err(|e| e.to_string())?;
        georod::simulation::Simulation::new(std::sync::Arc::new(scene), values)
            .map(|_| ())
            .map_err(|e| e.to_string())
    };
    let e = with(true).expect_err("refused");
    println!("{e}");
    assert!(e.contains("lyapunov_count"), "{e}");
    assert!(e.contains("link `strut` has a dashpot (c = 2000)"), "{e}");
    with(false).expect("without the link's dashpot exponents run");
}
