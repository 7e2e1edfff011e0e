//! Forward and backward sweeps over the factors of a [`SparseBlocks`], then the ties.
use super::SparseBlocks;
use nalgebra::Vector3;

impl SparseBlocks {
    /// Solves `A x = rhs` in place (after a factorization), then copies each tie's master into
    /// its slave.
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        self.solve_each(&mut [rhs]);
    }

    /// Solves `A x = a` and `A x = b` in place, in one pass over the factors (each to the bit
    /// as [`solve_in_place`](Self::solve_in_place) solves it).
    pub fn solve_pair(&self, a: &mut [f64], b: &mut [f64]) {
        self.solve_each(&mut [a, b]);
    }

    fn solve_each<const K: usize>(&self, rhs: &mut [&mut [f64]; K]) {
        assert!(self.factored, "solve before factor");
        let pattern = &*self.pattern;
        let blocks = &self.blocks[..];
        let steps = pattern.steps.iter().zip(&pattern.steps[1..]);
        // Forward: x_(q_a) -= L_a x_p, step after step.
        for (step, next) in steps.clone() {
            let later = &pattern.later[step.later..next.later];
            for x in rhs.iter_mut() {
                let xp = block(x, step.node);
                for (a, &q) in later.iter().enumerate() {
                    let y = block(x, q) - blocks[step.slot + 2 + 2 * a] * xp;
                    set_block(x, q, &y);
                }
            }
        }
        // Backward: x_p = D^-1 x_p - sum_a U_a x_(q_a), from the last step.
        for (step, next) in steps.rev() {
            let later = &pattern.later[step.later..next.later];
            for x in rhs.iter_mut() {
                let mut y = blocks[step.slot] * block(x, step.node);
                for (a, &q) in later.iter().enumerate() {
                    y -= blocks[step.slot + 1 + 2 * a] * block(x, q);
                }
                set_block(x, step.node, &y);
            }
        }
        for x in rhs.iter_mut() {
            for &(slave, master) in &self.ties {
                x[slave] = x[master];
            }
        }
    }
}

/// Node `i`'s three entries of a dof vector (one bounds check).
pub(super) fn block(x: &[f64], i: usize) -> Vector3<f64> {
    let entries: &[f64; 3] = x[3 * i..3 * i + 3].try_into().expect("three entries");
    Vector3::from(*entries)
}

pub(super) fn set_block(x: &mut [f64], i: usize, value: &Vector3<f64>) {
    let entries: &mut [f64; 3] = (&mut x[3 * i..3 * i + 3])
        .try_into()
        .expect("three entries");
    *entries = [value.x, value.y, value.z];
}
