//! Stability study (issue 7), part 1: very thin rods, L/h = 10 .. 10^4.
//!
//! - Static: a cantilever (L = 10, b = 1, 20 elements) under a tip force of fixed direction up
//!   to `P L^2 / EI = 10` (tip rotation about 80 degrees), against the exact solution of the same
//!   continuum (`common::cantilever_tip`, stretch and shear included). Three ways to get there:
//!   plain load steps of 0.5, finer load steps of 0.1, and the arc-length continuation of
//!   `src/integrator/continuation/` (followed by one Newton solve at the exact target load).
//! - Dynamic: the simply supported rod (right end on a roller) released from its first mode
//!   shape, undamped, implicit midpoint with 100 steps per period: the measured period against
//!   the Timoshenko beam's (`common::timoshenko_bending_omega`), and the Newton iterations.
//!
//! Locking would stiffen the element like `(L/h)^2`: the errors would grow by orders of
//! magnitude from L/h = 10 to 10^4. Here they do not.
//!
//! Run: `cargo test --profile quick --test suite stability_thin:: -- --nocapture`
use crate::common;
use crate::stability_driver as driver;

use common::{cantilever_tip, timoshenko_bending_omega, Table, NU};
use georod::integrator::continuation::{follow_path, ContinuationSettings};
use georod::integrator::{DynamicState, Midpoint, StaticSolver};
use georod::model::rod::{ROTATION, U1, U2};
use georod::model::{LoadSet, Rod};
use std::f64::consts::PI;

const LENGTH: f64 = 10.0;
const ELEMENTS: usize = 20;
const SLENDERNESS: [f64; 4] = [10.0, 100.0, 1e3, 1e4];
/// Target load `P L^2 / EI`.
const TARGET: f64 = 10.0;

fn cantilever(thickness: f64) -> Rod {
    let mut rod = common::straight_rod(LENGTH, 1.0, thickness, 0.0, ELEMENTS);
    for k in [U1, U2, ROTATION] {
        rod.fix(0, k);
    }
    rod
}

/// Tip force vector for `lambda = P L^2 / EI` along `-e2`.
fn tip_load(rod: &Rod, lambda: f64) -> Vec<f64> {
    let mut f = vec![0.0; rod.dofs()];
    f[3 * rod.last_node() + U2] = -lambda * rod.section.ei / (LENGTH * LENGTH);
    f
}

/// Outcome of one way of loading the cantilever to `TARGET`.
struct Loaded {
    /// Vertical tip deflection / L, or the failure.
    result: Result<f64, String>,
    /// Load increments (or path points) taken.
    increments: usize,
    /// Total Newton iterations.
    iterations: u32,
    /// Most Newton iterations of one increment.
    worst: u32,
}

fn load_stepping(rod: &Rod, step: f64) -> Loaded {
    let mut solver = StaticSolver::new(rod);
    let mut u = vec![0.0; rod.dofs()];
    let steps = (TARGET / step).round() as usize;
    let (mut iterations, mut worst) = (0, 0);
    for k in 1..=steps {
        let lambda = TARGET * k as f64 / steps as f64;
        match solver.solve(rod, &mut u, &tip_load(rod, lambda)) {
            Ok(s) => {
                iterations += s.iterations;
                worst = worst.max(s.iterations);
            }
            Err(e) => {
                return Loaded {
                    result: Err(format!("step {k}/{steps} (PL2/EI = {lambda:.1}): {e}")),
                    increments: k,
                    iterations,
                    worst,
                }
            }
        }
    }
    Loaded {
        result: Ok(-u[3 * rod.last_node() + U2] / LENGTH),
        increments: steps,
        iterations,
        worst,
    }
}

/// Arc-length continuation with the reference load `q` = the tip force at `lambda = 1` until
/// the load factor passes `TARGET`, then Newton at exactly `TARGET` from the last point below.
fn arc_length(rod: &Rod) -> Loaded {
    let q = tip_load(rod, 1.0);
    let u0 = vec![0.0; rod.dofs()];
    let mut settings = ContinuationSettings::for_rod(rod, TARGET);
    settings.max_arc_length = 0.05 * LENGTH;
    settings.max_points = 50_000;
    let path = follow_path(rod, &u0, 0.0, &q, &settings);
    let iterations: u32 = path.points.iter().map(|p| p.iterations).sum();
    let worst = path.points.iter().map(|p| p.iterations).max().unwrap_or(0);
    let below = path.points.iter().rev().find(|p| p.load <= TARGET);
    let reached = path.points.last().is_some_and(|p| p.load > TARGET);
    let Some(start) = below.filter(|_| reached) else {
        return Loaded {
            result: Err(format!("path stopped: {}", path.stop_reason)),
            increments: path.points.len(),
            iterations,
            worst,
        };
    };
    let mut u = start.u.clone();
    let mut solver = StaticSolver::new(rod);
    let result = solver
        .solve(rod, &mut u, &tip_load(rod, TARGET))
        .map(|s| s.iterations)
        .map_err(|e| e.to_string());
    match result {
        Ok(last) => Loaded {
            result: Ok(-u[3 * rod.last_node() + U2] / LENGTH),
            increments: path.points.len(),
            iterations: iterations + last,
            worst: worst.max(last),
        },
        Err(e) => Loaded {
            result: Err(e),
            increments: path.points.len(),
            iterations,
            worst,
        },
    }
}

#[test]
fn thin_cantilever_tip_load_without_locking() {
    let mut t = Table::new(&format!(
        "cantilever L = 10, b = 1, {ELEMENTS} elements, tip force to PL^2/EI = {TARGET}: \
         relative error of the vertical tip deflection vs the exact continuum solution; \
         Newton tolerance 1e-10 of the increment (NewtonSettings::tight); \
         increments / total Newton iterations / most per increment"
    ));
    t.row(format_args!(
        "{:>7} {:>10} | {:>34} | {:>34} | {:>34}",
        "L/h", "exact v/L", "load steps of 0.5", "load steps of 0.02", "arc length"
    ));
    let mut errors = Vec::new();
    for slenderness in SLENDERNESS {
        let rod = cantilever(LENGTH / slenderness);
        let exact = cantilever_tip(TARGET, slenderness, NU).0;
        let runs = [
            load_stepping(&rod, 0.5),
            load_stepping(&rod, 0.02),
            arc_length(&rod),
        ];
        let cell = |r: &Loaded| match &r.result {
            Ok(v) => format!(
                "{:>10.3e} {:>4} {:>5} {:>3}",
                (v - exact) / exact,
                r.increments,
                r.iterations,
                r.worst
            ),
            Err(_) => format!(
                "{:>10} {:>4} {:>5} {:>3}",
                "FAILED", r.increments, r.iterations, r.worst
            ),
        };
        t.row(format_args!(
            "{slenderness:>7} {exact:>10.6} | {:>34} | {:>34} | {:>34}",
            cell(&runs[0]),
            cell(&runs[1]),
            cell(&runs[2])
        ));
        for r in &runs {
            if let Err(e) = &r.result {
                t.row(format_args!("          failure: {e}"));
            }
        }
        // Load steps of 0.1 and the arc-length path must reach the target at every slenderness.
        for r in &runs[1..] {
            let v = r
                .result
                .as_ref()
                .unwrap_or_else(|e| panic!("L/h = {slenderness}: {e}"));
            errors.push((slenderness, (v - exact) / exact));
        }
    }
    // No locking: the discretization error at 20 elements is the same (within 1 %) for every
    // L/h >= 100, and within 25 % at L/h = 10 (where shear and stretch, ~(h/L)^2 = 1e-2 of the
    // deflection, carry their own discretization error); locking would multiply it by up to 1e8.
    let reference = errors[2].1; // L/h = 100, load steps of 0.02
    for &(s, e) in &errors {
        let slack = if s < 100.0 { 0.25 } else { 0.01 };
        assert!(e.abs() < 1e-3, "L/h = {s}: relative error {e:e}");
        assert!(
            (e - reference).abs() < slack * reference.abs(),
            "L/h = {s}: error {e:e} vs {reference:e} at L/h = 100"
        );
    }
}

/// The simply supported rod (pin at `s = 0`, roller at `s = L`) of slenderness `L/h`.
fn simply_supported(thickness: f64, elements: usize) -> Rod {
    let mut rod = common::straight_rod(LENGTH, 1.0, thickness, 0.0, elements);
    let last = rod.last_node();
    rod.fix(0, U1);
    rod.fix(0, U2);
    rod.fix(last, U2);
    rod
}

#[test]
fn thin_rod_vibration_without_locking() {
    let mut t = Table::new(&format!(
        "simply supported rod L = 10, b = 1, {ELEMENTS} elements, undamped, released from the \
         first mode shape (amplitude 1e-4 L): period from the zero crossings of w_mid over 3 \
         periods, midpoint rule with dt = T/100 (T of Timoshenko), Newton tolerance 1e-10"
    ));
    t.row(format_args!(
        "{:>7} {:>12} {:>12} {:>12} {:>11} {:>11} {:>10}",
        "L/h", "T exact", "T measured", "rel. error", "iter/step", "max iter", "cut steps"
    ));
    let mut errors = Vec::new();
    for slenderness in SLENDERNESS {
        let rod = simply_supported(LENGTH / slenderness, ELEMENTS);
        let omega = timoshenko_bending_omega(&rod.section, LENGTH, 1);
        let period = 2.0 * PI / omega;
        let dt = period / 100.0;
        let amplitude = 1e-4 * LENGTH;
        let k = PI / LENGTH;
        let mut state = DynamicState::at_rest(vec![0.0; rod.dofs()]);
        for i in 0..rod.nodes() {
            let s = rod.node_s[i];
            state.u[3 * i + U2] = amplitude * (k * s).sin();
            state.u[3 * i + ROTATION] = amplitude * k * (k * s).cos();
        }
        let loads = LoadSet::new(&rod, &[]);
        let mut mid = Midpoint::new(&rod);
        let w_mid = |u: &[f64]| rod.interpolate(u, rod.midspan(), U2);
        let (mut iterations, mut worst, mut cut_steps) = (0u32, 0u32, 0usize);
        let mut crossings = Vec::new();
        let mut previous = w_mid(&state.u);
        let steps = 300;
        for n in 0..steps {
            let stats =
                driver::step_adaptive(&mut mid, &rod, &loads, &mut state, n as f64 * dt, dt, 5)
                    .unwrap_or_else(|e| panic!("L/h = {slenderness}, step {n}: {e}"));
            iterations += stats.iterations;
            worst = worst.max(stats.iterations);
            if stats.cuts > 0 {
                cut_steps += 1;
            }
            let now = w_mid(&state.u);
            if previous * now < 0.0 {
                // Linear interpolation of the zero crossing within the step.
                crossings.push((n as f64 + previous / (previous - now)) * dt);
            }
            previous = now;
        }
        // Crossings at T/4, 3T/4, ...: the period from the first and last one.
        let measured =
            2.0 * (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
        let error = (measured - period) / period;
        t.row(format_args!(
            "{slenderness:>7} {period:>12.5e} {measured:>12.5e} {error:>12.3e} {:>11.2} {worst:>11} {cut_steps:>10}",
            iterations as f64 / steps as f64
        ));
        errors.push((slenderness, error));
        if slenderness <= 1e3 {
            assert!(
                worst <= 6 && cut_steps == 0,
                "L/h = {slenderness}: {worst} Newton iterations"
            );
        }
    }
    // Error = FE stiffening (~(pi/n)^2/12 ~ 2e-3 at 20 elements) + midpoint period stretch
    // ((omega dt)^2/12 = 3.3e-3): the same at every L/h (within 10 %), well below 1e-2. Locking
    // would shorten the period at L/h = 10^4 by a factor of order L/h.
    for &(s, e) in &errors {
        assert!(e.abs() < 1e-2, "L/h = {s}: period error {e:e}");
        assert!(
            (e - errors[1].1).abs() < 0.1 * errors[1].1.abs(),
            "L/h = {s}: {e:e} vs {:e}",
            errors[1].1
        );
    }
}
