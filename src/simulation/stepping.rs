//! Communication steps: a step of length `h` cut into equal midpoint sub-steps no longer than
//! `dt_max`, run on a trial state that replaces the state only when every sub-step converged
//! (else the sub-step is halved and the step restarted), with the work, dissipation and
//! reactions of each sub-step booked on the way.
use super::{setup, supports, SimError, Simulation};
use crate::integrator::NewtonFailure;
use crate::model::Assembly;

/// How often a failing sub-step is halved before a communication step is given up.
pub const MAX_STEP_CUTS: u32 = 5;

/// Most sub-steps one communication step may take (after cuts): beyond this a step is refused
/// rather than run for hours (`dt_max` far below the communication step).
pub const MAX_SUBSTEPS: usize = 10_000_000;

/// What one [`Simulation::advance`] did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AdvanceReport {
    pub substeps: usize,
    /// Corrections (Newton and chord) summed over the sub-steps.
    pub newton_iterations: u32,
    /// Jacobians factored, summed over the sub-steps.
    pub factorizations: u32,
    /// How many times the sub-step was halved after a Newton failure.
    pub cuts: u32,
    /// Something the host should know (e.g. an aliased excitation); the step succeeded.
    pub warning: Option<String>,
}

/// What a successful attempt at a communication step did: corrections, factorizations, and
/// (when checked) the kinetic and strain energy it ends with.
type Attempt = (u32, u32, Option<(f64, f64)>);

impl Simulation {
    /// The fewest equal sub-steps no longer than `dt_max` that make up `h`.
    pub fn substeps_for(&self, h: f64) -> usize {
        // The factor forgives round-off in h / dt_max (1e-4 / 1e-5 is 10.000000000000002).
        // (`as usize` saturates: an absurd ratio becomes usize::MAX, refused by `advance`.)
        ((h / self.values.dt_max()) * (1.0 - 1e-12)).ceil().max(1.0) as usize
    }

    /// Rebuilds the load set if a load's magnitude changed (inputs, tunable parameters).
    fn refresh_loads(&mut self) {
        if !std::mem::take(&mut self.loads_stale) {
            return;
        }
        setup::load_magnitudes(
            &self.scene,
            &self.values,
            &self.next_inputs,
            &mut self.scratch_magnitudes,
        );
        if self.scratch_magnitudes != self.magnitudes {
            self.magnitudes.copy_from_slice(&self.scratch_magnitudes);
            self.setup.loads.set_magnitudes(&self.magnitudes);
        }
    }

    /// One communication step of length `h` with the inputs held (loads) or followed linearly
    /// (support motions): equal midpoint sub-steps no longer than `dt_max`, the excitation taken
    /// at each sub-step's midpoint. A failing sub-step makes the whole step restart with half
    /// the sub-step size (at most [`MAX_STEP_CUTS`] times); if it still fails, the state is left
    /// exactly as it was.
    pub fn advance(&mut self, h: f64) -> Result<AdvanceReport, SimError> {
        self.advance_inner(h, false)
    }

    /// [`Simulation::advance`] that also refuses a step after which the kinetic or the strain
    /// energy is not a finite number (overflow on absurd parameters), so that every output of
    /// a successful step is finite; the energies are then kept for the outputs. What an FMU
    /// runs: computing the energies costs about one internal-force evaluation per
    /// communication step, which a host reading them would pay anyway.
    pub fn advance_checked(&mut self, h: f64) -> Result<AdvanceReport, SimError> {
        self.advance_inner(h, true)
    }

    fn advance_inner(&mut self, h: f64, check_energies: bool) -> Result<AdvanceReport, SimError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(SimError::BadArgument(format!(
                "step size {h} must be finite and > 0"
            )));
        }
        self.refresh_loads();
        let t0 = self.time();
        let mut substeps = self.substeps_for(h);
        if substeps > MAX_SUBSTEPS {
            return Err(SimError::BadArgument(format!(
                "a step of {h:e} s with dt_max = {:e} s needs {substeps} sub-steps, more than \
                 {MAX_SUBSTEPS}: raise dt_max or shorten the communication step",
                self.values.dt_max()
            )));
        }
        let mut last_failure = None;
        for cuts in 0..=MAX_STEP_CUTS {
            match self.try_substeps(h, substeps, check_energies) {
                Ok((newton_iterations, factorizations, energies)) => {
                    std::mem::swap(&mut self.state, &mut self.trial);
                    self.analysis.commit(&self.values);
                    self.readouts.commit();
                    self.energies.set(energies);
                    self.energy = self.trial_energy;
                    self.clock = self.clock.with_step(h / substeps as f64);
                    self.clock.count += substeps as u64;
                    self.last_newton_iterations = newton_iterations;
                    self.inputs.copy_from_slice(&self.next_inputs);
                    self.rest_cubic_bases();
                    if self.input_derivatives.iter().any(Option::is_some) {
                        self.input_derivatives.fill(None);
                        self.loads_stale = true;
                    }
                    for (r, j) in self.reactions.iter_mut().zip(&self.trial_impulses) {
                        *r = j.map(|x| x / h);
                    }
                    return Ok(AdvanceReport {
                        substeps,
                        newton_iterations,
                        factorizations,
                        cuts,
                        warning: self.aliasing_warning(h / substeps as f64),
                    });
                }
                Err(why) => last_failure = Some(why),
            }
            self.rest_cubic_bases();
            substeps = substeps.saturating_mul(2);
            if substeps > MAX_SUBSTEPS {
                break;
            }
        }
        Err(SimError::StepFailed {
            time: t0,
            reason: format!(
                "{} (after {MAX_STEP_CUTS} halvings of the sub-step)",
                last_failure.unwrap_or_default()
            ),
        })
    }

    /// Sub-steps of `h / substeps` on the trial state. Returns the corrections and the
    /// factorizations summed over the sub-steps and (when checked) the trial's kinetic and
    /// strain energy, or why it failed.
    fn try_substeps(
        &mut self,
        h: f64,
        substeps: usize,
        check_energies: bool,
    ) -> Result<Attempt, String> {
        self.trial.copy_from(&self.state);
        self.analysis
            .begin(&self.setup, &self.values, &mut self.trial);
        self.trial_energy = self.energy;
        self.trial_impulses.iter_mut().for_each(|j| *j = [0.0; 3]);
        self.start_motion(h);
        let dt = h / substeps as f64;
        let clock = self.clock.with_step(dt);
        let (mut iterations, mut factorizations) = (0, 0);
        for k in 0..substeps {
            let t_k = clock.at(k as u64);
            self.motion_increments(k, substeps);
            self.set_base_forces(k, substeps, dt);
            self.set_cubic_bases(k, substeps);
            self.interpolate_load_inputs((k as f64 + 0.5) * dt);
            if k + 1 == substeps {
                self.readouts.before_last_substep(&self.trial.v);
            }
            self.analysis
                .prepare(&self.setup, t_k, dt, &mut self.integrator);
            let s = &self.setup;
            let stats = self
                .integrator
                .step(
                    &s.structure,
                    &s.loads,
                    &mut self.trial,
                    t_k,
                    dt,
                    &self.prescribed,
                )
                .map_err(|e: NewtonFailure| e.to_string())?;
            iterations += stats.iterations;
            factorizations += stats.factorizations;
            self.analysis.substep(s, &self.integrator, t_k, dt);
            self.book(t_k + 0.5 * dt, dt);
            self.book_springs(k, substeps, dt);
            self.book_links(dt);
            self.book_stops(dt);
            self.check_softening()?;
        }
        self.readouts.after_last_substep(&self.trial.v, dt);
        // Moving supports end the step exactly at their targets (not a sum of increments).
        let moving = self.setup.held.iter().filter(|h| h.input.is_some());
        for (h, path) in moving.zip(&self.motion_path) {
            self.trial.u[h.dof] = path.position(1.0);
        }
        if !self.motion_path.is_empty() {
            self.setup.structure.make_consistent(&mut self.trial.u);
        }
        self.check_trial()
            .map_err(|what| format!("a non-finite {what} after the step"))?;
        let energies = if check_energies {
            Some(
                self.trial_energies()
                    .map_err(|what| format!("a non-finite {what} after the step"))?,
            )
        } else {
            None
        };
        Ok((iterations, factorizations, energies))
    }

    /// Books the work, dissipation and reactions of the sub-step just taken.
    fn book(&mut self, t_mid: f64, dt: f64) {
        let du = self.integrator.last_increment();
        let (external, input) = self.setup.loads.work(du, t_mid);
        let ledger = &mut self.trial_energy;
        ledger.external_work += external;
        ledger.input_work += input;
        ledger.dissipated += self.setup.structure.dissipation_rate(du) / dt;
        if self.setup.structure.has_state_damping() {
            // Dashpots along a current line (links), from the step's end and increment.
            let u = &self.trial.u;
            ledger.dissipated += self.setup.structure.state_damping_dissipation(u, du, dt);
        }
        supports::book_reactions(
            &self.setup,
            &self.integrator,
            dt,
            &mut self.trial_impulses,
            &mut self.trial_energy,
        );
    }

    /// Sub-steps of half a forcing period or more sample the excitation at its midpoints only:
    /// the step converges but cannot represent the load.
    pub fn aliasing_warning(&self, dt: f64) -> Option<String> {
        let omega = self.setup.loads.frequency;
        (omega * dt >= std::f64::consts::PI && self.setup.loads.has_harmonic()).then(|| {
            format!(
                "sub-step {dt:e} s is at least half the forcing period (Omega dt = {:.3} >= pi): \
                 the excitation is aliased; lower dt_max",
                omega * dt
            )
        })
    }
}
