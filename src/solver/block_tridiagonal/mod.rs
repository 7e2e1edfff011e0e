//! Block-tridiagonal matrices with 3x3 blocks (one block row per node) and their block LU
//! factorization: O(nodes) work and no allocation after construction.
//!
//! Storage: `diag[i]` is block `(i, i)`, `upper[i]` block `(i, i+1)`, `lower[i]` block `(i+1, i)`.
//!
//! The factorization and the solves are in the submodules `factor` and `solve`.
mod factor;
mod solve;
#[cfg(test)]
mod tests;

pub(crate) use factor::adjugate_and_determinant;
use nalgebra::{Matrix3, Vector3};
use solve::block;
use std::fmt;

/// A symmetric coupling `[[aa, ab], [ab^T, bb]]` of two neighbouring block rows, as
/// [`BlockTridiagonal::add_pair`] takes it: by its three 3x3 blocks, formed inside `add_pair`, so
/// a type that holds fewer numbers (a rod element's tangent holds ten) is read once and no
/// blocks are stored in between. Plain blocks are `[aa, ab, bb]`.
pub trait PairBlocks {
    /// `(aa, ab, bb)`; the block `(i + 1, i)` is `ab^T`.
    fn blocks(&self) -> (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>);
}

impl PairBlocks for [Matrix3<f64>; 3] {
    fn blocks(&self) -> (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>) {
        (self[0], self[1], self[2])
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct SingularMatrix {
    /// Block row where a pivot block could not be inverted.
    pub block: usize,
}

impl fmt::Display for SingularMatrix {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "singular pivot block at node {}", self.block)
    }
}

impl std::error::Error for SingularMatrix {}

#[derive(Clone, Debug)]
pub struct BlockTridiagonal {
    diag: Vec<Matrix3<f64>>,
    upper: Vec<Matrix3<f64>>,
    lower: Vec<Matrix3<f64>>,
    factored: bool,
    /// Number of pivot blocks with negative determinant (after `factor`).
    negative_pivots: usize,
    /// Number of negative eigenvalues of the pivots, when counted
    /// ([`BlockTridiagonal::factor_with_inertia`]).
    inertia: Option<usize>,
}

impl BlockTridiagonal {
    pub fn new(blocks: usize) -> BlockTridiagonal {
        assert!(blocks >= 1);
        BlockTridiagonal {
            diag: vec![Matrix3::zeros(); blocks],
            upper: vec![Matrix3::zeros(); blocks - 1],
            lower: vec![Matrix3::zeros(); blocks - 1],
            factored: false,
            negative_pivots: 0,
            inertia: None,
        }
    }

    pub fn blocks(&self) -> usize {
        self.diag.len()
    }

    pub fn set_zero(&mut self) {
        self.diag.iter_mut().for_each(|m| m.fill(0.0));
        self.upper.iter_mut().for_each(|m| m.fill(0.0));
        self.lower.iter_mut().for_each(|m| m.fill(0.0));
        self.factored = false;
    }

    /// Overwrites `self` with `other` (same size), unfactored.
    pub fn copy_from(&mut self, other: &BlockTridiagonal) {
        debug_assert!(!other.factored);
        self.diag.copy_from_slice(&other.diag);
        self.upper.copy_from_slice(&other.upper);
        self.lower.copy_from_slice(&other.lower);
        self.factored = false;
    }

    /// Adds `scale * [[aa, ab], [ab^T, bb]]` to the block rows and columns `i` and `i + 1`, with
    /// `(aa, ab, bb)` = `pair.blocks()`: a symmetric coupling of two neighbouring block rows (for
    /// a rod, one element's tangent).
    pub fn add_pair<P: PairBlocks + ?Sized>(&mut self, i: usize, pair: &P, scale: f64) {
        debug_assert!(!self.factored);
        let (aa, ab, bb) = pair.blocks();
        self.diag[i] += scale * aa;
        self.upper[i] += scale * ab;
        self.lower[i] += scale * ab.transpose();
        self.diag[i + 1] += scale * bb;
    }

    /// Adds `scale * [[2 c, c], [c, 2 c]]` per dof of a block (`coeffs = (c_0, c_1, c_2)`) to
    /// the block rows and columns `i` and `i + 1` (for a rod, the pattern of an element's
    /// consistent mass and damping matrices), or with `lumped` `scale * [[3 c, 0], [0, 3 c]]`.
    pub fn add_pair_pattern(&mut self, i: usize, coeffs: &Vector3<f64>, scale: f64, lumped: bool) {
        debug_assert!(!self.factored);
        let d = Matrix3::from_diagonal(&(coeffs * scale));
        if lumped {
            self.diag[i] += 3.0 * d;
            self.diag[i + 1] += 3.0 * d;
            return;
        }
        self.diag[i] += 2.0 * d;
        self.diag[i + 1] += 2.0 * d;
        self.upper[i] += d;
        self.lower[i] += d;
    }

    /// Adds `value` to the diagonal entry of global dof `dof` (a point mass, spring or dashpot).
    pub fn add_diagonal(&mut self, dof: usize, value: f64) {
        debug_assert!(!self.factored);
        self.diag[dof / 3][(dof % 3, dof % 3)] += value;
    }

    /// Replaces the rows and columns of the constrained `dofs` by those of the identity, which is
    /// the same as removing them from the system (their right-hand side must be zero).
    pub fn constrain(&mut self, dofs: &[usize]) {
        for &dof in dofs {
            let (i, k) = (dof / 3, dof % 3);
            self.diag[i].row_mut(k).fill(0.0);
            self.diag[i].column_mut(k).fill(0.0);
            self.diag[i][(k, k)] = 1.0;
            if i > 0 {
                self.upper[i - 1].column_mut(k).fill(0.0);
                self.lower[i - 1].row_mut(k).fill(0.0);
            }
            if i + 1 < self.blocks() {
                self.upper[i].row_mut(k).fill(0.0);
                self.lower[i].column_mut(k).fill(0.0);
            }
        }
    }

    /// Removes the motion of `node`'s translation along the unit vector `n` (a support on an
    /// incline): with `P = I - n n^T` on the node's `u1`, `u2`, its block row becomes `P A`, its
    /// block column `A P` and its diagonal block `P A P + n n^T`, so a solution's component
    /// along `n` is zero (its right-hand side's must be too) and a symmetric matrix stays
    /// symmetric.
    pub fn constrain_direction(&mut self, node: usize, n: [f64; 2]) {
        debug_assert!(!self.factored);
        let mut p = Matrix3::identity();
        let mut nn = Matrix3::zeros();
        for r in 0..2 {
            for c in 0..2 {
                nn[(r, c)] = n[r] * n[c];
            }
        }
        p -= nn;
        self.diag[node] = p * self.diag[node] * p + nn;
        if node + 1 < self.blocks() {
            self.upper[node] = p * self.upper[node];
            self.lower[node] *= p;
        }
        if node > 0 {
            self.upper[node - 1] *= p;
            self.lower[node - 1] = p * self.lower[node - 1];
        }
    }

    /// `out = A x` (before factorization).
    pub fn mul(&self, x: &[f64], out: &mut [f64]) {
        debug_assert!(!self.factored);
        let n = self.blocks();
        for i in 0..n {
            let mut y = self.diag[i] * block(x, i);
            if i + 1 < n {
                y += self.upper[i] * block(x, i + 1);
            }
            if i > 0 {
                y += self.lower[i - 1] * block(x, i - 1);
            }
            out[3 * i..3 * i + 3].copy_from_slice(y.as_slice());
        }
    }

    /// Row `dof` of `A` (before factorization) as its first column and the entries from there:
    /// the 9 columns of the node's block row (6 at the first and last node, padded with zeros).
    pub fn row_stencil(&self, dof: usize) -> (usize, [f64; 9]) {
        debug_assert!(!self.factored);
        let (i, k) = (dof / 3, dof % 3);
        let mut entries = [0.0; 9];
        let first = i.saturating_sub(1);
        let blocks = [
            (i > 0).then(|| &self.lower[i.wrapping_sub(1)]),
            Some(&self.diag[i]),
            (i + 1 < self.blocks()).then(|| &self.upper[i]),
        ];
        let mut at = 0;
        for m in blocks.into_iter().flatten() {
            for c in 0..3 {
                entries[at + c] = m[(k, c)];
            }
            at += 3;
        }
        (3 * first, entries)
    }
}
