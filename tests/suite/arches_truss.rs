//! Issue 5, static path following (arc-length continuation, limit points by bisection) against a
//! second method: a two-bar rod shaped like a von Mises truss (kinked reference curve
//! `ReferenceCurve::TwoBar`, one element per bar so the kink is the middle node, ends pinned,
//! crown load along `-e2`, `h = 0.01`, so `EI / (EA a^2) ~ 1e-7`), whose equilibrium path is also
//! written out by hand from the element's energy. What this checks is the continuation and the
//! assembly of the same discrete model, not the truss: the reference is the model itself
//! re-derived, and the pin-jointed truss formula is a different structure (printed, 17x off).
//!
//! Why one element per bar: a thin continuous rod cannot be a truss. The bars' Euler load
//! `pi^2 EI / l0^2` lies far below the bar force at the snap (for `h = 0.05`, 16 elements, the
//! tangent has 4 negative eigenvalues from the first increment on and the path follows buckled
//! bars); bars thick enough not to buckle (`h > ~0.6 H`) carry a bending share of the crown
//! stiffness of 10-40 %. A single linear element is straight by construction.
//!
//! The two load-deflection curves:
//! - the bar formula of the pin-jointed truss (printed only),
//!   `P(v) = 2 EA (l0 - l) / l0 * (H - v) / l`, `l = sqrt(a^2 + (H - v)^2)`: load rises to the snap load, falls through zero at the flat position `v = H` to `-P_max`
//!   (snap-back) and rises again through zero at the inverted position `v = 2H`;
//! - the same rod discretized (the reference of the test, a second method): by symmetry the
//!   crown keeps `u1 = 0`, `w = 0`, so the rod has two unknowns, `v` and the support rotation `w_a`; the element energy (two Gauss points,
//!   hybrid: `l/2 (EA e1m^2 + GA e2m^2)` with the mean strains, plus bending) is minimized over
//!   `w_a` (root of its derivative by bisection) and `P = dPi/dv`. The linear rotation field
//!   inside the bar (from `w_a ~ 2 phi` at the support to 0 at the crown, `phi` the bar's
//!   rotation) lowers the Gauss-point stretch by about `phi^2 / 6`, a discretization error that
//!   vanishes for small bar rotations; the hand derivation includes it exactly.
//!
//! The continuation must follow the hand-derived path to round-off, pass both limit points and
//! locate them by bisection. The bar formula is printed for comparison only: the rotation field
//! of the one-element bars is far from a hinge (measured: snap load 0.0683 against 0.0457 of the
//! bar formula, at v = 0.63 against 0.42; 17x off at worst along the path), so a thin continuous rod with a rigid joint does not
//! reproduce the pin-jointed truss at this mesh, and finer meshes buckle the bars.
//!
//! Run: `cargo test --profile quick --test suite arches_truss:: -- --nocapture`
use georod::integrator::continuation::{
    equilibria_at_load, follow_path, refine_critical_points, ContinuationSettings, CriticalKind,
};
use georod::model::rod::{U1, U2};
use georod::model::{ReferenceCurve, Rod, Section};

const HALF_SPAN: f64 = 10.0;
const RISE: f64 = 1.0;
const E: f64 = 1.2e4;
const H_SECTION: f64 = 0.01;

fn section() -> Section {
    Section::rectangular(E, 0.2, 1e-6, 1.0, H_SECTION)
}

fn truss() -> (Rod, Vec<f64>) {
    let curve = ReferenceCurve::TwoBar {
        span: 2.0 * HALF_SPAN,
        rise: RISE,
    };
    let mut rod = Rod::new(curve, section(), 0.0, 2);
    for node in [0, rod.last_node()] {
        rod.fix(node, U1);
        rod.fix(node, U2);
    }
    let mut q = vec![0.0; rod.dofs()];
    rod.add_point_transverse_load(&mut q, rod.midspan(), 1.0);
    (rod, q)
}

fn bar_length() -> f64 {
    (HALF_SPAN * HALF_SPAN + RISE * RISE).sqrt()
}

/// The bar-equilibrium crown load at crown deflection `v` (downwards).
fn bar_load(v: f64) -> f64 {
    let l0 = bar_length();
    let l = (HALF_SPAN * HALF_SPAN + (RISE - v) * (RISE - v)).sqrt();
    2.0 * section().ea * (l0 - l) / l0 * (RISE - v) / l
}

/// Mean Gauss-point strains of the left element and their derivatives with respect to `v` and
/// `w_a`: `(e1m, e2m, de1/dv, de2/dv, de1/dwa, de2/dwa)`.
fn left_element(v: f64, wa: f64) -> [f64; 6] {
    let l0 = bar_length();
    let alpha = RISE.atan2(HALF_SPAN);
    let du2 = -v / l0; // u1' = 0
    let mut r = [0.0; 6];
    for xi in [-1.0 / 3f64.sqrt(), 1.0 / 3f64.sqrt()] {
        let na = 0.5 * (1.0 - xi);
        let w = na * wa;
        let (s, c) = (alpha + w).sin_cos();
        let e1 = w.cos() + s * du2 - 1.0;
        let e2 = -w.sin() + c * du2;
        r[0] += 0.5 * e1;
        r[1] += 0.5 * e2;
        r[2] += 0.5 * s * (-1.0 / l0);
        r[3] += 0.5 * c * (-1.0 / l0);
        r[4] += 0.5 * na * e2;
        r[5] += 0.5 * na * -(1.0 + e1);
    }
    r
}

/// The crown load of the two-element rod at crown deflection `v`, from its energy by hand.
fn discrete_load(v: f64) -> f64 {
    let sec = section();
    let l0 = bar_length();
    let g = |wa: f64| {
        let r = left_element(v, wa);
        l0 * (sec.ea * r[0] * r[4] + sec.ga * r[1] * r[5]) + sec.ei * wa / l0
    };
    let (mut lo, mut hi) = (-1.0, 1.0);
    assert!(g(lo) < 0.0 && g(hi) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let r = left_element(v, 0.5 * (lo + hi));
    // P v is the work of the load: P = dPi/dv, Pi = 2 Pi_left.
    2.0 * l0 * (sec.ea * r[0] * r[2] + sec.ga * r[1] * r[3])
}

/// The maximum of `f` on `(lo, hi)` (golden section).
fn maximum(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> (f64, f64) {
    let (mut a, mut b) = (lo, hi);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if f(c) > f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    let v = 0.5 * (a + b);
    (v, f(v))
}

#[test]
fn continuation_follows_the_hand_derived_two_element_path_through_snap_and_snap_back() {
    let (rod, q) = truss();
    let (v_bar, p_bar) = maximum(bar_load, 0.0, RISE);
    let (v_snap, p_snap) = maximum(discrete_load, 0.0, RISE);
    let (v_back, p_back) = maximum(|v| -discrete_load(v), RISE, 2.8 * RISE);
    let mut settings = ContinuationSettings::for_rod(&rod, 10.0 * p_snap);
    settings.max_displacement = 3.0 * RISE;
    let path = follow_path(&rod, &vec![0.0; rod.dofs()], 0.0, &q, &settings);
    let mid = rod.midspan();
    let v = |u: &[f64]| -rod.interpolate(u, mid, U2);
    println!(
        "von Mises truss: a = {HALF_SPAN}, H = {RISE}, h = {H_SECTION}, 2 elements; {} points, \
         stopped: {}",
        path.points.len(),
        path.stop_reason
    );
    println!("  bar formula:         snap load {p_bar:.6e} at v = {v_bar:.6}");
    println!(
        "  hand-derived, same 2 elements: snap load {p_snap:.6e} at v = {v_snap:.6}, snap-back load \
         {:.6e} at v = {v_back:.6}",
        -p_back
    );
    // The path goes down past the inverted position.
    let v_end = v(&path.points.last().unwrap().u);
    assert!(v_end > 2.2 * RISE, "path ended at v = {v_end}");
    // Along the whole path the load is the hand-derived one to round-off (the bar formula is
    // only reported: see the module comment).
    let worst = |f: &dyn Fn(f64) -> f64| {
        path.points
            .iter()
            .map(|p| (p.load - f(v(&p.u))).abs())
            .fold(0.0, f64::max)
    };
    let (worst_disc, worst_bar) = (worst(&discrete_load), worst(&bar_load));
    println!(
        "  along the path: worst |P - P_discrete(v)| = {worst_disc:.2e} ({:.1e} of P_max), \
         worst |P - P_bar(v)| = {worst_bar:.2e} ({:.2} % of P_max)",
        worst_disc / p_snap,
        100.0 * worst_bar / p_bar
    );
    // Round-off: the path's loads are Newton-converged (quadratically) on a model with forces
    // ~EA = 1e2: measured 8.3e-14 of P_max; bound 1e-12.
    assert!(worst_disc < 1e-12 * p_snap);
    // Load rises, falls through the snap-back, rises again: two limit points at +-P_max.
    let critical = refine_critical_points(&rod, &q, &path, &settings);
    for c in &critical {
        println!(
            "  {:?} at P = {:.9e}, v = {:.6}, negative eigenvalues {} -> {} (bracket {:.1e})",
            c.kind,
            c.load,
            v(&c.u),
            c.negative_before,
            c.negative_after,
            c.bracket
        );
    }
    let limits: Vec<_> = critical
        .iter()
        .filter(|c| c.kind == CriticalKind::LimitPoint)
        .collect();
    assert_eq!(limits.len(), 2, "expected two limit points: {critical:?}");
    let (top, bottom) = (limits[0], limits[1]);
    let (dv_top, dv_bottom) = (v(&top.u) - v_snap, v(&bottom.u) - v_back);
    println!(
        "  snap load error {:.1e}, snap-back load error {:.1e} (relative); their positions \
         differ by {dv_top:.1e}, {dv_bottom:.1e}",
        (top.load - p_snap) / p_snap,
        (bottom.load + p_back) / p_back
    );
    // The limit loads: bisection brackets of 1e-13 and round-off, measured 3e-14 and 5.5e-14;
    // bound 1e-12. Their positions: at a load maximum dP/dv = 0, so a load error e moves v by
    // ~sqrt(e / P''), and the golden-section search of the reference stops at ~sqrt(eps) of v:
    // measured 8.5e-8 and 1.3e-7; bound 1e-6 of the rise.
    assert!((top.load - p_snap).abs() < 1e-12 * p_snap);
    assert!((bottom.load + p_back).abs() < 1e-12 * p_back);
    assert!(dv_top.abs() < 1e-6 * RISE && dv_bottom.abs() < 1e-6 * RISE);
    // Stable before the snap, one negative eigenvalue between the limit points, stable after.
    assert_eq!((top.negative_before, top.negative_after), (0, 1));
    assert_eq!((bottom.negative_before, bottom.negative_after), (1, 0));
    // Zero-load equilibria: the start, the flat position (unstable) and the inverted one.
    let eq = equilibria_at_load(&rod, &q, &path, 0.0, &settings);
    let vs: Vec<f64> = eq.iter().map(|e| v(&e.u)).collect();
    println!("  zero-load equilibria at v = {vs:?}");
    assert_eq!(eq.len(), 3);
    assert!(vs[0].abs() < 1e-12);
    assert!(vs[1] > v_snap && vs[1] < v_back && eq[1].negative_eigenvalues == 1);
    assert!(vs[2] > v_back && eq[2].negative_eigenvalues == 0);
    let worst_eq = vs
        .iter()
        .map(|&x| discrete_load(x).abs())
        .fold(0.0, f64::max);
    println!(
        "  hand-derived load at those v: at most {:.1e} of P_max",
        worst_eq / p_snap
    );
    // Located by bisection on the path's load to round-off: measured 6.6e-14; bound 1e-12.
    assert!(worst_eq < 1e-12 * p_snap, "not equilibria: v = {vs:?}");
}
