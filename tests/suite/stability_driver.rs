//! Shared by the stability tests (`#[path = "stability_driver.rs"] mod driver;`): one time step
//! of `Midpoint` that, like `Simulation::advance`, retries a step whose Newton fails with 2, 4,
//! ... 2^max_cuts equal sub-steps, and a CSV writer enabled by `STABILITY_CSV_DIR`.
//! (As a test target of its own it holds no test.)
#![allow(dead_code)]

use georod::integrator::{DynamicState, Midpoint, NewtonFailure};
use georod::model::{LoadSet, Rod};
use std::io::Write;

/// What one adaptive step did.
#[derive(Clone, Copy, Debug, Default)]
pub struct Adaptive {
    pub iterations: u32,
    /// Halvings needed (0: the step converged as is).
    pub cuts: u32,
}

/// One step of `dt` from `t`; on failure after `max_cuts` halvings `state` is unchanged.
pub fn step_adaptive(
    integrator: &mut Midpoint,
    rod: &Rod,
    loads: &LoadSet,
    state: &mut DynamicState,
    t: f64,
    dt: f64,
    max_cuts: u32,
) -> Result<Adaptive, NewtonFailure> {
    let mut trial = state.clone();
    let mut last = None;
    for cuts in 0..=max_cuts {
        let n = 1usize << cuts;
        let h = dt / n as f64;
        trial.copy_from(state);
        let mut iterations = 0;
        let mut ok = true;
        for k in 0..n {
            match integrator.step(rod, loads, &mut trial, t + k as f64 * h, h, &[]) {
                Ok(s) => iterations += s.iterations,
                Err(e) => {
                    last = Some(e);
                    ok = false;
                    break;
                }
            }
        }
        if ok {
            state.copy_from(&trial);
            return Ok(Adaptive { iterations, cuts });
        }
    }
    Err(last.expect("a failure was recorded"))
}

/// A CSV file in `$STABILITY_CSV_DIR/<name>.csv` if that variable is set.
pub fn csv(name: &str, comment: &str, header: &str) -> Option<std::io::BufWriter<std::fs::File>> {
    let dir = std::env::var("STABILITY_CSV_DIR").ok()?;
    std::fs::create_dir_all(&dir).expect("CSV directory");
    let path = format!("{dir}/{name}.csv");
    let mut f = std::io::BufWriter::new(std::fs::File::create(path).expect("CSV file"));
    writeln!(f, "# {comment}").unwrap();
    writeln!(f, "{header}").unwrap();
    Some(f)
}

/// `STABILITY_STEPS` (a number, `1e6` allowed) or `default`.
pub fn steps_from_env(default: usize) -> usize {
    std::env::var("STABILITY_STEPS")
        .ok()
        .and_then(|s| s.parse::<f64>().ok())
        .map_or(default, |s| s as usize)
}
