//! The implicit midpoint rule (paper eqs. 38-43, model.md):
//! `R(du) = M (2/dt^2 du - 2/dt v_n) + C du/dt + f_int(u_n + du/2) - f_ext(t_n + dt/2) = 0`,
//! solved by Newton with the exact Jacobian `2/dt^2 M + C/dt + K_T(u_n + du/2)/2`; then
//! `u_(n+1) = u_n + du`, `v_(n+1) = 2 du/dt - v_n`. Constrained dofs keep their values.
//! With [`Scheme::EnergyMomentum`] the internal force `f_int(u_n + du/2)` is replaced by the
//! discrete gradient of the element energies between `u_n` and `u_n + du`
//! ([`crate::model::Element::discrete_gradient`]): the step then conserves the energy of an
//! undamped, unforced rod and its linear and angular momentum exactly (to solver tolerance),
//! with rotations advanced by the Cayley rule: the angular velocity averaged over a step is
//! `2 tan(dw/2) / dt` instead of `dw / dt` (both second order; with the angle itself, exact energy
//! and exact angular momentum exclude each other: the director chord carries `sin(dw/2)` where
//! the rotation of the mid configuration carries `cos(dw/2)`, and `tan` reconciles them).
//! Newton uses the midpoint Jacobian (exact up to `O(du)`), so it converges fast but linearly.
//! All buffers live in [`Midpoint`]: a step allocates nothing.
use super::newton::{inf_norm, newton_correction, NewtonFailure, NewtonSettings, NewtonStats};
use crate::model::element::cayley;
use crate::model::rod::ROTATION;
use crate::model::{LoadCase, Rod};
use crate::solver::BlockTridiagonal;
use serde::{Deserialize, Serialize};

/// Displacements and velocities of every dof (constrained ones included).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DynamicState {
    pub u: Vec<f64>,
    pub v: Vec<f64>,
}

impl DynamicState {
    pub fn at_rest(u: Vec<f64>) -> DynamicState {
        let v = vec![0.0; u.len()];
        DynamicState { u, v }
    }

    pub fn copy_from(&mut self, other: &DynamicState) {
        self.u.copy_from_slice(&other.u);
        self.v.copy_from_slice(&other.v);
    }
}

/// The time integration scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Scheme {
    /// The implicit midpoint rule of the paper (symplectic, conserves momenta).
    #[default]
    Midpoint,
    /// The energy-momentum scheme (discrete gradient, Cayley rotations): conserves energy,
    /// linear and angular momentum.
    EnergyMomentum,
}

/// The increment that the velocities average over a step: `du` itself, except for rotations in
/// the energy-momentum scheme, whose angular velocity is `2 tan(dw / 2) / dt` (Cayley): with it
/// the discrete gradient conserves angular momentum exactly (see `Element::discrete_gradient`).
fn motion(scheme: Scheme, dof: usize, du: f64) -> f64 {
    if scheme == Scheme::EnergyMomentum && dof % 3 == ROTATION {
        cayley(du)
    } else {
        du
    }
}

#[derive(Clone, Debug)]
pub struct Midpoint {
    pub settings: NewtonSettings,
    pub scheme: Scheme,
    jac: BlockTridiagonal,
    du: Vec<f64>,
    u_mid: Vec<f64>,
    residual: Vec<f64>,
    inertia: Vec<f64>,
}

impl Midpoint {
    pub fn new(rod: &Rod) -> Midpoint {
        let n = rod.dofs();
        Midpoint {
            settings: NewtonSettings::tight(rod.curve.length()),
            scheme: Scheme::Midpoint,
            jac: BlockTridiagonal::new(rod.nodes()),
            du: vec![0.0; n],
            u_mid: vec![0.0; n],
            residual: vec![0.0; n],
            inertia: vec![0.0; n],
        }
    }

    /// One step of size `dt` from `t_n`. On failure `state` is untouched.
    pub fn step(
        &mut self,
        rod: &Rod,
        loads: &LoadCase,
        state: &mut DynamicState,
        t_n: f64,
        dt: f64,
    ) -> Result<NewtonStats, NewtonFailure> {
        let t_mid = t_n + 0.5 * dt;
        let (a, c) = (2.0 / (dt * dt), 1.0 / dt);
        // Predictor: constant velocity.
        for (d, v) in self.du.iter_mut().zip(&state.v) {
            *d = dt * v;
        }
        rod.zero_constrained(&mut self.du);
        // The inertia term's known part, -2/dt v_n.
        for (m, v) in self.inertia.iter_mut().zip(&state.v) {
            *m = -2.0 / dt * v;
        }
        let mut stats = NewtonStats::default();
        loop {
            self.jac.set_zero();
            match self.scheme {
                Scheme::Midpoint => {
                    for ((um, u), d) in self.u_mid.iter_mut().zip(&state.u).zip(&self.du) {
                        *um = u + 0.5 * d;
                    }
                    rod.internal_force_and_tangent(
                        &self.u_mid,
                        &mut self.residual,
                        &mut self.jac,
                        0.5,
                    );
                }
                Scheme::EnergyMomentum => {
                    // `u_mid` holds the end state u_n + du here.
                    for ((um, u), d) in self.u_mid.iter_mut().zip(&state.u).zip(&self.du) {
                        *um = u + d;
                    }
                    rod.discrete_gradient_and_tangent(
                        &state.u,
                        &self.u_mid,
                        &mut self.residual,
                        &mut self.jac,
                        0.5,
                    );
                }
            }
            rod.add_mass(&mut self.jac, a);
            rod.add_damping(&mut self.jac, c);
            // M (a du - 2/dt v_n): reuse `u_mid` as scratch for the bracket. The
            // energy-momentum scheme moves rotations by their Cayley increment (see `motion`).
            let scheme = self.scheme;
            for (i, ((s, d), m)) in
                (self.u_mid.iter_mut().zip(&self.du).zip(&self.inertia)).enumerate()
            {
                *s = a * motion(scheme, i, *d) + m;
            }
            rod.add_mass_times(&self.u_mid, &mut self.residual, 1.0);
            rod.add_damping_times(&self.du, &mut self.residual, c);
            loads.add_to(t_mid, &mut self.residual, -1.0);
            let (residual_norm, correction) =
                newton_correction(rod, &mut self.jac, &mut self.residual, stats.iterations)?;
            for (d, r) in self.du.iter_mut().zip(&self.residual) {
                *d += r;
            }
            stats.record(residual_norm, correction);
            if self.settings.converged(correction, inf_norm(&self.du)) {
                break;
            }
            if stats.iterations >= self.settings.max_iterations || !correction.is_finite() {
                return Err(NewtonFailure::NotConverged {
                    iterations: stats.iterations,
                    correction,
                });
            }
        }
        self.u_mid.copy_from_slice(&self.du);
        let dofs = state.u.iter_mut().zip(state.v.iter_mut()).zip(&self.du);
        for (i, ((u, v), d)) in dofs.enumerate() {
            *u += d;
            *v = 2.0 * motion(self.scheme, i, *d) / dt - *v;
        }
        Ok(stats)
    }

    /// The displacement increment `du` of the last successful step.
    pub fn last_increment(&self) -> &[f64] {
        &self.u_mid
    }
}
