//! Critical points of a traced path, where the number of negative tangent eigenvalues changes:
//! located coarsely between path points ([`critical_points`]) or to round-off by bisection
//! ([`refine_critical_points`]), and classified as limit points or bifurcations.
use super::bisection::bisect;
use super::{dot, ContinuationSettings, Path, Work};
use crate::model::Assembly;
use crate::solver::SystemMatrix;

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

/// `K_T(u)^-1 q` (None if singular).
fn tangent_direction<A: Assembly>(rod: &A, q: &[f64], u: &[f64]) -> Option<Vec<f64>> {
    let mut w = Work::new(rod);
    w.du_q.copy_from_slice(q);
    if !w.factor(rod, u) {
        return None;
    }
    w.jac.solve_in_place(&mut w.du_q);
    Some(w.du_q)
}

/// Every critical point of `path` (a change of the number of negative tangent eigenvalues between
/// consecutive points) located by bisection on the arc length, and classified by the tangent:
/// a limit point where the load component of the oriented path tangent changes sign.
pub fn refine_critical_points<A: Assembly>(
    rod: &A,
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
        // chord . K^-1 q (the tangent is (K^-1 q, 1) up to a factor), taken at the path's
        // points on either side: at the bisection's ends, a bracket of 1e-14 from the
        // critical point, K is singular to round-off and the sign of its small eigenvalue
        // depends on the order of elimination.
        let chord: Vec<f64> = p[i].u.iter().zip(&p[i - 1].u).map(|(a, b)| a - b).collect();
        let sign = |u: &[f64]| tangent_direction(rod, &q, u).map(|t| dot(&chord, &t).signum());
        let turns = match (sign(&p[i - 1].u), sign(&p[i].u)) {
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
