//! The `shape_x[i]`, `shape_y[i]` outputs read through the FMI 2.0 C API (the host is
//! `fmi_host`) are the rod's current positions at equally spaced arc lengths: on the
//! closed-form circle for an undeformed arch, and for a deflected cantilever the reference
//! curve plus the displacements of the core's state interpolated with the linear shape
//! functions (computed here from the nodal values), before and after steps.
#![cfg(any(
    target_arch = "x86_64",
    all(target_arch = "aarch64", not(target_vendor = "apple"))
))]

use crate::fmi_host;

use fmi_host::*;
use georod::fmi::types::fmi2Status;
use georod::scene::{Scene, Std};
use georod::simulation::Simulation;
use std::sync::Arc;

const SHAPE_X: u32 = 10_000;
const SHAPE_Y: u32 = 20_000;

/// `(shape_x[1..=points], shape_y[1..=points])` of an instance.
fn shape(fmu: &Fmu, points: u32) -> (Vec<f64>, Vec<f64>) {
    let x: Vec<u32> = (0..points).map(|i| SHAPE_X + i).collect();
    let y: Vec<u32> = (0..points).map(|i| SHAPE_Y + i).collect();
    (fmu.reals(&x), fmu.reals(&y))
}

/// The PinnedArch (L = 32, H = 2, 21 shape points) starts undeformed (no preload): its shape
/// points lie on the circle through (0, 0), (16, 2), (32, 0) at arc lengths `i S / 20`.
#[test]
fn the_arch_shape_is_the_circle_at_equal_arc_lengths() {
    let fmu = Fmu::new(PINNED);
    fmu.init();
    let (x, y) = shape(&fmu, 21);
    let (span, rise): (f64, f64) = (32.0, 2.0);
    let radius = (0.25 * span * span + rise * rise) / (2.0 * rise);
    let half_angle = (0.5 * span / radius).asin();
    let length = 2.0 * radius * half_angle;
    for i in 0..21 {
        // The angle from the vertical through the centre (L/2, H - R).
        let phi = half_angle - length * i as f64 / 20.0 / radius;
        let expected = [
            0.5 * span - radius * phi.sin(),
            rise - radius + radius * phi.cos(),
        ];
        // A few round-offs of the radius 65: 1e-12 of it.
        let off = (x[i] - expected[0]).hypot(y[i] - expected[1]);
        assert!(
            off < 1e-12 * radius,
            "point {}: ({}, {}) is {off:e} from {expected:?}",
            i + 1,
            x[i],
            y[i]
        );
    }
}

/// Positions at the Cantilever's 41 shape points (20 elements of length L/20: the even points
/// are the nodes, the odd ones the middles of the elements) from the core's nodal
/// displacements, interpolated here: a node's own value, in the middle the mean of the two ends.
fn positions(sim: &Simulation, length: f64) -> (Vec<f64>, Vec<f64>) {
    let u = &sim.state().u;
    (0..41)
        .map(|i| {
            let node = 3 * (i / 2);
            let at = |k: usize| match i % 2 {
                0 => u[node + k],
                _ => 0.5 * (u[node + k] + u[node + 3 + k]),
            };
            (length * i as f64 / 40.0 + at(0), at(1))
        })
        .unzip()
}

/// The Cantilever (tip load `P L^2 / EI = 1`) starts in its static equilibrium, bent by about a
/// third of its length; then a tip control force sets it moving. The FMU's shape outputs match
/// the core's state, step by step.
#[test]
fn the_cantilever_shape_is_the_core_state_interpolated() {
    let path = format!("{}/examples/Cantilever.toml", env!("CARGO_MANIFEST_DIR"));
    let scene = Arc::new(Scene::load(path).unwrap());
    let f_tip = scene.inputs.iter().position(|i| i.name == "f_tip").unwrap();
    let values = scene.defaults();
    let length = values.std(Std::Span);
    // A tenth of the tip load: it moves the tip visibly within a few steps.
    let push = 0.1 * values.get(scene.param("P").unwrap().0);
    let mut core = Simulation::new(scene.clone(), values).unwrap();
    let fmu = Fmu::new("Cantilever");
    fmu.init();
    let h = 1e-3;
    for step in 0..4 {
        let (x, y) = shape(&fmu, 41);
        let (cx, cy) = positions(&core, length);
        // The same computation in the FMU and the core; the interpolation here and there
        // differ in round-off of coordinates of order L: 1e-12 L.
        for i in 0..41 {
            let off = (x[i] - cx[i]).hypot(y[i] - cy[i]);
            assert!(
                off < 1e-12 * length,
                "step {step}, point {}: ({}, {}) instead of ({}, {})",
                i + 1,
                x[i],
                y[i],
                cx[i],
                cy[i]
            );
        }
        if step == 0 {
            assert!(cy[40] < -0.2 * length, "bent: tip at {}", cy[40]);
        }
        assert_eq!(fmu.set_real(1000, push), fmi2Status::OK);
        assert_eq!(
            fmu.step(fmu.time(), h),
            fmi2Status::OK,
            "{:?}",
            fmu.messages()
        );
        core.set_input(f_tip, push).unwrap();
        core.advance(h).unwrap();
    }
}
