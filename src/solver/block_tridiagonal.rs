//! Block-tridiagonal matrices with 3x3 blocks (one block row per node) and their block LU
//! factorization: O(nodes) work and no allocation after construction.
//!
//! Storage: `diag[i]` is block `(i, i)`, `upper[i]` block `(i, i+1)`, `lower[i]` block `(i+1, i)`.
//! `factor` overwrites `diag` with the inverses of the Schur complements `D'_i`, `lower` with
//! the multipliers `L_i = A_(i+1,i) D'_i^-1` and `upper` with `W_i = D'_i^-1 A_(i,i+1)`.
//!
//! Both sweeps run node after node, each node waiting for the one before: at a few nodes their
//! time is the latency of that chain, not the flops. So the factorization forms the next Schur
//! complement from the adjugate while the division by the determinant runs, and the backward
//! sweep `x_i = D'_i^-1 y_i - W_i x_(i+1)` keeps one block product on the chain instead of two.
use crate::model::element::Matrix6;
use nalgebra::{Matrix3, Vector3};
use std::fmt;

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

    /// Adds `scale * k` for the element between nodes `e` and `e + 1`.
    pub fn add_element(&mut self, e: usize, k: &Matrix6, scale: f64) {
        debug_assert!(!self.factored);
        self.diag[e] += scale * k.fixed_view::<3, 3>(0, 0);
        self.upper[e] += scale * k.fixed_view::<3, 3>(0, 3);
        self.lower[e] += scale * k.fixed_view::<3, 3>(3, 0);
        self.diag[e + 1] += scale * k.fixed_view::<3, 3>(3, 3);
    }

    /// Adds `scale * [[2 c, c], [c, 2 c]]` per dof kind (`coeffs = (c_u1, c_u2, c_w)`), the
    /// pattern of the consistent mass and damping matrices of element `e`, or with `lumped`
    /// `scale * [[3 c, 0], [0, 3 c]]`.
    pub fn add_element_pattern(
        &mut self,
        e: usize,
        coeffs: &Vector3<f64>,
        scale: f64,
        lumped: bool,
    ) {
        debug_assert!(!self.factored);
        let d = Matrix3::from_diagonal(&(coeffs * scale));
        if lumped {
            self.diag[e] += 3.0 * d;
            self.diag[e + 1] += 3.0 * d;
            return;
        }
        self.diag[e] += 2.0 * d;
        self.diag[e + 1] += 2.0 * d;
        self.upper[e] += d;
        self.lower[e] += d;
    }

    /// Replaces the rows and columns of the constrained dofs by those of the identity, which is
    /// the same as removing them from the system (their right-hand side must be zero).
    pub fn constrain(&mut self, fixed: &[bool]) {
        debug_assert_eq!(fixed.len(), 3 * self.blocks());
        for (dof, _) in fixed.iter().enumerate().filter(|(_, &f)| f) {
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

    /// Block LU factorization in place, without pivoting between blocks (the Jacobians here are
    /// symmetric and, in dynamics, mass-dominated). Fails on a pivot block that is singular to
    /// working precision.
    pub fn factor(&mut self) -> Result<(), SingularMatrix> {
        debug_assert!(!self.factored);
        self.negative_pivots = 0;
        let n = self.blocks();
        for i in 0..n {
            let (adjugate, det) = adjugate_and_determinant(&self.diag[i]);
            // Relative to the product of the column norms (Hadamard's bound), which is blind to
            // how differently the dofs are scaled (a slender rod's rotation columns are orders of
            // magnitude smaller than its translation columns). Squared: no square roots.
            let bound: f64 = self.diag[i]
                .column_iter()
                .map(|c| c.norm_squared())
                .product();
            if !det.is_finite() || det * det <= 1e-28 * bound || !bound.is_finite() {
                return Err(SingularMatrix { block: i });
            }
            if det < 0.0 {
                self.negative_pivots += 1;
            }
            let inv_det = 1.0 / det;
            self.diag[i] = adjugate * inv_det;
            if i + 1 < n {
                // D'_(i+1) = D_(i+1) - A_(i+1,i) adj(D'_i) A_(i,i+1) / det(D'_i): the products
                // with the adjugate do not wait for the division.
                let lower_adjugate = self.lower[i] * adjugate;
                let schur = lower_adjugate * self.upper[i];
                self.diag[i + 1] -= schur * inv_det;
                self.lower[i] = lower_adjugate * inv_det;
                self.upper[i] = (adjugate * self.upper[i]) * inv_det;
            }
        }
        self.factored = true;
        Ok(())
    }

    /// Solves `A x = rhs` in place (after [`factor`](Self::factor)).
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        assert!(self.factored, "solve before factor");
        let n = self.blocks();
        for i in 1..n {
            let y = block(rhs, i) - self.lower[i - 1] * block(rhs, i - 1);
            rhs[3 * i..3 * i + 3].copy_from_slice(y.as_slice());
        }
        let last = self.diag[n - 1] * block(rhs, n - 1);
        rhs[3 * (n - 1)..3 * n].copy_from_slice(last.as_slice());
        for i in (0..n - 1).rev() {
            // `upper[i]` holds W_i = D'_i^-1 A_(i,i+1).
            let x = self.diag[i] * block(rhs, i) - self.upper[i] * block(rhs, i + 1);
            rhs[3 * i..3 * i + 3].copy_from_slice(x.as_slice());
        }
    }

    /// Parity information for stability checks: the number of pivot blocks with a negative
    /// determinant; the sign of `det A` is `(-1)^negative_pivots`.
    pub fn negative_pivots(&self) -> usize {
        self.negative_pivots
    }

    /// Number of negative eigenvalues of a symmetric `A` (after factorization): by Sylvester's law
    /// of inertia it equals that of the block diagonal of `A = L D L^T`, i.e. of the pivot blocks
    /// (whose inverses `diag` holds; an inverse has the same eigenvalue signs). Zero means `A` is
    /// positive definite: a stable equilibrium when `A` is the tangent stiffness.
    pub fn negative_eigenvalues(&self) -> usize {
        assert!(self.factored, "inertia before factor");
        self.diag
            .iter()
            .map(|inverse| {
                let symmetric = 0.5 * (inverse + inverse.transpose());
                symmetric
                    .symmetric_eigenvalues()
                    .iter()
                    .filter(|&&l| l < 0.0)
                    .count()
            })
            .sum()
    }
}

/// The adjugate (its cofactors reused for the determinant) and the determinant: the inverse is
/// `adjugate / det`.
fn adjugate_and_determinant(m: &Matrix3<f64>) -> (Matrix3<f64>, f64) {
    let c00 = m[(1, 1)] * m[(2, 2)] - m[(1, 2)] * m[(2, 1)];
    let c01 = m[(1, 2)] * m[(2, 0)] - m[(1, 0)] * m[(2, 2)];
    let c02 = m[(1, 0)] * m[(2, 1)] - m[(1, 1)] * m[(2, 0)];
    let det = m[(0, 0)] * c00 + m[(0, 1)] * c01 + m[(0, 2)] * c02;
    #[rustfmt::skip]
    let adjugate = Matrix3::new(
        c00, m[(0, 2)] * m[(2, 1)] - m[(0, 1)] * m[(2, 2)], m[(0, 1)] * m[(1, 2)] - m[(0, 2)] * m[(1, 1)],
        c01, m[(0, 0)] * m[(2, 2)] - m[(0, 2)] * m[(2, 0)], m[(0, 2)] * m[(1, 0)] - m[(0, 0)] * m[(1, 2)],
        c02, m[(0, 1)] * m[(2, 0)] - m[(0, 0)] * m[(2, 1)], m[(0, 0)] * m[(1, 1)] - m[(0, 1)] * m[(1, 0)],
    );
    (adjugate, det)
}

fn block(x: &[f64], i: usize) -> Vector3<f64> {
    Vector3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each row stencil times `x` is that row of `A x`, at the ends and inside.
    #[test]
    fn row_stencils_are_the_rows_of_the_product() {
        let blocks = 4;
        let mut a = BlockTridiagonal::new(blocks);
        let fill = |m: &mut Matrix3<f64>, seed: f64| {
            for (n, x) in m.iter_mut().enumerate() {
                *x = (seed + n as f64).sin();
            }
        };
        for i in 0..blocks {
            fill(&mut a.diag[i], i as f64);
        }
        for i in 0..blocks - 1 {
            fill(&mut a.upper[i], 10.0 + i as f64);
            fill(&mut a.lower[i], 20.0 + i as f64);
        }
        let x: Vec<f64> = (0..3 * blocks).map(|j| (0.3 * j as f64).cos()).collect();
        let mut ax = vec![0.0; 3 * blocks];
        a.mul(&x, &mut ax);
        for (dof, want) in ax.iter().enumerate() {
            let (first, entries) = a.row_stencil(dof);
            let got: f64 = entries.iter().zip(&x[first..]).map(|(e, v)| e * v).sum();
            assert!((got - want).abs() <= 1e-14, "row {dof}: {got} vs {want}");
        }
    }

    #[test]
    fn adjugate_inverse_matches_nalgebra() {
        let m = Matrix3::new(4.0, -1.5, 0.3, 2.0, 7.0, -0.25, 1e-3, 0.5, 3e-4);
        let (adjugate, det) = adjugate_and_determinant(&m);
        let inverse = adjugate / det;
        assert!((det - m.determinant()).abs() <= 1e-14 * det.abs());
        let reference = m.try_inverse().unwrap();
        assert!((inverse - reference).norm() <= 1e-13 * reference.norm());
        assert!((inverse * m - Matrix3::identity()).norm() <= 1e-13);
    }

    /// `solve_in_place` inverts `mul` (a non-symmetric, diagonally dominant matrix of five
    /// blocks, so every block of the factorization is exercised): residual at round-off.
    #[test]
    fn solve_inverts_the_product() {
        let blocks = 5;
        let mut a = BlockTridiagonal::new(blocks);
        for i in 0..blocks {
            for (n, x) in a.diag[i].iter_mut().enumerate() {
                *x = (1.7 * (i * 9 + n) as f64).sin();
            }
            a.diag[i] += Matrix3::identity() * 6.0;
        }
        for i in 0..blocks - 1 {
            for (n, x) in a.upper[i].iter_mut().enumerate() {
                *x = (0.9 * (i * 9 + n) as f64 + 1.0).cos();
            }
            for (n, x) in a.lower[i].iter_mut().enumerate() {
                *x = (1.3 * (i * 9 + n) as f64 + 2.0).sin();
            }
        }
        let x: Vec<f64> = (0..3 * blocks).map(|j| (0.7 * j as f64).cos()).collect();
        let mut ax = vec![0.0; 3 * blocks];
        a.mul(&x, &mut ax);
        a.factor().unwrap();
        a.solve_in_place(&mut ax);
        for (got, want) in ax.iter().zip(&x) {
            assert!((got - want).abs() <= 1e-14, "{got} vs {want}");
        }
    }

    #[test]
    fn singular_pivot_is_reported() {
        let mut a = BlockTridiagonal::new(2);
        a.diag[0] = Matrix3::identity();
        a.diag[1] = Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0);
        assert_eq!(a.factor(), Err(SingularMatrix { block: 1 }));
    }
}
