//! What the integrators ask of a system matrix, whatever its sparsity: a rod's block-tridiagonal
//! matrix or a frame's general block-sparse one. [`SystemMatrix`] is the solver side (constraints,
//! factorization, solves), [`PairSink`] the assembly side that a chain of elements fills (each
//! element couples its two nodes, numbered along the chain).
use super::{BlockTridiagonal, PairBlocks, SingularMatrix};
use nalgebra::Vector3;

/// A square matrix over the dof vector, assembled, constrained, factored and solved in place.
pub trait SystemMatrix: Clone + std::fmt::Debug {
    fn set_zero(&mut self);
    /// Overwrites `self` with `other` (same size and pattern), unfactored.
    fn copy_from(&mut self, other: &Self);
    fn add_diagonal(&mut self, dof: usize, value: f64);
    /// Replaces the rows and columns of `dofs` by those of the identity.
    fn constrain(&mut self, dofs: &[usize]);
    fn factor(&mut self) -> Result<(), SingularMatrix>;
    fn factor_symmetric(&mut self) -> Result<(), SingularMatrix>;
    fn factor_with_inertia(&mut self) -> Result<(), SingularMatrix>;
    /// Negative eigenvalues of a symmetric matrix (after `factor_with_inertia`).
    fn negative_eigenvalues(&self) -> usize;
    fn solve_in_place(&self, x: &mut [f64]);
    fn solve_pair(&self, a: &mut [f64], b: &mut [f64]);
    /// `out = A x` (before factorization).
    fn mul(&self, x: &[f64], out: &mut [f64]);
    /// Row `dof` (before factorization) as `(column, value)` pairs, in increasing columns (made
    /// outside the step loop: it allocates).
    fn row_entries(&self, dof: usize) -> Vec<(usize, f64)>;
}

/// Where a chain of elements assembles: element `i` couples the chain's nodes `i` and `i + 1`.
pub trait PairSink {
    /// Adds `scale * [[aa, ab], [ab^T, bb]]` at the chain's nodes `i`, `i + 1`.
    fn add_pair<P: PairBlocks + ?Sized>(&mut self, i: usize, pair: &P, scale: f64);
    /// Adds the consistent pattern `scale * [[2 c, c], [c, 2 c]]` per dof (`coeffs`), or with
    /// `lumped` `scale * [[3 c, 0], [0, 3 c]]`, at the chain's nodes `i`, `i + 1`.
    fn add_pair_pattern(&mut self, i: usize, coeffs: &Vector3<f64>, scale: f64, lumped: bool);
    /// Adds `value` to the diagonal entry of the chain's dof `dof`.
    fn add_diagonal(&mut self, dof: usize, value: f64);
}

impl PairSink for BlockTridiagonal {
    fn add_pair<P: PairBlocks + ?Sized>(&mut self, i: usize, pair: &P, scale: f64) {
        BlockTridiagonal::add_pair(self, i, pair, scale);
    }

    fn add_pair_pattern(&mut self, i: usize, coeffs: &Vector3<f64>, scale: f64, lumped: bool) {
        BlockTridiagonal::add_pair_pattern(self, i, coeffs, scale, lumped);
    }

    fn add_diagonal(&mut self, dof: usize, value: f64) {
        BlockTridiagonal::add_diagonal(self, dof, value);
    }
}

impl SystemMatrix for BlockTridiagonal {
    fn set_zero(&mut self) {
        BlockTridiagonal::set_zero(self);
    }

    fn copy_from(&mut self, other: &Self) {
        BlockTridiagonal::copy_from(self, other);
    }

    fn add_diagonal(&mut self, dof: usize, value: f64) {
        BlockTridiagonal::add_diagonal(self, dof, value);
    }

    fn constrain(&mut self, dofs: &[usize]) {
        BlockTridiagonal::constrain(self, dofs);
    }

    fn factor(&mut self) -> Result<(), SingularMatrix> {
        BlockTridiagonal::factor(self)
    }

    fn factor_symmetric(&mut self) -> Result<(), SingularMatrix> {
        BlockTridiagonal::factor_symmetric(self)
    }

    fn factor_with_inertia(&mut self) -> Result<(), SingularMatrix> {
        BlockTridiagonal::factor_with_inertia(self)
    }

    fn negative_eigenvalues(&self) -> usize {
        BlockTridiagonal::negative_eigenvalues(self)
    }

    fn solve_in_place(&self, x: &mut [f64]) {
        BlockTridiagonal::solve_in_place(self, x);
    }

    fn solve_pair(&self, a: &mut [f64], b: &mut [f64]) {
        BlockTridiagonal::solve_pair(self, a, b);
    }

    fn mul(&self, x: &[f64], out: &mut [f64]) {
        BlockTridiagonal::mul(self, x, out);
    }

    /// The node's block row as its stencil: the 9 columns from the first neighbour's (6 at an
    /// end node, the padding zeros kept where they fall inside the matrix), so a product with
    /// them adds the same terms in the same order as the stencil itself.
    fn row_entries(&self, dof: usize) -> Vec<(usize, f64)> {
        let (first, entries) = self.row_stencil(dof);
        let n = 3 * self.blocks();
        (entries.iter().enumerate())
            .map(|(j, &a)| (first + j, a))
            .filter(|&(c, _)| c < n)
            .collect()
    }
}
