//! The step loop allocates nothing: a counting global allocator sees zero allocations during
//! `Simulation::advance` once the simulation is built (all buffers are preallocated). Only the
//! measuring thread's allocations count (the test harness's own threads allocate at will).
mod common;

use georod::scene::variables::{variables, Role};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

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

#[test]
fn advance_does_not_allocate() {
    for kind in ["BuckledBeam", "PinnedArch", "ClampedArch"] {
        let mut sim = common::simulation(kind, &[("F", 1.0)]);
        common::set_input(&mut sim, "f_ctrl", 0.1);
        let outputs: Vec<_> = (variables(sim.scene()).into_iter())
            .filter_map(|v| match v.role {
                Role::Output(id) => Some(id),
                _ => None,
            })
            .collect();
        sim.advance(1e-4).unwrap(); // first step outside the count
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        COUNTING.with(|c| c.set(true));
        for k in 0..50 {
            sim.set_input(0, 0.1 * (k as f64).sin()).unwrap();
            sim.advance(1e-4).unwrap();
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
