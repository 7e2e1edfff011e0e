//! Forward and backward sweeps over the factors of a [`BlockTridiagonal`], and the access to
//! a node's three entries of a dof vector.
use super::BlockTridiagonal;
use nalgebra::Vector3;

impl BlockTridiagonal {
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
}

pub(super) fn block(x: &[f64], i: usize) -> Vector3<f64> {
    Vector3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2])
}

fn set_block(x: &mut [f64], i: usize, value: &Vector3<f64>) {
    x[3 * i..3 * i + 3].copy_from_slice(value.as_slice());
}
