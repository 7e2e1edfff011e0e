//! Bisection on the arc length of one increment of a traced path: the points in between are
//! re-solved on the path (secant predictor, arc-length corrector), so a change along the
//! increment (of the tangent's inertia, of the side of a load) is bracketed to round-off.
use super::{correct, ContinuationSettings, Path, PathPoint, Work};
use crate::model::Assembly;
use crate::solver::SystemMatrix;

/// A point of the path re-solved at arc length `s` from `path.points[i - 1]` towards
/// `path.points[i]` (secant predictor, then the arc-length corrector).
fn resolve_partial<A: Assembly>(
    rod: &A,
    q: &[f64],
    path: &Path,
    i: usize,
    s: f64,
    w: &mut Work<A>,
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
pub(super) fn bisect<A: Assembly>(
    rod: &A,
    q: &[f64],
    path: &Path,
    i: usize,
    settings: &ContinuationSettings,
    flip: impl Fn(&PathPoint) -> bool,
) -> (PathPoint, PathPoint, f64) {
    let mut w = Work::new(rod);
    let chord = dot_diff(&path.points[i].u, &path.points[i - 1].u).sqrt();
    let (mut lo, mut hi) = (0.0, chord);
    let mut before = path.points[i - 1].clone();
    let mut after = path.points[i].clone();
    for _ in 0..60 {
        if hi - lo <= 1e-13 * chord.max(1e-300) + 1e-15 * rod.length_scale() {
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
