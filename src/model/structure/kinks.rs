//! The kinked terms of a structure as its Newton iterations see them: stops (their lists in
//! `nonlinear.rs`) and cables (axial elements that carry tension only, `axial.rs`). A
//! correction that takes one across its kink is tested itself (`Assembly::crosses_kink`); a
//! static iteration gives the open ones a small stiffness in its Jacobian and cuts a
//! correction just past the first it closes (docs/model.md, section 14).
use super::nonlinear::OPEN_STIFFNESS;
use nalgebra::Vector2;

/// A cable's chord (from its first node to its second) at `u + w du - w c`.
fn cable_chord(a: &super::Axial, u: &[f64], du: &[f64], c: Option<&[f64]>, w: f64) -> Vector2<f64> {
    let [p, q] = a.nodes;
    let at = |i: usize| u[i] + w * (du[i] - c.map_or(0.0, |c| c[i]));
    a.reference[1] - a.reference[0]
        + Vector2::new(at(3 * q) - at(3 * p), at(3 * q + 1) - at(3 * p + 1))
}

/// The kinked terms of a structure: its stops and its cables (axial elements, see `axial.rs`).
impl super::Structure {
    /// See [`crate::model::Assembly::crosses_kink`].
    pub(super) fn kink_crossed(&self, u: &[f64], du: &[f64], c: &[f64], w: f64) -> bool {
        self.nonlinear.crosses_kink(u, du, c, w)
            || self.nonlinear.cables.iter().any(|&i| {
                let a = &self.axial[i];
                let after = cable_chord(a, u, du, None, w).norm() >= a.rest;
                let before = cable_chord(a, u, du, Some(c), w).norm() >= a.rest;
                after != before
            })
    }

    /// See [`crate::model::Assembly::add_static_regularization`]: the open stops' and the slack
    /// cables' [`OPEN_STIFFNESS`] (a cable's along its chord).
    pub(super) fn regularize_statics(&self, u: &[f64], jac: &mut super::StructureMatrix) {
        self.nonlinear.add_static_regularization(u, jac);
        let (Some(g), super::StructureMatrix::Graph(m)) = (self.graph.as_ref(), jac) else {
            return;
        };
        for &i in &self.nonlinear.cables {
            let a = &self.axial[i];
            let r = a.chord(u);
            let l = r.norm();
            if l < a.rest {
                let e = r / l;
                g.add_axial_block(m, i, &(e * e.transpose()), OPEN_STIFFNESS * a.k);
            }
        }
    }

    /// See [`crate::model::Assembly::static_step_limit`]: the stops', and the first slack cable
    /// the correction would tighten (`|r + t d| = rest`, `r` its chord, `d` the correction's
    /// change of it).
    pub(super) fn static_limit(&self, u: &[f64], delta: &[f64]) -> f64 {
        let mut t = self.nonlinear.static_step_limit(u, delta);
        for &i in &self.nonlinear.cables {
            let a = &self.axial[i];
            let r = a.chord(u);
            let [p, q] = a.nodes;
            let d = Vector2::new(
                delta[3 * q] - delta[3 * p],
                delta[3 * q + 1] - delta[3 * p + 1],
            );
            let (dd, rd, c0) = (d.dot(&d), r.dot(&d), r.dot(&r) - a.rest * a.rest);
            if c0 < 0.0 && (r + d).norm() > a.rest {
                // The positive root of dd t^2 + 2 rd t + c0 = 0 (c0 < 0: one of each sign).
                let root = (-rd + (rd * rd - dd * c0).sqrt()) / dd;
                t = t.min(root * (1.0 + 1e-6));
            }
        }
        t
    }
}
