//! A scene brought to its initial state and advanced in time by midpoint sub-steps: everything
//! an FMU instance computes, without any FMI concern.
//!
//! - [`setup`]: the scene's rod, held dofs, loads and read points for given parameter values;
//! - [`initial`]: the initial static state (load stepping, branch choice);
//! - [`supports`]: moving supports, speed changes as impulses, reactions;
//! - [`outputs`]: sensors, shape, reactions and energies by output id;
//! - [`snapshot`]: clock, energy ledger and snapshots for exact restarts.
mod analysis;
pub mod initial;
pub mod outputs;
pub mod setup;
pub mod snapshot;
pub mod supports;

pub use analysis::LyapunovSnapshot;
pub use snapshot::{Clock, EnergyLedger, Snapshot, SNAPSHOT_VERSION};

use crate::integrator::{DynamicState, Midpoint, NewtonFailure, Scheme};
use crate::scene::{ParamError, ParamValues, Scene, Std, Variability};
use setup::Setup;
use std::cell::Cell;
use std::fmt;
use std::sync::Arc;
use supports::MotionSolver;

/// How often a failing sub-step is halved before a communication step is given up.
pub const MAX_STEP_CUTS: u32 = 5;

/// Most sub-steps one communication step may take (after cuts): beyond this a step is refused
/// rather than run for hours (`dt_max` far below the communication step).
pub const MAX_SUBSTEPS: usize = 10_000_000;

/// Why a simulation could not be built or advanced.
#[derive(Clone, Debug, PartialEq)]
pub enum SimError {
    /// A parameter out of range (names the variable and the allowed range).
    Param(ParamError),
    /// The initial static equilibrium could not be found.
    InitialState(String),
    /// A time step did not converge even after cutting it; the state is unchanged.
    StepFailed { time: f64, reason: String },
    /// A snapshot that does not belong to this simulation.
    BadSnapshot(String),
    /// A bad argument (non-finite or negative step size, ...).
    BadArgument(String),
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Param(e) => e.fmt(f),
            SimError::InitialState(why) => write!(f, "initial static state not found: {why}"),
            SimError::StepFailed { time, reason } => {
                write!(
                    f,
                    "step from t = {time} failed: {reason}; state left unchanged"
                )
            }
            SimError::BadSnapshot(why) => write!(f, "state snapshot refused: {why}"),
            SimError::BadArgument(why) => f.write_str(why),
        }
    }
}

impl std::error::Error for SimError {}

impl From<ParamError> for SimError {
    fn from(e: ParamError) -> Self {
        SimError::Param(e)
    }
}

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

pub struct Simulation {
    scene: Arc<Scene>,
    values: ParamValues,
    setup: Setup,
    integrator: Midpoint,
    initial: DynamicState,
    state: DynamicState,
    /// Scratch state of a communication step in progress (the state is replaced on success).
    trial: DynamicState,
    clock: Clock,
    last_newton_iterations: u32,
    /// The values the simulation was built with, restored by [`Simulation::reset`].
    initial_values: ParamValues,
    energy: EnergyLedger,
    trial_energy: EnergyLedger,
    /// Kinetic and strain energy of the state, computed when first asked for after a change
    /// (or by [`Simulation::advance_checked`]).
    energies: Cell<Option<(f64, f64)>>,
    /// The inputs held over the last communication step (part of the state)...
    inputs: Vec<f64>,
    /// ... and those to hold over the next one (set by the host).
    next_inputs: Vec<f64>,
    /// The load magnitudes the load set was last built with, and whether an input or a
    /// tunable parameter changed since.
    magnitudes: Vec<f64>,
    loads_stale: bool,
    scratch_magnitudes: Vec<f64>,
    /// Reactions reported after the last step (per support: Rx, Ry, M).
    reactions: Vec<[f64; 3]>,
    static_reactions: Vec<[f64; 3]>,
    trial_impulses: Vec<[f64; 3]>,
    /// `(dof, increment)` of the moving held dofs over the current sub-step.
    prescribed: Vec<(usize, f64)>,
    /// Start and target of each moving held dof over the current communication step, and its
    /// speed.
    motion_path: Vec<supports::MotionPath>,
    motion_speeds: Vec<f64>,
    /// Derivatives (first, second) of each input at the next communication point, if the host
    /// gave them: the input then follows their polynomial over the step.
    input_derivatives: Vec<Option<[f64; 2]>>,
    motion: Option<MotionSolver>,
    /// Lyapunov exponents and the `perturbation` kick.
    analysis: analysis::Analysis,
}

impl Simulation {
    /// Checks the values, meshes the scene and finds its initial state.
    pub fn new(scene: Arc<Scene>, values: ParamValues) -> Result<Simulation, SimError> {
        scene.check(&values)?;
        let mut setup = setup::setup(&scene, &values);
        let inputs: Vec<f64> = (0..scene.inputs.len())
            .map(|i| crate::scene::variables::input_start(&scene, i, &values))
            .collect();
        let mut magnitudes = vec![0.0; scene.loads.len()];
        setup::load_magnitudes(&scene, &values, &inputs, &mut magnitudes);
        setup.loads.set_magnitudes(&magnitudes);
        setup.loads.frequency = scene.param_index("Omega").map_or(0.0, |i| values.get(i));
        let mut initial =
            DynamicState::at_rest(initial::initial_displacements(&scene, &values, &setup)?);
        let static_reactions = supports::static_reactions(&setup, &initial.u);
        let mut integrator = Midpoint::new(&setup.rod);
        let held: Vec<usize> = setup.held.iter().map(|h| h.dof).collect();
        integrator.keep_rows(&held);
        integrator.scheme = if values.std(Std::Integrator) == 2.0 {
            Scheme::EnergyMomentum
        } else {
            Scheme::Midpoint
        };
        let analysis =
            analysis::Analysis::new(&scene, &values, &setup, integrator.scheme, &mut initial)?;
        let energy = EnergyLedger {
            initial_energy: setup.rod.strain_energy(&initial.u),
            ..EnergyLedger::default()
        };
        let moving = setup.held.iter().filter(|h| h.input.is_some()).count();
        let motion = match moving {
            0 => None,
            _ => Some(MotionSolver::new(&setup.rod).map_err(SimError::InitialState)?),
        };
        let sim = Simulation {
            integrator,
            energies: Cell::new(Some((0.0, energy.initial_energy))),
            energy,
            trial_energy: energy,
            state: initial.clone(),
            trial: initial.clone(),
            initial,
            clock: Clock::start(),
            last_newton_iterations: 0,
            initial_values: values.clone(),
            scratch_magnitudes: magnitudes.clone(),
            loads_stale: false,
            magnitudes,
            reactions: static_reactions.clone(),
            trial_impulses: vec![[0.0; 3]; static_reactions.len()],
            static_reactions,
            prescribed: Vec::with_capacity(moving),
            motion_path: vec![supports::MotionPath::default(); moving],
            motion_speeds: vec![0.0; moving],
            input_derivatives: vec![None; scene.inputs.len()],
            motion,
            analysis,
            next_inputs: inputs.clone(),
            inputs,
            values,
            setup,
            scene,
        };
        sim.check_outputs().map_err(|what| {
            SimError::InitialState(format!("the initial state has a non-finite {what}"))
        })?;
        Ok(sim)
    }

    pub fn scene(&self) -> &Arc<Scene> {
        &self.scene
    }

    pub fn values(&self) -> &ParamValues {
        &self.values
    }

    pub fn setup(&self) -> &Setup {
        &self.setup
    }

    pub fn rod(&self) -> &crate::model::Rod {
        &self.setup.rod
    }

    pub fn state(&self) -> &DynamicState {
        &self.state
    }

    /// Time since the start of the simulation.
    pub fn time(&self) -> f64 {
        self.clock.now()
    }

    /// The inputs the next communication step will hold.
    pub fn next_inputs(&self) -> &[f64] {
        &self.next_inputs
    }

    /// Sets input `i` (held over the next communication step).
    pub fn set_input(&mut self, i: usize, value: f64) -> Result<(), SimError> {
        let Some(input) = self.scene.inputs.get(i) else {
            return Err(SimError::BadArgument(format!("no input {i}")));
        };
        if !value.is_finite() {
            return Err(SimError::BadArgument(format!(
                "input `{}` = {value} is not finite",
                input.name
            )));
        }
        self.next_inputs[i] = value;
        self.loads_stale = true;
        Ok(())
    }

    /// Sets the `order`-th time derivative (1 or 2) of input `i` at the next communication
    /// point: over the next step the input follows the polynomial they define (a load input
    /// from its value set, a support motion from where the support is). Cleared by a
    /// successful step.
    pub fn set_input_derivative(
        &mut self,
        i: usize,
        order: usize,
        value: f64,
    ) -> Result<(), SimError> {
        let Some(input) = self.scene.inputs.get(i) else {
            return Err(SimError::BadArgument(format!("no input {i}")));
        };
        if !(1..=2).contains(&order) {
            return Err(SimError::BadArgument(format!(
                "input `{}`: derivative order {order}: orders 1 and 2 are supported",
                input.name
            )));
        }
        if !value.is_finite() {
            return Err(SimError::BadArgument(format!(
                "input `{}`: derivative {value} is not finite",
                input.name
            )));
        }
        let d = self.input_derivatives[i].get_or_insert([0.0; 2]);
        d[order - 1] = value;
        self.loads_stale = true;
        Ok(())
    }

    /// Changes a tunable parameter (a fixed one only to its current value).
    pub fn set_param(&mut self, index: usize, value: f64) -> Result<(), ParamError> {
        let param = &self.scene.params[index];
        param.check(value)?;
        if param.variability == Variability::Fixed && value != self.values.get(index) {
            return Err(crate::scene::params::refuse(
                &param.name,
                "is fixed: it cannot change once the simulation is built",
            ));
        }
        self.values.0[index] = value;
        self.loads_stale = true;
        if param.name == "Omega" {
            self.setup.loads.frequency = value;
        }
        Ok(())
    }

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
                    self.energies.set(energies);
                    self.energy = self.trial_energy;
                    self.clock = self.clock.with_step(h / substeps as f64);
                    self.clock.count += substeps as u64;
                    self.last_newton_iterations = newton_iterations;
                    self.inputs.copy_from_slice(&self.next_inputs);
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
            self.interpolate_load_inputs((k as f64 + 0.5) * dt);
            self.integrator.linearize = self.analysis.linearizes(t_k);
            let s = &self.setup;
            let stats = self
                .integrator
                .step(&s.rod, &s.loads, &mut self.trial, t_k, dt, &self.prescribed)
                .map_err(|e: NewtonFailure| e.to_string())?;
            iterations += stats.iterations;
            factorizations += stats.factorizations;
            self.analysis.substep(s, &self.integrator, t_k, dt);
            self.book(t_k + 0.5 * dt, dt);
        }
        // Moving supports end the step exactly at their targets (not a sum of increments).
        let moving = self.setup.held.iter().filter(|h| h.input.is_some());
        for (h, path) in moving.zip(&self.motion_path) {
            self.trial.u[h.dof] = path.position(1.0);
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
        ledger.dissipated += self.setup.rod.dissipation_rate(du) / dt;
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

    /// Newton iterations summed over the sub-steps of the last communication step.
    pub fn last_newton_iterations(&self) -> u32 {
        self.last_newton_iterations
    }

    pub fn energy(&self) -> &EnergyLedger {
        &self.energy
    }

    /// The reactions per support (Rx, Ry, M): averaged over the last communication step, or
    /// the static ones before the first.
    pub fn reactions(&self) -> &[[f64; 3]] {
        &self.reactions
    }
}
