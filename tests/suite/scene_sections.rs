//! `[section]`: rectangle, circle, tube and general sections. Their stiffnesses are the
//! closed-form section properties, a cantilever of each bends as the Timoshenko beam with that
//! section, the FMU declares exactly the shape's dimensions, and bad sections are refused with
//! the key and the allowed range.
//!
//! Run: `cargo test --profile quick --test suite scene_sections:: -- --nocapture`
use crate::common;

use common::{output, Table};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::f64::consts::PI;
use std::sync::Arc;

/// A 2 m steel cantilever with a tip load `P` along -e2 and the given `[section]` table.
fn cantilever(section: &str) -> String {
    format!(
        r#"
name = "Bar"
[geometry]
shape = "straight"
L = 2.0
[defaults]
E = 210e9
nu = 0.3
rho = 7850.0
elements = 40
[section]
{section}
[[parameter]]
name = "P"
start = 100.0
[[support]]
name = "root"
at = 0.0
fix = ["u1", "u2", "w"]
[[load]]
name = "tip"
kind = "point"
at = 1.0
direction = "-e2"
value = "P"
[[sensor]]
name = "w_tip"
at = 1.0
quantity = "u2"
"#
    )
}

fn parse(text: &str) -> Arc<Scene> {
    Arc::new(Scene::parse(text, "bar.toml").unwrap_or_else(|e| panic!("{e}")))
}

/// Tip deflection under `P`, Richardson-extrapolated from 40 and 80 elements (the hybrid
/// element's error is O(l^2)).
fn tip_deflection(scene: &Arc<Scene>) -> f64 {
    let tip = |n: f64| {
        let values = scene.values_with([("elements", n)]).unwrap();
        -output(&Simulation::new(scene.clone(), values).unwrap(), "w_tip")
    };
    let (coarse, fine) = (tip(40.0), tip(80.0));
    (4.0 * fine - coarse) / 3.0
}

/// (EA, GA_s, EI, rho A) of the built rod.
fn stiffness(scene: &Arc<Scene>) -> [f64; 4] {
    let sim = Simulation::new(scene.clone(), scene.defaults()).unwrap();
    let s = sim.rod().section;
    [s.ea, s.ga, s.ei, s.rho_a]
}

#[test]
fn section_properties_are_the_closed_forms() {
    let (e, g, rho) = (210e9, 210e9 / 2.6, 7850.0);
    let tube_inner: f64 = 0.1 - 2.0 * 0.005;
    let tube_area = PI * (0.01 - tube_inner.powi(2)) / 4.0;
    let tube_inertia = PI * (1e-4 - tube_inner.powi(4)) / 64.0;
    let cases = [
        (
            "shape = \"rectangle\"\nb = 0.05\nh = 0.1",
            [0.005, 0.005, 0.05 * 1e-3 / 12.0],
        ),
        (
            "shape = \"circle\"\nD = 0.1",
            [PI * 0.01 / 4.0, PI * 0.01 / 4.0, PI * 1e-4 / 64.0],
        ),
        (
            "shape = \"tube\"\nD = 0.1\nt = 0.005",
            [tube_area, tube_area, tube_inertia],
        ),
        (
            "shape = \"tube\"\nD = 0.1\nt = 0.005\nshear_factor = 0.5",
            [tube_area, 0.5 * tube_area, tube_inertia],
        ),
        (
            "shape = \"general\"\nA = 2.85e-3\nI = 8.36e-6\nAs = 1.4e-3\ndepth = 0.2",
            [2.85e-3, 1.4e-3, 8.36e-6],
        ),
    ];
    for (section, [area, shear_area, inertia]) in cases {
        let got = stiffness(&parse(&cantilever(section)));
        let want = [e * area, g * shear_area, e * inertia, rho * area];
        for (k, (a, b)) in got.iter().zip(want).enumerate() {
            // Round-off of the few products of each formula.
            assert!(
                (a - b).abs() <= 1e-14 * b,
                "{section}: property {k}: {a} vs {b}"
            );
        }
    }
}

/// The tube and the general section bend as Timoshenko cantilevers:
/// `P L^3 / (3 EI) + P L / (G As)` (the load is small: w/L up to 2e-3, so the geometric
/// nonlinearity, O((w/L)^2), stays at 4e-6 and below).
#[test]
fn cantilevers_of_each_shape_bend_as_timoshenko_beams() {
    let mut t = Table::new("2 m steel cantilevers, tip load 100 N: tip deflection vs Timoshenko");
    for section in [
        "shape = \"tube\"\nD = 0.1\nt = 0.005",
        "shape = \"tube\"\nD = 0.1\nt = 0.005\nshear_factor = 0.5",
        "shape = \"circle\"\nD = 0.05",
        "shape = \"general\"\nA = 2.85e-3\nI = 8.36e-6\nAs = 1.4e-3",
    ] {
        let scene = parse(&cantilever(section));
        let [_, ga, ei, _] = stiffness(&scene);
        let (load, length): (f64, f64) = (100.0, 2.0);
        let bending = load * length.powi(3) / (3.0 * ei);
        let shear = load * length / ga;
        let got = tip_deflection(&scene);
        let error = (got - bending - shear).abs() / (bending + shear);
        t.row(format_args!(
            "  {}: {got:.8e} vs {:.8e} (shear part {:.1e}), error {error:.1e}",
            section.replace('\n', " "),
            bending + shear,
            shear / bending
        ));
        // 1e-5: 30 times below the smallest shear part (3e-4 of the deflection), above the
        // extrapolated mesh error (1e-7) and the nonlinearity (4e-6 for the thin circle).
        assert!(error < 1e-5, "{section}: {got} vs {}", bending + shear);
    }
}

#[test]
fn the_fmu_declares_exactly_the_shapes_dimensions() {
    let xml = |s: &Scene| georod::packaging::model_description::model_description(s).xml;
    let tube = parse(&cantilever("shape = \"tube\"\nD = 0.1\nt = 0.005"));
    assert!(tube.param("b").is_err() && tube.param("h").is_err());
    let (_, d) = tube.param("D").unwrap();
    assert_eq!((d.start, d.unit.as_deref()), (0.1, Some("m")));
    let text = xml(&tube);
    assert!(text.contains("name=\"D\"") && text.contains("name=\"t\""));
    assert!(!text.contains("name=\"b\""));
    let general = parse(&cantilever(
        "shape = \"general\"\nA = 1e-3\nI = 1e-6\nAs = 5e-4",
    ));
    assert!(general.param("depth").is_err(), "depth only when given");
    assert_eq!(general.section.depth(&general.defaults()), None);
    // A rectangle's b and h may stay in [defaults], as in the paper's scenes.
    let rectangle = parse(&cantilever("").replace("elements = 40", "b = 0.05\nh = 0.1"));
    let values = rectangle.defaults();
    assert_eq!(rectangle.section.rectangle(&values), Some((0.05, 0.1)));
    assert_eq!(rectangle.section.depth(&values), Some(0.1));
}

#[test]
fn bad_sections_are_refused_with_the_key_and_the_range() {
    let cases = [
        (
            "shape = \"tube\"\nD = 0.1\nt = 0.05",
            vec!["section.t", "0.05 is out of range", "(0, 0.05)"],
        ),
        (
            "shape = \"tube\"\nD = 0.1",
            vec!["section.t", "missing", "D, t"],
        ),
        (
            "shape = \"circle\"\nD = 0.1\nb = 0.1",
            vec!["section.b", "not a dimension", "D"],
        ),
        (
            "shape = \"circle\"\nD = -0.1",
            vec!["section.D", "out of range"],
        ),
        ("shape = \"oval\"", vec!["section.shape", "rectangle"]),
        (
            "shape = \"general\"\nA = 1e-3\nI = 1e-6\nAs = 5e-4\nshear_factor = 0.8",
            vec!["section.shear_factor", "As directly"],
        ),
        (
            "shape = \"circle\"\nD = 0.1\nshear_factor = 0.0",
            vec!["section.shear_factor", "> 0"],
        ),
        (
            "shape = \"circle\"\nD = 0.1\nwidth = 1.0",
            vec!["section.width", "unknown field"],
        ),
    ];
    for (section, parts) in cases {
        let e = Scene::parse(&cantilever(section), "bad.toml")
            .unwrap_err()
            .to_string();
        for part in parts {
            assert!(e.contains(part), "{section}: `{e}` lacks `{part}`");
        }
    }
    let b_in_defaults = cantilever("shape = \"circle\"\nD = 0.1").replace("nu = 0.3", "b = 0.1");
    let e = Scene::parse(&b_in_defaults, "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("defaults.b") && e.contains("[section]"), "{e}");
    let twice = cantilever("b = 0.1").replace("nu = 0.3", "b = 0.1");
    let e = Scene::parse(&twice, "bad.toml").unwrap_err().to_string();
    assert!(e.contains("section.b") && e.contains("twice"), "{e}");
    let both = cantilever("shape = \"circle\"\nD = 0.1\nshear_factor = 0.9")
        + "[model]\nshear_factor = 0.9\n";
    let e = Scene::parse(&both, "bad.toml").unwrap_err().to_string();
    assert!(
        e.contains("section.shear_factor") && e.contains("once"),
        "{e}"
    );
    // A wall set thicker than the radius by the host: refused, naming t and the range.
    let tube = parse(&cantilever("shape = \"tube\"\nD = 0.1\nt = 0.005"));
    let e = tube.values_with([("t", 0.06)]).unwrap_err().to_string();
    assert!(e.contains("`t`") && e.contains("(0, 0.05)"), "{e}");
}

/// Fiber stresses take the scene's own section: on a tube cantilever under its tip load, at the
/// root, `sigma_top = N/A - M D/(2 I)` and `sigma_bottom = N/A + M D/(2 I)` with the tube's
/// closed-form A and I (to round-off: the same numbers, computed twice); a general section
/// without `depth` cannot read them, and the refusal names the sensor.
#[test]
fn fiber_stresses_use_the_section_and_need_its_depth() {
    use std::f64::consts::PI;
    let probes = "\n[[sensor]]\nname = \"n_root\"\nat = 0.0\nquantity = \"N\"\n\
        [[sensor]]\nname = \"m_root\"\nat = 0.0\nquantity = \"M\"\n\
        [[sensor]]\nname = \"top\"\nat = 0.0\nquantity = \"sigma_top\"\n\
        [[sensor]]\nname = \"bottom\"\nat = 0.0\nquantity = \"sigma_bottom\"\n";
    let (d, t) = (0.1, 0.01);
    let scene = parse(&(cantilever(&format!("shape = \"tube\"\nD = {d}\nt = {t}")) + probes));
    let sim = Simulation::new(scene.clone(), scene.defaults()).unwrap();
    let inner: f64 = d - 2.0 * t;
    let area = PI * (d * d - inner * inner) / 4.0;
    let inertia = PI * (d.powi(4) - inner.powi(4)) / 64.0;
    let (n, m) = (output(&sim, "n_root"), output(&sim, "m_root"));
    assert!(
        m.abs() > 100.0,
        "the root carries the tip load's moment: {m}"
    );
    let bending = m * d / (2.0 * inertia);
    let scale = bending.abs();
    assert!((output(&sim, "top") - (n / area - bending)).abs() < 1e-12 * scale);
    assert!((output(&sim, "bottom") - (n / area + bending)).abs() < 1e-12 * scale);

    let general = cantilever("shape = \"general\"\nA = 1e-3\nI = 1e-6\nAs = 5e-4") + probes;
    let e = Scene::parse(&general, "bad.toml").unwrap_err().to_string();
    assert!(e.contains("\"top\"") && e.contains("depth"), "{e}");
}
