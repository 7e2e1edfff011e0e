//! Block LU factorization of a [`SparseBlocks`] in place, in its pattern's elimination order,
//! and what it leaves: the sign of the determinant and the inertia.
//!
//! Step `k` eliminates node `p` with pivot `D` (the Schur complement so far) from its later
//! neighbours `q_a`: `A(q_a, q_b) -= A(q_a, p) D^-1 A(p, q_b)` for every pair, formed as
//! `(A(q_a, p) adj D) A(p, q_b) / det D` so that the products do not wait for the division (as
//! in [`BlockTridiagonal`](crate::solver::BlockTridiagonal)). It overwrites the pivot with
//! `D^-1`, `(q_a, p)` with the multiplier `L_a = A(q_a, p) D^-1` and `(p, q_a)` with `U_a = D^-1
//! A(p, q_a)`. The targets are precomputed slots: the loop does no searching.
use super::SparseBlocks;
use crate::solver::block_tridiagonal::adjugate_and_determinant;
use crate::solver::SingularMatrix;
use nalgebra::Matrix3;

impl SparseBlocks {
    /// Block LU factorization in place, without pivoting between blocks (the Jacobians are
    /// symmetric and, in dynamics, mass-dominated). Fails on a pivot block that is singular to
    /// working precision, naming its node.
    pub fn factor(&mut self) -> Result<(), SingularMatrix> {
        self.factor_blocks::<false, false>()
    }

    /// [`factor`](Self::factor) for a symmetric matrix: the Schur updates are symmetric, so
    /// one triangle of each is formed and mirrored, and `U_a = L_a^T`.
    pub fn factor_symmetric(&mut self) -> Result<(), SingularMatrix> {
        debug_assert!(
            self.is_symmetric(),
            "factor_symmetric of a non-symmetric matrix"
        );
        self.factor_blocks::<false, true>()
    }

    /// [`factor`](Self::factor) that also counts the negative eigenvalues of the (symmetric)
    /// matrix from its pivots, for [`negative_eigenvalues`](Self::negative_eigenvalues): a 3x3
    /// eigenvalue problem per node, for analyses, not for time steps.
    pub fn factor_with_inertia(&mut self) -> Result<(), SingularMatrix> {
        self.factor_blocks::<true, false>()
    }

    /// Whether `A` (before factorization) is symmetric to the bit, as
    /// [`factor_symmetric`](Self::factor_symmetric) requires (and debug builds check).
    pub fn is_symmetric(&self) -> bool {
        debug_assert!(!self.factored);
        let pattern = &*self.pattern;
        (0..pattern.nodes).all(|i| {
            let d = &self.blocks[pattern.steps[pattern.position[i]].slot];
            d == &d.transpose()
                && (pattern.couplings_of(i).iter())
                    .all(|c| self.blocks[c.row] == self.blocks[c.column].transpose())
        })
    }

    /// The factorization; with `INERTIA` counting the pivots' negative eigenvalues, with
    /// `SYMMETRIC` using the symmetry (separate instances: the time steps' factorization carries
    /// none of the other code).
    fn factor_blocks<const INERTIA: bool, const SYMMETRIC: bool>(
        &mut self,
    ) -> Result<(), SingularMatrix> {
        debug_assert!(!self.factored);
        let pattern = &*self.pattern;
        let blocks = &mut self.blocks;
        self.negative_pivots = 0;
        self.inertia = INERTIA.then_some(0);
        for (step, next) in pattern.steps.iter().zip(&pattern.steps[1..]) {
            let d = step.slot;
            let (adjugate, det) = adjugate_and_determinant(&blocks[d]);
            if is_singular(&blocks[d], det) {
                return Err(SingularMatrix { block: step.node });
            }
            self.negative_pivots += usize::from(det < 0.0);
            if let (true, Some(negative)) = (INERTIA, self.inertia.as_mut()) {
                // From the pivot itself, not its inverse: the inverse of a pivot singular to
                // round-off (at a critical point) carries its other eigenvalues below its
                // round-off.
                let symmetric = 0.5 * (blocks[d] + blocks[d].transpose());
                let eigenvalues = symmetric.symmetric_eigenvalues();
                *negative += eigenvalues.iter().filter(|&&l| l < 0.0).count();
            }
            let inv_det = 1.0 / det;
            let m = next.later - step.later;
            let targets = &pattern.targets[step.targets..next.targets];
            for a in 0..m {
                let (upper, lower) = (d + 1 + 2 * a, d + 2 + 2 * a);
                let lower_adjugate = blocks[lower] * adjugate;
                let row = &targets[a * m..(a + 1) * m];
                if SYMMETRIC {
                    // The diagonal target's update is symmetric, the others are mirrored; the
                    // columns `b < a` were updated with rows `b` (as the transposes).
                    let schur = symmetric_product(&lower_adjugate, &blocks[upper]);
                    blocks[row[a]] -= schur * inv_det;
                    for b in a + 1..m {
                        let schur = (lower_adjugate * blocks[d + 1 + 2 * b]) * inv_det;
                        blocks[row[b]] -= schur;
                        blocks[targets[b * m + a]] -= schur.transpose();
                    }
                    blocks[lower] = lower_adjugate * inv_det;
                    blocks[upper] = blocks[lower].transpose();
                } else {
                    for (b, &target) in row.iter().enumerate() {
                        let schur = lower_adjugate * blocks[d + 1 + 2 * b];
                        blocks[target] -= schur * inv_det;
                    }
                    blocks[lower] = lower_adjugate * inv_det;
                }
            }
            if !SYMMETRIC {
                // After all rows: each used every `A(p, q_b)`.
                for a in 0..m {
                    let upper = d + 1 + 2 * a;
                    blocks[upper] = (adjugate * blocks[upper]) * inv_det;
                }
            }
            blocks[d] = adjugate * inv_det;
        }
        self.factored = true;
        Ok(())
    }

    /// The number of pivot blocks with a negative determinant: `det A` has the sign
    /// `(-1)^negative_pivots` (as [`BlockTridiagonal::negative_pivots`](crate::solver::BlockTridiagonal::negative_pivots)).
    pub fn negative_pivots(&self) -> usize {
        self.negative_pivots
    }

    /// Number of negative eigenvalues of a symmetric `A` after
    /// [`factor_with_inertia`](Self::factor_with_inertia): those of its pivots (Sylvester).
    pub fn negative_eigenvalues(&self) -> usize {
        assert!(self.factored, "inertia before factor");
        (self.inertia).expect("negative_eigenvalues needs factor_with_inertia")
    }
}

/// A pivot singular to working precision (the test of the block-tridiagonal pivots): `det^2`
/// against the product of the squared column norms (Hadamard's bound, blind to how differently
/// the dofs are scaled), or not finite.
fn is_singular(pivot: &Matrix3<f64>, det: f64) -> bool {
    let bound: f64 = pivot.column_iter().map(|c| c.norm_squared()).product();
    !det.is_finite() || det * det <= 1e-28 * bound || !bound.is_finite()
}

/// `a b`, known to be symmetric (`a = B^T adj(D)`, `b = B` with `D` symmetric): the upper
/// triangle is formed and mirrored.
fn symmetric_product(a: &Matrix3<f64>, b: &Matrix3<f64>) -> Matrix3<f64> {
    let entry =
        |i: usize, j: usize| a[(i, 0)] * b[(0, j)] + a[(i, 1)] * b[(1, j)] + a[(i, 2)] * b[(2, j)];
    let (x00, x01, x02) = (entry(0, 0), entry(0, 1), entry(0, 2));
    let (x11, x12, x22) = (entry(1, 1), entry(1, 2), entry(2, 2));
    Matrix3::new(x00, x01, x02, x01, x11, x12, x02, x12, x22)
}
