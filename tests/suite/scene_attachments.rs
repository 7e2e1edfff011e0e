//! Point masses, springs and dashpots, Winkler foundations (`[[mass]]`, `[[spring]]`,
//! `[[foundation]]`) against closed forms: a cantilever with a tip mass (the Euler-Bernoulli
//! frequency equation with the mass ratio), a stiff rod on two end springs (heave and pitch),
//! a long beam on an elastic foundation under a point load (Hetenyi), point-mass weights in the
//! reactions, and the energy ledger with all of them.
//!
//! Run: `cargo test --profile quick --test suite scene_attachments:: -- --nocapture`
use crate::common;

use common::{output, Table};
use georod::model::modal::modes;
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;

const E: f64 = 210e9;
const RHO: f64 = 7850.0;

/// A straight steel rod of length `length`, section `b x h`, with `items` (TOML) added.
fn rod(length: f64, b: f64, h: f64, items: &str) -> Arc<Scene> {
    let text = format!(
        "name = \"Rod\"\n[geometry]\nshape = \"straight\"\nL = {length}\n[defaults]\nE = {E}\n\
         nu = 0.3\nrho = {RHO}\nd = 0.0\nb = {b}\nh = {h}\nelements = 40\n{items}\n"
    );
    Arc::new(Scene::parse(&text, "rod.toml").unwrap_or_else(|e| panic!("{e}")))
}

fn simulation(scene: &Arc<Scene>, overrides: &[(&str, f64)]) -> Simulation {
    let values = scene.values_with(overrides.iter().copied()).unwrap();
    Simulation::new(scene.clone(), values).expect("initial state")
}

/// The lowest circular frequencies of the simulation's initial state.
fn omegas(sim: &Simulation, count: usize) -> Vec<f64> {
    let m = modes(sim.rod(), &sim.state().u);
    m[..count].iter().map(|m| m.omega()).collect()
}

/// Roots `beta = lambda L` of the cantilever-with-tip-mass frequency equation
/// `1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0` (`mu` = tip mass / rod mass).
fn tip_mass_roots(mu: f64, count: usize) -> Vec<f64> {
    let f = |b: f64| 1.0 + b.cos() * b.cosh() + mu * b * (b.cos() * b.sinh() - b.sin() * b.cosh());
    let mut roots = Vec::new();
    let mut a = 0.01;
    while roots.len() < count {
        let b = a + 0.01;
        if f(a) * f(b) < 0.0 {
            let (mut lo, mut hi) = (a, b);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if f(lo) * f(mid) <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            roots.push(0.5 * (lo + hi));
        }
        a = b;
    }
    roots
}

#[test]
fn tip_mass_cantilever_frequencies_follow_the_frequency_equation() {
    let (length, b, h): (f64, f64, f64) = (2.0, 0.05, 0.01); // L/h = 200
    let rod_mass = RHO * b * h * length;
    let (area, inertia) = (b * h, b * h.powi(3) / 12.0);
    let mut t = Table::new(
        "steel cantilever 2 m, 50 x 10 mm, tip mass M: first two frequencies (40/80 elements \
         extrapolated) vs the Euler-Bernoulli frequency equation",
    );
    for mu in [0.5, 2.0] {
        let items = format!(
            "[[support]]\nname = \"root\"\nat = 0.0\nfix = [\"u1\", \"u2\", \"w\"]\n\
             [[mass]]\nname = \"tip\"\nat = 1.0\nm = {}\n",
            mu * rod_mass
        );
        let scene = rod(length, b, h, &items);
        let [coarsest, coarse, fine] =
            [20.0, 40.0, 80.0].map(|n| omegas(&simulation(&scene, &[("elements", n)]), 2));
        let roots = tip_mass_roots(mu, 2);
        for k in 0..2 {
            let extrapolated = (4.0 * fine[k] - coarse[k]) / 3.0;
            let exact = roots[k].powi(2) * (E * inertia / (RHO * area * length.powi(4))).sqrt();
            let error = (extrapolated - exact).abs() / exact;
            // Self-convergence: the differences between meshes quarter per halving.
            let order = ((coarsest[k] - coarse[k]) / (coarse[k] - fine[k])).log2();
            t.row(format_args!(
                "  M / (rho A L) = {mu}: mode {}: {extrapolated:.6} rad/s vs {exact:.6} (beta \
                 {:.5}), error {error:.1e}, order {order:.2}",
                k + 1,
                roots[k]
            ));
            // Second order in the element length; after extrapolation the rod's shear and
            // rotary inertia remain, O((beta h / L)^2) = 1e-4 for the second mode.
            assert!(
                error < 2e-4,
                "mu {mu}, mode {}: {extrapolated} vs {exact}",
                k + 1
            );
            assert!(
                (1.8..2.2).contains(&order),
                "mu {mu}, mode {}: order {order}",
                k + 1
            );
        }
    }
}

#[test]
fn stiff_rod_on_two_end_springs_heaves_and_pitches() {
    let (length, b, h, k) = (2.0, 0.1, 0.1, 100.0);
    let items = format!(
        "[[support]]\nname = \"axial\"\nat = 0.5\nfix = [\"u1\"]\n\
         [[spring]]\nname = \"left\"\nat = 0.0\ndof = \"u2\"\nk = {k}\n\
         [[spring]]\nname = \"right\"\nat = 1.0\ndof = \"u2\"\nk = {k}\n"
    );
    let scene = rod(length, b, h, &items);
    let got = omegas(&simulation(&scene, &[]), 2);
    let mass = RHO * b * h * length;
    // The rod's rotary inertia adds rho I L to the pitch inertia m L^2 / 12.
    let pitch_inertia = 1.0 + 12.0 * (h * h / 12.0) / (length * length);
    let want = [
        (2.0 * k / mass).sqrt(),
        (6.0 * k / mass / pitch_inertia).sqrt(),
    ];
    for (what, (g, w)) in ["heave", "pitch"].iter().zip(got.iter().zip(want)) {
        println!("{what}: {g:.8} rad/s vs {w:.8}");
        // The rod bends under the spring forces by k L^3 / EI = 5e-4 of the motion: the
        // frequencies are the rigid body's to that order.
        assert!((g / w - 1.0).abs() < 1e-3, "{what}: {g} vs {w}");
    }
}

/// Hetenyi's solution for an infinite beam on a Winkler foundation under a point load P:
/// `w(x) = P lambda / (2 k) exp(-lambda x) (cos lambda x + sin lambda x)`,
/// `lambda = (k / (4 EI))^(1/4)`. A free 20 m beam with `lambda L / 2 = 10` is long.
#[test]
fn long_beam_on_a_foundation_follows_hetenyi() {
    let (length, b, h, k, load): (f64, f64, f64, f64, f64) = (20.0, 0.1, 0.05, 1e6, 1e4);
    let ei = E * b * h.powi(3) / 12.0;
    let lambda = (k / (4.0 * ei)).powf(0.25);
    let xs = [0.0, 0.5, 1.0, 2.0];
    let mut items = format!(
        "[[support]]\nname = \"axial\"\nat = 0.0\nfix = [\"u1\"]\n\
         [[foundation]]\nname = \"soil\"\nk = {k}\n\
         [[load]]\nname = \"P\"\nkind = \"point\"\nat = 0.5\ndirection = \"-e2\"\nvalue = {load}\n"
    );
    for (i, x) in xs.iter().enumerate() {
        items += &format!(
            "[[sensor]]\nname = \"w{i}\"\nat = {}\nquantity = \"u2\"\n",
            0.5 + x / length
        );
    }
    let scene = rod(length, b, h, &items);
    let read = |n: f64| {
        let sim = simulation(&scene, &[("elements", n)]);
        (0..xs.len())
            .map(|i| output(&sim, &format!("w{i}")))
            .collect::<Vec<_>>()
    };
    let (coarse, fine) = (read(200.0), read(400.0));
    let peak = load * lambda / (2.0 * k);
    let mut t = Table::new(&format!(
        "free steel beam 20 m on a Winkler foundation, k = 1e6 N/m2, P = 10 kN at midspan \
         (lambda = {lambda:.4} /m): deflection vs Hetenyi"
    ));
    for (i, x) in xs.iter().enumerate() {
        let got = -(4.0 * fine[i] - coarse[i]) / 3.0;
        let l = lambda * x;
        let want = peak * (-l).exp() * (l.cos() + l.sin());
        t.row(format_args!(
            "  x = {x}: {got:.6e} vs {want:.6e}, difference {:.1e} of the peak",
            (got - want).abs() / peak
        ));
        // The rod's shear flexibility adds EI lambda^2 / (G A) = 6e-4 of the peak; the
        // extrapolated mesh error is below.
        assert!((got - want).abs() < 2e-3 * peak, "x = {x}: {got} vs {want}");
    }
}

/// Gravity acts on the point masses too: a cantilever's root carries the rod's and the tip
/// mass's weight, in the static state.
#[test]
fn point_masses_weigh_in_the_static_reactions() {
    let (length, b, h, tip) = (2.0, 0.05, 0.01, 3.0);
    let items = format!(
        "[[support]]\nname = \"root\"\nat = 0.0\nfix = [\"u1\", \"u2\", \"w\"]\n\
         [[mass]]\nname = \"tip\"\nat = 0.7\nm = {tip}\nJ = 0.01\n\
         [[load]]\nname = \"g\"\nkind = \"gravity\"\n"
    );
    let sim = simulation(&rod(length, b, h, &items), &[]);
    let weight = 9.81 * (RHO * b * h * length + tip);
    let ry = output(&sim, "root_Ry");
    assert!((ry / weight - 1.0).abs() < 1e-12, "{ry} vs {weight}");
}

/// The energy ledger with a tip mass (and rotary inertia), a spring and dashpot, and a partial
/// foundation with damping, under a harmonic tip load: exact for the energy-momentum scheme
/// (the dashpots and foundations damp translations only), and the dashpots dissipate.
#[test]
fn energy_ledger_books_springs_dashpots_foundations_and_masses() {
    let items = "[[support]]\nname = \"root\"\nat = 0.0\nfix = [\"u1\", \"u2\", \"w\"]\n\
                 [[mass]]\nname = \"tip\"\nat = 1.0\nm = 2.0\nJ = 0.05\n\
                 [[spring]]\nname = \"s\"\nat = 0.6\ndof = \"u2\"\nk = 2e3\nc = 30.0\n\
                 [[foundation]]\nname = \"f\"\nk = 1e3\nc = 20.0\nfrom = 0.2\nto = 0.45\n\
                 [[load]]\nname = \"p\"\nkind = \"point\"\nat = 1.0\ndirection = \"-e2\"\n\
                 time = \"harmonic\"\n";
    let scene = rod(2.0, 0.05, 0.01, items);
    let mut sim = simulation(
        &scene,
        &[
            ("F", 50.0),
            ("Omega", 30.0),
            ("integrator", 2.0),
            ("dt_max", 1e-3),
        ],
    );
    for _ in 0..300 {
        sim.advance(1e-3).unwrap();
    }
    let get = |name| output(&sim, name);
    let (work, damped, error) = (get("W_ext"), get("E_damped"), get("energy_error"));
    println!("W_ext {work:.6e}, E_damped {damped:.6e}, energy_error {error:.1e}");
    assert!(
        damped > 1e-3 * work.abs(),
        "the dashpots dissipated nothing"
    );
    assert!(error.abs() < 1e-9 * work.abs(), "{error:e}");
}

#[test]
fn bad_attachments_are_refused() {
    let base = "name = \"B\"\n[geometry]\nshape = \"straight\"\nL = 2.0\n[defaults]\nE = 1.0\n\
                rho = 1.0\n[[support]]\nname = \"A\"\nat = 0.0\nfix = [\"u1\", \"u2\", \"w\"]\n";
    for (item, parts) in [
        (
            "[[mass]]\nname = \"m\"\nat = 1.0\nm = -1.0",
            vec!["[[mass]] #1 \"m\", key `m`", ">= 0"],
        ),
        (
            "[[mass]]\nname = \"m\"\nat = 1.0",
            vec!["key `m`", "missing"],
        ),
        (
            "[[spring]]\nname = \"s\"\nat = 0.0\ndof = \"u2\"\nk = 1.0",
            vec!["key `dof`", "support `A` already holds u2"],
        ),
        (
            "[[spring]]\nname = \"s\"\nat = 1.0\ndof = \"u2\"\nk = -1.0",
            vec!["key `k`", ">= 0"],
        ),
        (
            "[[spring]]\nname = \"s\"\nat = 1.0\ndof = \"v2\"\nk = 1.0",
            vec!["key `dof`", "u1"],
        ),
        (
            "[[foundation]]\nname = \"f\"\nk = 1.0\nfrom = 0.8\nto = 0.2",
            vec!["key `to`", "below"],
        ),
        (
            "[[foundation]]\nname = \"f\"\nk = 1.0\nwidth = 0.2",
            vec!["unknown field `width`"],
        ),
    ] {
        common::assert_refused(item, &format!("{base}{item}\n"), &parts);
    }
    // Springs restrain: a rod held only by springs has a static state, one held too little not.
    let springs = "name = \"S\"\n[geometry]\nshape = \"straight\"\nL = 2.0\n[defaults]\nE = 1.0\n\
                   rho = 1.0\n[[spring]]\nname = \"a\"\nat = 0.0\ndof = \"u2\"\nk = 1.0\n\
                   [[spring]]\nname = \"b\"\nat = 1.0\ndof = \"u2\"\nk = 1.0\n";
    common::assert_refused("no u1", springs, &["free to translate along e1"]);
    let held = format!("{springs}[[spring]]\nname = \"c\"\nat = 0.5\ndof = \"u1\"\nk = 1.0\n");
    Scene::parse(&held, "ok.toml").expect("three springs hold the rod");
    let mut t = Table::new("mass stations");
    let scene = rod(2.0, 0.05, 0.01, "[[support]]\nname = \"root\"\nat = 0.0\nfix = [\"w\", \"u1\", \"u2\"]\n[[mass]]\nname = \"m\"\nat = 0.37\nm = 1.0\n");
    let sim = simulation(&scene, &[("elements", 7.0)]);
    let node = sim.rod().node_at(0.74);
    t.row(format_args!(
        "  mass at 0.37 of 2 m on 7 elements: node {node} at {}",
        sim.rod().node_s[node]
    ));
    assert!((sim.rod().node_s[node] - 0.74).abs() < 1e-12);
}

/// The FMU's documentation page lists the section, masses, springs, foundations and damping.
#[test]
fn documentation_lists_the_attachments() {
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for (example, parts) in [
        (
            "TipMassCantilever",
            vec![
                "Point mass <code>motor</code> at 1: m = 5 kg",
                "Rayleigh damping",
            ],
        ),
        (
            "BeamOnFoundation",
            vec!["Foundation <code>soil</code> over [0, 1]: k = 1000000 N/m2"],
        ),
        (
            "Bridge",
            vec!["Section: Rectangle, dimensions <code>b</code>, <code>h</code>"],
        ),
        (
            "ElasticBearings",
            vec!["(its base follows the input <code>left_base</code>)"],
        ),
    ] {
        let scene = Scene::load(repo.join(format!("examples/{example}.toml"))).unwrap();
        let page = georod::packaging::documentation::documentation(&scene, "{guid}");
        for part in parts {
            assert!(page.contains(part), "{example}: the page lacks `{part}`");
        }
    }
    let springs = rod(
        2.0,
        0.05,
        0.01,
        "[[support]]\nname = \"p\"\nat = 0.0\nfix = [\"u1\", \"u2\"]\n\
         [[spring]]\nname = \"s\"\nat = 1.0\ndof = \"u2\"\nk = 5.0\nc = 0.5\n",
    );
    let page = georod::packaging::documentation::documentation(&springs, "{guid}");
    assert!(
        page.contains("Spring <code>s</code> at 1 on u2: k = 5, c = 0.5 (to ground)"),
        "{page}"
    );
}

/// `<spring>_force`: before the first step the static force `-k u`; after a step the average
/// over it, which closes the discrete momentum balance of a rod held only by springs (no
/// damping `d`): `M (v1 - v0)` summed along e2 equals `h` times the applied load plus the
/// springs' averaged forces, to the Newton tolerance.
#[test]
fn spring_forces_are_static_then_step_averages() {
    let items = "[[support]]\nname = \"axial\"\nat = 0.5\nfix = [\"u1\"]\n\
                 [[spring]]\nname = \"left\"\nat = 0.0\ndof = \"u2\"\nk = 1e5\nc = 300.0\n\
                 [[spring]]\nname = \"right\"\nat = 1.0\ndof = \"u2\"\nk = 2e5\n\
                 [[load]]\nname = \"p\"\nkind = \"point\"\nat = 0.3\ndirection = \"-e2\"\nvalue = 1e3\n\
                 [[load]]\nname = \"kick\"\nkind = \"point\"\nat = 0.8\ndirection = \"e2\"\n\
                 time = \"input\"\n";
    let scene = rod(2.0, 0.05, 0.05, items);
    let mut sim = simulation(&scene, &[("dt_max", 1e-4)]);
    let (left, right) = (output(&sim, "left_force"), output(&sim, "right_force"));
    // Static: the springs carry the load, by the lever rule (the rod is stiff against them).
    assert!(
        ((left + right) / 1e3 - 1.0).abs() < 1e-9,
        "{left} + {right}"
    );
    assert!((left / 700.0 - 1.0).abs() < 1e-3, "left {left}");
    common::set_input(&mut sim, "kick", 5e3);
    let rod = sim.rod().clone();
    let momentum = |s: &Simulation| rod.linear_momentum(&s.state().v)[1];
    let h = 2e-3;
    for _ in 0..10 {
        let before = momentum(&sim);
        sim.advance(h).unwrap();
        let forces = output(&sim, "left_force") + output(&sim, "right_force");
        let applied = 5e3 - 1e3;
        let change = momentum(&sim) - before;
        assert!(
            (change - h * (applied + forces)).abs() < 1e-9 * h * applied,
            "{change} vs {}",
            h * (applied + forces)
        );
    }
}
