//! Block LU factorization of a [`BlockTridiagonal`] in place, and what it leaves: the sign of
//! the determinant and the inertia.
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
use super::{BlockTridiagonal, SingularMatrix};
use nalgebra::Matrix3;

impl BlockTridiagonal {
    /// Block LU factorization in place (twisted: see the module documentation), without
    /// pivoting between blocks (the Jacobians here are symmetric and, in dynamics,
    /// mass-dominated). Fails on a pivot block that is singular to working precision.
    pub fn factor(&mut self) -> Result<(), SingularMatrix> {
        self.inertia = None;
        self.factor_blocks::<false, false>()
    }

    /// [`factor`](Self::factor) for a symmetric matrix (every Jacobian of a step is one: its
    /// mass, damping and stiffness blocks are symmetric, and so is the removal of held dofs). Its
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
pub(crate) fn adjugate_and_determinant(m: &Matrix3<f64>) -> (Matrix3<f64>, f64) {
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
