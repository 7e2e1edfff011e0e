//! Symmetric matrices with the band structure of the consistent mass and damping matrices: a
//! diagonal and one band coupling each dof with the same dof of the next node (distance 3), so
//! products and quadratic forms are a few passes over the dof vector that the compiler
//! vectorizes.
use crate::solver::vector::sum;

/// A vector with its factor, `(a, x)` for `a x`.
pub type Scaled<'a> = (f64, &'a [f64]);

/// `P = diag(diagonal) + the band `off` at +3 and -3`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bands {
    diagonal: Vec<f64>,
    off: Vec<f64>,
}

impl Bands {
    /// The consistent pattern: element `e` (between nodes `e` and `e + 1`) adds
    /// `[[2 c, c], [c, 2 c]]` per dof kind, `c = coefficients[e][kind]`, or with `lumped`
    /// `[[3 c, 0], [0, 3 c]]` (row sums on the diagonal).
    pub fn consistent(coefficients: &[[f64; 3]], lumped: bool) -> Bands {
        let dofs = 3 * (coefficients.len() + 1);
        let mut bands = Bands {
            diagonal: vec![0.0; dofs],
            off: vec![0.0; dofs - 3],
        };
        let (own, shared) = if lumped { (3.0, 0.0) } else { (2.0, 1.0) };
        for (e, c) in coefficients.iter().enumerate() {
            for (k, c) in c.iter().enumerate() {
                bands.diagonal[3 * e + k] += own * c;
                bands.diagonal[3 * e + 3 + k] += own * c;
                bands.off[3 * e + k] += shared * c;
            }
        }
        bands
    }

    /// Zero bands for `dofs` dofs.
    pub fn zeros(dofs: usize) -> Bands {
        Bands {
            diagonal: vec![0.0; dofs],
            off: vec![0.0; dofs - 3],
        }
    }

    /// Adds `value` to the diagonal entry of `dof` (a point mass, spring or dashpot).
    pub fn add_diagonal(&mut self, dof: usize, value: f64) {
        self.diagonal[dof] += value;
    }

    /// Adds `[[2 c, c], [c, 2 c]]` on dof kind `k` of element `e` (the consistent pattern).
    pub fn add_pattern(&mut self, e: usize, k: usize, c: f64) {
        self.diagonal[3 * e + k] += 2.0 * c;
        self.diagonal[3 * e + 3 + k] += 2.0 * c;
        self.off[3 * e + k] += c;
    }

    /// `self += other`.
    pub fn add_bands(&mut self, other: &Bands) {
        for (a, b) in self.diagonal.iter_mut().zip(&other.diagonal) {
            *a += b;
        }
        for (a, b) in self.off.iter_mut().zip(&other.off) {
            *a += b;
        }
    }

    /// Row `dof` of `P x`: O(1).
    pub fn row_times(&self, x: &[f64], dof: usize) -> f64 {
        let mut r = self.diagonal[dof] * x[dof];
        if dof >= 3 {
            r += self.off[dof - 3] * x[dof - 3];
        }
        if dof + 3 < x.len() {
            r += self.off[dof] * x[dof + 3];
        }
        r
    }

    /// `out += scale * P x`.
    pub fn add_times(&self, x: &[f64], out: &mut [f64], scale: f64) {
        // Three passes: the diagonal, the band above, the band below.
        let n = out.len();
        let pass = |out: &mut [f64], p: &[f64], x: &[f64]| {
            let k = out.len();
            let (p, x) = (&p[..k], &x[..k]);
            for j in 0..k {
                out[j] += scale * (p[j] * x[j]);
            }
        };
        pass(out, &self.diagonal, x);
        pass(&mut out[..n - 3], &self.off, &x[3..]);
        pass(&mut out[3..], &self.off, &x[..n - 3]);
    }

    /// `out += self (a x + b y) + damping (c x) + z` (`self` the mass matrix; no `z` if
    /// `None`): the linear part of the midpoint rule's residual and of its tangent map, in
    /// three passes (diagonal, band above, band below). The bracket `a x + b y` is formed
    /// before it is multiplied: where it is a small difference of large terms (inertia of a
    /// fast, slowly accelerating motion), it keeps its precision.
    pub fn add_bracket_times(
        &self,
        damping: &Bands,
        ((a, x), (b, y)): (Scaled, Scaled),
        c: f64,
        z: Option<&[f64]>,
        out: &mut [f64],
    ) {
        let n = out.len();
        let (m, d) = (self, damping);
        // Slices of one length, indexed: no bounds checks, and the loop vectorizes.
        let pass = |out: &mut [f64], m: &[f64], d: &[f64], x: &[f64], y: &[f64]| {
            let k = out.len();
            let (m, d, x, y) = (&m[..k], &d[..k], &x[..k], &y[..k]);
            for j in 0..k {
                out[j] += m[j] * (a * x[j] + b * y[j]) + c * (d[j] * x[j]);
            }
        };
        if let Some(z) = z {
            let z = &z[..n];
            for j in 0..n {
                out[j] += z[j];
            }
        }
        pass(out, &m.diagonal, &d.diagonal, x, y);
        pass(&mut out[..n - 3], &m.off, &d.off, &x[3..], &y[3..]);
        pass(&mut out[3..], &m.off, &d.off, &x[..n - 3], &y[..n - 3]);
    }

    /// `x^T P x`: `x . (diagonal x) + 2 x . (off x shifted)`.
    pub fn form(&self, x: &[f64]) -> f64 {
        let n = x.len();
        let diagonal = sum(n, |j| self.diagonal[j] * x[j] * x[j]);
        let off = sum(n - 3, |j| self.off[j] * x[j] * x[j + 3]);
        diagonal + 2.0 * off
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Products and forms against the dense matrix of the same bands (three nodes, consistent
    /// and lumped).
    #[test]
    fn products_and_forms_match_the_dense_matrix() {
        let coefficients = [[1.0, 2.0, 0.5], [0.25, 3.0, 1.5]];
        for lumped in [false, true] {
            let p = Bands::consistent(&coefficients, lumped);
            let n = 9;
            let mut dense = [[0.0; 9]; 9];
            let (own, shared) = if lumped { (3.0, 0.0) } else { (2.0, 1.0) };
            for (e, c) in coefficients.iter().enumerate() {
                for (k, c) in c.iter().enumerate() {
                    let (a, b) = (3 * e + k, 3 * e + 3 + k);
                    dense[a][a] += own * c;
                    dense[b][b] += own * c;
                    dense[a][b] += shared * c;
                    dense[b][a] += shared * c;
                }
            }
            let x: Vec<f64> = (0..n).map(|i| (0.7 * i as f64).sin()).collect();
            let known: Vec<f64> = (0..n).map(|i| i as f64).collect();
            let (mut scaled, mut plus) = (vec![1.0; n], vec![1.0; n]);
            p.add_times(&x, &mut scaled, 2.0);
            // P (2 x - 0.5 x) + 0.5 P x + known = 2 P x + known (P as mass and damping).
            let pair = ((2.0, &x[..]), (-0.5, &x[..]));
            p.add_bracket_times(&p, pair, 0.5, Some(&known), &mut plus);
            let mut form = 0.0;
            for i in 0..n {
                let px: f64 = (0..n).map(|j| dense[i][j] * x[j]).sum();
                form += x[i] * px;
                assert!(
                    (scaled[i] - 1.0 - 2.0 * px).abs() < 1e-14,
                    "{lumped} row {i}"
                );
                assert!(
                    (plus[i] - 1.0 - 2.0 * px - known[i]).abs() < 1e-13,
                    "{lumped} row {i}"
                );
            }
            assert!((p.form(&x) - form).abs() < 1e-14, "{lumped}");
        }
    }
}
