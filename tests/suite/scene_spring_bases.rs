//! Springs whose bases follow FMI inputs (`[[spring]] motion = "input"`, inputs `<name>_base`):
//! a base offset set before the start shifts the static state by exactly that offset; a stiff
//! rod on two springs whose bases are shaken harmonically follows the closed-form base
//! transmissibility; the moving bases' work closes the energy ledger; bad keys are refused.
//!
//! Run: `cargo test --profile quick --test suite scene_spring_bases:: -- --nocapture`
use crate::common;

use common::output;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::f64::consts::PI;
use std::sync::Arc;

const RHO: f64 = 7850.0;

/// A straight steel rod `length` long, `b x h`, guided along e1 at midspan, on springs `k`
/// (dashpots `c`) along e2 at both ends whose bases follow inputs; `extra` TOML added.
fn rod_on_springs(length: f64, b: f64, h: f64, k: f64, c: f64, extra: &str) -> Arc<Scene> {
    let text = format!(
        "name = \"Bearings\"\n[geometry]\nshape = \"straight\"\nL = {length}\n[defaults]\n\
         E = 210e9\nnu = 0.3\nrho = {RHO}\nd = 0.0\nb = {b}\nh = {h}\nelements = 10\n\
         [[support]]\nname = \"guide\"\nat = 0.5\nfix = [\"u1\"]\n\
         [[spring]]\nname = \"left\"\nat = 0.0\ndof = \"u2\"\nk = {k}\nc = {c}\nmotion = \"input\"\n\
         [[spring]]\nname = \"right\"\nat = 1.0\ndof = \"u2\"\nk = {k}\nc = {c}\nmotion = \"input\"\n\
         {extra}\n"
    );
    Arc::new(Scene::parse(&text, "bearings.toml").unwrap_or_else(|e| panic!("{e}")))
}

/// The index of the input called `name`.
fn input(scene: &Scene, name: &str) -> usize {
    (scene.inputs.iter().position(|i| i.name == name)).unwrap_or_else(|| panic!("no {name}"))
}

fn simulation(scene: &Arc<Scene>, overrides: &[(&str, f64)], bases: f64) -> Simulation {
    let values = scene.values_with(overrides.iter().copied()).unwrap();
    let mut inputs = vec![0.0; scene.inputs.len()];
    for name in ["left_base", "right_base"] {
        inputs[input(scene, name)] = bases;
    }
    Simulation::with_inputs(scene.clone(), values, inputs).expect("initial state")
}

#[test]
fn base_inputs_are_declared_with_their_units() {
    let scene = rod_on_springs(1.0, 0.1, 0.1, 1e5, 0.0, "");
    let left = &scene.inputs[input(&scene, "left_base")];
    assert_eq!(left.unit.as_deref(), Some("m"));
    assert!(
        left.description.contains("spring left"),
        "{}",
        left.description
    );
    let rotary = rod_on_springs(
        1.0,
        0.1,
        0.1,
        1e5,
        0.0,
        "[[spring]]\nname = \"twist\"\nat = 0.25\ndof = \"w\"\nk = 10.0\nmotion = \"input\"\n",
    );
    let twist = &rotary.inputs[input(&rotary, "twist_base")];
    assert_eq!(twist.unit.as_deref(), Some("rad"));
}

/// A rod on two end springs under its weight, both bases raised by `offset` before the
/// start: a rigid translation strains nothing, so the static state is the one with the bases
/// at 0 shifted by `offset` along e2 (to the static solver's tolerance), and each spring still
/// carries half the weight.
#[test]
fn base_offset_set_before_the_start_shifts_the_static_state() {
    let (length, b, h, k) = (2.0, 0.1, 0.1, 1e5);
    let gravity = "[[load]]\nname = \"g\"\nkind = \"gravity\"\n";
    let scene = rod_on_springs(length, b, h, k, 50.0, gravity);
    let offset = 0.01;
    let (at_rest, raised) = (
        simulation(&scene, &[], 0.0),
        simulation(&scene, &[], offset),
    );
    let weight = RHO * b * h * length * 9.81;
    let mut worst = 0.0_f64;
    for (i, (a, r)) in at_rest.state().u.iter().zip(&raised.state().u).enumerate() {
        let shift = if i % 3 == 1 { offset } else { 0.0 };
        worst = worst.max((r - a - shift).abs());
    }
    let sag = -at_rest.state().u[1];
    println!("sag {sag:.6e} m; shifted state off by {worst:.1e} m");
    assert!((sag / (weight / 2.0 / k) - 1.0).abs() < 1e-6, "sag {sag}");
    // The static solver converges to 1e-10 of the rod's length: far below the offset.
    assert!(worst < 1e-9 * offset, "{worst:e}");
    for sim in [&at_rest, &raised] {
        for name in ["left_force", "right_force"] {
            let f = output(sim, name);
            assert!((f / (weight / 2.0) - 1.0).abs() < 1e-9, "{name} = {f}");
        }
    }
    // The springs store k (u - b)^2 / 2 each, whatever the offset (the rod's bending under
    // its weight adds under 1 %).
    let stored = 2.0 * 0.5 * (weight / 2.0).powi(2) / k;
    let (rest, up) = (output(&at_rest, "E_strain"), output(&raised, "E_strain"));
    println!("E_strain {rest:.9e} J at rest, {up:.9e} J raised; springs {stored:.9e} J");
    assert!((up / rest - 1.0).abs() < 1e-9, "{up} vs {rest}");
    assert!(rest > stored && rest < 1.01 * stored, "{rest} vs {stored}");
}

/// Steady amplitude of `x` (sampled at `times`) at circular frequency `w`, by projection onto
/// `sin` and `cos` over the samples (whole periods).
fn amplitude(times: &[f64], x: &[f64], w: f64) -> f64 {
    let n = x.len() as f64;
    let s: f64 = times.iter().zip(x).map(|(t, x)| x * (w * t).sin()).sum();
    let c: f64 = times.iter().zip(x).map(|(t, x)| x * (w * t).cos()).sum();
    2.0 * (s * s + c * c).sqrt() / n
}

/// A stiff short rod (1 m, 0.1 m wide, 0.2 m deep) on two
/// end springs and dashpots whose bases both move `Y sin(w t)`: its heave follows the
/// single-dof base transmissibility `|X / Y| = sqrt((K^2 + (C w)^2) / ((K - m w^2)^2 +
/// (C w)^2))`, `K`, `C` the two springs' sum. The transient decays as `exp(-zeta wn t)`:
/// after 20 of its time constants it is below 1e-8.
#[test]
fn shaken_bases_follow_the_base_transmissibility() {
    let (length, b, h, k, zeta) = (1.0, 0.1, 0.2, 1e5, 0.1);
    let mass = RHO * b * h * length;
    let (stiffness, wn) = (2.0 * k, (2.0 * k / mass).sqrt());
    let damping = 2.0 * zeta * (stiffness * mass).sqrt();
    let sensor = "[[sensor]]\nname = \"w_mid\"\nat = 0.5\nquantity = \"u2\"\n";
    let scene = rod_on_springs(length, b, h, k, damping / 2.0, sensor);
    let (left, right) = (input(&scene, "left_base"), input(&scene, "right_base"));
    let y = 1e-3;
    for ratio in [0.8, 1.0, 1.5] {
        let w = ratio * wn;
        let step = 2.0 * PI / w / 200.0;
        let mut sim = simulation(&scene, &[("dt_max", step)], 0.0);
        let settle = (20.0 / (zeta * wn) / step).ceil() as usize;
        let (mut times, mut heave) = (Vec::new(), Vec::new());
        for n in 0..settle + 2000 {
            let t = (n + 1) as f64 * step;
            for i in [left, right] {
                sim.set_input(i, y * (w * t).sin()).unwrap();
            }
            sim.advance(step).unwrap();
            if n >= settle {
                times.push(t);
                heave.push(output(&sim, "w_mid"));
            }
        }
        let got = amplitude(&times, &heave, w) / y;
        let cw = damping * w;
        let want =
            ((stiffness.powi(2) + cw * cw) / ((stiffness - mass * w * w).powi(2) + cw * cw)).sqrt();
        println!(
            "w/wn {ratio}: |X/Y| {got:.6} vs {want:.6} ({:+.1e})",
            got / want - 1.0
        );
        // The midpoint rule lengthens the period by (w dt)^2 / 12 = 8e-5 at 200 steps a
        // period, which at resonance moves the amplitude by about that over zeta (8e-4); the
        // rod's bending softens the springs by about k L^3 / (40 EI) = 2e-4, which below
        // resonance moves it by r^2 / (1 - r^2) times that (measured: 5e-4 at most).
        assert!(
            (got / want - 1.0).abs() < 2e-3,
            "w/wn {ratio}: {got} vs {want}"
        );
    }
}

/// The energy ledger with moving bases, dashpots and gravity: exact for the energy-momentum
/// scheme; the bases' work is `sum f db` over the steps, which the test rebuilds from the
/// step-averaged spring forces (the base moves linearly over each step, so the average force
/// times the step's base increment is that step's work).
#[test]
fn moving_bases_do_the_work_that_closes_the_ledger() {
    let gravity = "[[load]]\nname = \"g\"\nkind = \"gravity\"\n";
    let scene = rod_on_springs(2.0, 0.1, 0.1, 1e5, 300.0, gravity);
    let (left, right) = (input(&scene, "left_base"), input(&scene, "right_base"));
    for integrator in [1.0, 2.0] {
        let step = 1e-3;
        let overrides = [("integrator", integrator), ("dt_max", step / 4.0)];
        let mut sim = simulation(&scene, &overrides, 2e-3);
        let mut rebuilt = 0.0;
        let mut worst = 0.0_f64;
        for n in 1..=400 {
            let t = n as f64 * step;
            let before = sim.next_inputs().to_vec();
            sim.set_input(left, 2e-3 + 5e-3 * (40.0 * t).sin()).unwrap();
            sim.set_input(right, 2e-3 - 3e-3 * (55.0 * t).sin())
                .unwrap();
            let after = sim.next_inputs().to_vec();
            sim.advance(step).unwrap();
            for (i, name) in [(left, "left_force"), (right, "right_force")] {
                rebuilt += output(&sim, name) * (after[i] - before[i]);
            }
            worst = worst.max(sim.energy_error().abs());
        }
        let (work, damped) = (output(&sim, "W_supports"), output(&sim, "E_damped"));
        println!(
            "integrator {integrator}: W_supports {work:.6e} (rebuilt {rebuilt:.6e}), E_damped \
             {damped:.6e}, worst energy_error {worst:.1e}"
        );
        assert!(damped > 0.1 * work.abs() && work.abs() > 1e-3);
        assert!(
            (work - rebuilt).abs() < 1e-12 * work.abs(),
            "{work} vs {rebuilt}"
        );
        // Energy-momentum: exact to the solver's tolerance; midpoint: second order, at this
        // step (w dt = 0.014) well below a thousandth of the work.
        let bound = if integrator == 2.0 { 1e-9 } else { 1e-3 };
        assert!(
            worst < bound * work.abs(),
            "integrator {integrator}: {worst:e}"
        );
    }
}

#[test]
fn bad_spring_motions_are_refused() {
    let base = "name = \"B\"\n[geometry]\nshape = \"straight\"\nL = 2.0\n[defaults]\nE = 1.0\n\
                rho = 1.0\n[[support]]\nname = \"A\"\nat = 0.0\nfix = [\"u1\", \"u2\", \"w\"]\n\
                [[spring]]\nname = \"s\"\nat = 1.0\ndof = \"u2\"\nk = 1.0\n";
    common::assert_refused(
        "motion",
        &format!("{base}motion = \"harmonic\"\n"),
        &["[[spring]] #1 \"s\", key `motion`", "\"none\"", "\"input\""],
    );
    let clash = "[[sensor]]\nname = \"s_base\"\nat = 0.5\nquantity = \"u2\"\n";
    common::assert_refused(
        "clash",
        &format!("{base}motion = \"input\"\n{clash}"),
        &["`s_base` is used twice", "[[sensor]] s_base"],
    );
    Scene::parse(&format!("{base}motion = \"none\"\n{clash}"), "ok.toml")
        .expect("a fixed base declares no input");
}
