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
//!
//! This file holds the path following itself (predictor, arc-length corrector, step-size
//! control); `critical.rs` finds and classifies the critical points of a traced path,
//! `equilibria.rs` the equilibria at a given load, both by the bisection of `bisection.rs`.
mod bisection;
mod critical;
mod equilibria;

pub use critical::{
    critical_points, refine_critical_points, CriticalKind, CriticalPoint, RefinedCritical,
};
pub use equilibria::{equilibria_at_load, Equilibrium};

use super::newton::NewtonSettings;
use crate::model::Assembly;
use crate::solver::vector::inf_norm;
use crate::solver::SystemMatrix;

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
    pub fn for_rod<A: Assembly>(rod: &A, max_load: f64) -> ContinuationSettings {
        let length = rod.length_scale();
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

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Path {
    pub points: Vec<PathPoint>,
    /// Why the continuation stopped.
    pub stop_reason: String,
}

/// Buffers of the continuation.
struct Work<A: Assembly> {
    jac: A::Matrix,
    f: Vec<f64>,
    du_q: Vec<f64>,
    du_r: Vec<f64>,
}

impl<A: Assembly> Work<A> {
    fn new(rod: &A) -> Work<A> {
        Work {
            jac: rod.new_matrix(),
            f: vec![0.0; rod.dofs()],
            du_q: vec![0.0; rod.dofs()],
            du_r: vec![0.0; rod.dofs()],
        }
    }

    /// Factors `K_T(u)` and returns `f_int(u)` in `self.f`.
    fn factor(&mut self, rod: &A, u: &[f64]) -> bool {
        self.jac.set_zero();
        rod.internal_force_and_tangent(u, &mut self.f, &mut self.jac, 1.0);
        rod.constrain(&mut self.jac);
        self.jac.factor_with_inertia().is_ok()
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Follows the equilibrium path `f_int(u) = lambda q` from the equilibrium `u0` at `lambda0`.
pub fn follow_path<A: Assembly>(
    rod: &A,
    u0: &[f64],
    load0: f64,
    q: &[f64],
    settings: &ContinuationSettings,
) -> Path {
    let n = rod.dofs();
    let mut q = q.to_vec();
    rod.zero_constrained(&mut q);
    let mut w = Work::new(rod);
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
fn correct<A: Assembly>(
    rod: &A,
    q: &[f64],
    last: &PathPoint,
    du: &mut [f64],
    dload: &mut f64,
    dl: f64,
    u: &mut [f64],
    w: &mut Work<A>,
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

/// The path traced both ways from `u0` at `load0` (first increasing, then decreasing load, each
/// with `settings` but its own `initial_direction`), joined into one path that runs from the end
/// of the decreasing half through the start to the end of the increasing half. The start point
/// is at index `.1`.
pub fn follow_both_ways<A: Assembly>(
    rod: &A,
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
