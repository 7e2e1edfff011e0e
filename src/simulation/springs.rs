//! Springs and dashpots to ground during a communication step: their force on the rod (an
//! output, averaged over the step like a reaction) and the bases that follow an FMI input
//! (`motion = "input"`).
//!
//! A moving base goes linearly from where it was (the input held over the last step) to the
//! value set for the next step. The rod counts the spring as `k u` and the dashpot as `c du/dt`;
//! the base adds the force `k b + c db/dt` on the spring's dof, taken at each sub-step's
//! midpoint like every load. In the ledger the spring stores `k (u - b)^2 / 2`, the dashpot
//! dissipates `c (du - db)^2 / dt` and the base does the work `f db` (`f` the spring's force on
//! the rod): with the midpoint rule's `u_mid` and `du / dt` these three balance the base force's
//! work exactly, so `energy_error` stays what the rod alone makes it.
use super::setup::SpringOnRod;
use super::Simulation;
use crate::integrator::Scheme;
use crate::model::contact::{cubic_force, cubic_gradient};

/// Where the base of `spring` is after the fraction `f` (0..=1) of a step that moves it from
/// its input in `from` to its input in `to` (a fixed base stays at 0).
fn base_at(spring: &SpringOnRod, from: &[f64], to: &[f64], f: f64) -> f64 {
    match spring.base {
        None => 0.0,
        Some(i) if f == 1.0 => to[i],
        Some(i) => from[i] + (to[i] - from[i]) * f,
    }
}

/// Each spring's static force on the rod, `-k (u - b)`, with the bases at `inputs` (first
/// component; reported like a reaction before the first step).
pub fn static_forces<'a>(
    springs: &'a [SpringOnRod],
    u: &'a [f64],
    inputs: &'a [f64],
) -> impl Iterator<Item = [f64; 3]> + 'a {
    springs.iter().map(|s| {
        let b = base_at(s, inputs, inputs, 1.0);
        let r = u[s.dof] - b;
        if s.k3 != 0.0 {
            return [
                -(s.k * r + crate::model::contact::cubic_force(s.k3, r)),
                0.0,
                0.0,
            ];
        }
        [-s.k * (u[s.dof] - b), 0.0, 0.0]
    })
}

/// The moving bases' constant forces `k b` on the rod with the bases at `inputs`, added to
/// `load` (the loads of the static initial state).
pub fn add_static_base_forces(springs: &[SpringOnRod], inputs: &[f64], load: &mut [f64]) {
    for s in springs.iter().filter(|s| s.base.is_some()) {
        load[s.dof] += s.k * base_at(s, inputs, inputs, 1.0);
    }
}

/// What the springs store beyond the `k u^2 / 2` that the rod counts, with the bases at
/// `inputs`: `k ((u - b)^2 - u^2) / 2 = k b (b - 2 u) / 2`.
pub fn base_energy(springs: &[SpringOnRod], u: &[f64], inputs: &[f64]) -> f64 {
    (springs.iter().filter(|s| s.base.is_some()))
        .map(|s| {
            let b = base_at(s, inputs, inputs, 1.0);
            0.5 * s.k * b * (b - 2.0 * u[s.dof])
        })
        .sum()
}

impl Simulation {
    /// Before sub-step `k` of `n` (of size `dt`): each moving base's force through its spring
    /// and dashpot, `k b_mid + c db / dt`.
    pub(super) fn set_base_forces(&mut self, k: usize, n: usize, dt: f64) {
        let moving = self.setup.springs.iter().filter(|s| s.base.is_some());
        for (i, s) in moving.enumerate() {
            let at = |j: usize| base_at(s, &self.inputs, &self.next_inputs, j as f64 / n as f64);
            let (start, end) = (at(k), at(k + 1));
            let force = s.k * 0.5 * (start + end) + s.c * (end - start) / dt;
            self.setup.loads.set_base_force(i, force);
        }
    }

    /// After sub-step `k` of `n` (of size `dt`): adds each spring's impulse on the rod,
    /// `-(k (u_mid - b_mid) + c (du - db) / dt) dt`, to its entry after the supports' in the
    /// trial impulses; for a moving base, its work and the dashpot's dissipation relative to it
    /// (the rod booked `c du^2 / dt`).
    pub(super) fn book_springs(&mut self, k: usize, n: usize, dt: f64) {
        let first = self.setup.support_nodes.len();
        let du = self.integrator.last_increment();
        let (u, ledger) = (&self.trial.u, &mut self.trial_energy);
        let scheme = self.integrator.scheme;
        let impulses = &mut self.trial_impulses[first..];
        for (j, s) in impulses.iter_mut().zip(&self.setup.springs) {
            let at = |j: usize| base_at(s, &self.inputs, &self.next_inputs, j as f64 / n as f64);
            let (start, end) = (at(k), at(k + 1));
            let (db, b_mid) = (end - start, 0.5 * (start + end));
            let (d, u_mid) = (du[s.dof], u[s.dof] - 0.5 * du[s.dof]);
            let mut impulse = s.k * (u_mid - b_mid) * dt + s.c * (d - db);
            if s.k3 != 0.0 {
                // The cubic part as the step applied it (at the midpoint, or its gradient).
                let f = match scheme {
                    Scheme::Midpoint => cubic_force(s.k3, u_mid - b_mid),
                    Scheme::EnergyMomentum => {
                        cubic_gradient(s.k3, u[s.dof] - d - start, u[s.dof] - end)
                    }
                };
                impulse += f * dt;
            }
            j[0] -= impulse;
            if s.base.is_some() {
                ledger.support_work -= impulse / dt * db;
                ledger.dissipated += s.c * db * (db - 2.0 * d) / dt;
            }
        }
    }
}
