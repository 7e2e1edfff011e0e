//! Static snap-through of a pinned sinusoidal shallow arch under a sinusoidal load, against the
//! closed form of shallow-arch (Marguerre / von Karman) theory.
//!
//! Arch `y0 = e sin(k x)`, `k = pi / L`, pinned ends, load `q0 sin(k x)` per unit horizontal
//! length along -e2. Shallow theory keeps the response in the first mode, `w = A sin(k x)`, with
//! the thrust `N = EA k^2 (A^2 - e^2) / 4` (tension positive) and
//! `q0(A) = EI k^4 (e - A) + EA k^4 A (e^2 - A^2) / 4`. Its symmetric limit point is at
//! `A_L^2 = (e^2 - 4 r^2) / 3` (`r^2 = I/A`), reached before the asymmetric bifurcation
//! (`A_B^2 = e^2 - 16 r^2`) when `2 < e/r < sqrt(22)`. Here `e/r = 3.46`.
//!
//! The rod model is geometrically exact with shear; shallow theory drops `O((e k)^2)` = 6.2e-3
//! terms of the kinematics and the shear compliance `pi^2 EI / (GA L^2)` = 1.2e-3 here, so the
//! converged finite-element limit load must agree to within about 1 % (measured: -4.2e-3), and
//! the crown deflection at the limit likewise (measured: 2e-4).
use georod::integrator::continuation::{
    follow_path, refine_critical_points, ContinuationSettings, CriticalKind,
};
use georod::model::element::{shape_functions, Element, GAUSS_POINTS};
use georod::model::rod::{U1, U2};
use georod::model::{ReferenceCurve, Rod, Section};
use std::f64::consts::PI;

const SPAN: f64 = 40.0;
const RISE: f64 = 1.0;

fn slope(x: f64) -> f64 {
    RISE * PI / SPAN * (PI * x / SPAN).cos()
}

/// Arc length from x = 0 (composite 5-point Gauss-Legendre, 400 panels: round-off accurate).
fn arc_length(x: f64) -> f64 {
    const NODES: [f64; 5] = [
        -0.906_179_845_938_664,
        -0.538_469_310_105_683,
        0.0,
        0.538_469_310_105_683,
        0.906_179_845_938_664,
    ];
    const WEIGHTS: [f64; 5] = [
        0.236_926_885_056_189,
        0.478_628_670_499_366,
        0.568_888_888_888_889,
        0.478_628_670_499_366,
        0.236_926_885_056_189,
    ];
    let panels = 400;
    let h = x / panels as f64;
    let mut s = 0.0;
    for p in 0..panels {
        let mid = (p as f64 + 0.5) * h;
        for (xi, w) in NODES.iter().zip(WEIGHTS) {
            let t = slope(mid + 0.5 * h * xi);
            s += 0.5 * h * w * (1.0 + t * t).sqrt();
        }
    }
    s
}

/// The abscissa at arc length `s` (Newton on `arc_length(x) = s`).
fn abscissa(s: f64) -> f64 {
    let mut x = s;
    for _ in 0..30 {
        let t = slope(x);
        let dx = (arc_length(x) - s) / (1.0 + t * t).sqrt();
        x -= dx;
        if dx.abs() < 1e-14 * SPAN {
            break;
        }
    }
    x
}

/// The pinned sinusoidal arch with `n` equal elements in arc length, and the nodal forces of the
/// load `sin(k x)` per unit horizontal length along -e2 (two Gauss points per element).
fn sinusoidal_arch(n: usize) -> (Rod, Vec<f64>) {
    let section = Section::rectangular(1.2e4, 0.2, 1e-6, 1.0, 1.0);
    let length = arc_length(SPAN);
    // The element data (length, exact tangent angle at the Gauss points) is all the geometry the
    // rod's mechanics uses; a straight curve of the same length provides the uniform mesh.
    let mut rod = Rod::new(ReferenceCurve::Straight { length }, section, 0.0, n);
    let mut q = vec![0.0; rod.dofs()];
    for e in 0..n {
        let l = rod.elements[e].length;
        let mut alphas = [0.0; 2];
        for (g, &xi) in GAUSS_POINTS.iter().enumerate() {
            let (na, nb) = shape_functions(xi);
            let x = abscissa(rod.node_s[e] + nb * l);
            let alpha = slope(x).atan();
            alphas[g] = alpha;
            // Load per unit arc length: sin(k x) dx/ds; Gauss weight 1 times l/2.
            let load = (PI * x / SPAN).sin() * alpha.cos() * 0.5 * l;
            q[3 * e + U2] -= na * load;
            q[3 * (e + 1) + U2] -= nb * load;
        }
        rod.elements[e] = Element::new(l, alphas);
    }
    let last = rod.last_node();
    for node in [0, last] {
        rod.fix(node, U1);
        rod.fix(node, U2);
    }
    (rod, q)
}

/// Shallow-arch closed form: the limit load amplitude and the crown displacement there.
fn shallow_limit(section: &Section) -> (f64, f64) {
    let k = PI / SPAN;
    let r2 = section.ei / section.ea;
    let a = ((RISE * RISE - 4.0 * r2) / 3.0).sqrt();
    let q = section.ei * k.powi(4) * (RISE - a)
        + section.ea * k.powi(4) * a * (RISE * RISE - a * a) / 4.0;
    (q, a - RISE)
}

#[test]
fn sinusoidal_arch_snaps_at_the_shallow_arch_limit_load() {
    let section = Section::rectangular(1.2e4, 0.2, 1e-6, 1.0, 1.0);
    let (q_exact, w_exact) = shallow_limit(&section);
    println!(
        "shallow-arch closed form: limit load q0 = {q_exact:.6e}, crown deflection {w_exact:.5}"
    );
    println!(
        "elements   limit load   rel. to closed form   crown w at limit   change from coarser"
    );
    let mut loads = Vec::new();
    let mut crown = 0.0;
    for n in [10, 20, 40, 80] {
        let (rod, q) = sinusoidal_arch(n);
        let u0 = vec![0.0; rod.dofs()];
        let mut settings = ContinuationSettings::for_rod(&rod, 3.0 * q_exact);
        settings.max_displacement = 3.0 * RISE;
        let path = follow_path(&rod, &u0, 0.0, &q, &settings);
        let critical = refine_critical_points(&rod, &q, &path, &settings);
        let first = critical.first().expect("a critical point on the path");
        // The symmetric limit point comes first (e/r < sqrt(22)); the continuation turns there.
        assert_eq!(first.kind, CriticalKind::LimitPoint, "{critical:?}");
        let w = rod.interpolate(&first.u, rod.midspan(), U2);
        let change = loads
            .last()
            .map_or(f64::NAN, |&l: &f64| (first.load - l) / first.load);
        println!(
            "{n:8}   {:.6e}   {:+.3e}            {w:+.5}           {change:+.2e}",
            first.load,
            first.load / q_exact - 1.0
        );
        loads.push(first.load);
        crown = w;
    }
    // Second-order mesh convergence of the limit load (the change shrinks by about 4).
    let d: Vec<f64> = loads.windows(2).map(|p| p[1] - p[0]).collect();
    assert!(
        (3.0..5.0).contains(&(d[1] / d[2])),
        "mesh convergence ratios {d:?}"
    );
    // Against the closed form, within shallow theory's own neglected terms (see the top).
    let finest = *loads.last().unwrap();
    assert!(
        (finest / q_exact - 1.0).abs() < 1e-2,
        "limit load {finest} vs {q_exact}"
    );
    assert!(
        (crown / w_exact - 1.0).abs() < 1e-2,
        "crown deflection {crown} vs {w_exact}"
    );
}
