//! A state past its stability limit reports the instability: a straight pinned-pinned rod pushed
//! in beyond its buckling load and held straight (no branch, no transverse load: the straight
//! state is an equilibrium, an unstable one). Its lowest natural frequency is imaginary, which
//! `frequency[1]` and `georod modes` report as documented (docs/scenes.md, `[modes]`): negative,
//! `-sqrt(-omega^2) / (2 pi)`, never a positive number. Below the limit the same rod reads
//! positive frequencies.
//!
//! Closed form: a rod under the axial force `P` has `omega_1^2 = omega_0^2 (1 - P / P_cr)` in its
//! first bending mode (the geometric stiffness is linear in `P`, and the straight state's mode is
//! the unloaded one), with `P = EA eps` for the end shortening `eps L`.
//!
//! Run: `cargo test --profile quick --test suite stability_readouts:: -- --nocapture`
use crate::common;

use common::{critical_axial_force, output, Table};
use georod::model::Section;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::f64::consts::PI;
use std::process::Command;
use std::sync::Arc;

const LENGTH: f64 = 4.0;
const B: f64 = 0.05;
const H: f64 = 0.05; // L/h = 80: slender
const E: f64 = 210e9;
const NU: f64 = 0.3;
const RHO: f64 = 7850.0;

fn scene_text(shortening: f64) -> String {
    format!(
        r#"
name = "Strut"
[geometry]
shape = "straight"
L = {LENGTH}
[defaults]
E = {E}
nu = {NU}
rho = {RHO}
d = 0.0
b = {B}
h = {H}
elements = 40
[[parameter]]
name = "shortening"
start = {shortening}
unit = "m"
[[support]]
name = "pin"
at = 0.0
fix = ["u1", "u2"]
[[support]]
name = "pushed"
at = 1.0
fix = ["u1", "u2"]
displace = {{ u1 = "-shortening" }}
[modes]
count = 2
"#
    )
}

/// The shortening that puts the axial force at `ratio` times the buckling load.
fn shortening(ratio: f64) -> f64 {
    let section = Section::rectangular(E, NU, RHO, B, H);
    ratio * critical_axial_force(&section, LENGTH) / section.ea * LENGTH
}

/// The unloaded rod's first bending frequency (Hz), Euler-Bernoulli.
fn unloaded_hz() -> f64 {
    let (area, inertia) = (B * H, B * H.powi(3) / 12.0);
    (PI / LENGTH).powi(2) * (E * inertia / (RHO * area)).sqrt() / (2.0 * PI)
}

fn frequency_1(shortening: f64) -> f64 {
    let text = scene_text(shortening);
    let scene = Arc::new(Scene::parse(&text, "strut.toml").unwrap_or_else(|e| panic!("{e}")));
    let sim = Simulation::new(scene.clone(), scene.defaults()).expect("initial state");
    output(&sim, "frequency[1]")
}

/// `georod modes FILE --count 2`: the printed rows `mode  Hz  ...`, in order.
fn modes_printed(shortening: f64) -> Vec<f64> {
    let dir = std::env::temp_dir().join(format!(
        "georod_stability_readouts_{}_{}",
        std::process::id(),
        (shortening * 1e9) as u64
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("Strut.toml");
    std::fs::write(&file, scene_text(shortening)).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_georod"))
        .args(["modes", file.to_str().unwrap(), "--count", "2", "-o"])
        .arg(dir.join("shapes.csv"))
        .output()
        .expect("georod runs");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
    let printed: Vec<f64> = stdout
        .lines()
        .filter_map(|l| {
            let cols: Vec<&str> = l.split_whitespace().collect();
            (cols.len() >= 3 && cols[0].parse::<usize>().is_ok()).then(|| cols[1].parse().unwrap())
        })
        .collect();
    assert_eq!(printed.len(), 2, "{stdout}");
    printed
}

#[test]
fn a_strut_past_its_buckling_load_reads_a_negative_frequency() {
    let f0 = unloaded_hz();
    let mut t = Table::new(&format!(
        "steel strut {LENGTH} m, 50 x 50 mm, pinned-pinned, held straight at P / P_cr: \
         frequency[1] and georod modes vs f0 sqrt(1 - P/P_cr) (f0 = {f0:.4} Hz)"
    ));
    for ratio in [0.5, 1.5, 2.0] {
        let eps = shortening(ratio);
        let (output, printed) = (frequency_1(eps), modes_printed(eps));
        let lambda = 1.0 - ratio;
        let want = lambda.signum() * lambda.abs().sqrt() * f0;
        t.row(format_args!(
            "  P/P_cr = {ratio}: frequency[1] = {output:.5} Hz, georod modes {:.5} Hz, \
             closed form {want:.5} Hz",
            printed[0]
        ));
        assert_eq!(
            output.is_sign_negative(),
            ratio > 1.0,
            "P/P_cr = {ratio}: frequency[1] = {output}"
        );
        assert_eq!(
            printed[0].is_sign_negative(),
            ratio > 1.0,
            "P/P_cr = {ratio}: georod modes printed {printed:?}"
        );
        // The command prints the same number as the output (to its printed digits).
        assert!(
            (printed[0] - output).abs() < 1e-6 * output.abs(),
            "{printed:?} vs {output}"
        );
        // Shear, rotary inertia and the 40-element mesh move f0 by O((pi h / L)^2) = 1.5e-3
        // and P_cr by as much (measured: 1.2e-3 of f0); 5e-3 of f0 holds the magnitude.
        assert!(
            (output - want).abs() < 5e-3 * f0,
            "P/P_cr = {ratio}: {output} Hz vs {want} Hz"
        );
        // The second mode (two half waves, P_cr2 = 4 P_cr) is stable at all three loads.
        assert!(printed[1] > 0.0, "{printed:?}");
    }
}
