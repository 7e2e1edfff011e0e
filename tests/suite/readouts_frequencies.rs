//! `[modes] count = K`: the outputs `frequency[k]` (Hz) of the initial state against the
//! Timoshenko frequencies of a simply supported rod (second-order convergence in the element
//! length) and against the buckled beam's first frequency about its upper well (the paper
//! scene's 2503 rad/s of docs/figures/buckled_beam/table_sensitivity.md).
//!
//! Run: `cargo test --profile quick --test suite readouts_frequencies:: -- --nocapture`
use crate::common;

use common::{output, timoshenko_bending_omega, Table};
use georod::model::Section;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::f64::consts::TAU;
use std::sync::Arc;

fn simply_supported(n: usize) -> Arc<Scene> {
    let text = format!(
        "name = \"Modes\"\n[geometry]\nshape = \"straight\"\nL = 10.0\n\
         [defaults]\nE = 2.0e5\nnu = 0.3\nrho = 1.0\nb = 1.0\nh = 0.5\nelements = {n}\n\
         [[support]]\nname = \"pin\"\nat = 0.0\nfix = [\"u1\", \"u2\"]\n\
         [[support]]\nname = \"roller\"\nat = 1.0\nfix = [\"u2\"]\n\
         [modes]\ncount = 3\n"
    );
    Arc::new(Scene::parse(&text, "modes.toml").expect("scene"))
}

/// A pin and a roller (L/h = 20, so shear and rotary inertia shift the third frequency by
/// 2 %): `frequency[1..3]` tend to the Timoshenko bending frequencies, the error falling by four
/// when the elements double, about `1.2 (k / n)^2` for mode `k` on `n` elements.
#[test]
fn simply_supported_frequencies_are_timoshenko() {
    let section = Section::rectangular(2.0e5, 0.3, 1.0, 1.0, 0.5);
    let exact: Vec<f64> = (1..=3)
        .map(|k| timoshenko_bending_omega(&section, 10.0, k) / TAU)
        .collect();
    let mut t = Table::new("Simply supported rod, L/h = 20: frequency[k] vs Timoshenko");
    let mut errors = Vec::new();
    for n in [20, 40, 80] {
        let scene = simply_supported(n);
        let sim = Simulation::new(scene.clone(), scene.defaults()).expect("initial state");
        let e: Vec<f64> = (0..3)
            .map(|k| (output(&sim, &format!("frequency[{}]", k + 1)) - exact[k]).abs() / exact[k])
            .collect();
        t.row(format_args!(
            "{n:>3} elements: relative errors {:.2e} {:.2e} {:.2e} (exact {:.4} {:.4} {:.4} Hz)",
            e[0], e[1], e[2], exact[0], exact[1], exact[2]
        ));
        errors.push(e);
    }
    for k in 0..3 {
        let ratio = errors[1][k] / errors[2][k];
        assert!((3.5..4.5).contains(&ratio), "mode {}: {errors:?}", k + 1);
        // Second order in the mode's wave number times the element length: about
        // 1.2 (k / n)^2 for each mode k on n elements.
        let bound = 1.5 * ((k + 1) as f64 / 80.0).powi(2);
        assert!(errors[2][k] < bound, "mode {}: {errors:?}", k + 1);
    }
}

/// The paper's buckled beam (upper well, 10 elements): its first frequency about the static
/// state is 2503 rad/s (the table rounds to 1 rad/s); the higher ones ascend.
#[test]
fn buckled_beam_first_frequency_is_the_known_value() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/BuckledBeam.toml");
    let text = std::fs::read_to_string(path).unwrap() + "\n[modes]\ncount = 4\n";
    let scene = Arc::new(Scene::parse(&text, "BuckledBeam+modes").unwrap());
    let sim = Simulation::new(scene.clone(), scene.defaults()).expect("upper well");
    let f: Vec<f64> = (1..=4)
        .map(|k| output(&sim, &format!("frequency[{k}]")))
        .collect();
    let mut t = Table::new("BuckledBeam, upper well: frequency[k]");
    t.row(format_args!(
        "frequency[1] = {:.4} Hz = {:.2} rad/s (known 2503); then {:.1} {:.1} {:.1} Hz",
        f[0],
        f[0] * TAU,
        f[1],
        f[2],
        f[3]
    ));
    assert!((f[0] * TAU - 2503.0).abs() <= 0.5, "{f:?}");
    assert!(f.windows(2).all(|w| w[0] < w[1]), "{f:?}");
}
