//! The energy-momentum discrete gradient of the element energy ([`Element::discrete_gradient`])
//! and the Cayley increment of a rotation ([`cayley`]) it is conjugate to: the scheme of the
//! energy-momentum integrator, apart from the midpoint rule's force and tangent in `element`. A
//! child module of `element` (declared there, `cayley` re-exported as `element::cayley`), so it
//! reads the element's private reference angles.
use super::{shape_functions, Element, Vector6, GAUSS_POINTS};
use crate::model::section::Section;
use nalgebra::{Matrix2x3, SMatrix, Vector2};

type Matrix2x6 = SMatrix<f64, 2, 6>;
type Matrix3x6 = SMatrix<f64, 3, 6>;

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
            let (cos_al, sin_al) = self.tangent[g];
            let stretch = |u: &Vector6| {
                let x1 = cos_al + (u[3] - u[0]) * inv_l;
                let x2 = sin_al + (u[4] - u[1]) * inv_l;
                (x1, x2, self.alpha[g] + na * u[2] + nb * u[5])
            };
            let (xa1, xa2, theta_a) = stretch(ua);
            let (xb1, xb2, theta_b) = stretch(ub);
            let (sa, ca) = libm::sincos(theta_a);
            let (sb, cb) = libm::sincos(theta_b);
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
    2.0 * libm::tan(0.5 * dw)
}
