//! Stops (`[[stop]]`) against closed forms:
//! - a stiff beam on two springs released onto a stop at its midspan: with the stop at the
//!   equilibrium (gap 0) the bilinear oscillator's period `pi/w1 + pi/w2` whatever the amplitude,
//!   with a gap the piecewise closed form at the released amplitude;
//! - the same beam, free, striking a stop with a dashpot: the coefficient of restitution of
//!   this contact law (the Kelvin-Voigt force cut at zero) against its exact value;
//! - a beam pinned at one end settling under its weight onto a stop under the other: the static
//!   initial state rests on it, with the force statics gives.
//!
//! The beam is 1000 times as stiff as steel (E = 2.1e16 Pa): its lowest bending frequency is
//! 800 times the contact frequency, so it heaves as a rigid body (the rigid-body closed forms
//! then hold to about (w2 / w_bend)^2 = 1.5e-6 and the stop's compliance against the beam's,
//! 1e-5).
//!
//! Run: `cargo test --profile quick --test suite contact_stops:: -- --nocapture`
use crate::common;

use common::contact::{mean_period, release, up_crossings};
use common::{output, simulation_of};
use georod::simulation::Simulation;
use std::f64::consts::PI;

/// A 1 m beam (0.1 x 0.1, 78.5 kg) on two springs `K_SPRING` at its ends, its midspan guided
/// along e2 (u1 held), a stop `K_STOP` under its midspan at the gap `GAP`.
fn on_springs(gap: f64, c: f64, springs: bool, integrator: f64) -> String {
    let springs = if springs {
        format!(
            r#"
[[spring]]
name = "left"
at = 0.0
dof = "u2"
k = {K_SPRING}
[[spring]]
name = "right"
at = 1.0
dof = "u2"
k = {K_SPRING}
"#
        )
    } else {
        // Free to rock: no static state to look for.
        "[initial]\nstate = \"reference\"\n".to_string()
    };
    let head = common::contact::guided_block("Bilinear", DT, integrator);
    format!(
        r#"{head}{springs}
[[stop]]
name = "stop"
at = 0.5
dof = "u2"
side = "-"
gap = {gap}
k = {K_STOP}
c = {c}
[[sensor]]
name = "mid"
at = 0.5
quantity = "u2"
[[sensor]]
name = "v_mid"
at = 0.5
quantity = "v2"
"#
    )
}

const K_SPRING: f64 = 1e5;
const K_STOP: f64 = 1e6;
const DT: f64 = 1e-5;
/// The beam's mass, `rho b h L`.
const MASS: f64 = 7850.0 * 0.01;

/// Runs for `time` in communication steps of `DT`: the times and midspan displacements.
fn run(sim: &mut Simulation, time: f64) -> (Vec<f64>, Vec<f64>) {
    let steps = (time / DT).round() as usize;
    let (mut t, mut x) = (vec![0.0], vec![output(sim, "mid")]);
    for _ in 0..steps {
        sim.advance(DT).expect("a step");
        t.push(sim.time());
        x.push(output(sim, "mid"));
    }
    (t, x)
}

/// Gap 0: `pi/w1 + pi/w2`, `w1 = sqrt(2 k / m)` off the stop, `w2 = sqrt((2 k + k_c) / m)` on
/// it, for any amplitude; both integrators. Error budget: both schemes lengthen a linear
/// oscillation's period by `(w dt)^2 / 12` (their frequency is `2/dt atan(w dt / 2)`), here
/// `pi dt^2 (w1 + w2) / (12 T)` = 5.2e-8 of the period (the error measured: 5.6e-8), plus the
/// crossing of the kink inside a step (second order as well) and the beam's flexibility
/// (above, 1e-8): 2e-7 leaves room over them.
#[test]
fn bilinear_period_at_gap_zero() {
    let w1 = (2.0 * K_SPRING / MASS).sqrt();
    let w2 = ((2.0 * K_SPRING + K_STOP) / MASS).sqrt();
    let exact = PI / w1 + PI / w2;
    for integrator in [1.0, 2.0] {
        // The period does not depend on the amplitude (the midpoint rule: at two of them).
        let amplitudes: &[f64] = if integrator == 1.0 {
            &[1e-3, 5e-2]
        } else {
            &[1e-3]
        };
        for &amplitude in amplitudes {
            let mut sim = simulation_of(&on_springs(0.0, 0.0, true, integrator), &[]);
            release(&mut sim, amplitude, 0.0);
            let (t, x) = run(&mut sim, 5.2 * exact);
            let period = mean_period(&up_crossings(&t, &x, 0.0));
            let error = (period - exact).abs() / exact;
            println!(
                "integrator {integrator}, amplitude {amplitude}: period {period:.9} s, \
                 closed form {exact:.9} s, relative error {error:.2e}"
            );
            assert!(error < 2e-7, "{error}");
        }
    }
}

/// The period of the bilinear oscillator with the stop at `gap` below the equilibrium,
/// released at rest from `amplitude` above it: the free arc above `-gap`,
/// `2 acos(-gap / A) / w1`, and the arc below it about the contact equilibrium
/// `x_c = -k_c gap / (2 k + k_c)`, `2 acos(|d| / B) / w2` with `d = -gap - x_c` and
/// `B = sqrt(d^2 + (v / w2)^2)`, `v = w1 sqrt(A^2 - gap^2)` the speed at contact.
fn period_with_gap(gap: f64, amplitude: f64) -> f64 {
    let w1 = (2.0 * K_SPRING / MASS).sqrt();
    let w2 = ((2.0 * K_SPRING + K_STOP) / MASS).sqrt();
    let v = w1 * (amplitude * amplitude - gap * gap).sqrt();
    let xc = -K_STOP * gap / (2.0 * K_SPRING + K_STOP);
    let d = -gap - xc;
    let b = (d * d + (v / w2).powi(2)).sqrt();
    2.0 * (-gap / amplitude).acos() / w1 + 2.0 * (d.abs() / b).acos() / w2
}

/// With a gap: the piecewise closed form at the released amplitude (both schemes keep the
/// amplitude, the energy-momentum scheme exactly), same budget as at gap 0 (measured: 2.5e-8
/// to 5.7e-8).
#[test]
fn bilinear_period_with_a_gap() {
    for integrator in [1.0, 2.0] {
        for (gap, amplitude) in [(5e-4, 1e-3), (2e-3, 1e-2)] {
            let exact = period_with_gap(gap, amplitude);
            let mut sim = simulation_of(&on_springs(gap, 0.0, true, integrator), &[]);
            release(&mut sim, amplitude, 0.0);
            let (t, x) = run(&mut sim, 5.2 * exact);
            let period = mean_period(&up_crossings(&t, &x, 0.0));
            let error = (period - exact).abs() / exact;
            let top = x.iter().copied().fold(f64::MIN, f64::max);
            println!(
                "integrator {integrator}, gap {gap}, amplitude {amplitude} (largest {top:.6e}): \
                 period {period:.9} s, closed form {exact:.9} s, relative error {error:.2e}"
            );
            assert!(error < 2e-7, "{error}");
        }
    }
}

/// The coefficient of restitution of this contact law: a mass `m` striking the stop at speed
/// `v0` penetrates as `m x'' + c x' + k x = 0` (`x(0) = 0`, `x'(0) = v0`) while the force
/// `k x + c x'` is positive; it leaves when that force reaches zero (`x'' = 0`, at `x > 0`: the
/// cut at zero ends the contact before the penetration does) and flies off at the speed it has
/// then. With `beta = c / (2 m)`, `w0 = sqrt(k / m)`, `w = sqrt(w0^2 - beta^2)` and
/// `x(t) = v0 / w e^(-beta t) sin(w t)`, the force vanishes at
/// `w t* = pi - atan(2 beta w / (w^2 - beta^2))` (zeta = beta / w0 below 1/sqrt(2)), where
/// `x'(t*) = -v0 e^(-beta t*)`: `e = exp(-beta t*)` (Schwager and Poeschel, 2008). The issue's
/// `exp(-zeta pi / sqrt(1 - zeta^2))` = `exp(-beta pi / w)` is the classical value of the law
/// without the cut, whose contact lasts the half period `pi / w` and ends with the dashpot
/// pulling: it dissipates more (at zeta = 0.1, e = 0.7292 against this law's 0.7445).
fn restitution(zeta: f64) -> (f64, f64) {
    let w0 = (K_STOP / MASS).sqrt();
    let beta = zeta * w0;
    let w = (w0 * w0 - beta * beta).sqrt();
    let t_star = (PI - (2.0 * beta * w / (w * w - beta * beta)).atan()) / w;
    ((-beta * t_star).exp(), (-beta * PI / w).exp())
}

/// The free beam (no springs) strikes the stop at 0.1 m/s; its speed after the contact over the
/// speed before, the speed of its centre of mass (its momentum over its mass: the stiff beam's
/// bending vibration, excited by the dashpot's force at the first touch, adds to a node's
/// velocity). The contact (0.028 s) takes 2800 steps; e is within 2.5e-7 of this law's (the
/// error is no smaller at half the step: it is the beam's compliance, 1e-7 of the stop's,
/// which lowers the contact stiffness; at E = 2.1e14 the error was 100 times as large);
/// 1e-6 leaves room. Everything the impact took went into
/// the dashpot (d = 0, no spring): `E_damped` is the mechanical energy lost, to round-off with
/// the energy-momentum scheme, to the midpoint rule's energy error with it.
#[test]
fn restitution_of_a_kelvin_voigt_contact_cut_at_zero() {
    for integrator in [1.0, 2.0] {
        for zeta in [0.05, 0.1, 0.3, 0.6] {
            let c = 2.0 * zeta * (K_STOP * MASS).sqrt();
            let mut sim = simulation_of(&on_springs(0.0, c, false, integrator), &[]);
            let v0 = 0.1;
            release(&mut sim, 1e-4, -v0);
            let energy = output(&sim, "E_kin");
            // Before, through and after the contact (0.001 s + 0.028 s), into free flight.
            run(&mut sim, 0.05);
            let v = sim.structure().linear_momentum(&sim.state().v)[1] / MASS;
            let measured = v / v0;
            let (exact, classical) = restitution(zeta);
            let error = (measured - exact).abs() / exact;
            let lost = energy - output(&sim, "E_kin") - output(&sim, "E_strain");
            let damped = output(&sim, "E_damped");
            println!(
                "integrator {integrator}, zeta {zeta}: e = {measured:.8}, this law {exact:.8} \
                 (relative error {error:.1e}), the law without the cut {classical:.7}; \
                 E_damped {damped:.9e} J, mechanical energy lost {lost:.9e} J"
            );
            println!(
                "  E_damped - lost: {:.2e} of it; energy_error {:.2e} J",
                (damped - lost) / lost,
                output(&sim, "energy_error")
            );
            assert!(error < 1e-6, "{error}");
            // The energy-momentum scheme: Newton's tolerance (1e-10 of each increment) and
            // round-off over 5000 steps (measured 1.4e-12); the midpoint rule: its energy
            // error, O(dt^2) (measured 1.5e-7).
            let tolerance = if integrator == 2.0 { 1e-11 } else { 1e-6 };
            assert!(
                (damped - lost).abs() < tolerance * lost,
                "{damped} vs {lost}"
            );
            assert_eq!(output(&sim, "stop_force"), 0.0, "in free flight");
            assert_eq!(output(&sim, "stop_contact"), 0.0);
        }
    }
}

/// A steel beam (1 m, 20 x 20 mm) pinned at its left end, held at its right end only by a stop
/// `gap` below it: under its weight it turns about the pin until it rests on the stop, which
/// then carries half its weight (moment about the pin; the beam's sag shortens the arms by
/// (sag / L)^2 ~ 1e-7) and is pressed in by that force over `k`. The static solve starts with
/// the beam free to turn (a mechanism but for the open stop): its Newton correction is cut
/// where the stop is reached, then the stop holds it.
#[test]
fn a_beam_settles_onto_a_stop_under_its_weight() {
    for gap in [0.0, 1e-3, 2e-2] {
        let text = format!(
            r#"
name = "Resting"
[defaults]
E = 210e9
rho = 7850.0
elements = 10
[section]
b = 0.02
h = 0.02
[geometry]
shape = "straight"
L = 1.0
[[support]]
name = "pin"
at = 0.0
fix = ["u1", "u2"]
[[stop]]
name = "rest"
at = 1.0
dof = "u2"
side = "-"
gap = {gap}
k = 1e6
[[load]]
name = "weight"
kind = "gravity"
[[sensor]]
name = "tip"
at = 1.0
quantity = "u2"
"#
        );
        let sim = simulation_of(&text, &[]);
        let weight = 9.81 * 7850.0 * 0.02 * 0.02;
        let force = output(&sim, "rest_force");
        let tip = output(&sim, "tip");
        let pressed = -(gap + force / 1e6);
        println!(
            "gap {gap}: stop force {force:.9} N (half the weight {:.9} N), tip {tip:.9e} m \
             (gap + force / k: {pressed:.9e} m), pin Ry {:.9} N, contact {}",
            0.5 * weight,
            output(&sim, "pin_Ry"),
            output(&sim, "rest_contact")
        );
        assert!((force - 0.5 * weight).abs() < 1e-5 * weight, "{force}");
        assert!((output(&sim, "pin_Ry") - 0.5 * weight).abs() < 1e-5 * weight);
        // The tip's deflection is the stop's: the gap and its penetration.
        assert!((tip - pressed).abs() < 1e-12, "{tip} vs {pressed}");
        assert_eq!(output(&sim, "rest_contact"), 1.0);
    }
}

/// The outputs over whole periods of the bilinear oscillator at gap 0 (released at `A`): the
/// stop is touched for `pi / w2` of each period `T` (`<stop>_contact` averaged over the periods)
/// and pushes with the impulse `2 k_c v / w2^2` per period (`v = w1 A` the speed at contact:
/// `<stop>_force` averaged). Communication steps of 10 sub-steps, read at each: second-order
/// errors (the kink inside a sub-step), 1e-6 leaves room over the measured.
#[test]
fn the_outputs_average_the_contact() {
    let amplitude = 1e-3;
    let w1 = (2.0 * K_SPRING / MASS).sqrt();
    let w2 = ((2.0 * K_SPRING + K_STOP) / MASS).sqrt();
    let period = PI / w1 + PI / w2;
    let mut sim = simulation_of(&on_springs(0.0, 0.0, true, 1.0), &[]);
    release(&mut sim, amplitude, 0.0);
    let h = 10.0 * DT;
    let steps = (4.0 * period / h).floor() as usize;
    let (mut contact, mut impulse) = (0.0, 0.0);
    for _ in 0..steps {
        sim.advance(h).expect("a step");
        let (c, f) = (output(&sim, "stop_contact"), output(&sim, "stop_force"));
        assert!((0.0..=1.0).contains(&c) && f >= 0.0, "{c} {f}");
        contact += c * h;
        impulse += f * h;
    }
    // Over the periods run (up to the last step, which falls within a step of the top, in
    // free flight: the contact half-cycles are centred on the bottom).
    let periods = (steps as f64 * h / period).round();
    let exact_contact = periods * PI / w2;
    let exact_impulse = periods * 2.0 * K_STOP * w1 * amplitude / (w2 * w2);
    println!(
        "{periods} periods: time in contact {contact:.9} s (closed form {exact_contact:.9} s), \
         impulse {impulse:.9} N s (closed form {exact_impulse:.9} N s)"
    );
    assert!((contact - exact_contact).abs() < 1e-6 * exact_contact);
    assert!((impulse - exact_impulse).abs() < 1e-6 * exact_impulse);
}

/// A stop the motion never reaches changes nothing: the same trajectory to the last bit as
/// without it (an open stop adds no force, no stiffness and no correction).
#[test]
fn a_stop_never_reached_changes_nothing() {
    let with = on_springs(1.0, 0.0, true, 1.0);
    let start = with.find("[[stop]]").unwrap();
    let end = with.find("[[sensor]]").unwrap();
    let without = format!("{}{}", &with[..start], &with[end..]);
    let mut a = simulation_of(&with, &[]);
    let mut b = simulation_of(&without, &[]);
    release(&mut a, 1e-3, 0.1);
    release(&mut b, 1e-3, 0.1);
    for _ in 0..2000 {
        let (ra, rb) = (a.advance(1e-4).unwrap(), b.advance(1e-4).unwrap());
        assert_eq!(ra.newton_iterations, rb.newton_iterations);
    }
    assert_eq!(a.state(), b.state());
    assert_eq!(output(&a, "energy_error"), output(&b, "energy_error"));
}
