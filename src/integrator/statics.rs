//! Static equilibrium `f_int(u) = f_ext` by Newton with the consistent tangent. Constrained dofs
//! keep the values they have in `u` (prescribed displacements are set by the caller).
use super::newton::{newton_correction, Factorization, NewtonFailure, NewtonSettings, NewtonStats};
use crate::model::Assembly;
use crate::solver::SystemMatrix;

/// Buffers of a static solve, reused between solves.
#[derive(Clone, Debug)]
pub struct StaticSolver<A: Assembly = crate::model::Rod> {
    pub settings: NewtonSettings,
    jac: A::Matrix,
    residual: Vec<f64>,
    start: Vec<f64>,
}

impl<A: Assembly> StaticSolver<A> {
    pub fn new(rod: &A) -> StaticSolver<A> {
        StaticSolver {
            settings: NewtonSettings::tight(rod.length_scale()),
            jac: rod.new_matrix(),
            residual: vec![0.0; rod.dofs()],
            start: vec![0.0; rod.dofs()],
        }
    }

    /// Solves `f_int(u) = f_ext` starting from `u`; on failure `u` is restored.
    pub fn solve(
        &mut self,
        rod: &A,
        u: &mut [f64],
        f_ext: &[f64],
    ) -> Result<NewtonStats, NewtonFailure> {
        self.start.copy_from_slice(u);
        let result = self.iterate(rod, u, f_ext);
        if result.is_err() {
            u.copy_from_slice(&self.start);
        }
        result
    }

    fn iterate(
        &mut self,
        rod: &A,
        u: &mut [f64],
        f_ext: &[f64],
    ) -> Result<NewtonStats, NewtonFailure> {
        let mut stats = NewtonStats::default();
        loop {
            self.jac.set_zero();
            rod.internal_force_and_tangent(u, &mut self.residual, &mut self.jac, 1.0);
            rod.add_static_regularization(u, &mut self.jac);
            for (r, f) in self.residual.iter_mut().zip(f_ext) {
                *r -= f;
            }
            let (residual_norm, mut correction) = newton_correction(
                rod,
                &mut self.jac,
                &mut self.residual,
                None,
                stats.iterations,
                Factorization::General,
            )?;
            // A correction that closes an open stop or a slack cable stops just past it.
            let limit = rod.static_step_limit(u, &self.residual);
            if limit < 1.0 {
                self.residual.iter_mut().for_each(|d| *d *= limit);
                correction *= limit;
            }
            for (x, d) in u.iter_mut().zip(&self.residual) {
                *x += d;
            }
            stats.record(residual_norm, correction);
            let moved = u
                .iter()
                .zip(&self.start)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            if limit == 1.0 && self.settings.converged(correction, moved) {
                return Ok(stats);
            }
            if stats.iterations >= self.settings.max_iterations || !correction.is_finite() {
                return Err(NewtonFailure::NotConverged {
                    iterations: stats.iterations,
                    correction,
                });
            }
        }
    }

    /// Reaches `f_int(u) = f_ext` through `steps` equal load steps `k / steps * f_ext` (each
    /// started from the previous solution); on failure `u` is restored and the error names the
    /// load step.
    pub fn solve_ramped(
        &mut self,
        rod: &A,
        u: &mut [f64],
        f_ext: &[f64],
        steps: usize,
    ) -> Result<NewtonStats, (usize, NewtonFailure)> {
        let initial = u.to_vec();
        let mut load = vec![0.0; f_ext.len()];
        let mut stats = NewtonStats::default();
        for k in 1..=steps.max(1) {
            let factor = k as f64 / steps.max(1) as f64;
            load.iter_mut()
                .zip(f_ext)
                .for_each(|(l, f)| *l = factor * f);
            match self.solve(rod, u, &load) {
                Ok(s) => stats = s,
                Err(e) => {
                    u.copy_from_slice(&initial);
                    return Err((k, e));
                }
            }
        }
        Ok(stats)
    }

    /// The number of negative eigenvalues of the tangent at `u` (constraints removed): zero
    /// for a stable equilibrium. `None` if the tangent is singular to working precision.
    pub fn negative_eigenvalues(&mut self, rod: &A, u: &[f64]) -> Option<usize> {
        self.jac.set_zero();
        rod.internal_force_and_tangent(u, &mut self.residual, &mut self.jac, 1.0);
        rod.constrain(&mut self.jac);
        self.jac.factor_with_inertia().ok()?;
        Some(self.jac.negative_eigenvalues())
    }
}
