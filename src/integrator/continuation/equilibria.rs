//! The equilibria of a traced path at a prescribed load (e.g. the zero-load equilibria of an
//! arch): each crossing bracketed by bisection, then solved by Newton at exactly that load.
use super::bisection::bisect;
use super::{ContinuationSettings, Path};
use crate::model::Assembly;
use crate::solver::SystemMatrix;

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
pub fn equilibria_at_load<A: Assembly>(
    rod: &A,
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
        let mut solver = crate::integrator::StaticSolver::new(rod);
        let f_ext: Vec<f64> = q.iter().map(|x| load * x).collect();
        if solver.solve(rod, &mut u, &f_ext).is_err() {
            continue;
        }
        let mut jac = rod.new_matrix();
        let mut f = vec![0.0; rod.dofs()];
        rod.internal_force_and_tangent(&u, &mut f, &mut jac, 1.0);
        rod.constrain(&mut jac);
        let negative = if jac.factor_with_inertia().is_ok() {
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
