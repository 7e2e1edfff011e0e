//! Natural frequencies about an equilibrium: the dense generalized symmetric eigenproblem
//! `K_T(u) phi = omega^2 M phi` on the free dofs (constrained tangent, consistent mass). Meant for
//! small meshes (a few hundred dofs) and analysis, never for the time-step loop.
use super::rod::{Rod, U2};
use crate::solver::BlockTridiagonal;
use nalgebra::{DMatrix, DVector};

/// One mode about an equilibrium.
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    /// `omega^2` (negative: the equilibrium is unstable in this direction).
    pub omega_squared: f64,
    /// Mode shape on all dofs (zero on the constrained ones), mass-normalized (`phi^T M phi = 1`).
    pub shape: Vec<f64>,
    /// Transverse displacement of the shape at `s = S/2`.
    pub w_mid: f64,
    /// Symmetric about the midspan (the crown moves), rather than antisymmetric.
    pub symmetric: bool,
}

impl Mode {
    /// Angular frequency `omega` in rad/s (NaN for an unstable direction).
    pub fn omega(&self) -> f64 {
        if self.omega_squared >= 0.0 {
            self.omega_squared.sqrt()
        } else {
            f64::NAN
        }
    }

    /// Frequency in Hz.
    pub fn hertz(&self) -> f64 {
        self.omega() / (2.0 * std::f64::consts::PI)
    }
}

/// Free dofs of `rod`.
pub fn free_dofs(rod: &Rod) -> Vec<usize> {
    (0..rod.dofs()).filter(|&i| !rod.fixed[i]).collect()
}

/// Dense `(K_T(u), M)` restricted to the free dofs.
pub fn dense_tangent_and_mass(rod: &Rod, u: &[f64]) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = rod.dofs();
    let free = free_dofs(rod);
    let mut jac = BlockTridiagonal::new(rod.nodes());
    let mut f = vec![0.0; n];
    rod.internal_force_and_tangent(u, &mut f, &mut jac, 1.0);
    let m = free.len();
    let mut k = DMatrix::zeros(m, m);
    let mut mass = DMatrix::zeros(m, m);
    let mut e = vec![0.0; n];
    let mut col = vec![0.0; n];
    for (j, &dj) in free.iter().enumerate() {
        e[dj] = 1.0;
        jac.mul(&e, &mut col);
        for (i, &di) in free.iter().enumerate() {
            k[(i, j)] = col[di];
        }
        col.fill(0.0);
        rod.add_mass_times(&e, &mut col, 1.0);
        for (i, &di) in free.iter().enumerate() {
            mass[(i, j)] = col[di];
        }
        e[dj] = 0.0;
    }
    // Symmetrize round-off.
    let k = 0.5 * (&k + k.transpose());
    (k, mass)
}

/// All modes about the equilibrium `u`, lowest `omega^2` first.
pub fn modes(rod: &Rod, u: &[f64]) -> Vec<Mode> {
    let free = free_dofs(rod);
    let (k, mass) = dense_tangent_and_mass(rod, u);
    let chol = mass
        .cholesky()
        .expect("the consistent mass is positive definite");
    // A = L^-1 K L^-T.
    let l = chol.l();
    let linv = l.clone().try_inverse().expect("Cholesky factor invertible");
    let a = &linv * &k * linv.transpose();
    let a = 0.5 * (&a + a.transpose());
    let eig = a.symmetric_eigen();
    let mut order: Vec<usize> = (0..eig.eigenvalues.len()).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    let mid = rod.midspan();
    let mirror = |shape: &[f64]| {
        // Symmetric about s = S/2: u2 even, u1 and w odd under the mirror. Compare the u2 part.
        let nodes = rod.nodes();
        let (mut even, mut odd) = (0.0, 0.0);
        for i in 0..nodes {
            let j = nodes - 1 - i;
            let (a, b) = (shape[3 * i + U2], shape[3 * j + U2]);
            even += (a + b) * (a + b);
            odd += (a - b) * (a - b);
        }
        even >= odd
    };
    order
        .into_iter()
        .map(|i| {
            let y: DVector<f64> = eig.eigenvectors.column(i).into_owned();
            let phi = linv.transpose() * y;
            let mut shape = vec![0.0; rod.dofs()];
            for (k, &d) in free.iter().enumerate() {
                shape[d] = phi[k];
            }
            let w_mid = rod.interpolate(&shape, mid, U2);
            let symmetric = mirror(&shape);
            Mode {
                omega_squared: eig.eigenvalues[i],
                shape,
                w_mid,
                symmetric,
            }
        })
        .collect()
}
