//! The hybrid two-node element (paper section 4, model.md "Element").
//!
//! Element dofs `ue = [u1a, u2a, wa, u1b, u2b, wb]`. Linear shape functions, so `u1'`, `u2'` are
//! constant; `w` and the exact reference angle `alpha` are taken at two Gauss points. The constant
//! normal and shear forces `S = (S1, S2)` are eliminated per element: with `C = diag(EA, GA)`,
//! `b(u) = integral (e1, e2) ds`, `S = C b / l`, internal force `B^T S + K_bend u`,
//! energy `b^T C b / (2 l) + EI l k^2 / 2`, tangent `B^T C B / l + S1 b1'' + S2 b2'' + K_bend`.
//!
//! The force and tangent are written out entry by entry (this is the inner loop of every Newton
//! iteration): `B` has only four distinct translational entries, and the second derivatives of
//! `b` couple the translations only with the rotations, so the generic products
//! `B^T C B` and `map^T H map` reduce to a few dozen multiply-adds.
use super::section::Section;
use nalgebra::{SMatrix, SVector, Vector2, Vector3};

#[path = "discrete_gradient.rs"]
mod discrete_gradient;
#[path = "element_tangent.rs"]
mod element_tangent;

pub use discrete_gradient::cayley;
pub use element_tangent::ElementTangent;

pub type Vector6 = SVector<f64, 6>;
pub type Matrix6 = SMatrix<f64, 6, 6>;

/// Gauss points on `[-1, 1]` (weights 1): two points for everything (model.md).
pub const GAUSS_POINTS: [f64; 2] = [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8];

/// Linear shape functions `(N_a, N_b)` at `xi` in `[-1, 1]`.
pub fn shape_functions(xi: f64) -> (f64, f64) {
    (0.5 * (1.0 - xi), 0.5 * (1.0 + xi))
}

/// `(sin w, cos w)` of the rotation `w` at the two Gauss points.
pub type GaussTrig = [(f64, f64); 2];

/// `(sin w, cos w)` at the two Gauss points of an element with dofs `ue`.
pub fn gauss_trig(ue: &Vector6) -> GaussTrig {
    SHAPE_AT_GAUSS.map(|(na, nb)| libm::sincos(na * ue[2] + nb * ue[5]))
}

/// Shape functions at the two Gauss points.
const SHAPE_AT_GAUSS: [(f64, f64); 2] = [
    (0.788_675_134_594_812_9, 0.211_324_865_405_187_1),
    (0.211_324_865_405_187_1, 0.788_675_134_594_812_9),
];

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Element {
    /// Length `l` in arc length.
    pub length: f64,
    /// Exact reference tangent angle at the two Gauss points.
    alpha: [f64; 2],
    /// `(cos alpha, sin alpha)` at the two Gauss points (saves two `sin_cos` per evaluation).
    tangent: [(f64, f64); 2],
}

/// Strains at one Gauss point: `e1`, `e2` and the current director angle's `cos`, `sin`.
#[derive(Clone, Copy)]
struct GaussStrain {
    e1: f64,
    e2: f64,
    cos_aw: f64,
    sin_aw: f64,
}

/// `b = integral (e1, e2) ds` and its gradient `B = db/du`. `B` has the structure
/// `[[-p1, -p2, r0a, p1, p2, r0b], [p2, -p1, r1a, -p2, p1, r1b]]`.
#[derive(Clone, Copy)]
struct StrainIntegrals {
    b: [f64; 2],
    p1: f64,
    p2: f64,
    /// `(r0a, r0b, r1a, r1b)`: the rotation columns of `B`.
    r: [f64; 4],
    gauss: [GaussStrain; 2],
}

impl StrainIntegrals {
    /// `B` as an array of its two rows.
    fn rows(&self) -> [[f64; 6]; 2] {
        let (p1, p2, r) = (self.p1, self.p2, self.r);
        [
            [-p1, -p2, r[0], p1, p2, r[1]],
            [p2, -p1, r[2], -p2, p1, r[3]],
        ]
    }
}

impl Element {
    pub fn new(length: f64, alpha: [f64; 2]) -> Element {
        Element {
            length,
            alpha,
            tangent: alpha.map(|a| {
                let (s, c) = libm::sincos(a);
                (c, s)
            }),
        }
    }

    /// Exact reference tangent angle at the two Gauss points.
    pub fn alpha(&self) -> [f64; 2] {
        self.alpha
    }

    /// The strain integrals at `ue`, whose rotation has the sines and cosines `trig` at the
    /// Gauss points ([`gauss_trig`]).
    #[inline(always)]
    fn strain_integrals(&self, ue: &Vector6, trig: &GaussTrig) -> StrainIntegrals {
        let half_l = 0.5 * self.length;
        let inv_l = 1.0 / self.length;
        let du1 = (ue[3] - ue[0]) * inv_l;
        let du2 = (ue[4] - ue[1]) * inv_l;
        let mut out = StrainIntegrals {
            b: [0.0; 2],
            p1: 0.0,
            p2: 0.0,
            r: [0.0; 4],
            gauss: [GaussStrain {
                e1: 0.0,
                e2: 0.0,
                cos_aw: 1.0,
                sin_aw: 0.0,
            }; 2],
        };
        for (g, &(na, nb)) in SHAPE_AT_GAUSS.iter().enumerate() {
            let (sin_w, cos_w) = trig[g];
            let (cos_a, sin_a) = self.tangent[g];
            let cos_aw = cos_a * cos_w - sin_a * sin_w;
            let sin_aw = sin_a * cos_w + cos_a * sin_w;
            let e1 = cos_w + cos_aw * du1 + sin_aw * du2 - 1.0;
            let e2 = -sin_w - sin_aw * du1 + cos_aw * du2;
            out.b[0] += half_l * e1;
            out.b[1] += half_l * e2;
            // d(e1, e2)/d(u1', u2', w) = [[cos, sin, e2], [-sin, cos, -(1 + e1)]]; u1' = (u1b -
            // u1a) / l carries the weight l/2 * 1/l = 1/2.
            out.p1 += 0.5 * cos_aw;
            out.p2 += 0.5 * sin_aw;
            out.r[0] += half_l * e2 * na;
            out.r[1] += half_l * e2 * nb;
            out.r[2] -= half_l * (1.0 + e1) * na;
            out.r[3] -= half_l * (1.0 + e1) * nb;
            out.gauss[g] = GaussStrain {
                e1,
                e2,
                cos_aw,
                sin_aw,
            };
        }
        out
    }

    /// `S = C b / l`.
    fn forces(&self, section: &Section, b: &[f64; 2]) -> [f64; 2] {
        let inv_l = 1.0 / self.length;
        [section.ea * b[0] * inv_l, section.ga * b[1] * inv_l]
    }

    /// The eliminated constant forces `S = (S1, S2) = C b / l` (normal and shear force).
    pub fn stress_resultants(&self, section: &Section, ue: &Vector6) -> Vector2<f64> {
        let s = self.forces(section, &self.strain_integrals(ue, &gauss_trig(ue)).b);
        Vector2::new(s[0], s[1])
    }

    /// Strain energy `b^T C b / (2 l) + EI l k^2 / 2`.
    pub fn strain_energy(&self, section: &Section, ue: &Vector6) -> f64 {
        let b = self.strain_integrals(ue, &gauss_trig(ue)).b;
        let kappa = (ue[5] - ue[2]) / self.length;
        0.5 * (section.ea * b[0] * b[0] + section.ga * b[1] * b[1]) / self.length
            + 0.5 * section.ei * self.length * kappa * kappa
    }

    /// `f = B^T S + K_bend u` from the strain integrals.
    fn force_from(&self, section: &Section, ue: &Vector6, si: &StrainIntegrals) -> Vector6 {
        let s = self.forces(section, &si.b);
        let rows = si.rows();
        let mut f = Vector6::from_fn(|i, _| rows[0][i] * s[0] + rows[1][i] * s[1]);
        let moment = section.ei * (ue[5] - ue[2]) / self.length;
        f[2] -= moment;
        f[5] += moment;
        f
    }

    /// Internal force `B^T S + K_bend u`.
    pub fn internal_force(&self, section: &Section, ue: &Vector6) -> Vector6 {
        self.internal_force_with(section, ue, &gauss_trig(ue))
    }

    /// [`internal_force`](Self::internal_force) with the Gauss points' `trig` given.
    #[inline(always)]
    pub fn internal_force_with(
        &self,
        section: &Section,
        ue: &Vector6,
        trig: &GaussTrig,
    ) -> Vector6 {
        self.force_from(section, ue, &self.strain_integrals(ue, trig))
    }

    /// Internal force and consistent (symmetric) tangent as a 6x6 matrix.
    pub fn force_and_tangent(&self, section: &Section, ue: &Vector6) -> (Vector6, Matrix6) {
        let mut f = Vector6::zeros();
        let mut k = ElementTangent::default();
        self.force_and_tangent_into(section, ue, &gauss_trig(ue), &mut f, &mut k);
        (f, k.to_matrix())
    }

    /// Internal force and consistent tangent, the tangent as its node blocks (what the
    /// assembly adds), written into `f` and `k` (overwritten; returning them would copy them),
    /// with the Gauss points' `trig` given ([`gauss_trig`]). Written out block by block: the translation rows of `B` at the two
    /// nodes are opposite (`-t`, `t`), so the material part `B^T (C / l) B` has one 2x2
    /// translation block `T` (`+T` on the diagonal blocks, `-T` off them), one 2-vector per
    /// rotation coupling it with the translations, and three rotation entries; the geometric
    /// part `S1 b1'' + S2 b2''` adds to the couplings and the rotation entries only.
    #[inline(always)]
    pub fn force_and_tangent_into(
        &self,
        section: &Section,
        ue: &Vector6,
        trig: &GaussTrig,
        f: &mut Vector6,
        k: &mut ElementTangent,
    ) {
        let half_l = 0.5 * self.length;
        let inv_l = 1.0 / self.length;
        let si = self.strain_integrals(ue, trig);
        *f = self.force_from(section, ue, &si);
        let s = self.forces(section, &si.b);
        let (p1, p2, r) = (si.p1, si.p2, si.r);
        let (ka, kg) = (section.ea * inv_l, section.ga * inv_l);
        // Material part. `t = (t0, t1)`, the translation columns of B at the second node:
        // t0 = (p1, p2) (row b1), t1 = (-p2, p1) (row b2).
        let t00 = ka * p1 * p1 + kg * p2 * p2;
        let t01 = (ka - kg) * p1 * p2;
        let t11 = ka * p2 * p2 + kg * p1 * p1;
        // Coupling of the second node's translations with rotation `x`: t0 ka r0x + t1 kg r1x.
        let coupling = |r0: f64, r1: f64| {
            let (c, g) = (ka * r0, kg * r1);
            [p1 * c - p2 * g, p2 * c + p1 * g]
        };
        let mut h = [coupling(r[0], r[2]), coupling(r[1], r[3])];
        let kb = section.ei * inv_l;
        let mut rot = [
            ka * r[0] * r[0] + kg * r[2] * r[2] + kb,
            ka * r[0] * r[1] + kg * r[2] * r[3] - kb,
            ka * r[1] * r[1] + kg * r[3] * r[3] + kb,
        ];
        // Geometric part per Gauss point, with respect to (u1', u2', w):
        // [[0, 0, a], [0, 0, c], [a, c, ww]]; u' carries the weight half_l / l = 1/2.
        for (gp, &(na, nb)) in si.gauss.iter().zip(&SHAPE_AT_GAUSS) {
            let a = 0.5 * (-s[0] * gp.sin_aw - s[1] * gp.cos_aw);
            let c = 0.5 * (s[0] * gp.cos_aw - s[1] * gp.sin_aw);
            let ww = half_l * (-s[0] * (1.0 + gp.e1) - s[1] * gp.e2);
            h[0][0] += a * na;
            h[0][1] += c * na;
            h[1][0] += a * nb;
            h[1][1] += c * nb;
            rot[0] += ww * na * na;
            rot[1] += ww * na * nb;
            rot[2] += ww * nb * nb;
        }
        *k = ElementTangent {
            t: [t00, t01, t11],
            h,
            rot,
        };
    }
}

/// Mass and damping coefficients of one element: the consistent pattern (two Gauss points
/// integrate `N^T N` exactly) `[[2, 1], [1, 2]] * l / 6`, or the lumped one `[[3, 0], [0, 3]] *
/// l / 6` (see `Rod::with_lumped_mass`), scaled per dof kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementInertia {
    /// `rho A l / 6` on `u1`, `u2`.
    pub translational: f64,
    /// `rho I l / 6` on `w`.
    pub rotational: f64,
    /// `d l / 6` on `u1`, `u2`.
    pub damping: f64,
    /// `d_w l / 6` on `w` (0: the model damps translations only).
    pub rotational_damping: f64,
}

impl ElementInertia {
    pub fn new(section: &Section, damping: f64, length: f64) -> ElementInertia {
        ElementInertia {
            translational: section.rho_a * length / 6.0,
            rotational: section.rho_i * length / 6.0,
            damping: damping * length / 6.0,
            rotational_damping: 0.0,
        }
    }

    /// Per-dof-kind coefficients `(u1, u2, w)` of the mass (or damping if `damping`).
    pub fn coefficients(&self, damping: bool) -> Vector3<f64> {
        if damping {
            Vector3::new(self.damping, self.damping, self.rotational_damping)
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
        let el = Element::new(0.8, [0.3, 0.1]);
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
        let el = Element::new(0.8, [0.3, 0.1]);
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
        // Rigid translations (rotations: the free-flight tests of tests/suite/energy_momentum.rs).
        assert!((f[0] + f[3]).abs() < 1e-10 * f.norm() && (f[1] + f[4]).abs() < 1e-10 * f.norm());
        let small = ua + 1e-4 * (ub - ua);
        let near = el.discrete_gradient(&section, &ua, &small);
        let at = el.internal_force(&section, &(0.5 * (ua + small)));
        assert!((near - at).norm() < 1e-6 * at.norm(), "consistency");
    }
}
