//! The hybrid two-node element (paper section 4, model.md "Element").
//!
//! Element dofs `ue = [u1a, u2a, wa, u1b, u2b, wb]`. Linear shape functions, so `u1'`, `u2'` are
//! constant; `w` and the exact reference angle `alpha` are taken at two Gauss points. The constant
//! normal and shear forces `S = (S1, S2)` are eliminated per element: with `C = diag(EA, GA)`,
//! `b(u) = integral (e1, e2) ds`, `S = C b / l`, internal force `B^T S + K_bend u`,
//! energy `b^T C b / (2 l) + EI l k^2 / 2`, tangent `B^T C B / l + S1 b1'' + S2 b2'' + K_bend`.
use super::section::Section;
use nalgebra::{Matrix2x3, Matrix3, SMatrix, SVector, Vector2, Vector3};

pub type Vector6 = SVector<f64, 6>;
pub type Matrix6 = SMatrix<f64, 6, 6>;
type Matrix2x6 = SMatrix<f64, 2, 6>;
type Matrix3x6 = SMatrix<f64, 3, 6>;

/// Gauss points on `[-1, 1]` (weights 1): two points for everything (model.md).
pub const GAUSS_POINTS: [f64; 2] = [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8];

/// Linear shape functions `(N_a, N_b)` at `xi` in `[-1, 1]`.
pub fn shape_functions(xi: f64) -> (f64, f64) {
    (0.5 * (1.0 - xi), 0.5 * (1.0 + xi))
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Element {
    /// Length `l` in arc length.
    pub length: f64,
    /// Exact reference tangent angle at the two Gauss points.
    pub alpha: [f64; 2],
}

/// Strains at one Gauss point and the map from element dofs to `(u1', u2', w)` there.
struct GaussPoint {
    e1: f64,
    e2: f64,
    cos_aw: f64,
    sin_aw: f64,
    /// `d(u1', u2', w) / d ue`.
    map: Matrix3x6,
}

impl Element {
    fn gauss_point(&self, g: usize, ue: &Vector6) -> GaussPoint {
        let inv_l = 1.0 / self.length;
        let (na, nb) = shape_functions(GAUSS_POINTS[g]);
        let du1 = (ue[3] - ue[0]) * inv_l;
        let du2 = (ue[4] - ue[1]) * inv_l;
        let w = na * ue[2] + nb * ue[5];
        let (sin_w, cos_w) = w.sin_cos();
        let (sin_aw, cos_aw) = (self.alpha[g] + w).sin_cos();
        #[rustfmt::skip]
        let map = Matrix3x6::new(
            -inv_l, 0.0, 0.0, inv_l, 0.0, 0.0,
            0.0, -inv_l, 0.0, 0.0, inv_l, 0.0,
            0.0, 0.0, na, 0.0, 0.0, nb,
        );
        GaussPoint {
            e1: cos_w + cos_aw * du1 + sin_aw * du2 - 1.0,
            e2: -sin_w - sin_aw * du1 + cos_aw * du2,
            cos_aw,
            sin_aw,
            map,
        }
    }

    /// `b(u)` (integrated stretch and shear strain) and `B = db/du`.
    fn strain_integrals(&self, ue: &Vector6) -> (Vector2<f64>, Matrix2x6, [GaussPoint; 2]) {
        let half_l = 0.5 * self.length;
        let gps = [self.gauss_point(0, ue), self.gauss_point(1, ue)];
        let mut b = Vector2::zeros();
        let mut b_mat = Matrix2x6::zeros();
        for gp in &gps {
            b += half_l * Vector2::new(gp.e1, gp.e2);
            // Gradients of (e1, e2) with respect to (u1', u2', w); note de1/dw = e2 and
            // de2/dw = -(1 + e1).
            #[rustfmt::skip]
            let grad = Matrix2x3::new(
                gp.cos_aw, gp.sin_aw, gp.e2,
                -gp.sin_aw, gp.cos_aw, -(1.0 + gp.e1),
            );
            b_mat += half_l * grad * gp.map;
        }
        (b, b_mat, gps)
    }

    /// The eliminated constant forces `S = (S1, S2) = C b / l` (normal and shear force).
    pub fn stress_resultants(&self, section: &Section, ue: &Vector6) -> Vector2<f64> {
        let (b, _, _) = self.strain_integrals(ue);
        Vector2::new(section.ea * b[0], section.ga * b[1]) / self.length
    }

    /// Strain energy `b^T C b / (2 l) + EI l k^2 / 2`.
    pub fn strain_energy(&self, section: &Section, ue: &Vector6) -> f64 {
        let (b, _, _) = self.strain_integrals(ue);
        let kappa = (ue[5] - ue[2]) / self.length;
        0.5 * (section.ea * b[0] * b[0] + section.ga * b[1] * b[1]) / self.length
            + 0.5 * section.ei * self.length * kappa * kappa
    }

    /// Internal force `B^T S + K_bend u`.
    pub fn internal_force(&self, section: &Section, ue: &Vector6) -> Vector6 {
        let (b, b_mat, _) = self.strain_integrals(ue);
        let s = Vector2::new(section.ea * b[0], section.ga * b[1]) / self.length;
        let mut f = b_mat.transpose() * s;
        let moment = section.ei * (ue[5] - ue[2]) / self.length;
        f[2] -= moment;
        f[5] += moment;
        f
    }

    /// Internal force and consistent (symmetric) tangent.
    pub fn force_and_tangent(&self, section: &Section, ue: &Vector6) -> (Vector6, Matrix6) {
        let half_l = 0.5 * self.length;
        let (b, b_mat, gps) = self.strain_integrals(ue);
        let inv_l = 1.0 / self.length;
        let s = Vector2::new(section.ea * b[0], section.ga * b[1]) * inv_l;
        let mut f = b_mat.transpose() * s;
        let c_over_l = nalgebra::Matrix2::new(section.ea * inv_l, 0.0, 0.0, section.ga * inv_l);
        let mut k = b_mat.transpose() * c_over_l * b_mat;
        for gp in &gps {
            // S1 d2e1 + S2 d2e2 with respect to (u1', u2', w).
            let a = -s[0] * gp.sin_aw - s[1] * gp.cos_aw;
            let c = s[0] * gp.cos_aw - s[1] * gp.sin_aw;
            let ww = -s[0] * (1.0 + gp.e1) - s[1] * gp.e2;
            #[rustfmt::skip]
            let h = Matrix3::new(
                0.0, 0.0, a,
                0.0, 0.0, c,
                a, c, ww,
            );
            k += half_l * gp.map.transpose() * h * gp.map;
        }
        let kb = section.ei * inv_l;
        let moment = kb * (ue[5] - ue[2]);
        f[2] -= moment;
        f[5] += moment;
        k[(2, 2)] += kb;
        k[(5, 5)] += kb;
        k[(2, 5)] -= kb;
        k[(5, 2)] -= kb;
        (f, k)
    }
}

impl Element {
    /// Energy-momentum discrete gradient of the element energy between the states `ua` and
    /// `ub`, conjugate to the translation increments and to the Cayley increments of the nodal
    /// rotations, `tau = 2 tan(Dw / 2)` (see [`cayley`]): a force `f` with
    /// `f_x . Dx + f_w . tau = V(ub) - V(ua)` exactly, which vanishes on rigid translations and
    /// on the rigid rotation `(dx, tau) = (e3 x xbar, 1)` of the mid configuration (so a scheme
    /// that moves rotations by `tau` conserves energy, linear and angular momentum).
    ///
    /// Per Gauss point, with the strain `Gamma = Lambda(theta)^T x' - E1`, the averaged rotation
    /// `Lambdabar = (Lambda_a + Lambda_b) / 2 = cos(Dtheta/2) Lambda(theta_mid)` and
    /// `xbar' = (x'_a + x'_b) / 2`, the increment is exactly
    /// `DGamma = Lambdabar^T (Dx' - tau_gp J xbar')`, `tau_gp = 2 tan(Dtheta_gp / 2)`;
    /// `tau_gp` is written with weights on the nodal `tau` that sum to one (secant
    /// interpolation), and the bending increment `Dw_b - Dw_a` with weights `(-g, g)`.
    /// The membrane energy is quadratic in `b`, so the averaged force `Sbar = C (ba + bb) / (2 l)`
    /// gives `Sbar . Db = DV` exactly; likewise the average curvature for bending.
    pub fn discrete_gradient(&self, section: &Section, ua: &Vector6, ub: &Vector6) -> Vector6 {
        let half_l = 0.5 * self.length;
        let inv_l = 1.0 / self.length;
        let (dwa, dwb) = (ub[2] - ua[2], ub[5] - ua[5]);
        let (ta, tb) = (cayley(dwa), cayley(dwb));
        // Rotation increments as linear forms in the nodal tau: Dw = dw_dtau(t1, t2) (t2 - t1)
        // between two tau values, exact (the secant of 2 atan(t / 2)).
        let distinct = (tb - ta).abs() > 1e-9 * (1.0 + ta.abs() + tb.abs());
        let mut b_bar = Matrix2x6::zeros();
        let mut b_sum = Vector2::zeros();
        for (g, &xi) in GAUSS_POINTS.iter().enumerate() {
            let (na, nb) = shape_functions(xi);
            let (sin_al, cos_al) = self.alpha[g].sin_cos();
            let stretch = |u: &Vector6| {
                let x1 = cos_al + (u[3] - u[0]) * inv_l;
                let x2 = sin_al + (u[4] - u[1]) * inv_l;
                (x1, x2, self.alpha[g] + na * u[2] + nb * u[5])
            };
            let (xa1, xa2, theta_a) = stretch(ua);
            let (xb1, xb2, theta_b) = stretch(ub);
            let (sa, ca) = theta_a.sin_cos();
            let (sb, cb) = theta_b.sin_cos();
            b_sum += half_l
                * Vector2::new(
                    xa1 * ca + xa2 * sa + xb1 * cb + xb2 * sb - 2.0,
                    -xa1 * sa + xa2 * ca - xb1 * sb + xb2 * cb,
                );
            // Lambdabar^T rows (averaged directors) and J xbar'.
            let d1 = (0.5 * (ca + cb), 0.5 * (sa + sb));
            let d2 = (-0.5 * (sa + sb), 0.5 * (ca + cb));
            let (jx1, jx2) = (-0.5 * (xa2 + xb2), 0.5 * (xa1 + xb1));
            let rot1 = -(d1.0 * jx1 + d1.1 * jx2);
            let rot2 = -(d2.0 * jx1 + d2.1 * jx2);
            // tau_gp = wa tau_a + wb tau_b exactly, with wa + wb = 1.
            let (wa, wb) = if distinct {
                let t_gp = cayley(na * dwa + nb * dwb);
                ((tb - t_gp) / (tb - ta), (t_gp - ta) / (tb - ta))
            } else {
                (na, nb)
            };
            #[rustfmt::skip]
            let grad = Matrix2x3::new(
                d1.0, d1.1, rot1,
                d2.0, d2.1, rot2,
            );
            #[rustfmt::skip]
            let map = Matrix3x6::new(
                -inv_l, 0.0, 0.0, inv_l, 0.0, 0.0,
                0.0, -inv_l, 0.0, 0.0, inv_l, 0.0,
                0.0, 0.0, wa, 0.0, 0.0, wb,
            );
            b_bar += half_l * grad * map;
        }
        let s_bar = 0.5 * Vector2::new(section.ea * b_sum[0], section.ga * b_sum[1]) * inv_l;
        let mut f = b_bar.transpose() * s_bar;
        // Bending: D(w_b - w_a) = g (tau_b - tau_a).
        let g = if distinct {
            (dwb - dwa) / (tb - ta)
        } else {
            1.0 / (1.0 + 0.25 * ta * tb)
        };
        let moment = section.ei * inv_l * 0.5 * ((ua[5] - ua[2]) + (ub[5] - ub[2])) * g;
        f[2] -= moment;
        f[5] += moment;
        f
    }
}

/// Cayley increment of a rotation increment: `tau = 2 tan(Dw / 2)` (the rotation that the
/// energy-momentum scheme's angular velocity `tau / dt` describes; `tau = Dw + O(Dw^3)`).
pub fn cayley(dw: f64) -> f64 {
    2.0 * (0.5 * dw).tan()
}

/// Consistent mass and damping coefficients of one element (two Gauss points integrate
/// `N^T N` exactly): the `[[2, 1], [1, 2]] * l / 6` pattern, scaled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementInertia {
    /// `rho A l / 6` on `u1`, `u2`.
    pub translational: f64,
    /// `rho I l / 6` on `w`.
    pub rotational: f64,
    /// `d l / 6` on `u1`, `u2`.
    pub damping: f64,
}

impl ElementInertia {
    pub fn new(section: &Section, damping: f64, length: f64) -> ElementInertia {
        ElementInertia {
            translational: section.rho_a * length / 6.0,
            rotational: section.rho_i * length / 6.0,
            damping: damping * length / 6.0,
        }
    }

    /// Per-dof-kind coefficients `(u1, u2, w)` of the mass (or damping if `damping`).
    pub fn coefficients(&self, damping: bool) -> Vector3<f64> {
        if damping {
            Vector3::new(self.damping, self.damping, 0.0)
        } else {
            Vector3::new(self.translational, self.translational, self.rotational)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tangent is the derivative of the internal force, and the force that of the energy
    /// (central differences, relative error below 1e-6), for a curved element at large rotation.
    #[test]
    fn tangent_and_force_are_derivatives() {
        let section = Section::rectangular(1.2e4, 0.2, 1e-6, 1.0, 1.0);
        let el = Element {
            length: 0.8,
            alpha: [0.3, 0.1],
        };
        let ue = Vector6::new(0.05, -0.2, 1.3, 0.4, 0.1, 2.1);
        let (f, k) = el.force_and_tangent(&section, &ue);
        let h = 1e-6;
        for j in 0..6 {
            let mut up = ue;
            let mut dn = ue;
            up[j] += h;
            dn[j] -= h;
            let fd =
                (el.internal_force(&section, &up) - el.internal_force(&section, &dn)) / (2.0 * h);
            let err = (fd - k.column(j)).norm() / k.norm();
            assert!(err < 1e-6, "column {j}: {err}");
            let de =
                (el.strain_energy(&section, &up) - el.strain_energy(&section, &dn)) / (2.0 * h);
            assert!(
                (de - f[j]).abs() < 1e-6 * f.norm(),
                "force {j}: {de} vs {}",
                f[j]
            );
        }
        assert!((k - k.transpose()).norm() < 1e-12 * k.norm());
    }

    /// The discrete gradient gives the exact energy difference (conjugate to the Cayley
    /// rotation increments), vanishes on rigid translations and on the rigid rotation of the
    /// mid configuration, and tends to the force at the midpoint.
    #[test]
    fn discrete_gradient_is_exact_and_invariant() {
        let section = Section::rectangular(1.2e4, 0.2, 1e-6, 1.0, 1.0);
        let el = Element {
            length: 0.8,
            alpha: [0.3, 0.1],
        };
        let ua = Vector6::new(0.05, -0.2, 1.3, 0.4, 0.1, 2.1);
        let ub = Vector6::new(0.09, -0.1, 1.9, 0.3, 0.3, 2.7);
        let f = el.discrete_gradient(&section, &ua, &ub);
        let d = ub - ua;
        let work = f[0] * d[0]
            + f[1] * d[1]
            + f[3] * d[3]
            + f[4] * d[4]
            + f[2] * cayley(d[2])
            + f[5] * cayley(d[5]);
        let dv = el.strain_energy(&section, &ub) - el.strain_energy(&section, &ua);
        assert!(
            (work - dv).abs() < 1e-12 * dv.abs().max(1.0),
            "energy {work} vs {dv}"
        );
        // Rigid translations (rotations: the free-flight tests of tests/energy_momentum.rs).
        assert!((f[0] + f[3]).abs() < 1e-10 * f.norm() && (f[1] + f[4]).abs() < 1e-10 * f.norm());
        let small = ua + 1e-4 * (ub - ua);
        let near = el.discrete_gradient(&section, &ua, &small);
        let at = el.internal_force(&section, &(0.5 * (ua + small)));
        assert!((near - at).norm() < 1e-6 * at.norm(), "consistency");
    }
}
