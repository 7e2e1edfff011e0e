//! Newton iteration settings, statistics and failures shared by the static and dynamic solvers.
use crate::model::Assembly;
use crate::solver::vector::{inf_norm, update_and_norm};
use crate::solver::{SingularMatrix, SystemMatrix};
use std::fmt;

/// When Newton stops. Convergence: `|delta|_inf <= relative * |increment|_inf + absolute`, where
/// `increment` is the step's total change so far; `absolute` is a length (about round-off of the
/// positions of a rod of this size) so that a step that barely moves still converges.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonSettings {
    pub max_iterations: u32,
    pub relative: f64,
    pub absolute: f64,
}

impl NewtonSettings {
    /// The tight tolerances of model.md, for a rod of characteristic length `length`.
    pub fn tight(length: f64) -> NewtonSettings {
        NewtonSettings {
            max_iterations: 25,
            relative: 1e-10,
            absolute: 1e-13 * length.max(1e-3),
        }
    }

    pub fn converged(&self, correction: f64, increment: f64) -> bool {
        correction <= self.relative * increment + self.absolute
    }
}

/// Capacity of the per-iteration history kept without allocation.
pub const HISTORY: usize = 32;

/// What a converged Newton solve did; `residuals[..iterations]` are the residual norms (inf norm,
/// constrained dofs excluded) at the start of each iteration, `corrections` the Newton updates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonStats {
    /// Corrections applied (Newton and chord).
    pub iterations: u32,
    /// Jacobians assembled and factored (Newton corrections and exact tangent-map solves).
    pub factorizations: u32,
    /// Of those, the factorizations for the tangent map (where its refinement could not be
    /// trusted: `tangent_map.rs`).
    pub tangent_factorizations: u32,
    pub residuals: [f64; HISTORY],
    pub corrections: [f64; HISTORY],
}

impl Default for NewtonStats {
    fn default() -> Self {
        NewtonStats {
            iterations: 0,
            factorizations: 0,
            tangent_factorizations: 0,
            residuals: [0.0; HISTORY],
            corrections: [0.0; HISTORY],
        }
    }
}

impl NewtonStats {
    pub fn record(&mut self, residual: f64, correction: f64) {
        let i = self.iterations as usize;
        if i < HISTORY {
            self.residuals[i] = residual;
            self.corrections[i] = correction;
        }
        self.iterations += 1;
    }

    pub fn residual_history(&self) -> &[f64] {
        &self.residuals[..(self.iterations as usize).min(HISTORY)]
    }

    pub fn correction_history(&self) -> &[f64] {
        &self.corrections[..(self.iterations as usize).min(HISTORY)]
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum NewtonFailure {
    NotConverged { iterations: u32, correction: f64 },
    Singular(SingularMatrix),
    NonFinite { iteration: u32 },
}

impl fmt::Display for NewtonFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NewtonFailure::NotConverged { iterations, correction } => write!(
                f,
                "Newton did not converge in {iterations} iterations (last correction {correction:.3e})"
            ),
            NewtonFailure::Singular(s) => write!(f, "Newton: tangent matrix has a {s}"),
            NewtonFailure::NonFinite { iteration } => {
                write!(f, "Newton: non-finite residual at iteration {iteration}")
            }
        }
    }
}

impl std::error::Error for NewtonFailure {}

impl From<SingularMatrix> for NewtonFailure {
    fn from(s: SingularMatrix) -> Self {
        NewtonFailure::Singular(s)
    }
}

/// How a Newton correction factors its Jacobian.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Factorization {
    /// Block LU: for the tangents of statics, which for very slender rods are ill-conditioned
    /// (L/h = 1e4: the cantilever of tests/suite/stability_thin.rs), where its round-off is the
    /// smaller (the symmetric elimination's stalls Newton at 8e-12 there).
    General,
    /// The symmetric elimination, a third cheaper: for the time steps' Jacobians, which the
    /// mass keeps well-conditioned.
    Symmetric,
}

/// One Newton correction: with the residual `R` in `residual` and the Jacobian assembled in
/// `jac` (constraints not yet applied), removes the constrained dofs, factors and overwrites
/// `residual` with `-J^-1 R`, and `also` (if given) with `J^-1 also` in the same pass. Returns
/// the norms of `R` (free dofs) and of the correction.
pub(crate) fn newton_correction<A: Assembly>(
    rod: &A,
    jac: &mut A::Matrix,
    residual: &mut [f64],
    also: Option<&mut [f64]>,
    iteration: u32,
    factorization: Factorization,
) -> Result<(f64, f64), NewtonFailure> {
    rod.zero_constrained(residual);
    // Constrained entries are zero now: the norm over all is the norm over the free dofs.
    let residual_norm = negate_and_norm(residual);
    if !residual_norm.is_finite() {
        return Err(NewtonFailure::NonFinite { iteration });
    }
    rod.constrain(jac);
    match factorization {
        Factorization::General => jac.factor()?,
        Factorization::Symmetric => jac.factor_symmetric()?,
    }
    solve(jac, residual, also);
    Ok((residual_norm, inf_norm(residual)))
}

/// A chord correction: with the residual `R` in `residual` and `jac` factored earlier (at a
/// nearby iterate), overwrites `residual` with `-J^-1 R`, and `also` (if given) with
/// `J^-1 also` in the same pass. Returns the norms of `R` (free dofs) and of the correction,
/// or `None` when `R` is not finite.
pub(crate) fn chord_correction<A: Assembly>(
    rod: &A,
    jac: &A::Matrix,
    residual: &mut [f64],
    also: Option<&mut [f64]>,
) -> Option<(f64, f64)> {
    rod.zero_constrained(residual);
    // Constrained entries are zero now: the norm over all is the norm over the free dofs.
    let residual_norm = negate_and_norm(residual);
    if !residual_norm.is_finite() {
        return None;
    }
    solve(jac, residual, also);
    Some((residual_norm, inf_norm(residual)))
}

/// `x = J^-1 x`, and the same for `also` in one pass over the factors.
fn solve<M: SystemMatrix>(jac: &M, x: &mut [f64], also: Option<&mut [f64]>) {
    match also {
        Some(y) => jac.solve_pair(x, y),
        None => jac.solve_in_place(x),
    }
}

/// Negates `x` and returns its largest magnitude (NaN if it holds a NaN): one pass.
fn negate_and_norm(x: &mut [f64]) -> f64 {
    update_and_norm(x, |_, v| -v)
}
