//! A scene brought to its initial state and advanced in time by midpoint sub-steps: everything
//! an FMU instance computes, without any FMI concern.
//!
//! - [`setup`]: the scene's rod, held dofs, loads and read points for given parameter values;
//! - [`initial`]: the initial static state (load stepping, branch choice);
//! - [`supports`]: moving supports, speed changes as impulses, reactions;
//! - [`springs`]: spring forces, and spring bases that follow inputs (their force, work and
//!   dissipation);
//! - [`outputs`]: sensors, shape, reactions and energies by output id;
//! - [`readouts`]: accelerations, section quantities and natural frequencies;
//! - [`snapshot`]: clock, energy ledger and snapshots for exact restarts;
//! - `stepping`: communication steps, sub-steps, cuts and the ledger of each sub-step;
//! - `analysis`: Lyapunov exponents and the `perturbation` kick.
//!
//! This file holds [`Simulation`] itself: building it, its accessors, and what the host sets
//! (inputs, their derivatives, tunable parameters).
mod analysis;
mod contact;
pub mod initial;
mod links;
pub mod outputs;
pub mod readouts;
pub mod setup;
mod setup_frame;
mod setup_loads;
pub mod snapshot;
pub mod springs;
mod stepping;
pub mod supports;

pub use analysis::LyapunovSnapshot;
pub use snapshot::{Clock, EnergyLedger, Snapshot, SNAPSHOT_VERSION};
pub use stepping::{AdvanceReport, MAX_STEP_CUTS, MAX_SUBSTEPS};

use crate::integrator::{DynamicState, Midpoint, Scheme};
use crate::model::{Assembly, Structure};
use crate::scene::{ParamError, ParamValues, Scene, Std, Variability};
use setup::Setup;
use std::cell::Cell;
use std::fmt;
use std::sync::Arc;
use supports::MotionSolver;

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

pub struct Simulation {
    scene: Arc<Scene>,
    values: ParamValues,
    setup: Setup,
    integrator: Midpoint<Structure>,
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
    /// The inputs the initial state was found with (moving supports at these values).
    initial_inputs: Vec<f64>,
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
    motion: Option<MotionSolver<Structure>>,
    /// Lyapunov exponents and the `perturbation` kick.
    analysis: analysis::Analysis,
    /// Accelerations, section quantities and natural frequencies.
    readouts: readouts::Readouts,
}

impl Simulation {
    /// Checks the values, meshes the scene and finds its initial state, with the inputs at
    /// their start values.
    pub fn new(scene: Arc<Scene>, values: ParamValues) -> Result<Simulation, SimError> {
        let inputs: Vec<f64> = (0..scene.inputs.len())
            .map(|i| crate::scene::variables::input_start(&scene, i, &values))
            .collect();
        Simulation::with_inputs(scene, values, inputs)
    }

    /// [`Simulation::new`] with the inputs at these values (as a host set them during
    /// initialization mode): the moving supports' inputs are part of the static initial state.
    pub fn with_inputs(
        scene: Arc<Scene>,
        values: ParamValues,
        inputs: Vec<f64>,
    ) -> Result<Simulation, SimError> {
        scene.check(&values)?;
        if inputs.len() != scene.inputs.len() || inputs.iter().any(|x| !x.is_finite()) {
            return Err(SimError::BadArgument(format!(
                "{} input values, all finite, are needed ({} given)",
                scene.inputs.len(),
                inputs.len()
            )));
        }
        let mut setup = setup::setup(&scene, &values);
        contact::rest_bases(&mut setup.structure, &setup.springs, &inputs);
        let mut magnitudes = vec![0.0; setup.loads.len()];
        setup::load_magnitudes(&scene, &values, &inputs, &mut magnitudes);
        setup.loads.set_magnitudes(&magnitudes);
        setup.loads.frequency = scene.param_index("Omega").map_or(0.0, |i| values.get(i));
        let mut initial = DynamicState::at_rest(initial::initial_displacements(
            &scene, &values, &setup, &inputs,
        )?);
        let refused = contact::past_peak(&scene, &setup.structure, &initial.u)
            .or_else(|| contact::slack_joint(&scene, &setup, &initial.u));
        if let Some(why) = refused {
            return Err(SimError::InitialState(format!(
                "the equilibrium reached is refused: {why}"
            )));
        }
        if let Some(r) = scene.rayleigh {
            // K0: the tangent of the initial static state, a constant matrix.
            setup.structure.with_rayleigh(r.alpha, r.beta, &initial.u);
        }
        let static_reactions = supports::static_reactions(&setup, &initial.u, &inputs);
        let mut integrator = Midpoint::new(&setup.structure);
        let rows: Vec<usize> = (setup.held.iter())
            .flat_map(|h| h.rows().iter().map(move |r| h.dof + r))
            .collect();
        integrator.keep_rows(&rows);
        integrator.scheme = if values.std(Std::Integrator) == 2.0 {
            Scheme::EnergyMomentum
        } else {
            Scheme::Midpoint
        };
        (setup.structure).set_energy_momentum(integrator.scheme == Scheme::EnergyMomentum);
        let analysis =
            analysis::Analysis::new(&scene, &values, &setup, integrator.scheme, &mut initial)?;
        integrator.reserve_tangents(analysis.vectors(), &setup.structure);
        let energy = EnergyLedger {
            initial_energy: setup.structure.strain_energy(&initial.u)
                + springs::base_energy(&setup.springs, &initial.u, &inputs),
            ..EnergyLedger::default()
        };
        let moving = setup.held.iter().filter(|h| h.input.is_some()).count();
        let motion = match moving {
            0 => None,
            _ => Some(MotionSolver::new(&setup.structure).map_err(SimError::InitialState)?),
        };
        let readouts = readouts::Readouts::new(&scene, &values, &setup, &initial.u)?;
        let sim = Simulation {
            readouts,
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
            initial_inputs: inputs.clone(),
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

    /// The inputs the initial state was found with.
    pub fn initial_inputs(&self) -> &[f64] {
        &self.initial_inputs
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

    /// The first member's rod (a scene without joints: the rod).
    pub fn rod(&self) -> &crate::model::Rod {
        self.setup.structure.rod()
    }

    pub fn structure(&self) -> &Structure {
        &self.setup.structure
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
