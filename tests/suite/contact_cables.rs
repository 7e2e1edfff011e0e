//! Cables (`[[member]] kind = "cable"`: a truss member that carries tension only).
//! - A stay at a beam's midspan: pulled down, the load splits between the taut stay and the
//!   beam as between two springs in parallel, `N = P k_c / (k_c + k_b)`; pushed up, the stay
//!   goes slack (no force) and the beam alone carries the load.
//! - The same frame shaken up and down so that the stay goes slack and taut in turn: with the
//!   energy-momentum integrator the ledger closes to round-off through every tightening.
//! - A joint hung on two cables: its equilibrium hanging and, pushed up, upside down; with its
//!   cables slack and nothing else holding it, refused naming the cables.
//! - Stops on a frame (at a joint and on a member) and a hardening spring at a joint, on the
//!   same beam.
//!
//! Run: `cargo test --profile quick --test suite contact_cables:: -- --nocapture`
use crate::common;

use common::{output, simulation_of};

/// A 4 m steel beam (100 x 100 mm) on a pin and a roller, in two members meeting at its
/// midspan joint M, stayed from M to an anchor T 2 m above by a 5 mm steel cable (or without
/// the stay), a point load `p` along -e2 at M.
fn stayed_beam(stay: bool, p: f64, extra: &str) -> String {
    let stay = if stay {
        r#"
[[joint]]
name = "T"
x = 2.0
y = 2.0
[[support]]
name = "anchor"
joint = "T"
fix = ["u1", "u2"]
[[member]]
name = "stay"
from = "M"
to = "T"
kind = "cable"
section = { shape = "circle", D = 0.005 }
"#
    } else {
        ""
    };
    format!(
        r#"
name = "Stayed"
[defaults]
E = 210e9
nu = 0.3
rho = 7850.0
d = 0.0
elements = 40
{extra}
[section]
b = 0.1
h = 0.1
[[joint]]
name = "A"
x = 0.0
y = 0.0
[[joint]]
name = "M"
x = 2.0
y = 0.0
[[joint]]
name = "B"
x = 4.0
y = 0.0
[[member]]
name = "left"
from = "A"
to = "M"
[[member]]
name = "right"
from = "M"
to = "B"
{stay}
[[support]]
name = "pin"
joint = "A"
fix = ["u1", "u2"]
[[support]]
name = "roller"
joint = "B"
fix = ["u2"]
[[load]]
name = "P"
kind = "point"
joint = "M"
direction = "-e2"
value = {p}
[[sensor]]
name = "mid"
joint = "M"
quantity = "u2"
"#
    )
}

/// The stay's stiffness `EA / L` (5 mm, 2 m) and the beam's at midspan, `P / deflection` of the
/// same beam without the stay (the model's own, shear included). Loads of 100 N deflect the
/// beam by 1e-5 of its length: the geometric nonlinearity changes the split by about that much
/// squared; 1e-7 of the load leaves room for it and the solver's tolerance.
#[test]
fn a_stay_shares_the_load_when_taut_and_goes_slack_when_pushed() {
    let p = 100.0;
    let area = std::f64::consts::PI * 0.005 * 0.005 / 4.0;
    let k_c = 210e9 * area / 2.0;
    let alone = simulation_of(&stayed_beam(false, p, ""), &[]);
    let k_b = p / -output(&alone, "mid");
    let taut = simulation_of(&stayed_beam(true, p, ""), &[]);
    let n = output(&taut, "stay_N_start");
    let split = p * k_c / (k_c + k_b);
    println!(
        "pulled down by {p} N: stay {n:.9} N (P k_c / (k_c + k_b) = {split:.9} N, k_c = \
         {k_c:.6e}, k_b = {k_b:.6e} N/m), deflection {:.6e} m",
        output(&taut, "mid")
    );
    assert!((n - split).abs() < 1e-7 * p, "{n} vs {split}");
    assert_eq!(output(&taut, "stay_N_end"), n);
    let slack = simulation_of(&stayed_beam(true, -p, ""), &[]);
    let alone_up = simulation_of(&stayed_beam(false, -p, ""), &[]);
    println!(
        "pushed up by {p} N: stay {} N, deflection {:.9e} m (the beam alone: {:.9e} m)",
        output(&slack, "stay_N_start"),
        output(&slack, "mid"),
        output(&alone_up, "mid")
    );
    assert_eq!(output(&slack, "stay_N_start"), 0.0);
    let (a, b) = (output(&slack, "mid"), output(&alone_up, "mid"));
    assert!((a - b).abs() < 1e-9 * b.abs(), "{a} vs {b}");
}

/// Shaken at midspan by `F cos(Omega t)` about a preload that keeps the stay taut at rest, with
/// an amplitude that slackens it in every upward swing: the energy-momentum scheme keeps the
/// ledger closed to round-off (Newton's tolerance over 4000 sub-steps: 1e-11 of the energy
/// held, against the measured), the stay's force is never negative and it is slack part of
/// the time.
#[test]
fn a_stay_that_slackens_and_tightens_keeps_the_ledger_closed() {
    let extra = "integrator = 2\ndt_max = 2.5e-5\nF = 2000.0\nOmega = 300.0";
    let mut text = stayed_beam(true, 500.0, extra);
    text += "[[load]]\nname = \"shake\"\nkind = \"point\"\njoint = \"M\"\ndirection = \"-e2\"\nvalue = \"F\"\ntime = \"harmonic\"\n";
    let mut sim = simulation_of(&text, &[]);
    let (mut worst, mut scale, mut slack, mut taut) = (0.0f64, 0.0f64, 0, 0);
    for _ in 0..400 {
        sim.advance(2.5e-4).expect("a step");
        worst = worst.max(output(&sim, "energy_error").abs());
        scale = scale.max(output(&sim, "E_kin") + output(&sim, "E_strain"));
        let n = output(&sim, "stay_N_start");
        assert!(n >= 0.0, "{n}");
        if n == 0.0 {
            slack += 1;
        } else {
            taut += 1;
        }
    }
    println!(
        "stay slack at {slack} and taut at {taut} of 400 samples; largest |energy_error| \
         {worst:.2e} J, energy up to {scale:.3e} J ({:.1e} of it)",
        worst / scale
    );
    assert!(slack > 20 && taut > 20, "{slack} {taut}");
    assert!(worst < 1e-11 * scale, "{worst}");
}

/// A joint hung on two cables from two anchors. Loaded down, both cables carry `W / (2 cos 45)`;
/// pushed up, there is an equilibrium too, the geometrically exact one: the joint swings through
/// between the anchors to the mirror position above them, where the cables pull it down. With
/// no load and the anchors moved towards each other (their supports' `displace`), both cables
/// are slack and nothing holds the joint: refused when the initial state is computed (by the
/// packager, before anything is written), naming the joint, its cables and the key.
#[test]
fn a_joint_held_only_by_slack_cables_is_refused() {
    let text = |load: &str, displace: f64| {
        format!(
            r#"
name = "Hung"
[defaults]
E = 210e9
rho = 7850.0
[section]
shape = "circle"
D = 0.005
[[joint]]
name = "L"
x = 0.0
y = 0.0
[[joint]]
name = "R"
x = 2.0
y = 0.0
[[joint]]
name = "H"
x = 1.0
y = -1.0
[[member]]
name = "left"
from = "L"
to = "H"
kind = "cable"
[[member]]
name = "right"
from = "R"
to = "H"
kind = "cable"
[[support]]
name = "a"
joint = "L"
fix = ["u1", "u2"]
displace = {{ u1 = {displace} }}
[[support]]
name = "b"
joint = "R"
fix = ["u1", "u2"]
displace = {{ u1 = {} }}
[[sensor]]
name = "y"
joint = "H"
quantity = "u2"
{load}
"#,
            -displace
        )
    };
    let load = |direction: &str| {
        format!(
            "[[load]]\nname = \"W\"\nkind = \"point\"\njoint = \"H\"\ndirection = \"{direction}\"\nvalue = 100.0\n"
        )
    };
    let exact = 100.0 / 2.0_f64.sqrt();
    let hung = simulation_of(&text(&load("-e2"), 0.0), &[]);
    let n = output(&hung, "left_N_start");
    println!("hung: left cable {n:.6} N (W / sqrt(2) = {exact:.6} N at the reference geometry)");
    // The joint sinks by W / (2 k cos^2 45) = 3.5e-5 of the length: the angle changes by that.
    assert!((n - exact).abs() < 1e-4 * exact, "{n}");
    let flipped = simulation_of(&text(&load("e2"), 0.0), &[]);
    let (y, n) = (output(&flipped, "y"), output(&flipped, "left_N_start"));
    println!("pushed up: the joint at u2 = {y:.6} m (mirror position: +2), left cable {n:.6} N");
    assert!(
        (y - 2.0).abs() < 1e-3 && (n - exact).abs() < 1e-4 * exact,
        "{y} {n}"
    );
    let scene = georod::scene::Scene::parse(&text("", 0.1), "bad.toml").unwrap();
    let e = georod::packaging::check_initial_state(&scene).unwrap_err();
    println!("{e}");
    assert!(e.contains("[[member]] #1 \"left\", key `kind`"), "{e}");
    assert!(e.contains("joint `H` (left, right) is slack"), "{e}");
}

/// Stops on a frame: the beam without its stay, a stop under its midspan joint and one under the
/// middle of its left member (a station on the member: a node), both touching at rest (gap 0).
/// Under the midspan load both press: the supports and stops balance the load (vertical
/// equilibrium to the solver's tolerance), each stop's force is its stiffness times the
/// deflection there, and a step at rest keeps them (its reactions are averaged over the step).
#[test]
fn stops_at_a_joint_and_on_a_member_of_a_frame() {
    let stops = r#"
[[stop]]
name = "under_M"
joint = "M"
dof = "u2"
side = "-"
k = 1e6
[[stop]]
name = "under_left"
member = "left"
at = 0.5
dof = "u2"
side = "-"
k = 2e6
[[sensor]]
name = "y_left"
member = "left"
at = 0.5
quantity = "u2"
"#;
    let mut sim = simulation_of(&(stayed_beam(false, 1000.0, "") + stops), &[]);
    for step in 0..2 {
        let (f_m, f_l) = (
            output(&sim, "under_M_force"),
            output(&sim, "under_left_force"),
        );
        let supports = output(&sim, "pin_Ry") + output(&sim, "roller_Ry");
        println!(
            "{}: stops {f_m:.6} N (k u: {:.6} N), {f_l:.6} N (k u: {:.6} N), supports \
             {supports:.6} N; sum {:.9} N",
            if step == 0 { "static" } else { "after a step" },
            -1e6 * output(&sim, "mid"),
            -2e6 * output(&sim, "y_left"),
            f_m + f_l + supports
        );
        assert!(f_m > 0.0 && f_l > 0.0);
        assert!((f_m + f_l + supports - 1000.0).abs() < 1e-6, "equilibrium");
        assert!((f_m + 1e6 * output(&sim, "mid")).abs() < 1e-9 * f_m);
        assert!((f_l + 2e6 * output(&sim, "y_left")).abs() < 1e-9 * f_l);
        assert_eq!(output(&sim, "under_M_contact"), 1.0);
        sim.advance(1e-4).expect("a step at rest");
    }
}

/// A hardening spring at a frame's joint (the beam without its stay, a spring under M with
/// `k3`): in the static state its force output is `-(k u + k3 u^3)` at M's deflection, and the
/// supports and the spring balance the load.
#[test]
fn a_cubic_spring_at_a_frame_joint() {
    let spring = r#"
[[spring]]
name = "bearing"
joint = "M"
dof = "u2"
k = 1e5
k3 = 1e15
"#;
    let sim = simulation_of(&(stayed_beam(false, 20000.0, "") + spring), &[]);
    let u = output(&sim, "mid");
    let force = output(&sim, "bearing_force");
    let law = -(1e5 * u + 1e15 * u * u * u);
    let supports = output(&sim, "pin_Ry") + output(&sim, "roller_Ry");
    println!(
        "M at {u:.6e} m: spring {force:.6} N (k u + k3 u^3: {law:.6} N, the cubic part {:.6} N), \
         supports {supports:.6} N",
        -1e15 * u * u * u
    );
    assert!((force - law).abs() < 1e-12 * law.abs());
    assert!(-1e15 * u * u * u > 0.1 * force, "the cubic part matters");
    assert!((force + supports - 20000.0).abs() < 1e-6, "equilibrium");
}
