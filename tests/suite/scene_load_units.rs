//! The units and descriptions modelDescription.xml gives the input loads: a point load is a
//! force (N), a distributed load a force per unit length (N/m), each with its own generated
//! description unless the scene gives one; the units are defined with their SI base units.
//! A host that scales its signals by the declared unit depends on these.
//!
//! Run: `cargo test --profile quick --test suite scene_load_units::`
use georod::packaging::model_description::model_description;
use georod::scene::Scene;

/// A cantilever with two input loads of each kind, one of each with its own description, and
/// a distributed harmonic load (whose amplitude `F` is then per unit length).
const LOADED: &str = r#"
name = "Loaded"

[geometry]
shape = "straight"
L = 4.0

[defaults]
E = 210e9
rho = 7850.0

[[support]]
name = "root"
at = 0.0
fix = ["u1", "u2", "w"]

[[load]]
name = "tip_push"
kind = "point"
at = 1.0
direction = "-e1"
time = "input"

[[load]]
name = "wind"
kind = "distributed"
direction = "e2"
time = "input"

[[load]]
name = "hand"
kind = "point"
at = 0.5
direction = "-e2"
time = "input"
description = "A hand pressing at midspan"

[[load]]
name = "rain"
kind = "distributed"
direction = "-e2"
time = "input"
description = "Weight of the rain"

[[load]]
name = "shaker"
kind = "distributed"
direction = "e2"
time = "harmonic"
"#;

/// The `<ScalarVariable>` element (through its closing tag) of the variable `name`.
fn variable<'a>(xml: &'a str, name: &str) -> &'a str {
    let open = format!(r#"<ScalarVariable name="{name}" "#);
    let start = xml
        .find(&open)
        .unwrap_or_else(|| panic!("no variable {name}"));
    let end = start + xml[start..].find("</ScalarVariable>").unwrap();
    &xml[start..end]
}

#[test]
fn input_loads_are_declared_in_newtons_or_newtons_per_metre() {
    let scene = Scene::parse(LOADED, "Loaded.toml").unwrap();
    let xml = model_description(&scene).xml;
    for (name, unit, description) in [
        (
            "tip_push",
            "N",
            "Point load along -e1 at 1 of the length, held over each communication step",
        ),
        (
            "wind",
            "N/m",
            "Distributed load along e2, held over each communication step",
        ),
        ("hand", "N", "A hand pressing at midspan"),
        ("rain", "N/m", "Weight of the rain"),
    ] {
        let var = variable(&xml, name);
        assert!(var.contains(r#"causality="input""#), "{var}");
        assert!(
            var.contains(&format!(r#"description="{description}""#)),
            "{name}: {var}"
        );
        assert!(
            var.contains(&format!(r#"<Real unit="{unit}""#)),
            "{name}: {var}"
        );
    }
    // The amplitude of a distributed harmonic load is per unit length too.
    assert!(variable(&xml, "F").contains(r#"<Real unit="N/m""#));
    // Both units defined with their base units: N = kg m s^-2, N/m = kg s^-2.
    for (unit, base) in [
        ("N", r#"<BaseUnit kg="1" m="1" s="-2"/>"#),
        ("N/m", r#"<BaseUnit kg="1" s="-2"/>"#),
    ] {
        let definition = format!("<Unit name=\"{unit}\">\n      {base}\n    </Unit>");
        assert!(xml.contains(&definition), "{unit}: {xml}");
    }
}
