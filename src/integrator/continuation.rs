//! Static path following by the arc-length method (Crisfield's cylindrical constraint): the load
//! factor `lambda` of a reference load `q` is an unknown, and each increment has a fixed length
//! `|du| = dl` in displacement space, so the path passes limit points (load maxima) and
//! snap-backs. Stability along the path comes from the inertia of the tangent (negative
//! eigenvalues of the factored block-tridiagonal matrix): a change of that count marks a critical
//! point, a limit point if `lambda` turns there, a bifurcation point otherwise.
//!
//! [`refine_critical_points`] locates each critical point to round-off by bisection on the arc
//! length of the increment that crossed it (the inertia is evaluated at re-solved points of the
//! path), and classifies it by the tangent: at a limit point the load component of the path
//! tangent changes sign (the turn), at a bifurcation it does not. [`follow_both_ways`] traces the
//! path with increasing and decreasing load from the start and joins the two halves;
//! [`equilibria_at_load`] finds where the path crosses a given load (e.g. the zero-load
//! equilibria of an arch). Note: on a perfectly symmetric structure the path stays on the
//! symmetric branch through a symmetry-breaking bifurcation (the asymmetric branch is only
//! reached with an imperfection).
use super::newton::{inf_norm, NewtonSettings};
use crate::model::Rod;
use crate::solver::BlockTridiagonal;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContinuationSettings {
    /// First arc length (a displacement norm).
    pub arc_length: f64,
    pub min_arc_length: f64,
    pub max_arc_length: f64,
    /// Newton iterations aimed at per increment (the arc length adapts to it).
    pub target_iterations: u32,
    /// Stop after this many points.
    pub max_points: usize,
    /// Stop when `|lambda|` exceeds this.
    pub max_load: f64,
    /// Stop when the largest displacement exceeds this.
    pub max_displacement: f64,
    /// +1: start with increasing load, -1: decreasing.
    pub initial_direction: f64,
    pub newton: NewtonSettings,
}

impl ContinuationSettings {
    pub fn for_rod(rod: &Rod, max_load: f64) -> ContinuationSettings {
        let length = rod.curve.length();
        ContinuationSettings {
            arc_length: 1e-3 * length,
            min_arc_length: 1e-7 * length,
            max_arc_length: 5e-3 * length,
            target_iterations: 5,
            max_points: 2000,
            max_load,
            max_displacement: length,
            initial_direction: 1.0,
            newton: NewtonSettings {
                max_iterations: 20,
                ..NewtonSettings::tight(length)
            },
        }
    }
}

/// A converged point of the equilibrium path.
#[derive(Clone, Debug, PartialEq)]
pub struct PathPoint {
    pub load: f64,
    pub u: Vec<f64>,
    /// Negative eigenvalues of the tangent: 0 on stable branches.
    pub negative_eigenvalues: usize,
    pub iterations: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CriticalKind {
    /// The load factor has a local extremum (snap-through under load control).
    LimitPoint,
    /// The stability changes without a turn in the load (a branch crosses the path).
    Bifurcation,
}

/// A critical point between path points `index - 1` and `index`; `load` is interpolated (for a
/// limit point: the vertex of the parabola through the three points around the turn).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CriticalPoint {
    pub index: usize,
    pub kind: CriticalKind,
    pub load: f64,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Path {
    pub points: Vec<PathPoint>,
    /// Why the continuation stopped.
    pub stop_reason: String,
}

/// Buffers of the continuation.
struct Work {
    jac: BlockTridiagonal,
    f: Vec<f64>,
    du_q: Vec<f64>,
    du_r: Vec<f64>,
}

impl Work {
    /// Factors `K_T(u)` and returns `f_int(u)` in `self.f`.
    fn factor(&mut self, rod: &Rod, u: &[f64]) -> bool {
        self.jac.set_zero();
        rod.internal_force_and_tangent(u, &mut self.f, &mut self.jac, 1.0);
        self.jac.constrain(&rod.fixed);
        self.jac.factor().is_ok()
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Follows the equilibrium path `f_int(u) = lambda q` from the equilibrium `u0` at `lambda0`.
pub fn follow_path(
    rod: &Rod,
    u0: &[f64],
    load0: f64,
    q: &[f64],
    settings: &ContinuationSettings,
) -> Path {
    let n = rod.dofs();
    let mut q = q.to_vec();
    rod.zero_constrained(&mut q);
    let mut w = Work {
        jac: BlockTridiagonal::new(rod.nodes()),
        f: vec![0.0; n],
        du_q: vec![0.0; n],
        du_r: vec![0.0; n],
    };
    let mut path = Path::default();
    if !w.factor(rod, u0) {
        path.stop_reason = "singular tangent at the start".into();
        return path;
    }
    path.points.push(PathPoint {
        load: load0,
        u: u0.to_vec(),
        negative_eigenvalues: w.jac.negative_eigenvalues(),
        iterations: 0,
    });
    let mut dl = settings.arc_length;
    let mut previous_du: Option<Vec<f64>> = None;
    let mut du = vec![0.0; n];
    let mut u = vec![0.0; n];
    while path.points.len() < settings.max_points {
        let last = path.points.last().expect("path starts with a point");
        // Predictor along the tangent K du_q = q, oriented like the previous increment.
        if !w.factor(rod, &last.u) {
            path.stop_reason = "singular tangent on the path (exactly at a critical point)".into();
            return path;
        }
        w.du_q.copy_from_slice(&q);
        w.jac.solve_in_place(&mut w.du_q);
        let norm_q = dot(&w.du_q, &w.du_q).sqrt();
        let sign = match &previous_du {
            Some(prev) => dot(prev, &w.du_q).signum(),
            None => settings.initial_direction.signum(),
        };
        let mut dload = sign * dl / norm_q;
        du.iter_mut().zip(&w.du_q).for_each(|(d, t)| *d = dload * t);
        match correct(
            rod, &q, last, &mut du, &mut dload, dl, &mut u, &mut w, settings,
        ) {
            Some(iterations) => {
                let load = last.load + dload;
                let stable = w.factor(rod, &u);
                let negative = if stable {
                    w.jac.negative_eigenvalues()
                } else {
                    usize::MAX
                };
                path.points.push(PathPoint {
                    load,
                    u: u.clone(),
                    negative_eigenvalues: negative,
                    iterations,
                });
                previous_du = Some(du.clone());
                let ratio = settings.target_iterations as f64 / iterations.max(1) as f64;
                dl = (dl * ratio.sqrt().clamp(0.5, 2.0))
                    .clamp(settings.min_arc_length, settings.max_arc_length);
                if load.abs() > settings.max_load {
                    path.stop_reason = format!("load factor beyond {}", settings.max_load);
                    return path;
                }
                if inf_norm(&u) > settings.max_displacement {
                    path.stop_reason = format!("displacement beyond {}", settings.max_displacement);
                    return path;
                }
            }
            None => {
                dl *= 0.25;
                if dl < settings.min_arc_length {
                    path.stop_reason = "arc length below its minimum: Newton fails".into();
                    return path;
                }
            }
        }
    }
    path.stop_reason = format!("{} points", settings.max_points);
    path
}

/// Newton corrector on the arc-length constraint `|du| = dl`; returns the iterations, with
/// `u = u_last + du` and `dload` updated, or `None` if it fails.
#[allow(clippy::too_many_arguments)]
fn correct(
    rod: &Rod,
    q: &[f64],
    last: &PathPoint,
    du: &mut [f64],
    dload: &mut f64,
    dl: f64,
    u: &mut [f64],
    w: &mut Work,
    settings: &ContinuationSettings,
) -> Option<u32> {
    for iteration in 1..=settings.newton.max_iterations {
        u.iter_mut()
            .zip(&last.u)
            .zip(du.iter())
            .for_each(|((x, a), d)| *x = a + d);
        if !w.factor(rod, u) {
            return None;
        }
        let load = last.load + *dload;
        // Residual R = f_int - lambda q; du_r = -K^-1 R, du_q = K^-1 q.
        w.du_r
            .iter_mut()
            .zip(&w.f)
            .zip(q)
            .for_each(|((r, f), qq)| *r = load * qq - f);
        rod.zero_constrained(&mut w.du_r);
        if w.du_r.iter().any(|x| !x.is_finite()) {
            return None;
        }
        w.jac.solve_in_place(&mut w.du_r);
        w.du_q.copy_from_slice(q);
        w.jac.solve_in_place(&mut w.du_q);
        // |du + du_r + c du_q|^2 = dl^2: a c^2 + b c + k = 0.
        let base: Vec<f64> = du.iter().zip(&w.du_r).map(|(d, r)| d + r).collect();
        let a = dot(&w.du_q, &w.du_q);
        let b = 2.0 * dot(&w.du_q, &base);
        let k = dot(&base, &base) - dl * dl;
        let disc = b * b - 4.0 * a * k;
        if disc < 0.0 || a == 0.0 {
            return None;
        }
        let roots = [
            (-b + disc.sqrt()) / (2.0 * a),
            (-b - disc.sqrt()) / (2.0 * a),
        ];
        // The root whose increment turns least from the current one.
        let score = |c: f64| dot(du, &base) + c * dot(du, &w.du_q);
        let c = if score(roots[0]) >= score(roots[1]) {
            roots[0]
        } else {
            roots[1]
        };
        let mut correction = 0.0f64;
        for ((d, bb), t) in du.iter_mut().zip(&base).zip(&w.du_q) {
            let new = bb + c * t;
            correction = correction.max((new - *d).abs());
            *d = new;
        }
        *dload += c;
        if settings.newton.converged(correction, inf_norm(du)) {
            u.iter_mut()
                .zip(&last.u)
                .zip(du.iter())
                .for_each(|((x, a), d)| *x = a + d);
            return Some(iteration);
        }
    }
    None
}

/// The critical points of a path: where the number of negative tangent eigenvalues changes.
pub fn critical_points(path: &Path) -> Vec<CriticalPoint> {
    let p = &path.points;
    let mut found = Vec::new();
    for i in 1..p.len() {
        if p[i].negative_eigenvalues == p[i - 1].negative_eigenvalues {
            continue;
        }
        let turns = |j: usize| {
            j >= 1
                && j + 1 < p.len()
                && (p[j].load - p[j - 1].load) * (p[j + 1].load - p[j].load) < 0.0
        };
        // Where the load turns next to the change, refine by a parabola through three points.
        let vertex = [i - 1, i].into_iter().find(|&j| turns(j));
        match vertex {
            Some(j) => {
                let (y0, y1, y2) = (p[j - 1].load, p[j].load, p[j + 1].load);
                let curvature = y0 - 2.0 * y1 + y2;
                let load = if curvature != 0.0 {
                    y1 - 0.125 * (y2 - y0).powi(2) / curvature
                } else {
                    y1
                };
                found.push(CriticalPoint {
                    index: i,
                    kind: CriticalKind::LimitPoint,
                    load,
                });
            }
            None => found.push(CriticalPoint {
                index: i,
                kind: CriticalKind::Bifurcation,
                load: 0.5 * (p[i].load + p[i - 1].load),
            }),
        }
    }
    found
}

/// A critical point located to round-off: the load at the change of the tangent's inertia, the
/// state there (the last point before the change) and the inertia on both sides.
#[derive(Clone, Debug, PartialEq)]
pub struct RefinedCritical {
    /// The path increment (`index - 1` to `index`) that crossed it.
    pub index: usize,
    pub kind: CriticalKind,
    pub load: f64,
    pub u: Vec<f64>,
    pub negative_before: usize,
    pub negative_after: usize,
    /// Arc length of the bracket left by the bisection.
    pub bracket: f64,
}

/// A point of the path re-solved at arc length `s` from `path.points[i - 1]` towards
/// `path.points[i]` (secant predictor, then the arc-length corrector).
fn resolve_partial(
    rod: &Rod,
    q: &[f64],
    path: &Path,
    i: usize,
    s: f64,
    w: &mut Work,
    settings: &ContinuationSettings,
) -> Option<PathPoint> {
    let (a, b) = (&path.points[i - 1], &path.points[i]);
    let chord = dot_diff(&b.u, &a.u).sqrt();
    if chord == 0.0 {
        return None;
    }
    let f = s / chord;
    let mut du: Vec<f64> = b.u.iter().zip(&a.u).map(|(x, y)| f * (x - y)).collect();
    let mut dload = f * (b.load - a.load);
    let mut u = vec![0.0; rod.dofs()];
    let iterations = correct(rod, q, a, &mut du, &mut dload, s, &mut u, w, settings)?;
    let negative = if w.factor(rod, &u) {
        w.jac.negative_eigenvalues()
    } else {
        usize::MAX
    };
    Some(PathPoint {
        load: a.load + dload,
        u,
        negative_eigenvalues: negative,
        iterations,
    })
}

fn dot_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Bisection on the arc length of increment `i` for the first point where `flip` turns true
/// (`flip` is false at `path.points[i - 1]`, true at `path.points[i]`). Returns the last points
/// before and after, and the bracket length.
fn bisect(
    rod: &Rod,
    q: &[f64],
    path: &Path,
    i: usize,
    settings: &ContinuationSettings,
    flip: impl Fn(&PathPoint) -> bool,
) -> (PathPoint, PathPoint, f64) {
    let mut w = Work {
        jac: BlockTridiagonal::new(rod.nodes()),
        f: vec![0.0; rod.dofs()],
        du_q: vec![0.0; rod.dofs()],
        du_r: vec![0.0; rod.dofs()],
    };
    let chord = dot_diff(&path.points[i].u, &path.points[i - 1].u).sqrt();
    let (mut lo, mut hi) = (0.0, chord);
    let mut before = path.points[i - 1].clone();
    let mut after = path.points[i].clone();
    for _ in 0..60 {
        if hi - lo <= 1e-13 * chord.max(1e-300) + 1e-15 * rod.curve.length() {
            break;
        }
        let mid = 0.5 * (lo + hi);
        match resolve_partial(rod, q, path, i, mid, &mut w, settings) {
            Some(p) if flip(&p) => {
                hi = mid;
                after = p;
            }
            Some(p) => {
                lo = mid;
                before = p;
            }
            None => break,
        }
    }
    (before, after, hi - lo)
}

/// `K_T(u)^-1 q` (None if singular).
fn tangent_direction(rod: &Rod, q: &[f64], u: &[f64]) -> Option<Vec<f64>> {
    let mut w = Work {
        jac: BlockTridiagonal::new(rod.nodes()),
        f: vec![0.0; rod.dofs()],
        du_q: q.to_vec(),
        du_r: vec![0.0; rod.dofs()],
    };
    if !w.factor(rod, u) {
        return None;
    }
    w.jac.solve_in_place(&mut w.du_q);
    Some(w.du_q)
}

/// Every critical point of `path` (a change of the number of negative tangent eigenvalues between
/// consecutive points) located by bisection on the arc length, and classified by the tangent:
/// a limit point where the load component of the oriented path tangent changes sign.
pub fn refine_critical_points(
    rod: &Rod,
    q: &[f64],
    path: &Path,
    settings: &ContinuationSettings,
) -> Vec<RefinedCritical> {
    let mut q = q.to_vec();
    rod.zero_constrained(&mut q);
    let p = &path.points;
    let mut found = Vec::new();
    for i in 1..p.len() {
        let n0 = p[i - 1].negative_eigenvalues;
        if p[i].negative_eigenvalues == n0 || n0 == usize::MAX {
            continue;
        }
        let (before, after, bracket) = bisect(rod, &q, path, i, settings, |pt| {
            pt.negative_eigenvalues != n0
        });
        // Orientation of the path: the increment's chord. dlambda/ds has the sign of
        // chord . K^-1 q (the tangent is (K^-1 q, 1) up to a factor).
        let chord: Vec<f64> = p[i].u.iter().zip(&p[i - 1].u).map(|(a, b)| a - b).collect();
        let sign = |u: &[f64]| tangent_direction(rod, &q, u).map(|t| dot(&chord, &t).signum());
        let turns = match (sign(&before.u), sign(&after.u)) {
            (Some(a), Some(b)) => a != b,
            // Fall back on the loads around the point.
            _ => (before.load - p[i - 1].load) * (p[i].load - after.load) < 0.0,
        };
        found.push(RefinedCritical {
            index: i,
            kind: if turns {
                CriticalKind::LimitPoint
            } else {
                CriticalKind::Bifurcation
            },
            load: 0.5 * (before.load + after.load),
            u: before.u.clone(),
            negative_before: n0,
            negative_after: after.negative_eigenvalues,
            bracket,
        });
    }
    found
}

/// The path traced both ways from `u0` at `load0` (first increasing, then decreasing load, each
/// with `settings` but its own `initial_direction`), joined into one path that runs from the end
/// of the decreasing half through the start to the end of the increasing half. The start point
/// is at index `.1`.
pub fn follow_both_ways(
    rod: &Rod,
    u0: &[f64],
    load0: f64,
    q: &[f64],
    settings: &ContinuationSettings,
) -> (Path, usize) {
    let up = follow_path(
        rod,
        u0,
        load0,
        q,
        &ContinuationSettings {
            initial_direction: 1.0,
            ..*settings
        },
    );
    let down = follow_path(
        rod,
        u0,
        load0,
        q,
        &ContinuationSettings {
            initial_direction: -1.0,
            ..*settings
        },
    );
    let start = down.points.len().saturating_sub(1);
    let mut points: Vec<PathPoint> = down.points.into_iter().rev().collect();
    points.extend(up.points.into_iter().skip(usize::from(!points.is_empty())));
    (
        Path {
            points,
            stop_reason: format!(
                "decreasing load: {}; increasing load: {}",
                down.stop_reason, up.stop_reason
            ),
        },
        start,
    )
}

/// An equilibrium of the path at a prescribed load.
#[derive(Clone, Debug, PartialEq)]
pub struct Equilibrium {
    pub load: f64,
    pub u: Vec<f64>,
    pub negative_eigenvalues: usize,
    /// Index of the path point after the crossing (or at it).
    pub index: usize,
}

/// Every equilibrium where `path` crosses `load`: bisection on the arc length of the crossing
/// increment, then Newton at exactly `load` (fixed load) from the bracketing point.
pub fn equilibria_at_load(
    rod: &Rod,
    q: &[f64],
    path: &Path,
    load: f64,
    settings: &ContinuationSettings,
) -> Vec<Equilibrium> {
    let mut q = q.to_vec();
    rod.zero_constrained(&mut q);
    let p = &path.points;
    let mut found = Vec::new();
    let side = |x: f64| (x - load).signum();
    for i in 0..p.len() {
        let start = if p[i].load == load {
            Some(p[i].u.clone())
        } else if i > 0 && p[i - 1].load != load && side(p[i - 1].load) != side(p[i].load) {
            let s0 = side(p[i - 1].load);
            let (before, after, _) = bisect(rod, &q, path, i, settings, |pt| side(pt.load) != s0);
            Some(if (before.load - load).abs() <= (after.load - load).abs() {
                before.u
            } else {
                after.u
            })
        } else {
            None
        };
        let Some(mut u) = start else { continue };
        let mut solver = super::StaticSolver::new(rod);
        let f_ext: Vec<f64> = q.iter().map(|x| load * x).collect();
        if solver.solve(rod, &mut u, &f_ext).is_err() {
            continue;
        }
        let mut jac = BlockTridiagonal::new(rod.nodes());
        let mut f = vec![0.0; rod.dofs()];
        rod.internal_force_and_tangent(&u, &mut f, &mut jac, 1.0);
        jac.constrain(&rod.fixed);
        let negative = if jac.factor().is_ok() {
            jac.negative_eigenvalues()
        } else {
            usize::MAX
        };
        found.push(Equilibrium {
            load,
            u,
            negative_eigenvalues: negative,
            index: i,
        });
    }
    found
}
