//! What joins the rod's matrices after meshing: Rayleigh damping (`alpha M` in the damping
//! bands, `beta K0` kept apart) and the attachments (point masses, springs, dashpots,
//! foundations). A child module of `rod` (declared there), so it sets the rod's private bands.
use super::Rod;
use crate::model::attachments::Attachments;
use crate::model::bands::Bands;
use crate::model::rayleigh::StiffnessDamping;
use crate::solver::PairSink;

impl Rod {
    /// Rayleigh damping `alpha M + beta K0` added to the damping matrix, `K0` the tangent
    /// stiffness at `u0` (the initial state).
    pub fn with_rayleigh(&mut self, alpha: f64, beta: f64, u0: &[f64]) {
        if alpha != 0.0 {
            for m in &mut self.inertia {
                m.damping += alpha * m.translational;
                m.rotational_damping += alpha * m.rotational;
            }
            self.update_bands();
        }
        self.stiffness_damping = (beta != 0.0).then(|| StiffnessDamping::new(self, beta, u0));
    }

    /// The rod with point masses, springs, dashpots and foundations attached.
    pub fn with_attachments(mut self, attachments: Attachments) -> Rod {
        self.attached_stiffness = attachments.stiffness(self.dofs());
        self.attachments = attachments;
        self.update_bands();
        self
    }

    /// The stiffness of the springs and foundations, if any.
    pub fn attached_stiffness(&self) -> Option<&Bands> {
        self.attached_stiffness.as_ref()
    }

    /// `jac += scale * K_attached` (springs and foundations).
    pub fn add_attached_stiffness(&self, jac: &mut impl PairSink, scale: f64) {
        self.attachments.add_stiffness(jac, scale);
    }

    /// `f += K_attached u`.
    pub(super) fn add_attached_force(&self, u: &[f64], f: &mut [f64]) {
        if let Some(k) = &self.attached_stiffness {
            k.add_times(u, f, 1.0);
        }
    }

    /// `f += K_attached (ua + ub) / 2`: the discrete gradient of a quadratic energy.
    pub(super) fn add_attached_midpoint_force(&self, ua: &[f64], ub: &[f64], f: &mut [f64]) {
        if let Some(k) = &self.attached_stiffness {
            k.add_times(ua, f, 0.5);
            k.add_times(ub, f, 0.5);
        }
    }
}
