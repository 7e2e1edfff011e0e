//! The linear systems of the midpoint rule's tangent map, `J* y = b`, solved inside a step
//! without factoring the converged step's Jacobian `J*` (see `tangent.rs` for the map itself).
//!
//! A step factors the Jacobian `J0` at an iterate of its Newton iteration and ends with a chord
//! correction: a residual evaluation at the next iterate `u1`, solved with `J0`. The
//! convergence test puts `u1` within the solver's tolerance of the converged step, so its
//! Jacobian `J1 = A + K(u1) / 2` (`A = 2/dt^2 M + C/dt`) is `J*` to that tolerance; `J0` is off
//! by the Newton correction, which makes `y1 = J0^-1 b` off by a relative
//! `rho = |J0^-1 (J1 - J0)|`: 1e-7 to 1e-5 at T/180 on the buckled beam, up to 1e-4 at T/128.
//! Iterative refinement, `y <- y + J0^-1 (b - J1 y)`, divides the error by `1/rho` per pass,
//! and its residuals need no assembly: both residual evaluations keep each element's tangent
//! (ten numbers; the sines and cosines are those of the residual), and since `J0 y1 = b`,
//! `b - J1 y1 = -(J1 - J0) y1 = -(K1 - K0) y1 / 2` (`A` cancels), and after each correction
//! `c` the next residual is `-(K1 - K0) c / 2`: the change of the element tangents times a
//! vector, matrix-free, which also keeps the residual free of the cancellation of two full
//! products. A step thus costs one solve per right-hand side with `J0` and one or two
//! refinements, instead of assembling and factoring a second Jacobian.
//!
//! The refinement stops when the error it leaves, estimated like the Newton iteration's from
//! the contraction of its corrections, is below [`TOLERANCE`] of the solution a hundred times
//! over. If it does not contract (or no chord evaluation kept tangents since the current
//! factorization), `J1` is assembled from the kept element tangents and factored: the exact
//! solve. (When the iteration ends on a Newton correction, `J0` is already at an iterate
//! within the tolerance and the first solve is exact.) From [`EXACT_FROM`] systems on, one
//! factorization of `J1` costs less than refining each system, and the step solves exactly.
use crate::model::Assembly;
use crate::solver::vector::inf_norm;
use crate::solver::{SingularMatrix, SystemMatrix};

/// The relative error of a tangent solution that the refinement must estimate to leave: the
/// solver's tolerance 1e-10 with the margin 100 of the Newton iteration's estimate (a solution
/// is exact to 1e-10 even where the estimate is off by a hundred).
pub const TOLERANCE: f64 = 1e-12;
/// Refinements before the exact solve takes over; also where a refinement that does not
/// halve the correction ends them.
const MAX_REFINEMENTS: usize = 4;
/// From this many systems on, a step assembles and factors `J1` once and solves each system
/// once, instead of solving and refining each with `J0`: with one or two refinements per
/// system, a factorization is cheaper from two systems on (callgrind, BuckledBeam, 10
/// elements, T/64: see the README's Lyapunov table).
pub const EXACT_FROM: usize = 2;

/// Right-hand sides of the tangent map, their solutions and the element tangents of the last
/// chord correction, `count` of them (0: the step solves none). Buffers are reserved outside
/// the step loop.
#[derive(Clone, Debug)]
pub struct TangentMap<A: Assembly> {
    count: usize,
    dofs: usize,
    rhs: Vec<f64>,
    solution: Vec<f64>,
    /// The element tangents at the last chord correction's iterate (`K1`).
    tangents: A::Tangents,
    /// The element tangents at the iterate of the current factorization (`K0`).
    newton: A::Tangents,
    /// Whether `tangents` belong to the current factorization (a chord evaluation since).
    tangents_current: bool,
    /// Scratch for the refinement's residual, and the correction before it.
    scratch: Vec<f64>,
    correction: Vec<f64>,
    /// Whether `scratch` holds the first refinement's correction of the one system, solved
    /// with the last chord correction ([`TangentMap::paired_refinement`]).
    refinement_solved: bool,
}

impl<A: Assembly> Default for TangentMap<A> {
    fn default() -> Self {
        TangentMap {
            count: 0,
            dofs: 0,
            rhs: Vec::new(),
            solution: Vec::new(),
            tangents: A::Tangents::default(),
            newton: A::Tangents::default(),
            tangents_current: false,
            scratch: Vec::new(),
            correction: Vec::new(),
            refinement_solved: false,
        }
    }
}

impl<A: Assembly> TangentMap<A> {
    /// Room for `count` right-hand sides of a rod (allocates; call before stepping).
    pub fn reserve(&mut self, count: usize, rod: &A) {
        self.dofs = rod.dofs();
        self.rhs.resize(count * self.dofs, 0.0);
        self.solution.resize(count * self.dofs, 0.0);
        self.tangents = rod.new_tangents();
        self.newton = rod.new_tangents();
        self.scratch.resize(self.dofs, 0.0);
        self.correction.resize(self.dofs, 0.0);
        self.count = 0;
    }

    /// How many right-hand sides the next step solves (at most those reserved).
    pub fn set_count(&mut self, count: usize) {
        assert!(
            count * self.dofs <= self.rhs.len(),
            "tangent map not reserved"
        );
        self.count = count;
    }

    pub fn count(&self) -> usize {
        self.count
    }

    /// Right-hand side `j` (constrained entries must be zero), to fill before the step.
    pub fn rhs_mut(&mut self, j: usize) -> &mut [f64] {
        &mut self.rhs[j * self.dofs..(j + 1) * self.dofs]
    }

    /// Solution `j` after the step: `J*^-1 b_j`.
    pub fn solution(&self, j: usize) -> &[f64] {
        &self.solution[j * self.dofs..(j + 1) * self.dofs]
    }

    /// Where a chord correction's residual evaluation keeps its element tangents.
    pub(super) fn element_tangents(&mut self) -> &mut A::Tangents {
        self.tangents_current = true;
        &mut self.tangents
    }

    /// Where a Newton correction's evaluation keeps its element tangents, when the step
    /// refines ([`TangentMap::refine`]; not when it solves exactly).
    pub(super) fn newton_tangents(&mut self) -> Option<&mut A::Tangents> {
        (self.count > 0 && !self.exact()).then_some(&mut self.newton)
    }

    /// `y = J^-1 b` with the factorization `jac`.
    pub(super) fn solve(&mut self, jac: &A::Matrix) {
        let n = self.count * self.dofs;
        self.solution[..n].copy_from_slice(&self.rhs[..n]);
        for y in self.solution[..n].chunks_exact_mut(self.dofs) {
            jac.solve_in_place(y);
        }
        self.tangents_current = false;
        self.refinement_solved = false;
    }

    /// With one system: its solution set to `b`, for the Newton correction to solve with its
    /// own ([`TangentMap::solved_first`] follows); else `None`.
    pub(super) fn paired_first_solve(&mut self) -> Option<&mut [f64]> {
        if self.count != 1 {
            return None;
        }
        let y = &mut self.solution[..self.dofs];
        y.copy_from_slice(&self.rhs[..self.dofs]);
        Some(y)
    }

    /// Whether the step solves with `J1` factored ([`TangentMap::solve_exactly`], or `J0` when
    /// the iteration ends on a Newton correction) rather than refining: from [`EXACT_FROM`]
    /// systems on.
    pub(super) fn exact(&self) -> bool {
        self.count >= EXACT_FROM
    }

    /// After a new factorization `jac`: the first solve, unless it was `paired` with the
    /// Newton correction's or the step solves exactly at its end.
    pub(super) fn solved_first(&mut self, jac: &A::Matrix, paired: bool) {
        if paired || self.exact() {
            self.tangents_current = false;
            self.refinement_solved = false;
        } else {
            self.solve(jac);
        }
    }

    /// With one system and the element tangents of this chord evaluation: the first
    /// refinement's residual `b - J1 y = -(K1 - K0) y / 2`, for the chord correction to solve
    /// with its own; else `None`.
    pub(super) fn paired_refinement(&mut self, rod: &A) -> Option<&mut [f64]> {
        self.refinement_solved = false;
        if self.count != 1 || !self.tangents_current {
            return None;
        }
        let tangents = (&self.tangents, &self.newton);
        refinement_residual(
            rod,
            tangents,
            &self.solution[..self.dofs],
            &mut self.scratch,
        );
        self.refinement_solved = true;
        Some(&mut self.scratch)
    }

    /// Refines the solutions towards `J1^-1 b` with `J0` factored in `jac`. Returns false where
    /// that cannot be trusted (no element tangents for this factorization, or no
    /// contraction): the caller then solves exactly ([`TangentMap::solve_exactly`]).
    pub(super) fn refine(&mut self, rod: &A, jac: &A::Matrix) -> bool {
        if !self.tangents_current {
            return false;
        }
        let n = self.dofs;
        let tangents = (&self.tangents, &self.newton);
        for j in 0..self.count {
            let range = j * n..(j + 1) * n;
            let size = inf_norm(&self.solution[range.clone()]);
            if size == 0.0 {
                continue;
            }
            // The error of the first solve is about its first correction.
            let mut previous = size;
            let mut converged = false;
            for pass in 0..MAX_REFINEMENTS {
                // The first pass of a single system came with the chord correction.
                if !(pass == 0 && j == 0 && self.refinement_solved) {
                    if pass == 0 {
                        let y = &self.solution[range.clone()];
                        refinement_residual(rod, tangents, y, &mut self.scratch);
                    } else {
                        // The correction just applied (in `scratch`) gives the next residual.
                        std::mem::swap(&mut self.scratch, &mut self.correction);
                        refinement_residual(rod, tangents, &self.correction, &mut self.scratch);
                    }
                    jac.solve_in_place(&mut self.scratch);
                }
                let (r, y) = (&self.scratch, &mut self.solution[range.clone()]);
                y.iter_mut().zip(r.iter()).for_each(|(y, r)| *y += r);
                let correction = inf_norm(r);
                // NaN-aware: a NaN is neither converged nor contracting.
                if !(correction.is_finite() && correction <= 0.5 * previous) {
                    break;
                }
                // Left after it: the contraction `correction / previous` times itself.
                if correction / previous * correction <= TOLERANCE * size {
                    converged = true;
                    break;
                }
                previous = correction;
            }
            if !converged {
                return false;
            }
        }
        true
    }

    /// `y = J1^-1 b` with `J1 = dynamic + K/2` assembled from the kept element tangents into
    /// `jac` and factored.
    pub(super) fn solve_exactly(
        &mut self,
        rod: &A,
        dynamic: &A::Matrix,
        jac: &mut A::Matrix,
    ) -> Result<(), SingularMatrix> {
        debug_assert!(self.tangents_current);
        jac.copy_from(dynamic);
        rod.add_kept_tangents(jac, &self.tangents, 0.5);
        rod.constrain(jac);
        jac.factor_symmetric()?;
        self.solve(jac);
        Ok(())
    }
}

/// A refinement's residual `b - J1 y` from the last vector solved with `J0` (the first
/// solution, or the last correction `x`): `-(K1 - K0) x / 2` over the free dofs, with `K1`, `K0`
/// the element tangents `(k1, k0)` of the chord and Newton iterates (see the module doc).
fn refinement_residual<A: Assembly>(
    rod: &A,
    tangents: (&A::Tangents, &A::Tangents),
    x: &[f64],
    out: &mut [f64],
) {
    rod.tangent_change_times(tangents, x, out, -0.5);
    rod.zero_constrained(out);
}
