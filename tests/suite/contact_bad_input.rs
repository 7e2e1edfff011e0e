//! Stops, cubic springs and cables that must be refused, each with the file, the key and what
//! is allowed (the packager and fmi2Instantiate read scenes through the same checker; refusals
//! that need the static state come from the initial state, which the packager computes before
//! it writes anything), and steps that cannot go on (a softening spring past its peak): refused
//! with the state unchanged.
use crate::common;

use common::{assert_refused, output, simulation_of};

/// A cantilever with a stop under its tip; each case edits it.
const BASE: &str = r#"
name = "Stopped"
[defaults]
E = 210e9
rho = 7850.0
elements = 10
[section]
b = 0.02
h = 0.002
[geometry]
shape = "straight"
L = 0.5
[[support]]
name = "root"
at = 0.0
fix = ["u1", "u2", "w"]
[[stop]]
name = "bump"
at = 1.0
dof = "u2"
side = "-"
gap = 1e-3
k = 1e4
[[spring]]
name = "soft"
at = 0.5
dof = "u2"
k = 100.0
k3 = -1e6
"#;

fn with(replace: &str, by: &str) -> String {
    assert!(BASE.contains(replace), "{replace}");
    BASE.replacen(replace, by, 1)
}

#[test]
fn the_base_scene_is_accepted() {
    let sim = simulation_of(BASE, &[]);
    assert_eq!(output(&sim, "bump_force"), 0.0);
    assert_eq!(output(&sim, "bump_contact"), 0.0);
}

#[test]
fn bad_stops_are_refused_with_their_key() {
    let key = |k: &str| format!("[[stop]] #1 \"bump\", key `{k}`");
    let cases: Vec<(&str, String, Vec<String>)> = vec![
        (
            "negative gap",
            with("gap = 1e-3", "gap = -1e-3"),
            vec![key("gap"), "must be >= 0".into()],
        ),
        (
            "zero stiffness",
            with("k = 1e4", "k = 0.0"),
            vec![key("k"), "must be > 0".into()],
        ),
        (
            "negative stiffness",
            with("k = 1e4", "k = -5.0"),
            vec![key("k"), "must be > 0".into()],
        ),
        (
            "no stiffness",
            with("k = 1e4\n", "\n"),
            vec![key("k"), "missing".into()],
        ),
        (
            "negative dashpot",
            with("k = 1e4", "k = 1e4\nc = -1.0"),
            vec![key("c"), "must be >= 0".into()],
        ),
        (
            "a side that is not + or -",
            with("side = \"-\"", "side = \"below\""),
            vec![key("side"), "\"+\"".into(), "\"-\"".into()],
        ),
        (
            "no side",
            with("side = \"-\"\n", "\n"),
            vec![key("side"), "missing".into()],
        ),
        (
            "a rotation",
            with("dof = \"u2\"\nside", "dof = \"w\"\nside"),
            vec![key("dof"), "\"u1\"".into(), "\"u2\"".into()],
        ),
        (
            "a dof a support holds",
            with(
                "at = 1.0\ndof = \"u2\"\nside",
                "at = 0.0\ndof = \"u2\"\nside",
            ),
            vec![key("dof"), "support `root` already holds u2".into()],
        ),
        (
            "outside the rod",
            with(
                "at = 1.0\ndof = \"u2\"\nside",
                "at = 1.5\ndof = \"u2\"\nside",
            ),
            vec![key("at"), "[0, 1]".into()],
        ),
        (
            "an unknown key",
            with("gap = 1e-3", "gap = 1e-3\ndamping = 2.0"),
            vec!["damping".into()],
        ),
        (
            "a name clash with its outputs",
            format!("{BASE}[[sensor]]\nname = \"bump_force\"\nat = 0.5\nquantity = \"u2\"\n"),
            vec!["bump_force".into(), "used twice".into()],
        ),
    ];
    for (what, text, parts) in cases {
        let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
        assert_refused(what, &text, &parts);
    }
}

#[test]
fn a_spring_with_a_bad_k3_is_refused() {
    assert_refused(
        "k3 not a number",
        &with("k3 = -1e6", "k3 = \"much\""),
        &["spring", "k3"],
    );
    assert_refused(
        "k3 infinite",
        &with("k3 = -1e6", "k3 = inf"),
        &["[[spring]] #1 \"soft\", key `k3`", "not a finite number"],
    );
}

/// A softening spring whose static state is past its peak: refused when the initial state is
/// computed, naming the spring's key and its peak. Its peak force is 2/3 k sqrt(k / (3 |k3|))
/// = 0.385 N at |u| = 5.8 mm; the cantilever's own stiffness at midspan (3 EI / (L/2)^3 = 538
/// N/m) keeps the whole stable under 5 N up (away from the stop), at u = 9 mm: past the peak.
#[test]
fn a_softening_spring_past_its_peak_in_the_static_state_is_refused() {
    let text = format!(
        "{BASE}[[load]]\nname = \"P\"\nkind = \"point\"\nat = 0.5\ndirection = \"e2\"\nvalue = 5.0\n"
    );
    let scene = std::sync::Arc::new(georod::scene::Scene::parse(&text, "bad.toml").unwrap());
    let e = georod::packaging::check_initial_state(&scene).unwrap_err();
    println!("{e}");
    assert!(e.contains("[[spring]] #1 \"soft\", key `k3`"), "{e}");
    assert!(e.contains("past the peak"), "{e}");
}

/// A step that takes a softening spring past its peak fails (after its cuts: the same each
/// time) with a message naming the spring, and leaves the state as it was.
#[test]
fn a_step_past_a_softening_peak_is_refused_with_the_state_unchanged() {
    let text = format!(
        "{BASE}[[load]]\nname = \"push\"\nkind = \"point\"\nat = 0.5\ndirection = \"-e2\"\ntime = \"input\"\n"
    );
    let mut sim = simulation_of(&text, &[("dt_max", 1e-4)]);
    common::set_input(&mut sim, "push", 50.0);
    for _ in 0..200 {
        let before = sim.snapshot();
        if let Err(e) = sim.advance(1e-3) {
            let e = e.to_string();
            println!("{e}");
            assert!(
                e.contains("spring `soft` is past the peak of its force"),
                "{e}"
            );
            assert!(e.contains("state left unchanged"), "{e}");
            let after = sim.snapshot();
            assert_eq!(after.displacements, before.displacements);
            assert_eq!(after.velocities, before.velocities);
            assert_eq!(after.time, before.time);
            assert_eq!(after.energy, before.energy);
            return;
        }
    }
    panic!("the spring passes its peak");
}
