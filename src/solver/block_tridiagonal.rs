//! Block-tridiagonal matrices with 3x3 blocks (one block row per node) and their block LU
//! factorization: O(nodes) work and no allocation after construction.
//!
//! Storage: `diag[i]` is block `(i, i)`, `upper[i]` block `(i, i+1)`, `lower[i]` block `(i+1, i)`.
//!
//! The factorization is twisted (eliminated from both ends towards the middle block `m =
//! nodes / 2`): the nodes above `m` are eliminated downwards, those below `m` upwards, and `m`
//! last. Each sweep runs node after node, each node waiting for the one before, so at a few
//! nodes its time is the latency of that chain, not the flops; from both ends there are two
//! independent chains of half the length, which the processor runs side by side. It is the
//! block LU of the matrix with its nodes reordered (`0, n-1, 1, n-2, ..., m`), so the pivots are
//! Schur complements as in plain block LU and a symmetric matrix has the inertia of its pivots.
//! `factor` overwrites `diag` with the inverses of the pivots `D'_i`; above `m`, `lower[i]` with
//! the multiplier `A_(i+1,i) D'_i^-1` and `upper[i]` with `D'_i^-1 A_(i,i+1)`; below `m`,
//! `upper[i]` with `A_(i,i+1) D'_(i+1)^-1` and `lower[i]` with `D'_(i+1)^-1 A_(i+1,i)`.
//! Each pivot's next Schur complement is formed from its adjugate while the division by the
//! determinant runs, and the backward sweeps keep one block product on their chains.
use crate::model::element::ElementTangent;
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

    /// Adds `scale * k` for the element between nodes `e` and `e + 1`.
    pub fn add_element(&mut self, e: usize, k: &ElementTangent, scale: f64) {
        debug_assert!(!self.factored);
        let (aa, ab, bb) = k.blocks();
        self.diag[e] += scale * aa;
        self.upper[e] += scale * ab;
        self.lower[e] += scale * ab.transpose();
        self.diag[e + 1] += scale * bb;
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

    /// Block LU factorization in place (twisted: see the module documentation), without
    /// pivoting between blocks (the Jacobians here are symmetric and, in dynamics,
    /// mass-dominated). Fails on a pivot block that is singular to working precision.
    pub fn factor(&mut self) -> Result<(), SingularMatrix> {
        self.inertia = None;
        self.factor_blocks::<false, false>()
    }

    /// [`factor`](Self::factor) for a symmetric matrix (every Jacobian of a step is one: mass,
    /// damping and element tangents are symmetric, and so is the removal of held dofs). Its
    /// Schur complements are symmetric too, and the multipliers of the two triangles are each
    /// other's transposes: a third fewer operations per node.
    pub fn factor_symmetric(&mut self) -> Result<(), SingularMatrix> {
        debug_assert!(
            self.is_symmetric(),
            "factor_symmetric of a non-symmetric matrix"
        );
        self.inertia = None;
        self.factor_blocks::<false, true>()
    }

    fn is_symmetric(&self) -> bool {
        self.diag.iter().all(|d| d == &d.transpose())
            && (self.upper.iter().zip(&self.lower)).all(|(u, l)| u == &l.transpose())
    }

    /// [`factor`](Self::factor) that also counts the negative eigenvalues of the (symmetric)
    /// matrix from its pivots, for [`negative_eigenvalues`](Self::negative_eigenvalues): three
    /// 3x3 eigenvalue problems per node, for analyses, not for time steps.
    pub fn factor_with_inertia(&mut self) -> Result<(), SingularMatrix> {
        self.inertia = Some(0);
        self.factor_blocks::<true, false>()
    }

    /// The factorization; with `INERTIA`, counting the pivots' negative eigenvalues, with
    /// `SYMMETRIC` using the symmetry (separate instances: the time steps' factorization carries
    /// none of the other code).
    fn factor_blocks<const INERTIA: bool, const SYMMETRIC: bool>(
        &mut self,
    ) -> Result<(), SingularMatrix> {
        debug_assert!(!self.factored);
        self.negative_pivots = 0;
        let n = self.blocks();
        let middle = n / 2;
        // The chain from the top has `middle` pivots, the one from the bottom `n - 1 - middle`
        // (as many or one fewer): one loop runs both, so their latencies overlap.
        for k in 0..middle {
            self.eliminate_down::<INERTIA, SYMMETRIC>(k)?;
            let j = n - 1 - k;
            if j > middle {
                self.eliminate_up::<INERTIA, SYMMETRIC>(j)?;
            }
        }
        let (adjugate, inv_det) = self.pivot::<INERTIA>(middle)?;
        self.diag[middle] = adjugate * inv_det;
        self.factored = true;
        Ok(())
    }

    /// The adjugate and `1 / det` of the pivot block `i`, checked and counted.
    fn pivot<const INERTIA: bool>(
        &mut self,
        i: usize,
    ) -> Result<(Matrix3<f64>, f64), SingularMatrix> {
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
        if let (true, Some(negative)) = (INERTIA, self.inertia.as_mut()) {
            // From the pivot itself: the inverse of a pivot that is singular to round-off (at a
            // critical point) carries its other eigenvalues below its round-off.
            let symmetric = 0.5 * (self.diag[i] + self.diag[i].transpose());
            *negative += symmetric
                .symmetric_eigenvalues()
                .iter()
                .filter(|&&l| l < 0.0)
                .count();
        }
        Ok((adjugate, 1.0 / det))
    }

    /// Eliminates node `i` (above the middle) from node `i + 1`.
    fn eliminate_down<const INERTIA: bool, const SYMMETRIC: bool>(
        &mut self,
        i: usize,
    ) -> Result<(), SingularMatrix> {
        let (adjugate, inv_det) = self.pivot::<INERTIA>(i)?;
        self.diag[i] = adjugate * inv_det;
        // D'_(i+1) = D_(i+1) - A_(i+1,i) adj(D'_i) A_(i,i+1) / det(D'_i): the products with the
        // adjugate do not wait for the division.
        let lower_adjugate = self.lower[i] * adjugate;
        let schur = schur_product::<SYMMETRIC>(&lower_adjugate, &self.upper[i]);
        self.diag[i + 1] -= schur * inv_det;
        self.lower[i] = lower_adjugate * inv_det;
        self.upper[i] = if SYMMETRIC {
            self.lower[i].transpose()
        } else {
            (adjugate * self.upper[i]) * inv_det
        };
        Ok(())
    }

    /// Eliminates node `j` (below the middle) from node `j - 1`.
    fn eliminate_up<const INERTIA: bool, const SYMMETRIC: bool>(
        &mut self,
        j: usize,
    ) -> Result<(), SingularMatrix> {
        let (adjugate, inv_det) = self.pivot::<INERTIA>(j)?;
        self.diag[j] = adjugate * inv_det;
        let upper_adjugate = self.upper[j - 1] * adjugate;
        let schur = schur_product::<SYMMETRIC>(&upper_adjugate, &self.lower[j - 1]);
        self.diag[j - 1] -= schur * inv_det;
        self.upper[j - 1] = upper_adjugate * inv_det;
        self.lower[j - 1] = if SYMMETRIC {
            self.upper[j - 1].transpose()
        } else {
            (adjugate * self.lower[j - 1]) * inv_det
        };
        Ok(())
    }

    /// Solves `A x = rhs` in place (after [`factor`](Self::factor)): both sweeps run from the
    /// two ends at once.
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        self.solve_each(&mut [rhs]);
    }

    /// Solves `A x = a` and `A x = b` in place, in one pass over the factors.
    pub fn solve_pair(&self, a: &mut [f64], b: &mut [f64]) {
        self.solve_each(&mut [a, b]);
    }

    fn solve_each<const K: usize>(&self, rhs: &mut [&mut [f64]; K]) {
        assert!(self.factored, "solve before factor");
        let n = self.blocks();
        let middle = n / 2;
        for k in 0..middle {
            for x in rhs.iter_mut() {
                let y = block(x, k + 1) - self.lower[k] * block(x, k);
                set_block(x, k + 1, &y);
            }
            let j = n - 1 - k;
            if j > middle {
                for x in rhs.iter_mut() {
                    let z = block(x, j - 1) - self.upper[j - 1] * block(x, j);
                    set_block(x, j - 1, &z);
                }
            }
        }
        for x in rhs.iter_mut() {
            let m = self.diag[middle] * block(x, middle);
            set_block(x, middle, &m);
        }
        for k in 0..middle {
            let i = middle - 1 - k;
            for x in rhs.iter_mut() {
                let y = self.diag[i] * block(x, i) - self.upper[i] * block(x, i + 1);
                set_block(x, i, &y);
            }
            let j = middle + 1 + k;
            if j < n {
                for x in rhs.iter_mut() {
                    let y = self.diag[j] * block(x, j) - self.lower[j - 1] * block(x, j - 1);
                    set_block(x, j, &y);
                }
            }
        }
    }

    /// Parity information for stability checks: the number of pivot blocks with a negative
    /// determinant; the sign of `det A` is `(-1)^negative_pivots`.
    pub fn negative_pivots(&self) -> usize {
        self.negative_pivots
    }

    /// Number of negative eigenvalues of a symmetric `A` (after
    /// [`factor_with_inertia`](Self::factor_with_inertia)): by Sylvester's law of inertia it
    /// equals that of the pivot blocks of its block LDL^T factorization. Zero means `A` is
    /// positive definite: a stable equilibrium when `A` is the tangent stiffness.
    pub fn negative_eigenvalues(&self) -> usize {
        assert!(self.factored, "inertia before factor");
        self.inertia
            .expect("negative_eigenvalues needs factor_with_inertia")
    }
}

/// `a b`; with `SYMMETRIC` the product is known to be symmetric (`a = B^T adj(D)`, `b = B`
/// with `D` symmetric): its upper triangle is computed and mirrored.
fn schur_product<const SYMMETRIC: bool>(a: &Matrix3<f64>, b: &Matrix3<f64>) -> Matrix3<f64> {
    if !SYMMETRIC {
        return a * b;
    }
    let entry =
        |i: usize, j: usize| a[(i, 0)] * b[(0, j)] + a[(i, 1)] * b[(1, j)] + a[(i, 2)] * b[(2, j)];
    let (x00, x01, x02) = (entry(0, 0), entry(0, 1), entry(0, 2));
    let (x11, x12, x22) = (entry(1, 1), entry(1, 2), entry(2, 2));
    Matrix3::new(x00, x01, x02, x01, x11, x12, x02, x12, x22)
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

fn set_block(x: &mut [f64], i: usize, value: &Vector3<f64>) {
    x[3 * i..3 * i + 3].copy_from_slice(value.as_slice());
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

    /// A diagonally dominant matrix of `blocks` blocks, non-symmetric unless `symmetric`.
    fn test_matrix(blocks: usize, symmetric: bool, shift: f64) -> BlockTridiagonal {
        let mut a = BlockTridiagonal::new(blocks);
        for i in 0..blocks {
            for (n, x) in a.diag[i].iter_mut().enumerate() {
                *x = (1.7 * (i * 9 + n) as f64).sin();
            }
            a.diag[i] += Matrix3::identity() * shift;
        }
        for i in 0..blocks - 1 {
            for (n, x) in a.upper[i].iter_mut().enumerate() {
                *x = (0.9 * (i * 9 + n) as f64 + 1.0).cos();
            }
            for (n, x) in a.lower[i].iter_mut().enumerate() {
                *x = (1.3 * (i * 9 + n) as f64 + 2.0).sin();
            }
        }
        if symmetric {
            for i in 0..blocks {
                a.diag[i] = 0.5 * (a.diag[i] + a.diag[i].transpose());
            }
            for i in 0..blocks - 1 {
                a.lower[i] = a.upper[i].transpose();
            }
        }
        a
    }

    /// The dense form of `a` (before factorization).
    fn dense(a: &BlockTridiagonal) -> nalgebra::DMatrix<f64> {
        let n = 3 * a.blocks();
        let mut d = nalgebra::DMatrix::zeros(n, n);
        for j in 0..n {
            let mut e = vec![0.0; n];
            e[j] = 1.0;
            let mut col = vec![0.0; n];
            a.mul(&e, &mut col);
            for i in 0..n {
                d[(i, j)] = col[i];
            }
        }
        d
    }

    /// `solve_in_place` inverts `mul` for every size from one block (the middle block alone)
    /// to eight (both chains, with one or two blocks more on the top chain): residual at
    /// round-off of a well-conditioned system.
    #[test]
    fn solve_inverts_the_product() {
        for blocks in 1..=8 {
            let mut a = test_matrix(blocks, false, 6.0);
            let x: Vec<f64> = (0..3 * blocks).map(|j| (0.7 * j as f64).cos()).collect();
            let mut ax = vec![0.0; 3 * blocks];
            a.mul(&x, &mut ax);
            a.factor().unwrap();
            a.solve_in_place(&mut ax);
            for (got, want) in ax.iter().zip(&x) {
                assert!(
                    (got - want).abs() <= 1e-14,
                    "{blocks} blocks: {got} vs {want}"
                );
            }
        }
    }

    /// A pair of right-hand sides solves like each alone, to the bit.
    #[test]
    fn pairs_solve_like_singles() {
        let mut a = test_matrix(7, false, 6.0);
        a.factor().unwrap();
        let mut x: Vec<f64> = (0..21).map(|j| (0.7 * j as f64).cos()).collect();
        let mut y: Vec<f64> = (0..21).map(|j| (1.3 * j as f64).sin()).collect();
        let (mut x1, mut y1) = (x.clone(), y.clone());
        a.solve_in_place(&mut x1);
        a.solve_in_place(&mut y1);
        a.solve_pair(&mut x, &mut y);
        assert_eq!((x, y), (x1, y1));
    }

    /// The symmetric factorization of a symmetric matrix solves like the general one.
    #[test]
    fn symmetric_factorization_solves() {
        for blocks in 1..=8 {
            let mut a = test_matrix(blocks, true, 6.0);
            let mut general = a.clone();
            let x: Vec<f64> = (0..3 * blocks).map(|j| (0.7 * j as f64).cos()).collect();
            let mut ax = vec![0.0; 3 * blocks];
            a.mul(&x, &mut ax);
            let mut ax_general = ax.clone();
            a.factor_symmetric().unwrap();
            general.factor().unwrap();
            a.solve_in_place(&mut ax);
            general.solve_in_place(&mut ax_general);
            for ((got, general), want) in ax.iter().zip(&ax_general).zip(&x) {
                assert!(
                    (got - want).abs() <= 1e-14,
                    "{blocks} blocks: {got} vs {want}"
                );
                assert!(
                    (got - general).abs() <= 1e-14,
                    "{blocks} blocks: {got} vs {general}"
                );
            }
        }
    }

    /// The determinant's sign and the inertia of a symmetric indefinite matrix from the pivots
    /// equal those of its dense eigenvalues.
    #[test]
    fn pivots_give_the_determinant_sign_and_the_inertia() {
        let mut checked = 0;
        for blocks in 1..=7 {
            for shift in [-1.5, 0.3, 2.5] {
                let mut a = test_matrix(blocks, true, shift);
                let d = dense(&a);
                let eigenvalues = d.clone().symmetric_eigenvalues();
                let negative = eigenvalues.iter().filter(|&&l| l < 0.0).count();
                if eigenvalues.iter().any(|l| l.abs() < 1e-6) || a.factor_with_inertia().is_err() {
                    continue;
                }
                assert_eq!(
                    a.negative_eigenvalues(),
                    negative,
                    "{blocks} blocks, {shift}"
                );
                let sign = if a.negative_pivots() % 2 == 0 {
                    1.0
                } else {
                    -1.0
                };
                assert_eq!(sign, d.determinant().signum(), "{blocks} blocks, {shift}");
                checked += 1;
            }
        }
        assert!(checked >= 15, "only {checked} matrices checked");
    }

    #[test]
    fn singular_pivot_is_reported() {
        let mut a = BlockTridiagonal::new(2);
        a.diag[0] = Matrix3::identity();
        a.diag[1] = Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0);
        assert_eq!(a.factor(), Err(SingularMatrix { block: 1 }));
    }
}
