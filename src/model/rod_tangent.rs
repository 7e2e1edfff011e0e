//! The internal force of a [`Rod`] with its tangent stiffness: assembled into a block
//! tridiagonal Jacobian, kept element by element for the tangent map, or applied matrix-free as
//! the change between two states. Apart from `rod` to keep that file short; a child module of
//! `rod` (declared there), so it uses the rod's element loop (`assemble`).
use super::{assemble, Rod};
use crate::model::element::ElementTangent;
use crate::solver::PairSink;
use nalgebra::Vector6;

impl Rod {
    /// `f = f_int(u)` (overwrites) and `jac += scale * K_T(u)`.
    pub fn internal_force_and_tangent(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: &mut impl PairSink,
        scale: f64,
    ) {
        let (mut fe, mut ke) = (Vector6::zeros(), ElementTangent::default());
        assemble(f, &self.elements, u, |e, el, ue, trig| {
            el.force_and_tangent_into(&self.section, ue, trig, &mut fe, &mut ke);
            jac.add_pair(e, &ke, scale);
            fe
        });
        self.add_attached_force(u, f);
        self.add_attached_stiffness(jac, scale);
    }

    /// [`Rod::internal_force_and_tangent`] that also keeps each element's tangent in `kept`
    /// (one per element).
    pub fn internal_force_and_tangent_kept(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: &mut impl PairSink,
        scale: f64,
        kept: &mut [ElementTangent],
    ) {
        let mut fe = Vector6::zeros();
        assemble(f, &self.elements, u, |e, el, ue, trig| {
            el.force_and_tangent_into(&self.section, ue, trig, &mut fe, &mut kept[e]);
            jac.add_pair(e, &kept[e], scale);
            fe
        });
        self.add_attached_force(u, f);
        self.add_attached_stiffness(jac, scale);
    }

    /// `f = f_int(u)` (overwrites) and each element's tangent into `tangents` (one per
    /// element), not assembled.
    pub fn internal_force_and_element_tangents(
        &self,
        u: &[f64],
        f: &mut [f64],
        tangents: &mut [ElementTangent],
    ) {
        let mut fe = Vector6::zeros();
        assemble(f, &self.elements, u, |e, el, ue, trig| {
            el.force_and_tangent_into(&self.section, ue, trig, &mut fe, &mut tangents[e]);
            fe
        });
        self.add_attached_force(u, f);
    }

    /// `out = scale * (K1 - K0) y` (overwrites), `K1`, `K0` assembled from the element
    /// tangents `k1`, `k0` (matrix-free): the change of the tangent stiffness between two
    /// states, without the cancellation of two full products.
    pub fn tangent_change_times(
        &self,
        (k1, k0): (&[ElementTangent], &[ElementTangent]),
        y: &[f64],
        out: &mut [f64],
        scale: f64,
    ) {
        out[..3].fill(0.0);
        for (e, (k1, k0)) in k1.iter().zip(k0).enumerate() {
            let fe = scale * k1.minus(k0).mul(&Self::element_dofs(y, e));
            let (first, second) = out[3 * e..3 * e + 6].split_at_mut(3);
            for k in 0..3 {
                first[k] += fe[k];
                second[k] = fe[3 + k];
            }
        }
    }
}
