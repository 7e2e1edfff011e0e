//! Cost of the midpoint rule against the number of elements: prints microseconds per time step
//! (and per step and element) for 10 to 10,000 elements, the corrections (Newton and chord) and
//! factorizations per step, and the ratio between consecutive sizes (10x more elements should
//! cost about 10x: linear, block-tridiagonal work).
//!
//! Run: `cargo bench --bench scaling` (release profile). Each size runs the BuckledBeam with the
//! default excitation from its static buckled state, with steps of 1e-6 s, for about one second.
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;
use std::time::Instant;

/// (us per step, corrections per step, factorizations per step)
fn measure(elements: usize) -> (f64, f64, f64) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/BuckledBeam.toml");
    let scene = Arc::new(Scene::load(path).expect("scene file"));
    let values = scene
        .values_with([("elements", elements as f64), ("dt_max", 1e-6)])
        .expect("valid parameters");
    let mut sim = Simulation::new(scene, values).expect("initial state");
    // Warm up, then time enough steps for about a second.
    sim.advance(1e-6).expect("step");
    let mut steps = 1usize;
    loop {
        let start = Instant::now();
        let (mut corrections, mut factorizations) = (0u64, 0u64);
        for _ in 0..steps {
            let report = sim.advance(1e-6).expect("step");
            corrections += report.newton_iterations as u64;
            factorizations += report.factorizations as u64;
        }
        let seconds = start.elapsed().as_secs_f64();
        if seconds > 1.0 || steps >= 1 << 22 {
            return (
                1e6 * seconds / steps as f64,
                corrections as f64 / steps as f64,
                factorizations as f64 / steps as f64,
            );
        }
        steps *= if seconds < 0.05 { 10 } else { 2 };
    }
}

fn main() {
    println!("| elements | us / time step | us / step / element | corrections / step | factorizations / step | ratio (step) |");
    println!("|---:|---:|---:|---:|---:|---:|");
    let mut previous: Option<f64> = None;
    for elements in [10, 100, 1000, 10000] {
        let (per_step, corrections, factorizations) = measure(elements);
        let per_element = per_step / elements as f64;
        let ratio = |now: f64, before: Option<f64>| {
            before.map_or("".to_string(), |b| format!("{:.2}", now / b))
        };
        println!(
            "| {elements} | {per_step:.2} | {per_element:.3} | {corrections:.2} | {factorizations:.2} | {} |",
            ratio(per_step, previous),
        );
        previous = Some(per_step);
    }
}
