//! Assembly into a [`SparseBlocks`] by slot, the removal of held dofs and directions, and the
//! matrix's products and rows (before factorization).
use super::solve::{block, set_block};
use super::SparseBlocks;
use nalgebra::{Matrix3, Vector3};

impl SparseBlocks {
    /// Adds `scale * block` to the block at `slot` (from [`BlockPattern::slot`](super::BlockPattern::slot)).
    pub fn add_block(&mut self, slot: usize, block: &Matrix3<f64>, scale: f64) {
        debug_assert!(!self.factored);
        self.blocks[slot] += scale * block;
    }

    /// Adds `scale * [[aa, ab], [ab^T, bb]]` to the block rows and columns `i` and `j` given by
    /// their slots `[ii, ij, ji, jj]` (from [`BlockPattern::pair_slots`](super::BlockPattern::pair_slots)):
    /// the assembly of one element, as [`BlockTridiagonal::add_pair`](crate::solver::BlockTridiagonal::add_pair).
    pub fn add_pair_slots(
        &mut self,
        slots: [usize; 4],
        aa: &Matrix3<f64>,
        ab: &Matrix3<f64>,
        bb: &Matrix3<f64>,
        scale: f64,
    ) {
        debug_assert!(!self.factored);
        let [ii, ij, ji, jj] = slots;
        self.blocks[ii] += scale * aa;
        self.blocks[ij] += scale * ab;
        self.blocks[ji] += scale * ab.transpose();
        self.blocks[jj] += scale * bb;
    }

    /// Adds `value` to entry `(row_dof, col_dof)`; panics if its block is not in the pattern.
    /// Looks the slot up: for setup and sparse additions, not for the elements' blocks.
    pub fn add_entry(&mut self, row_dof: usize, col_dof: usize, value: f64) {
        debug_assert!(!self.factored);
        let slot = (self.pattern.slot(row_dof / 3, col_dof / 3))
            .unwrap_or_else(|| panic!("entry ({row_dof}, {col_dof}) is not in the pattern"));
        self.blocks[slot][(row_dof % 3, col_dof % 3)] += value;
    }

    /// Adds `value` to entry `(r, c)` of the block at `slot`: an entry's assembly with its
    /// slot looked up once, at setup ([`BlockPattern::slot`](super::BlockPattern::slot)).
    pub fn add_slot_entry(&mut self, slot: usize, r: usize, c: usize, value: f64) {
        debug_assert!(!self.factored);
        self.blocks[slot][(r, c)] += value;
    }

    /// Adds `value` to the diagonal entry of dof `dof` (a point mass, spring or dashpot).
    pub fn add_diagonal(&mut self, dof: usize, value: f64) {
        debug_assert!(!self.factored);
        let slot = self.diagonal_slot(dof / 3);
        self.blocks[slot][(dof % 3, dof % 3)] += value;
    }

    /// Replaces the rows and columns of the constrained `dofs` by those of the identity, which is
    /// the same as removing them from the system (their right-hand side must be zero).
    pub fn constrain(&mut self, dofs: &[usize]) {
        debug_assert!(!self.factored);
        for &dof in dofs {
            let (i, k) = (dof / 3, dof % 3);
            let d = self.diagonal_slot(i);
            self.blocks[d].row_mut(k).fill(0.0);
            self.blocks[d].column_mut(k).fill(0.0);
            self.blocks[d][(k, k)] = 1.0;
            for c in self.pattern.couplings_of(i) {
                self.blocks[c.row].row_mut(k).fill(0.0);
                self.blocks[c.column].column_mut(k).fill(0.0);
            }
        }
    }

    /// Holds `node` in the direction of the unit vector `n = (n1, n2)` of its `(u1, u2)` plane
    /// (a support on an incline): with `P = I - n n^T` (3x3, `w` untouched) its block row
    /// becomes `P A`, its block column `A P` and its diagonal block `P A P + n n^T`. The
    /// solution's component along `n` is then the right-hand side's, which the caller makes
    /// zero (`b -= n (n . b)` at the node), and the other equations are the projected ones. The
    /// products are formed entry by entry so that a symmetric matrix stays symmetric to the bit.
    pub fn constrain_direction(&mut self, node: usize, n: [f64; 2]) {
        debug_assert!(!self.factored);
        debug_assert!(
            (n[0] * n[0] + n[1] * n[1] - 1.0).abs() <= 1e-12,
            "n is not a unit vector"
        );
        let n = Vector3::new(n[0], n[1], 0.0);
        // n^T B and B n (w's zero term left out), then (P B)_rc = B_rc - n_r (n^T B)_c and
        // (B P)_rc = B_rc - (B n)_r n_c: for B^T the same numbers, transposed.
        let n_b = |b: &Matrix3<f64>| Vector3::from_fn(|c, _| n[0] * b[(0, c)] + n[1] * b[(1, c)]);
        let b_n = |b: &Matrix3<f64>| Vector3::from_fn(|r, _| b[(r, 0)] * n[0] + b[(r, 1)] * n[1]);
        for c in self.pattern.couplings_of(node) {
            let (row, column) = (self.blocks[c.row], self.blocks[c.column]);
            let (nb, bn) = (n_b(&row), b_n(&column));
            self.blocks[c.row] = Matrix3::from_fn(|r, c| row[(r, c)] - n[r] * nb[c]);
            self.blocks[c.column] = Matrix3::from_fn(|r, c| column[(r, c)] - bn[r] * n[c]);
        }
        // P D P + n n^T = D - (n (n^T D) + (D n) n^T) + (n^T D n + 1) n n^T: each term
        // symmetric in (r, c) when D is, in its rounding too.
        let d = self.diagonal_slot(node);
        let m = self.blocks[d];
        let (nm, mn) = (n_b(&m), b_n(&m));
        let along = n[0] * mn[0] + n[1] * mn[1] + 1.0;
        self.blocks[d] = Matrix3::from_fn(|r, c| {
            m[(r, c)] - (n[r] * nm[c] + mn[r] * n[c]) + along * (n[r] * n[c])
        });
    }

    /// `out = A x` (before factorization).
    pub fn mul(&self, x: &[f64], out: &mut [f64]) {
        debug_assert!(!self.factored);
        for i in 0..self.pattern.nodes {
            let mut y = self.blocks[self.diagonal_slot(i)] * block(x, i);
            for c in self.pattern.couplings_of(i) {
                y += self.blocks[c.row] * block(x, c.node);
            }
            set_block(out, i, &y);
        }
    }

    /// Row `dof` of `A` (before factorization) as `(column dof, value)` pairs by column: every
    /// entry of the blocks of its block row, zeros and fill blocks included. Setup-time helper:
    /// allocates.
    pub fn row_entries(&self, dof: usize) -> Vec<(usize, f64)> {
        debug_assert!(!self.factored);
        let (i, k) = (dof / 3, dof % 3);
        let couplings = self.pattern.couplings_of(i).iter();
        let mut entries: Vec<(usize, f64)> = (couplings.map(|c| (c.node, c.row)))
            .chain([(i, self.diagonal_slot(i))])
            .flat_map(|(j, slot)| (0..3).map(move |c| (3 * j + c, self.blocks[slot][(k, c)])))
            .collect();
        entries.sort_unstable_by_key(|e| e.0);
        entries
    }

    fn diagonal_slot(&self, node: usize) -> usize {
        self.pattern.steps[self.pattern.position[node]].slot
    }
}
