//! Frames through limit points (arc-length continuation, `georod path`'s engine):
//! - the von Mises truss (two shallow truss bars, exact axial strain): the static path against
//!   the exact curve `P(w) = 2 EA (1 - l / L) y / l` (apex height `y = h - w`, bar length `l`)
//!   and its limit load against the maximum of that curve;
//! - Lee's frame (a pinned column and a pinned beam, rigidly joined, the load 24 from the
//!   corner): its first limit load `P L^2 / EI` against the literature's 18.5, and the path
//!   through the snap-back that follows. The hybrid element converges to it at second order:
//!   1.86335, 1.85683, 1.85520 at 40, 80, 160 elements (`P` for `L = 120`, `EI = 1440`); the
//!   extrapolation from 80 and 160 gives 1.85466, `P L^2 / EI` = 18.547.
//!
//! Run: `cargo test --profile quick --test suite frames_stability:: -- --nocapture`
use crate::common;

use common::simulation_of;
use georod::integrator::continuation::{
    follow_path, refine_critical_points, ContinuationSettings, CriticalKind,
};
use georod::model::Place;

const VON_MISES: &str = r#"
name = "VonMises"
[defaults]
E = 210e9
rho = 7850.0
[section]
shape = "general"
A = 1e-4
I = 1e-9
As = 1e-4
[[joint]]
name = "L"
x = 0.0
y = 0.0
[[joint]]
name = "A"
x = 1.0
y = 0.1
[[joint]]
name = "R"
x = 2.0
y = 0.0
[[member]]
name = "left"
from = "L"
to = "A"
kind = "truss"
[[member]]
name = "right"
from = "A"
to = "R"
kind = "truss"
[[support]]
name = "pl"
joint = "L"
fix = ["u1", "u2"]
[[support]]
name = "pr"
joint = "R"
fix = ["u1", "u2"]
[[load]]
name = "P"
kind = "point"
joint = "A"
direction = "-e2"
value = 0.0
"#;

/// The exact load of the von Mises truss at apex deflection `w` (down).
fn von_mises_load(ea: f64, a: f64, h: f64, w: f64) -> f64 {
    let (l0, y) = ((a * a + h * h).sqrt(), h - w);
    let l = (a * a + y * y).sqrt();
    2.0 * ea * (1.0 - l / l0) * y / l
}

#[test]
fn von_mises_truss_follows_the_exact_path_and_snaps_at_its_limit_load() {
    let sim = simulation_of(VON_MISES, &[]);
    let s = sim.structure();
    let ea = 210e9 * 1e-4;
    let apex = Place::Joint(1);
    let mut q = vec![0.0; s.dofs()];
    s.add_point_force(&mut q, apex, 1, -1.0);
    let u0 = vec![0.0; s.dofs()];
    let mut settings = ContinuationSettings::for_rod(s, 1e9);
    settings.max_displacement = 0.25;
    settings.max_arc_length = 2e-3;
    let path = follow_path(s, &u0, 0.0, &q, &settings);
    assert!(path.points.len() > 50, "{}", path.stop_reason);
    let mut worst = 0.0f64;
    for p in &path.points {
        let w = -s.interpolate(&p.u, apex, 1);
        worst = worst.max((p.load - von_mises_load(ea, 1.0, 0.1, w)).abs());
    }
    let scale = von_mises_load(ea, 1.0, 0.1, 0.1 - 0.1 / 3f64.sqrt());
    println!(
        "{} points to w = {:.3}: largest load error {worst:.3e} N of {scale:.4e} N",
        path.points.len(),
        -s.interpolate(&path.points.last().unwrap().u, apex, 1)
    );
    // Newton's tolerance on the displacements (1e-10 relative) moves the load by as much.
    assert!(worst < 1e-8 * scale, "{worst}");
    // The limit load: where dP/dw = 0, on the exact curve by golden sections.
    let (mut lo, mut hi) = (0.0, 0.1);
    for _ in 0..200 {
        let (m1, m2) = (lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo));
        if von_mises_load(ea, 1.0, 0.1, m1) < von_mises_load(ea, 1.0, 0.1, m2) {
            lo = m1;
        } else {
            hi = m2;
        }
    }
    let exact = von_mises_load(ea, 1.0, 0.1, 0.5 * (lo + hi));
    let limits: Vec<_> = refine_critical_points(s, &q, &path, &settings)
        .into_iter()
        .filter(|c| c.kind == CriticalKind::LimitPoint)
        .collect();
    assert!(!limits.is_empty(), "no limit point");
    println!("limit load {:.10e} N, exact {exact:.10e} N", limits[0].load);
    assert!(
        (limits[0].load / exact - 1.0).abs() < 1e-8,
        "{} vs {exact}",
        limits[0].load
    );
}

/// Lee's frame's first limit load (`P`) and its path with `elements` elements.
fn lee(elements: f64) -> (f64, georod::integrator::continuation::Path, Vec<f64>) {
    let sim = simulation_of(common::scenes::LEE_FRAME, &[("elements", elements)]);
    let s = sim.structure();
    let at = s.member_place(1, 24.0);
    let mut q = vec![0.0; s.dofs()];
    s.add_point_force(&mut q, at, 1, -1.0);
    let u0 = vec![0.0; s.dofs()];
    let mut settings = ContinuationSettings::for_rod(s, 10.0);
    settings.max_displacement = 100.0;
    settings.max_points = 20_000;
    let path = follow_path(s, &u0, 0.0, &q, &settings);
    let critical = refine_critical_points(s, &q, &path, &settings);
    let first = critical
        .iter()
        .find(|c| c.kind == CriticalKind::LimitPoint)
        .expect("a limit point");
    let down = path
        .points
        .iter()
        .map(|p| -s.interpolate(&p.u, at, 1))
        .collect();
    (first.load, path, down)
}

#[test]
fn lee_frame_reaches_its_limit_load_and_snaps_back() {
    let (l, ei) = (120.0, 720.0 * 2.0);
    let (coarse, path, down) = lee(80.0);
    let (fine, _, _) = lee(160.0);
    let ratio = (4.0 * fine - coarse) / 3.0 * l * l / ei;
    println!("limit loads {coarse:.6} (80 elements), {fine:.6} (160): P L^2 / EI = {ratio:.4}");
    // The literature's 18.5 (18.5 to 18.6 for shear-flexible and inextensible models).
    assert!((ratio - 18.5).abs() < 0.1, "{ratio}");
    // Past it the load falls while the deflection grows to about 61, then both fall: the
    // snap-back (the deflection down to about 51 as the load passes zero).
    let first = path
        .points
        .iter()
        .position(|p| p.load >= coarse - 1e-3)
        .expect("the limit");
    let highest = (first..down.len())
        .take_while(|&k| k + 1 < down.len() && down[k + 1] >= down[k])
        .last()
        .map_or(first, |k| k + 1);
    let lowest_after = down[highest..]
        .iter()
        .zip(&path.points[highest..])
        .take_while(|(_, p)| p.load > -0.9)
        .map(|(v, _)| *v)
        .fold(f64::INFINITY, f64::min);
    let turned = lowest_after < down[highest] - 5.0 && path.points[highest].load < coarse;
    println!(
        "deflection {:.3} at load {:.4} after the limit, back to {lowest_after:.3}",
        down[highest], path.points[highest].load
    );
    assert!(
        turned,
        "no snap-back after the deflection {}",
        down[highest]
    );
}
