//! The midpoint rule's residual: what it takes from the start of the step (inertia of the old
//! velocity, loads at the step's midpoint), set once per step, and its evaluation at an
//! iterate (internal force, optionally with the Jacobian or the element tangents, plus the
//! linear part `M (2/dt^2 du - 2/dt v_n) + C du/dt - f_ext` in one banded pass).
use super::{DynamicState, Midpoint, Scheme};
use crate::model::element::cayley;
use crate::model::rod::ROTATION;
use crate::model::{Assembly, LoadSet};
use crate::solver::SystemMatrix;

/// The increment that the velocities average over a step: `du` itself, except for rotations in
/// the energy-momentum scheme, whose angular velocity is `2 tan(dw / 2) / dt` (Cayley): with it
/// the discrete gradient conserves angular momentum exactly (see `Element::discrete_gradient`).
pub(super) fn motion(scheme: Scheme, dof: usize, du: f64) -> f64 {
    if scheme == Scheme::EnergyMomentum && dof % 3 == ROTATION {
        cayley(du)
    } else {
        du
    }
}

/// What a residual evaluation computes with the tangent stiffness.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Tangent {
    Skip,
    /// The Jacobian, into `jac`, for a Newton correction.
    Iteration,
    /// The element tangents, kept for the tangent map (see `TangentMap`).
    Elements,
}

impl<A: Assembly> Midpoint<A> {
    /// Before the iteration of a step of size `dt` from `t_n`: the constant part of the
    /// Jacobian (when `dt` changed), what the residual takes from the start of the step
    /// (`-2/dt v_n`, `-f_ext(t_n + dt/2)`) and the predictor (constant velocity; held dofs by
    /// their `prescribed` increments).
    pub(super) fn prepare(
        &mut self,
        rod: &A,
        loads: &LoadSet,
        state: &DynamicState,
        t_n: f64,
        dt: f64,
        prescribed: &[(usize, f64)],
    ) {
        if self.dynamic_dt != dt {
            let (a, c) = (2.0 / (dt * dt), 1.0 / dt);
            self.dynamic_part.set_zero();
            rod.add_mass(&mut self.dynamic_part, a);
            rod.add_damping(&mut self.dynamic_part, c);
            self.dynamic_dt = dt;
            for (stencil, &dof) in self.held_stencils.iter_mut().zip(&self.held) {
                *stencil = self.dynamic_part.row_entries(dof);
            }
        }
        self.load.fill(0.0);
        loads.add_to(t_n + 0.5 * dt, &mut self.load, -1.0);
        for ((d, m), v) in self.du.iter_mut().zip(&mut self.inertia).zip(&state.v) {
            *d = dt * v;
            *m = -2.0 / dt * v;
        }
        rod.zero_constrained(&mut self.du);
        for &(dof, increment) in prescribed {
            self.du[dof] = increment;
        }
        if !prescribed.is_empty() {
            // A frame's member ends at a moving joint move with it.
            rod.make_consistent(&mut self.du);
        }
    }

    /// The residual `R(du)` at the current `du` into `residual` and the Jacobian where
    /// `tangent` says (constraints not yet applied).
    pub(super) fn residual(&mut self, rod: &A, state: &DynamicState, dt: f64, tangent: Tangent) {
        let mut jac = (tangent == Tangent::Iteration).then_some(&mut self.jac);
        if let Some(j) = jac.as_deref_mut() {
            j.copy_from(&self.dynamic_part);
        }
        match self.scheme {
            Scheme::Midpoint => {
                for ((um, u), d) in self.u_mid.iter_mut().zip(&state.u).zip(&self.du) {
                    *um = u + 0.5 * d;
                }
                if let Some(jac) = jac {
                    match self.tangents.newton_tangents() {
                        Some(kept) => rod.internal_force_and_tangent_kept(
                            &self.u_mid,
                            &mut self.residual,
                            jac,
                            0.5,
                            kept,
                        ),
                        None => rod.internal_force_and_tangent(
                            &self.u_mid,
                            &mut self.residual,
                            jac,
                            0.5,
                        ),
                    }
                } else if tangent == Tangent::Elements {
                    rod.internal_force_and_element_tangents(
                        &self.u_mid,
                        &mut self.residual,
                        self.tangents.element_tangents(),
                    );
                } else {
                    rod.internal_force(&self.u_mid, &mut self.residual);
                }
                // + M (2/dt^2 du - 2/dt v_n) + C du/dt - f_ext.
                let (a, c) = (2.0 / (dt * dt), 1.0 / dt);
                let bracket = ((a, &self.du[..]), (1.0, &self.inertia[..]));
                rod.add_bracket_times(bracket, c, Some(&self.load), &mut self.residual);
            }
            Scheme::EnergyMomentum => {
                // `u_mid` holds the end state u_n + du here.
                for ((um, u), d) in self.u_mid.iter_mut().zip(&state.u).zip(&self.du) {
                    *um = u + d;
                }
                if let Some(jac) = jac {
                    rod.discrete_gradient_and_tangent(
                        &state.u,
                        &self.u_mid,
                        &mut self.residual,
                        jac,
                        0.5,
                    );
                } else {
                    rod.discrete_gradient(&state.u, &self.u_mid, &mut self.residual);
                }
                // Rotations move by their Cayley increment (see `motion`).
                let a = 2.0 / (dt * dt);
                let brackets = self.bracket.iter_mut().zip(&self.du).zip(&self.inertia);
                for (i, ((s, d), m)) in brackets.enumerate() {
                    *s = a * motion(self.scheme, i, *d) + m;
                }
                rod.add_mass_and_damping_times(
                    (&self.bracket, 1.0),
                    (&self.du, 1.0 / dt),
                    &mut self.residual,
                );
                for (r, l) in self.residual.iter_mut().zip(&self.load) {
                    *r += l;
                }
            }
        }
        if rod.has_state_damping() {
            let jac = (tangent == Tangent::Iteration).then_some(&mut self.jac);
            rod.add_state_damping(&state.u, &self.du, dt, &mut self.residual, jac);
        }
        for (row, &dof) in self.held_rows.iter_mut().zip(&self.held) {
            *row = self.residual[dof];
        }
    }
}
