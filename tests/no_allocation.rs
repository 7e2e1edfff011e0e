//! The step loop allocates nothing: a counting global allocator sees zero allocations during
//! `Simulation::advance` once the simulation is built (all buffers are preallocated), for every
//! scene file of scenes/ and examples/ with all its inputs driven. Only the
//! measuring thread's allocations count (the test harness's own threads allocate at will).
mod common;

use georod::scene::variables::{variables, Role};
use georod::scene::InputKind;
use georod::simulation::Simulation;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    // Const-initialized: reading it never allocates, so the allocator may consult it.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The value of input `i` at step `k`: load inputs swing by 0.1 (N or N/m), support motions by
/// 1e-4 (m or rad) about their start values, spring bases like support motions.
fn input_value(sim: &Simulation, i: usize, k: usize) -> f64 {
    let input = &sim.scene().inputs[i];
    let amplitude = match input.kind {
        InputKind::Load(_) => 0.1,
        InputKind::Motion { .. } | InputKind::SpringBase(_) => 1e-4,
    };
    let start = georod::scene::variables::input_start(sim.scene(), i, sim.values());
    start + amplitude * ((k + i) as f64).sin()
}

#[test]
fn advance_does_not_allocate() {
    // Every scene without and with two Lyapunov tangent vectors (advanced from t = 0).
    for (scene, exponents) in common::scene_files()
        .into_iter()
        .flat_map(|s| [(Arc::clone(&s), 0.0), (s, 2.0)])
    {
        let kind = format!("{} (lyapunov_count = {exponents})", scene.name);
        let mut values = scene.defaults();
        if let Some(f) = scene.param_index("F") {
            if values.get(f) == 0.0 {
                // The harmonic load acts (the arches' default F is 0).
                scene.set(&mut values, "F", 1.0).unwrap();
            }
        }
        scene.set(&mut values, "lyapunov_count", exponents).unwrap();
        scene.set(&mut values, "lyapunov_start", 0.0).unwrap();
        let mut sim =
            Simulation::new(Arc::clone(&scene), values).unwrap_or_else(|e| panic!("{kind}: {e}"));
        let inputs = scene.inputs.len();
        let outputs: Vec<_> = (variables(sim.scene()).into_iter())
            .filter_map(|v| match v.role {
                Role::Output(id) => Some(id),
                _ => None,
            })
            .collect();
        for i in 0..inputs {
            let value = input_value(&sim, i, 1);
            sim.set_input(i, value).unwrap();
        }
        sim.advance(1e-4).unwrap(); // first step outside the count
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        COUNTING.with(|c| c.set(true));
        for k in 0..50 {
            for i in 0..inputs {
                let value = input_value(&sim, i, k);
                sim.set_input(i, value).unwrap();
            }
            sim.advance(1e-4)
                .unwrap_or_else(|e| panic!("{kind}: step {k}: {e}"));
            for &id in &outputs {
                std::hint::black_box(sim.output(id));
            }
        }
        COUNTING.with(|c| c.set(false));
        let after = ALLOCATIONS.load(Ordering::Relaxed);
        assert_eq!(
            after - before,
            0,
            "{kind}: {} allocations in 50 steps",
            after - before
        );
    }
}
