//! Stability study (issue 7), part 2: long undamped free vibration of a stiff rod from a large
//! initial deformation with a coarse step: the implicit midpoint rule (`Scheme::Midpoint`)
//! against the energy-momentum scheme (`Scheme::EnergyMomentum`).
//!
//! The rod: a cantilever L = 10, b = 1, h = 0.1 (L/h = 100), the scenes' material (E = 1.2e4,
//! nu = 0.2, rho = 1e-6), 20 elements, d = 0. It is bent statically by a tip force
//! `P L^2 / EI = 5` (tip deflection 0.71 L, tip rotation 70 degrees), then the force is removed
//! and the rod swings freely. Its first bending period is about 1.8 s while the stiffest axial
//! mode of the mesh has a period of about 1e-5 s: the step (T1 / 20 and T1 / 5) is coarse by a
//! factor 10^4 for the stiff modes, the setting in which the midpoint rule is known to be able
//! to blow up (Simo & Tarnow 1992; Gonzalez 2000).
//!
//! A step whose Newton fails is retried with 2, 4, .. 32 sub-steps (as `Simulation::advance`
//! does); the number of such steps is reported. A step that fails even then ends the run
//! (the FMU would return fmi2Discard there).
//!
//! `STABILITY_STEPS` sets the number of steps: 20000 by default (100 periods at T1 / 200, the
//! suite's smoke version), 10^5 in `scripts/study_stability`, which writes the tables of
//! docs/stability.md; `STABILITY_CSV_DIR` makes the
//! tests write the energy histories there (`stability_energy_<case>_<scheme>.csv`, used by
//! `python -m georod_tools.stability plot`).
//!
//! Run: `cargo test --profile quick --test suite stability_energy:: -- --nocapture`
use crate::common;
use crate::stability_driver as driver;

use common::Table;
use driver::step_adaptive;
use georod::integrator::{DynamicState, Midpoint, Scheme, StaticSolver};
use georod::model::rod::{ROTATION, U1, U2};
use georod::model::{LoadSet, Rod};
use std::io::Write;

const LENGTH: f64 = 10.0;
const THICKNESS: f64 = 0.1;
const ELEMENTS: usize = 20;
/// Initial tip load `P L^2 / EI`.
const PRELOAD: f64 = 5.0;
/// Steps per run unless `STABILITY_STEPS` says otherwise.
const SUITE_STEPS: usize = 20_000;

fn cantilever() -> Rod {
    let mut rod = common::straight_rod(LENGTH, 1.0, THICKNESS, 0.0, ELEMENTS);
    for k in [U1, U2, ROTATION] {
        rod.fix(0, k);
    }
    rod
}

/// The statically bent cantilever (tip force ramped in 20 steps).
fn bent_state(rod: &Rod) -> Vec<f64> {
    let mut f = vec![0.0; rod.dofs()];
    f[3 * rod.last_node() + U2] = -PRELOAD * rod.section.ei / (LENGTH * LENGTH);
    let mut u = vec![0.0; rod.dofs()];
    StaticSolver::new(rod)
        .solve_ramped(rod, &mut u, &f, 20)
        .expect("static bent state");
    u
}

/// First bending period of the linear cantilever, `2 pi / (1.8751^2 sqrt(EI / (rho A L^4)))`.
fn first_period(rod: &Rod) -> f64 {
    let beta = 1.875_104_068_711_961;
    let omega = beta * beta * (rod.section.ei / (rod.section.rho_a * LENGTH.powi(4))).sqrt();
    2.0 * std::f64::consts::PI / omega
}

struct Run {
    /// Steps completed (all of them unless Newton failed).
    completed: usize,
    failure: Option<String>,
    max_rel_energy_error: f64,
    final_rel_energy_error: f64,
    max_iterations: u32,
    mean_iterations: f64,
    max_tip_deflection: f64,
    /// Steps that needed sub-steps.
    cut_steps: usize,
}

fn run(case: &str, scheme: Scheme, dt: f64, steps: usize) -> Run {
    let rod = cantilever();
    let loads = LoadSet::new(&rod, &[]); // amplitude 0: free
    let mut state = DynamicState::at_rest(bent_state(&rod));
    let mut integrator = Midpoint::new(&rod);
    integrator.scheme = scheme;
    let energy = |s: &DynamicState| rod.kinetic_energy(&s.v) + rod.strain_energy(&s.u);
    let e0 = energy(&state);
    let tip = 3 * rod.last_node() + U2;
    let mut csv = driver::csv(
        &format!("stability_energy_{case}_{scheme:?}"),
        &format!("cantilever L=10 h=0.1 20 el, d=0, released from PL2/EI={PRELOAD}; dt={dt:e}; scheme {scheme:?}"),
        "step,time,energy,rel_energy_error,kinetic,strain,tip_deflection,newton_iterations,cuts",
    );
    let every = (steps / 5000).max(1);
    let mut out = Run {
        completed: 0,
        failure: None,
        max_rel_energy_error: 0.0,
        final_rel_energy_error: 0.0,
        max_iterations: 0,
        mean_iterations: 0.0,
        max_tip_deflection: 0.0,
        cut_steps: 0,
    };
    let mut total_iterations = 0u64;
    let mut last_iterations;
    let mut last_cuts;
    for n in 0..steps {
        match step_adaptive(
            &mut integrator,
            &rod,
            &loads,
            &mut state,
            n as f64 * dt,
            dt,
            5,
        ) {
            Ok(s) => {
                last_cuts = s.cuts;
                if s.cuts > 0 {
                    out.cut_steps += 1;
                }
                last_iterations = s.iterations;
                total_iterations += s.iterations as u64;
                out.max_iterations = out.max_iterations.max(s.iterations);
            }
            Err(e) => {
                out.failure = Some(format!("step {n}: {e}"));
                break;
            }
        }
        out.completed = n + 1;
        let e = energy(&state);
        let rel = (e - e0) / e0;
        assert!(e.is_finite(), "{scheme:?}: non-finite energy at step {n}");
        out.max_rel_energy_error = out.max_rel_energy_error.max(rel.abs());
        out.final_rel_energy_error = rel;
        out.max_tip_deflection = out.max_tip_deflection.max(state.u[tip].abs() / LENGTH);
        if let Some(f) = csv.as_mut() {
            // Every `every` steps, and every step once the energy is off by 1 % (a blow-up).
            if (n + 1) % every == 0 || n + 1 == steps || rel.abs() > 1e-2 {
                writeln!(
                    f,
                    "{},{:e},{e:.12e},{rel:.6e},{:.12e},{:.12e},{:.8e},{},{last_cuts}",
                    n + 1,
                    (n + 1) as f64 * dt,
                    rod.kinetic_energy(&state.v),
                    rod.strain_energy(&state.u),
                    state.u[tip],
                    last_iterations
                )
                .unwrap();
            }
        }
    }
    out.mean_iterations = total_iterations as f64 / out.completed.max(1) as f64;
    out
}

fn report(t: &mut Table, name: &str, r: &Run) {
    t.row(format_args!(
        "{name:<16} {:>8} {:>7} {:>14.3e} {:>14.3e} {:>9.2} {:>5} {:>8.3}  {}",
        r.completed,
        r.cut_steps,
        r.max_rel_energy_error,
        r.final_rel_energy_error,
        r.mean_iterations,
        r.max_iterations,
        r.max_tip_deflection,
        r.failure.as_deref().unwrap_or("")
    ));
}

/// Both schemes at one step size; returns (midpoint, energy-momentum).
fn compare(case: &str, steps_per_period: f64) -> (Run, Run) {
    let rod = cantilever();
    let period = first_period(&rod);
    let dt = period / steps_per_period;
    let steps = driver::steps_from_env(SUITE_STEPS);
    let mid = run(case, Scheme::Midpoint, dt, steps);
    let em = run(case, Scheme::EnergyMomentum, dt, steps);
    let mut t = Table::new(&format!(
        "free vibration of the cantilever L = 10, h = 0.1 ({ELEMENTS} el., d = 0) released from \
         PL^2/EI = {PRELOAD}: T1 = {period:.4} s, dt = T1/{steps_per_period} = {dt:.4e} s, \
         {steps} steps ({:.0} periods); Newton tolerance 1e-10 of the increment",
        steps as f64 / steps_per_period
    ));
    t.row(format_args!(
        "{:<16} {:>8} {:>7} {:>14} {:>14} {:>9} {:>5} {:>8}",
        "scheme", "steps", "cut", "max |dE|/E0", "final dE/E0", "iter/step", "max", "max v/L"
    ));
    report(&mut t, "midpoint", &mid);
    report(&mut t, "energy-momentum", &em);
    (mid, em)
}

/// Shared checks: the energy-momentum scheme runs every step and keeps the energy to 1e-8
/// (Newton leaves corrections of 1e-10 of the increment; accumulated over 10^5 steps); the
/// midpoint rule may drift or fail, but never returns non-finite values (asserted in `run`).
fn check(mid: &Run, em: &Run) {
    let steps = driver::steps_from_env(SUITE_STEPS);
    assert_eq!(
        em.completed, steps,
        "energy-momentum failed: {:?}",
        em.failure
    );
    assert!(
        em.max_rel_energy_error < 1e-8,
        "energy-momentum energy error {:e}",
        em.max_rel_energy_error
    );
    assert!(mid.completed > 0);
}

#[test]
fn free_vibration_step_t1_over_200() {
    let (mid, em) = compare("T1_200", 200.0);
    check(&mid, &em);
}

#[test]
fn free_vibration_step_t1_over_400() {
    let (mid, em) = compare("T1_400", 400.0);
    check(&mid, &em);
}

/// Coarser still: the energy-momentum scheme needs sub-steps for its Newton in most steps
/// (about 30 s for 10^5 steps): run by `scripts/study_stability`.
#[test]
#[ignore]
fn free_vibration_step_t1_over_50() {
    let (mid, em) = compare("T1_50", 50.0);
    check(&mid, &em);
}
