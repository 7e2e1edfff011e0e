//! What the scene attaches to the rod besides supports: point masses with rotary inertia,
//! springs and dashpots from a dof to ground, and Winkler foundations (stiffness and damping
//! per unit length on `u2` over whole elements). All are constant and linear: they join the
//! mass, damping and stiffness of the rod as a few diagonal entries and consistent bands, so a
//! step costs nothing more than their own terms.
use super::bands::Bands;
use crate::solver::PairSink;
use nalgebra::Vector3;

/// A value on one global dof.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OnDof {
    pub dof: usize,
    pub value: f64,
}

/// A foundation on element `element`: the coefficients `k l / 6` and `c l / 6` of the
/// consistent pattern on `u2` (`k`, `c` per unit length, `l` the element's length).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FoundationPart {
    pub element: usize,
    pub k: f64,
    pub c: f64,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attachments {
    pub masses: Vec<OnDof>,
    pub springs: Vec<OnDof>,
    pub dashpots: Vec<OnDof>,
    pub foundation: Vec<FoundationPart>,
}

impl Attachments {
    pub fn is_empty(&self) -> bool {
        self.masses.is_empty()
            && self.springs.is_empty()
            && self.dashpots.is_empty()
            && self.foundation.is_empty()
    }

    /// The stiffness they add, as bands (`None` without springs and foundations).
    pub fn stiffness(&self, dofs: usize) -> Option<Bands> {
        if self.springs.is_empty() && self.foundation.is_empty() {
            return None;
        }
        let mut k = Bands::zeros(dofs);
        for s in &self.springs {
            k.add_diagonal(s.dof, s.value);
        }
        for f in &self.foundation {
            k.add_pattern(f.element, 1, f.k);
        }
        Some(k)
    }

    /// Adds their masses to the mass bands and their dashpots and foundation damping to the
    /// damping bands.
    pub fn add_to_bands(&self, mass: &mut Bands, damping: &mut Bands) {
        for m in &self.masses {
            mass.add_diagonal(m.dof, m.value);
        }
        for d in &self.dashpots {
            damping.add_diagonal(d.dof, d.value);
        }
        for f in &self.foundation {
            damping.add_pattern(f.element, 1, f.c);
        }
    }

    /// `jac += scale * M_attached`.
    pub fn add_mass(&self, jac: &mut impl PairSink, scale: f64) {
        for m in &self.masses {
            jac.add_diagonal(m.dof, scale * m.value);
        }
    }

    /// `jac += scale * C_attached`.
    pub fn add_damping(&self, jac: &mut impl PairSink, scale: f64) {
        for d in &self.dashpots {
            jac.add_diagonal(d.dof, scale * d.value);
        }
        for f in self.foundation.iter().filter(|f| f.c != 0.0) {
            let c = Vector3::new(0.0, f.c, 0.0);
            jac.add_pair_pattern(f.element, &c, scale, false);
        }
    }

    /// `jac += scale * K_attached`.
    pub fn add_stiffness(&self, jac: &mut impl PairSink, scale: f64) {
        for s in &self.springs {
            jac.add_diagonal(s.dof, scale * s.value);
        }
        for f in &self.foundation {
            let k = Vector3::new(0.0, f.k, 0.0);
            jac.add_pair_pattern(f.element, &k, scale, false);
        }
    }
}
