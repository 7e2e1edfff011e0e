//! The tangent of one element by its ten distinct numbers, [`ElementTangent`]: how it is
//! multiplied, split into node blocks (which is how a block-tridiagonal matrix takes it:
//! [`PairBlocks`]; the solver knows no element) and expanded. Separate from `element` (the force and tangent
//! evaluation that fills it) to keep that file short; a child module of `element` (declared
//! there, re-exported as `element::ElementTangent`) so that the fields stay visible to `element`
//! alone.
use super::{Matrix6, Vector6};
use crate::solver::PairBlocks;
use nalgebra::Matrix3;

/// The symmetric 6x6 tangent of an element by its ten distinct numbers: with `T` the 2x2
/// translation block `[[t00, t01], [t01, t11]]`, `h_a`, `h_b` the couplings of the second
/// node's translations with each rotation and `rot` the rotation entries,
/// `K = [[T, -h_a, -T, -h_b], [-h_a^T, r_aa, h_a^T, r_ab], [-T, h_a, T, h_b],
/// [-h_b^T, r_ab, h_b^T, r_bb]]` (dofs ordered translation, rotation per node).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ElementTangent {
    pub(super) t: [f64; 3],
    pub(super) h: [[f64; 2]; 2],
    pub(super) rot: [f64; 3],
}

impl ElementTangent {
    /// `K y` for the element dofs `y`: with `d` the second node's translation minus the
    /// first's, `(-T d - h_a y_wa - h_b y_wb, h_a.d + r_aa y_wa + r_ab y_wb)` at the first node,
    /// the negated translation part and `h_b.d + r_ab y_wa + r_bb y_wb` at the second.
    pub fn mul(&self, y: &Vector6) -> Vector6 {
        let [t00, t01, t11] = self.t;
        let [ha, hb] = self.h;
        let (d0, d1) = (y[3] - y[0], y[4] - y[1]);
        let (wa, wb) = (y[2], y[5]);
        let f0 = t00 * d0 + t01 * d1 + ha[0] * wa + hb[0] * wb;
        let f1 = t01 * d0 + t11 * d1 + ha[1] * wa + hb[1] * wb;
        let ma = ha[0] * d0 + ha[1] * d1 + self.rot[0] * wa + self.rot[1] * wb;
        let mb = hb[0] * d0 + hb[1] * d1 + self.rot[1] * wa + self.rot[2] * wb;
        Vector6::new(-f0, -f1, ma, f0, f1, mb)
    }

    /// `self - other`, entry by entry (the change of an element's tangent between two states).
    pub fn minus(&self, other: &ElementTangent) -> ElementTangent {
        let sub = |a: &[f64], b: &[f64], out: &mut [f64]| {
            for ((o, a), b) in out.iter_mut().zip(a).zip(b) {
                *o = a - b;
            }
        };
        let mut d = ElementTangent::default();
        sub(&self.t, &other.t, &mut d.t);
        sub(&self.h[0], &other.h[0], &mut d.h[0]);
        sub(&self.h[1], &other.h[1], &mut d.h[1]);
        sub(&self.rot, &other.rot, &mut d.rot);
        d
    }

    /// The node blocks `(K_aa, K_ab, K_bb)`; `K_ba = K_ab^T`.
    pub fn blocks(&self) -> (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>) {
        let [t00, t01, t11] = self.t;
        let [ha, hb] = self.h;
        let rot = self.rot;
        #[rustfmt::skip]
        let blocks = (
            Matrix3::new(
                t00, t01, -ha[0],
                t01, t11, -ha[1],
                -ha[0], -ha[1], rot[0],
            ),
            Matrix3::new(
                -t00, -t01, -hb[0],
                -t01, -t11, -hb[1],
                ha[0], ha[1], rot[1],
            ),
            Matrix3::new(
                t00, t01, hb[0],
                t01, t11, hb[1],
                hb[0], hb[1], rot[2],
            ),
        );
        blocks
    }

    pub fn to_matrix(&self) -> Matrix6 {
        let (aa, ab, bb) = self.blocks();
        let mut k = Matrix6::zeros();
        k.fixed_view_mut::<3, 3>(0, 0).copy_from(&aa);
        k.fixed_view_mut::<3, 3>(0, 3).copy_from(&ab);
        k.fixed_view_mut::<3, 3>(3, 0).copy_from(&ab.transpose());
        k.fixed_view_mut::<3, 3>(3, 3).copy_from(&bb);
        k
    }
}

/// The element's tangent as the solver adds it: its node blocks, formed inside
/// `BlockTridiagonal::add_pair` from the ten numbers.
impl PairBlocks for ElementTangent {
    fn blocks(&self) -> (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>) {
        ElementTangent::blocks(self)
    }
}
