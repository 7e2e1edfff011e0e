//! What a simulation computes for analyses besides the motion: Lyapunov exponents from the
//! exact tangent map of each sub-step ([`crate::integrator::tangent`]), and the `perturbation`
//! kick that twin-trajectory checks use. Neither changes the trajectory of an unkicked run.
use super::setup::Setup;
use super::SimError;
use crate::integrator::tangent::{seeded_direction, Lyapunov};
use crate::integrator::{DynamicState, Midpoint, Scheme};
use crate::model::{Assembly, Structure};
use crate::scene::params::{refuse, LYAPUNOV, LYAPUNOV_ALIGN, LYAPUNOV_START, PERTURBATION};
use crate::scene::{ParamValues, Scene, Std};

/// The exponents of the state and of the communication step in progress, and the kick.
#[derive(Clone, Debug)]
pub(super) struct Analysis {
    exponents: Option<Lyapunov>,
    /// The exponents at `t = 0`, for a reset.
    initial: Option<Lyapunov>,
    trial: Option<Lyapunov>,
    /// Sub-steps from this time on advance the tangent vectors.
    start: f64,
    /// Weight of the velocities in the norm of tangent vectors and kicks (a time): `1/Omega`
    /// when the scene is forced, else the bending time scale `L^2 sqrt(rho A / (E I))`.
    tau: f64,
    /// Index of the `perturbation` parameter and the value the state has been kicked by.
    perturbation: usize,
    applied: f64,
}

fn index(scene: &Scene, name: &str) -> usize {
    scene
        .param_index(name)
        .expect("every scene has the analysis parameters")
}

impl Analysis {
    /// Checks the analysis parameters and kicks `initial` by the start value of
    /// `perturbation`.
    pub fn new(
        scene: &Scene,
        values: &ParamValues,
        setup: &Setup,
        scheme: Scheme,
        initial: &mut DynamicState,
    ) -> Result<Analysis, SimError> {
        let rod = &setup.structure;
        let omega = setup.loads.frequency;
        let tau = if omega > 0.0 {
            1.0 / omega
        } else {
            // The time scale of bending over the span, L^2 sqrt(rho A / EI) (for a rectangle
            // written with its height, as it always was).
            let (e, rho, l) = (
                values.std(Std::E),
                values.std(Std::Rho),
                values.std(Std::Span),
            );
            match (scene.section.rectangle(values), rod.is_single()) {
                (Some((_, h)), true) => l * l * (12.0 * rho / (e * h * h)).sqrt(),
                (None, true) => l * l * (rod.rod().section.rho_a / rod.rod().section.ei).sqrt(),
                // A frame: its softest member's bending time scale (a bar's axial one).
                (_, false) => 1.0 / rod.bending_scale().sqrt(),
            }
        };
        if !(tau.is_finite() && tau > 0.0) {
            return Err(SimError::InitialState(format!(
                "the time scale of the analysis norm is {tau:e} s, not a positive number"
            )));
        }
        let k = values.get(index(scene, LYAPUNOV)) as usize;
        let free = rod.dofs() - rod.constrained().len();
        if k > 0 && scheme != Scheme::Midpoint {
            return Err(refuse(
                LYAPUNOV,
                format!(
                    "{k} exponents need integrator = 1 (midpoint rule): the tangent map of the \
                     energy-momentum scheme is not implemented"
                ),
            )
            .into());
        }
        if let Some(stop) = scene.stops.iter().find(|s| s.c > 0.0).filter(|_| k > 0) {
            return Err(refuse(
                LYAPUNOV,
                format!(
                    "{k} exponents: stop `{}` has a contact dashpot (c = {}), whose force \
                     depends on the state and the step together; the tangent map does not \
                     include it (docs/model.md, section 14). Set its c = 0 (a penalty stop \
                     without a dashpot; damp with d or [damping] instead) for exponents",
                    stop.name, stop.c
                ),
            )
            .into());
        }
        let links = scene.frame.iter().flat_map(|f| &f.links);
        if let Some(link) = links.filter(|l| l.c > 0.0).find(|_| k > 0) {
            return Err(refuse(
                LYAPUNOV,
                format!(
                    "{k} exponents: link `{}` has a dashpot (c = {}), whose force along the \
                     link's current line depends on the state and the step together; the \
                     tangent map does not include it. Set its c = 0 (damp with d or [damping] \
                     instead) for exponents",
                    link.name, link.c
                ),
            )
            .into());
        }
        if k > 2 * free {
            return Err(refuse(
                LYAPUNOV,
                format!(
                    "{k} exponents: this rod has only {} state variables",
                    2 * free
                ),
            )
            .into());
        }
        let start = values.get(index(scene, LYAPUNOV_START));
        let count_from = start + values.get(index(scene, LYAPUNOV_ALIGN));
        let exponents = (k > 0).then(|| Lyapunov::new(rod, k, tau, count_from));
        let perturbation = index(scene, PERTURBATION);
        let mut analysis = Analysis {
            trial: exponents.clone(),
            initial: exponents.clone(),
            exponents,
            start,
            tau,
            perturbation,
            applied: 0.0,
        };
        analysis.kick(setup, values, initial);
        analysis.applied = values.get(perturbation);
        Ok(analysis)
    }

    /// Displaces `state` by the change of `perturbation` since the last kick (a state
    /// snapshot of the run, not yet committed: see [`Analysis::commit`]).
    fn kick(&self, setup: &Setup, values: &ParamValues, state: &mut DynamicState) {
        let change = values.get(self.perturbation) - self.applied;
        if change == 0.0 {
            return;
        }
        // Seed 0: not one of the tangent vectors' seeds (1..=k).
        let (du, dv) = seeded_direction(&setup.structure, 0, self.tau);
        state
            .u
            .iter_mut()
            .zip(&du)
            .for_each(|(x, d)| *x += change * d);
        state
            .v
            .iter_mut()
            .zip(&dv)
            .for_each(|(x, d)| *x += change * d);
    }

    /// Starts an attempt at a communication step: the trial exponents from the state's, and
    /// the trial state kicked by a change of `perturbation`.
    pub fn begin(&mut self, setup: &Setup, values: &ParamValues, trial: &mut DynamicState) {
        if let (Some(t), Some(e)) = (&mut self.trial, &self.exponents) {
            t.copy_from(e);
        }
        self.kick(setup, values, trial);
    }

    /// Sets the tangent map's systems that the sub-step from `t_n` of size `dt` solves:
    /// those of the trial tangent vectors from the start time on, else none.
    pub fn prepare(
        &mut self,
        setup: &Setup,
        t_n: f64,
        dt: f64,
        integrator: &mut Midpoint<Structure>,
    ) {
        let map = integrator.tangent_map_mut();
        match self.trial.as_ref().filter(|_| t_n >= self.start) {
            Some(t) => t.prepare(&setup.structure, dt, map),
            None => map.set_count(0),
        }
    }

    /// Advances the trial tangent vectors over the sub-step from `t_n` that `integrator` just
    /// took (if [`Analysis::prepare`] set its systems).
    pub fn substep(&mut self, setup: &Setup, integrator: &Midpoint<Structure>, t_n: f64, dt: f64) {
        if let Some(t) = self.trial.as_mut().filter(|_| t_n >= self.start) {
            t.advance(&setup.structure, integrator.tangent_map(), t_n, dt);
        }
    }

    /// Whether the trial exponents are finite.
    pub fn trial_is_finite(&self) -> bool {
        self.trial.as_ref().is_none_or(Lyapunov::is_finite)
    }

    /// The attempt succeeded: its exponents and kick become the state's.
    pub fn commit(&mut self, values: &ParamValues) {
        std::mem::swap(&mut self.exponents, &mut self.trial);
        self.applied = values.get(self.perturbation);
    }

    /// Exponent `j` per second, or per forcing period of `omega` (0 when `omega` is 0).
    pub fn exponent(&self, j: usize, per_period: Option<f64>) -> f64 {
        let Some(e) = self.exponents.as_ref().filter(|e| j < e.count()) else {
            return 0.0;
        };
        match per_period {
            None => e.exponent(j),
            Some(omega) if omega > 0.0 => e.exponent(j) * std::f64::consts::TAU / omega,
            Some(_) => 0.0,
        }
    }

    /// The number of tangent vectors (exponents) estimated.
    pub fn vectors(&self) -> usize {
        self.exponents.as_ref().map_or(0, Lyapunov::count)
    }

    pub fn counted_time(&self) -> f64 {
        self.exponents.as_ref().map_or(0.0, Lyapunov::counted_time)
    }

    /// What a snapshot keeps of the exponents.
    pub fn snapshot(&self) -> Option<LyapunovSnapshot> {
        self.exponents.as_ref().map(|e| {
            let (du, dv, log_growth, counted_time) = e.parts();
            LyapunovSnapshot {
                du: du.to_vec(),
                dv: dv.to_vec(),
                log_growth: log_growth.to_vec(),
                counted_time,
            }
        })
    }

    /// Checks a snapshot's exponents against this simulation's (same count and dofs, finite).
    pub fn check(&self, s: Option<&LyapunovSnapshot>) -> Result<(), String> {
        match (&self.exponents, s) {
            (None, None) => Ok(()),
            (Some(e), Some(s)) => {
                let (du, dv, log_growth, _) = e.parts();
                if s.du.len() != du.len() || s.dv.len() != dv.len() {
                    return Err("tangent vectors of the wrong length".to_string());
                }
                if s.log_growth.len() != log_growth.len() {
                    return Err(format!(
                        "{} Lyapunov exponents (this simulation has {})",
                        s.log_growth.len(),
                        log_growth.len()
                    ));
                }
                let numbers = s.du.iter().chain(&s.dv).chain(&s.log_growth);
                if !(numbers.chain([&s.counted_time]).all(|x| x.is_finite())
                    && s.counted_time >= 0.0)
                {
                    return Err("non-finite Lyapunov data".to_string());
                }
                Ok(())
            }
            (Some(_), None) => {
                Err("no Lyapunov data (this simulation has lyapunov_count > 0)".into())
            }
            (None, Some(_)) => Err("Lyapunov data (this simulation has lyapunov_count = 0)".into()),
        }
    }

    /// After a restore (of a snapshot that passed [`Analysis::check`]): the state has these
    /// exponents and has been kicked by the current `perturbation`.
    pub fn restore(&mut self, values: &ParamValues, s: Option<&LyapunovSnapshot>) {
        if let (Some(mine), Some(s)) = (&mut self.exponents, s) {
            mine.set_parts(&s.du, &s.dv, &s.log_growth, s.counted_time);
        }
        self.applied = values.get(self.perturbation);
    }

    /// Back to `t = 0` (the initial state was kicked by the start value of `perturbation`).
    pub fn reset(&mut self, values: &ParamValues) {
        if let (Some(mine), Some(initial)) = (&mut self.exponents, &self.initial) {
            mine.copy_from(initial);
        }
        self.applied = values.get(self.perturbation);
    }
}

/// The Lyapunov part of a [`super::Snapshot`]: tangent vectors and accumulated growth.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LyapunovSnapshot {
    pub du: Vec<f64>,
    pub dv: Vec<f64>,
    pub log_growth: Vec<f64>,
    pub counted_time: f64,
}
