//! The energies and momenta of a [`Rod`]'s state: strain and kinetic energy, the power the
//! damping dissipates, linear and angular momentum. The quantities a simulation reports and the
//! conservation tests check, apart from the assembly of forces and matrices in `rod`; a child
//! module of `rod` (declared there), so it reads the rod's private mass and damping bands.
use super::{Rod, ROTATION, U1, U2};
use nalgebra::Vector2;

impl Rod {
    /// The elements' strain energy and the energy stored in the springs and foundations.
    pub fn strain_energy(&self, u: &[f64]) -> f64 {
        let attached = self
            .attached_stiffness
            .as_ref()
            .map_or(0.0, |k| 0.5 * k.form(u));
        let elements: f64 = (self.elements.iter().enumerate())
            .map(|(e, el)| el.strain_energy(&self.section, &Self::element_dofs(u, e)))
            .sum();
        elements + attached
    }

    /// `v^T M v / 2`.
    pub fn kinetic_energy(&self, v: &[f64]) -> f64 {
        0.5 * self.mass_bands.form(v)
    }

    /// `v^T C v` (power dissipated by the damping).
    pub fn dissipation_rate(&self, v: &[f64]) -> f64 {
        let rayleigh = self.stiffness_damping.as_ref().map_or(0.0, |k0| k0.form(v));
        self.damping_bands.form(v) + rayleigh
    }

    /// Linear momentum `sum M v` over the translations.
    pub fn linear_momentum(&self, v: &[f64]) -> Vector2<f64> {
        let mut p = vec![0.0; v.len()];
        self.add_mass_times(v, &mut p, 1.0);
        let mut total = Vector2::zeros();
        for i in 0..self.nodes() {
            total += Vector2::new(p[3 * i + U1], p[3 * i + U2]);
        }
        total
    }

    /// Angular momentum about the origin, `integral (x × rho A du/dt + rho I dw/dt) ds`, with the
    /// consistent (exactly integrated) mass: `sum_i x_i × (M v)_i + (M v)_w`.
    pub fn angular_momentum(&self, u: &[f64], v: &[f64]) -> f64 {
        let mut p = vec![0.0; v.len()];
        self.add_mass_times(v, &mut p, 1.0);
        let mut total = 0.0;
        for i in 0..self.nodes() {
            let x = self.node_position(u, i);
            total += x[0] * p[3 * i + U2] - x[1] * p[3 * i + U1] + p[3 * i + ROTATION];
        }
        total
    }
}
