//! Supports as data: moving supports (`examples/BeamOnBase.toml`), reactions in a dynamic run
//! and in a statically indeterminate beam (`examples/ThreeSpan.toml`), and the mesh check.
//!
//! Run: `cargo test --profile quick --test suite scene_supports:: -- --nocapture`
use crate::common;

use common::{output, set_input, Table};
use georod::model::rod::{U1, U2};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

/// The non-dimensional beam the bounds of these tests are derived for (the examples themselves
/// are steel and aluminium): E = 1.2e4, rho = 1e-6, b = 1, nu = 0.2.
const REFERENCE_MATERIAL: [(&str, f64); 4] = [("E", 1.2e4), ("rho", 1e-6), ("b", 1.0), ("nu", 0.2)];

fn example(name: &str) -> Arc<Scene> {
    let path = format!("{}/examples/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    Arc::new(Scene::load(path).expect("example scene"))
}

/// `sum` over the dofs of component `k` (0: e1, 1: e2) of a nodal vector.
fn component_sum(x: &[f64], k: usize) -> f64 {
    x.iter().skip(k).step_by(3).sum()
}

/// What a run on the moving base gives: the largest deviation from the base motion, and the
/// largest differences of the reactions from the discrete momentum balance and from a rigid
/// body, with the scale of the latter.
struct BaseRun {
    /// Largest speed of the base along e2.
    speed: f64,
    rigid: f64,
    balance: f64,
    physical: f64,
    scale: f64,
}

/// Both clamped ends of the beam follow the same slow base motion `g(t) = A (1 - cos(W t))^2 / 4`
/// (e2) and half of it along e1, sampled at the communication points (linear in between), for one period
/// of the base motion.
fn ride_the_base(damping: f64, t: &mut Table) -> BaseRun {
    let scene = example("BeamOnBase");
    let beam = [("d", damping), ("L", 10.0), ("h", 0.2)];
    let values = scene
        .values_with(REFERENCE_MATERIAL.into_iter().chain(beam))
        .unwrap();
    let mut sim = Simulation::new(scene.clone(), values).expect("initial state");
    let rod = sim.rod().clone();
    let (amplitude, omega, h) = (0.1, 14.0, 1e-3);
    // A smooth start (zero speed and acceleration at t = 0): a base that jumps to full speed
    // would hit the beam with an impulse, one that jumps to full acceleration would set it
    // ringing by a / omega_1^2, as large as its quasi-static response.
    let g = |t: f64| {
        let lift = 0.25 * amplitude * (1.0 - (omega * t).cos()).powi(2);
        [0.5 * lift, lift]
    };
    let mass = rod.section.rho_a * rod.curve.length();
    let drag = rod.damping * rod.curve.length();
    let momentum = |s: &Simulation| rod.linear_momentum(&s.state().v);
    let damped = |s: &Simulation| {
        let mut c = vec![0.0; rod.dofs()];
        rod.add_damping_times(&s.state().u, &mut c, 1.0);
        [component_sum(&c, U1), component_sum(&c, U2)]
    };
    let (mut rigid, mut balance, mut physical, mut scale) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut kinetic, mut speed) = (0.0f64, 0.0f64);
    let mut slope_before = [0.0, 0.0];
    let steps = 450; // one period of the base motion
    for k in 0..steps {
        let (t0, t1) = (k as f64 * h, (k + 1) as f64 * h);
        let (p0, c0) = (momentum(&sim), damped(&sim));
        let target = g(t1);
        for support in ["left", "right"] {
            set_input(&mut sim, &format!("{support}_u1"), target[0]);
            set_input(&mut sim, &format!("{support}_u2"), target[1]);
        }
        sim.advance(h).expect("step");
        let (p1, c1) = (momentum(&sim), damped(&sim));
        let slope = [(target[0] - g(t0)[0]) / h, (target[1] - g(t0)[1]) / h];
        for c in 0..2 {
            let name = ["Rx", "Ry"][c];
            let reaction =
                output(&sim, &format!("left_{name}")) + output(&sim, &format!("right_{name}"));
            // The discrete equations summed over all dofs: internal forces cancel.
            let discrete = (p1[c] - p0[c] + c1[c] - c0[c]) / h;
            // A rigid body: the impulse that changes the slope, and the damping force.
            let rigid_body = mass * (slope[c] - slope_before[c]) / h + drag * slope[c];
            balance = balance.max((reaction - discrete).abs());
            physical = physical.max((reaction - rigid_body).abs());
            scale = scale.max(rigid_body.abs());
        }
        slope_before = slope;
        speed = speed.max(slope[1].abs());
        kinetic = kinetic.max(sim.kinetic_energy());
        // The supports are exactly where their inputs put them.
        let last = rod.last_node();
        for node in [0, last] {
            assert_eq!(sim.state().u[3 * node + U1], target[0]);
            assert_eq!(sim.state().u[3 * node + U2], target[1]);
        }
        for i in 0..rod.nodes() {
            for (c, g) in target.iter().enumerate() {
                rigid = rigid.max((sim.state().u[3 * i + c] - g).abs());
            }
        }
    }
    t.row(format_args!("  d = {damping:e}:"));
    t.row(format_args!(
        "  max deviation from the rigid motion: {:.2e} of A",
        rigid / amplitude
    ));
    t.row(format_args!(
        "  reactions vs the discrete momentum balance: {:.2e} of max |m a + c v| = {scale:.3e}",
        balance / scale
    ));
    t.row(format_args!(
        "  reactions vs the rigid body (m a + c v): {:.2e} of the same",
        physical / scale
    ));
    t.row(format_args!(
        "  energy: W_supports = {:.4e}, E_damped = {:.4e}, energy_error = {:.2e}",
        output(&sim, "W_supports"),
        output(&sim, "E_damped"),
        output(&sim, "energy_error")
    ));
    // The energy bookkeeping includes the supports' work: the balance error stays small against
    // the kinetic energy the base puts in (midpoint rule: O(dt^2) quadrature error).
    let energy_error = output(&sim, "energy_error").abs();
    assert!(
        energy_error < 1e-3 * kinetic,
        "energy error {energy_error:e} vs {kinetic:e}"
    );
    BaseRun {
        speed,
        rigid,
        balance,
        physical,
        scale,
    }
}

/// With little damping the beam rides along rigidly (its first frequency, ~1400 rad/s, is 100
/// times the base's); the reactions are exactly the discrete momentum balance of each step
/// (impulse of the supports = change of momentum + damping impulse), and close to the rod's
/// mass times the base acceleration plus the damping force.
#[test]
fn clamped_beam_on_a_moving_base_moves_rigidly() {
    let mut t = Table::new(
        "BeamOnBase (clamped-clamped, 20 elements, EI = 8, rho A = 2e-7) on a base \
         g(t) = (A/2, A) (1 - cos(W t))^2 / 4, A = 0.1, W = 14 rad/s, communication step 1e-3 s",
    );
    let run = ride_the_base(5e-7, &mut t);
    // Rigid: the inertia load rho A a bends the clamped beam by rho A a L^4 / (384 EI) = 1.3e-4 A
    // at the peak acceleration, the drag d v by d v L^4 / (384 EI) = 2e-6 A; 1e-3 A.
    assert!(run.rigid < 1e-3 * 0.1, "deviation {:e}", run.rigid);
    // The discrete balance holds to the solver tolerance: a reaction leaves out the internal
    // force's part K c / 2 of the last Newton correction c, which passed |c| <= 1e-10 |du| +
    // 1e-13 L; with K ~ EA / l (EA = 2400, l = 0.5) that is at most 2.4e-9 per held dof.
    assert!(
        run.balance < newton_bound(),
        "discrete balance off by {:e}",
        run.balance
    );
    // Close to the rigid body within the deviations above: 1e-2 of the largest force.
    assert!(
        run.physical < 1e-2 * run.scale,
        "rigid-body reactions off by {:e}",
        run.physical
    );
}

/// The scene's own damping, d = 5e-4, is an absolute (drag) damping: moving through it at the
/// base's peak speed v the beam carries a distributed drag d v and bends under it
/// quasi-statically (W is far below its first frequency) by d v L^4 / (384 EI) at midspan, the
/// clamped-clamped beam formula: the deviation from the rigid motion is that deflection.
#[test]
fn drag_damping_bends_the_beam_on_a_moving_base() {
    let mut t = Table::new("BeamOnBase with the scene's drag damping d = 5e-4");
    let run = ride_the_base(5e-4, &mut t);
    let drag = 5e-4 * run.speed * 1e4 / (384.0 * 8.0);
    t.row(format_args!(
        "  clamped-clamped deflection under the peak drag d v L^4 / (384 EI) = {drag:.4e}; \
         measured {:.4e}",
        run.rigid
    ));
    // 5 %: the inertia load adds rho A a L^4 / (384 EI) (1e-5, small but not in phase with the
    // drag) and the base moves the beam along e1 too; the mesh's bending is exact to 1e-3.
    assert!(
        (run.rigid / drag - 1.0).abs() < 0.05,
        "{} vs {drag}",
        run.rigid
    );
    assert!(
        run.balance < newton_bound(),
        "discrete balance off by {:e}",
        run.balance
    );
}

/// The continuous beam over three equal spans under a small constant uniform load q (the
/// example's load made static and small enough for linear theory, deflections of 4e-5 of a
/// span, and the rod slender): the support reactions of Euler-Bernoulli theory are
/// 0.4 q l at the ends and 1.1 q l at the interior supports (l the span length).
#[test]
fn three_span_beam_reactions_match_beam_theory() {
    let text = std::fs::read_to_string(format!(
        "{}/examples/ThreeSpan.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .replace("time = \"harmonic\"", "time = \"constant\"\nvalue = 1e-6")
    .lines()
    .filter(|l| !l.starts_with("F =") && !l.starts_with("Omega ="))
    .collect::<Vec<_>>()
    .join("\n");
    let scene = Arc::new(Scene::parse(&text, "ThreeSpan (static)").expect("scene"));
    let (q, l) = (1e-6, 10.0);
    let expected = [0.4, 1.1, 1.1, 0.4].map(|c| c * q * l);
    let mut t = Table::new(
        "ThreeSpan with a constant uniform load q = 1e-6, h = 0.05 (l/h = 200): static \
         reactions vs continuous-beam theory, on the uniform mesh (60) and on spread ones",
    );
    // 60: the uniform mesh; 61 and 62: the elements spread over the spans (21-20-20, 21-21-20).
    for n in [60.0, 61.0, 62.0] {
        let beam = [("h", 0.05), ("elements", n)];
        let values = scene
            .values_with(REFERENCE_MATERIAL.into_iter().chain(beam))
            .unwrap();
        let sim = Simulation::new(scene.clone(), values).expect("static state");
        let mut total = 0.0;
        for (name, want) in ["A", "B", "C", "D"].iter().zip(expected) {
            let ry = output(&sim, &format!("{name}_Ry"));
            total += ry;
            let error = (ry - want).abs() / want;
            t.row(format_args!(
                "  {n} elements: {name}_Ry = {ry:.8} (theory {want:.4}), relative error {error:.2e}"
            ));
            // Shear flexibility changes the redundant reactions by O(EI / (GA l^2)) = 1.5e-5
            // here; the mesh (20 elements per span) by less: 1e-3 is a clear margin.
            assert!(error < 1e-3, "{n} elements, {name}: {ry} vs {want}");
        }
        assert!(
            (total - q * 3.0 * l).abs() < 1e-9 * q * 3.0 * l,
            "{n}: {total}"
        );
    }
    // Fewer elements than spans: refused, naming the counts that work.
    let e = scene
        .values_with([("elements", 2.0)])
        .expect_err("2 elements");
    t.row(format_args!("  elements = 2: {e}"));
    assert!(e.to_string().contains("[3, 100000]"), "{e}");
}

/// The largest error of the summed reactions Ry of the two supports allowed by Newton's
/// convergence test (see the first test): 2 x (EA / l) x 1e-13 L / 2.
fn newton_bound() -> f64 {
    let (ea, l, length) = (1.2e4 * 1.0 * 0.2, 0.5, 10.0);
    ea / l * 1e-13 * length
}
