//! The stiffness part of Rayleigh damping, `beta K0`: `K0` the tangent stiffness of the initial
//! state, kept element by element (constant, so the dissipation `beta v^T K0 v` is a quadratic
//! form of the velocity and the energy ledger stays exact). The mass part, `alpha M`, joins the
//! rod's damping matrix itself ([`Rod::with_rayleigh`](super::Rod::with_rayleigh)).
use super::bands::Bands;
use super::element::{ElementTangent, Vector6};
use super::Rod;
use crate::solver::PairSink;

#[derive(Clone, Debug, PartialEq)]
pub struct StiffnessDamping {
    pub beta: f64,
    /// Each element's tangent in the initial state.
    tangents: Vec<ElementTangent>,
    /// The springs' and foundations' stiffness.
    attached: Option<Bands>,
}

impl StiffnessDamping {
    /// `beta K_T(u0)` of `rod`.
    pub fn new(rod: &Rod, beta: f64, u0: &[f64]) -> StiffnessDamping {
        let mut tangents = vec![ElementTangent::default(); rod.elements.len()];
        let mut force = vec![0.0; rod.dofs()];
        rod.internal_force_and_element_tangents(u0, &mut force, &mut tangents);
        let attached = rod.attached_stiffness().cloned();
        StiffnessDamping {
            beta,
            tangents,
            attached,
        }
    }

    /// `out += scale * beta K0 x`: one pass over the elements.
    pub fn add_times(&self, x: &[f64], out: &mut [f64], scale: f64) {
        let s = scale * self.beta;
        if let Some(k) = &self.attached {
            k.add_times(x, out, s);
        }
        for (e, k) in self.tangents.iter().enumerate() {
            let f = k.mul(&Rod::element_dofs(x, e));
            for (o, f) in out[3 * e..3 * e + 6].iter_mut().zip(f.iter()) {
                *o += s * f;
            }
        }
    }

    /// `jac += scale * beta K0`.
    pub fn add_to(&self, rod: &Rod, jac: &mut impl PairSink, scale: f64) {
        for (e, k) in self.tangents.iter().enumerate() {
            jac.add_pair(e, k, scale * self.beta);
        }
        if self.attached.is_some() {
            rod.add_attached_stiffness(jac, scale * self.beta);
        }
    }

    /// `beta v^T K0 v`: the power it dissipates.
    pub fn form(&self, v: &[f64]) -> f64 {
        let sum: f64 = (self.tangents.iter().enumerate())
            .map(|(e, k)| {
                let ve: Vector6 = Rod::element_dofs(v, e);
                ve.dot(&k.mul(&ve))
            })
            .sum();
        let attached = self.attached.as_ref().map_or(0.0, |k| k.form(v));
        self.beta * (sum + attached)
    }
}
