//! A scene brought to its initial static state and advanced in time by midpoint sub-steps:
//! everything an FMU instance computes, without any FMI concern.
use crate::integrator::{DynamicState, Midpoint, NewtonFailure, StaticSolver};
use crate::model::rod::{ROTATION, U1, U2};
use crate::model::{ExcitationKind, LoadCase, ReferenceCurve, Rod, Section};
use crate::scene::{ParamError, SceneKind, SceneParams};
use serde::{Deserialize, Serialize};
use std::fmt;

/// Version of [`Snapshot`]'s layout; bump it when the fields change.
pub const SNAPSHOT_VERSION: u32 = 2;

/// How often a failing sub-step is halved before a communication step is given up.
pub const MAX_STEP_CUTS: u32 = 5;

/// Most sub-steps one communication step may take (after cuts): beyond this a step is refused
/// rather than run for hours (`dt_max` far below the communication step).
pub const MAX_SUBSTEPS: usize = 10_000_000;

/// Load steps used to reach the initial static state.
const RAMP_STEPS: usize = 20;

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

/// The outputs of the FMU at the current time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outputs {
    pub w_mid: f64,
    pub v_mid: f64,
    pub kinetic_energy: f64,
    pub strain_energy: f64,
    pub energy: EnergyLedger,
    /// `E_kin + E_strain - E(0) - W_ext - W_ctrl + E_damped`.
    pub energy_error: f64,
}

impl Outputs {
    /// The output with this FMU variable name.
    pub fn by_name(&self, name: &str) -> Option<f64> {
        Some(match name {
            "w_mid" => self.w_mid,
            "v_mid" => self.v_mid,
            "E_kin" => self.kinetic_energy,
            "E_strain" => self.strain_energy,
            "W_ext" => self.energy.external_work,
            "W_ctrl" => self.energy.control_work,
            "E_damped" => self.energy.dissipated,
            "energy_error" => self.energy_error,
            _ => return None,
        })
    }
}

/// Energy bookkeeping since `t = 0`: with `du` a sub-step's increment, the work of the loads
/// held at the sub-step's midpoint is `du . f`, the dissipated energy `du . C du / dt`. The
/// discrete-gradient scheme balances these exactly; the midpoint rule up to `O(dt^2)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EnergyLedger {
    /// Work of the excitation `F cos(Omega t)` and of the preload `P0`.
    pub external_work: f64,
    /// Work of the control force `f_ctrl`.
    pub control_work: f64,
    pub dissipated: f64,
    /// `E_kin + E_strain` at `t = 0`.
    pub initial_energy: f64,
}

/// What one [`Simulation::advance`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AdvanceReport {
    pub substeps: usize,
    /// Corrections (Newton and chord) summed over the sub-steps.
    pub newton_iterations: u32,
    /// Jacobians factored, summed over the sub-steps.
    pub factorizations: u32,
    /// How many times the sub-step was halved after a Newton failure.
    pub cuts: u32,
}

/// Simulation time as a step counter (model.md: `t_n = n dt`, not a running sum): while
/// communication steps keep the same sub-step `step`, sub-step `n` starts at
/// `origin + n * step`; a different sub-step size restarts the count at the current time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Clock {
    pub origin: f64,
    pub step: f64,
    pub count: u64,
}

impl Clock {
    fn start() -> Clock {
        Clock {
            origin: 0.0,
            step: 0.0,
            count: 0,
        }
    }

    pub fn now(&self) -> f64 {
        self.origin + self.count as f64 * self.step
    }

    /// The clock that counts sub-steps of `step` from now on.
    fn with_step(self, step: f64) -> Clock {
        if step == self.step {
            self
        } else {
            Clock {
                origin: self.now(),
                step,
                count: 0,
            }
        }
    }

    /// Start time of sub-step `k` from now.
    fn at(&self, k: u64) -> f64 {
        self.origin + (self.count + k) as f64 * self.step
    }
}

/// Everything needed to continue a simulation exactly: self-contained, versioned.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    pub version: u32,
    pub kind: SceneKind,
    pub elements: usize,
    pub time: f64,
    pub displacements: Vec<f64>,
    pub velocities: Vec<f64>,
    pub forcing_amplitude: f64,
    pub forcing_frequency: f64,
    pub last_newton_iterations: u32,
    pub energy: EnergyLedger,
    pub clock: Clock,
}

/// The rod of a scene with its supports, and where its excitation acts.
pub fn build_rod(p: &SceneParams) -> (Rod, ExcitationKind) {
    let section = Section::rectangular(
        p.youngs_modulus,
        p.poisson_ratio,
        p.density,
        p.width,
        p.height,
    );
    match p.kind {
        SceneKind::BuckledBeam => {
            let curve = ReferenceCurve::Straight { length: p.span };
            let mut rod = Rod::new(curve, section, p.damping, p.elements);
            let last = rod.last_node();
            rod.fix(0, U1);
            rod.fix(0, U2);
            rod.fix(last, U1);
            rod.fix(last, U2);
            (rod, ExcitationKind::Distributed)
        }
        SceneKind::PinnedArch | SceneKind::ClampedArch => {
            let curve = ReferenceCurve::arc(p.span, p.rise);
            let mut rod = Rod::new(curve, section, p.damping, p.elements);
            let clamped = p.kind == SceneKind::ClampedArch;
            for node in [0, rod.last_node()] {
                rod.fix(node, U1);
                rod.fix(node, U2);
                if clamped {
                    rod.fix(node, ROTATION);
                }
            }
            (rod, ExcitationKind::Crown)
        }
    }
}

/// Axial strain at the buckling load of the pinned-pinned straight rod of this model (shear and
/// stretch included): the root of `P^2 (1 - GA/EA) + GA P - GA EI (pi/L)^2 = 0`, over `EA`.
fn critical_strain(p: &SceneParams, rod: &Rod) -> f64 {
    let (ea, ga, ei) = (rod.section.ea, rod.section.ga, rod.section.ei);
    let k2 = (std::f64::consts::PI / p.span).powi(2);
    let a = 1.0 - ga / ea;
    let force = if a.abs() < 1e-12 {
        ei * k2
    } else {
        (-ga + (ga * ga + 4.0 * a * ga * ei * k2).sqrt()) / (2.0 * a)
    };
    force / ea
}

/// Newton's starting point for the buckled beam: the first buckling mode `A sin(pi s / L)` in the
/// chosen well, with the amplitude of the inextensible elastica at small amplitude,
/// `Delta = eps_cr L + (pi A)^2 / (4 L)`, and the matching axial displacements and rotations.
/// (A ramp of the end shortening through the bifurcation is fragile on fine meshes; this guess
/// lies within Newton's quadratic basin of the buckled state for any mesh.)
fn buckled_guess(p: &SceneParams, rod: &Rod, u: &mut [f64]) {
    let (span, shortening) = (p.span, p.pre_shortening);
    let strain = critical_strain(p, rod).min(shortening / span);
    let geometric = (shortening - strain * span).max(0.0);
    let amplitude = p.well.signum() as f64 * (4.0 * span * geometric).sqrt() / std::f64::consts::PI;
    let k = std::f64::consts::PI / span;
    for (i, &s) in rod.node_s.iter().enumerate() {
        let slope = amplitude * k * (k * s).cos();
        u[3 * i + U1] =
            -strain * s - 0.25 * (amplitude * k).powi(2) * (s + (2.0 * k * s).sin() / (2.0 * k));
        u[3 * i + U2] = amplitude * (k * s).sin();
        u[3 * i + ROTATION] = slope.atan();
    }
    let last = rod.last_node();
    u[3 * last + U1] = -shortening;
    u[3 * last + U2] = 0.0;
    u[U2] = 0.0;
}

/// The initial static state of model.md: the buckled beam in its well, or the arch under `P0`.
pub fn initial_displacements(p: &SceneParams, rod: &Rod) -> Result<Vec<f64>, SimError> {
    let mut solver = StaticSolver::new(rod);
    let mut u = vec![0.0; rod.dofs()];
    let fail = |what: &str, e: NewtonFailure| SimError::InitialState(format!("{what}: {e}"));
    match p.kind {
        SceneKind::BuckledBeam => {
            let zero = vec![0.0; rod.dofs()];
            let in_well = |u: &[f64]| rod.interpolate(u, rod.midspan(), U2) * p.well as f64 > 0.0;
            buckled_guess(p, rod, &mut u);
            solver
                .solve(rod, &mut u, &zero)
                .map_err(|e| fail("buckled equilibrium", e))?;
            if in_well(&u) {
                return Ok(u);
            }
            // Newton found the straight state. It is the answer if it is stable (this mesh does
            // not buckle at this shortening); otherwise push it into the well with a transverse
            // imperfection load (a linear deflection of 1e-3 L) and remove that again.
            if solver.factored_tangent().negative_pivots() == 0 {
                return Ok(u);
            }
            let q = 1e-3 * p.span * 384.0 * rod.section.ei / (5.0 * p.span.powi(4));
            let mut imperfection = vec![0.0; rod.dofs()];
            rod.add_uniform_transverse_load(&mut imperfection, -(p.well as f64) * q);
            buckled_guess(p, rod, &mut u);
            solver
                .solve(rod, &mut u, &imperfection)
                .map_err(|e| fail("imperfect beam", e))?;
            solver
                .solve(rod, &mut u, &zero)
                .map_err(|e| fail("buckled equilibrium", e))?;
            if !in_well(&u) {
                let w_mid = rod.interpolate(&u, rod.midspan(), U2);
                return Err(SimError::InitialState(format!(
                    "the static state has w_mid = {w_mid:.4e}, not in the well {}",
                    p.well
                )));
            }
            Ok(u)
        }
        SceneKind::PinnedArch | SceneKind::ClampedArch => {
            if p.preload == 0.0 {
                return Ok(u);
            }
            let mut f_ext = vec![0.0; rod.dofs()];
            rod.add_point_transverse_load(&mut f_ext, rod.midspan(), p.preload);
            solver
                .solve_ramped(rod, &mut u, &f_ext, RAMP_STEPS)
                .map_err(|(k, e)| {
                    fail(&format!("preload ramp, load step {k} of {RAMP_STEPS}"), e)
                })?;
            Ok(u)
        }
    }
}

pub struct Simulation {
    params: SceneParams,
    rod: Rod,
    loads: LoadCase,
    integrator: Midpoint,
    initial: DynamicState,
    state: DynamicState,
    /// Scratch state of a communication step in progress (the state is replaced only on success).
    trial: DynamicState,
    clock: Clock,
    last_newton_iterations: u32,
    /// `(F, Omega)` at construction, restored by [`Simulation::reset`].
    initial_forcing: (f64, f64),
    energy: EnergyLedger,
    /// The ledger of a communication step in progress.
    trial_energy: EnergyLedger,
    /// `f_ctrl` held over the communication step in progress.
    f_ctrl: f64,
}

impl Simulation {
    /// Validates the parameters, builds the rod and solves its initial static state.
    pub fn new(params: SceneParams) -> Result<Simulation, SimError> {
        params.validate()?;
        let (rod, excitation) = build_rod(&params);
        let mut loads = LoadCase::new(&rod, excitation);
        loads.amplitude = params.forcing_amplitude;
        loads.frequency = params.forcing_frequency;
        let initial = DynamicState::at_rest(initial_displacements(&params, &rod)?);
        let mut integrator = Midpoint::new(&rod);
        integrator.scheme = params.integrator;
        let energy = EnergyLedger {
            initial_energy: rod.strain_energy(&initial.u),
            ..EnergyLedger::default()
        };
        Ok(Simulation {
            integrator,
            energy,
            trial_energy: energy,
            f_ctrl: 0.0,
            state: initial.clone(),
            trial: initial.clone(),
            initial,
            loads,
            rod,
            clock: Clock::start(),
            last_newton_iterations: 0,
            initial_forcing: (params.forcing_amplitude, params.forcing_frequency),
            params,
        })
    }

    pub fn params(&self) -> &SceneParams {
        &self.params
    }

    pub fn rod(&self) -> &Rod {
        &self.rod
    }

    pub fn state(&self) -> &DynamicState {
        &self.state
    }

    /// Time since the start of the simulation.
    pub fn time(&self) -> f64 {
        self.clock.now()
    }

    /// Changes the tunable excitation `F cos(Omega t)`.
    pub fn set_forcing(&mut self, amplitude: f64, frequency: f64) -> Result<(), ParamError> {
        let mut p = self.params.clone();
        p.set("F", amplitude)?;
        p.set("Omega", frequency)?;
        self.params = p;
        self.loads.amplitude = amplitude;
        self.loads.frequency = frequency;
        Ok(())
    }

    /// The fewest equal sub-steps no longer than `dt_max` that make up `h`.
    pub fn substeps_for(&self, h: f64) -> usize {
        // The factor forgives round-off in h / dt_max (1e-4 / 1e-5 is 10.000000000000002).
        // (`as usize` saturates: an absurd ratio becomes usize::MAX, refused by `advance`.)
        ((h / self.params.dt_max) * (1.0 - 1e-12)).ceil().max(1.0) as usize
    }

    /// One communication step of length `h` with the control force `f_ctrl` held: equal midpoint
    /// sub-steps no longer than `dt_max`, the excitation taken at each sub-step's midpoint. A
    /// failing sub-step makes the whole step restart with half the sub-step size (at most
    /// [`MAX_STEP_CUTS`] times); if it still fails, the state is left exactly as it was.
    pub fn advance(&mut self, h: f64, f_ctrl: f64) -> Result<AdvanceReport, SimError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(SimError::BadArgument(format!(
                "step size {h} must be finite and > 0"
            )));
        }
        if !f_ctrl.is_finite() {
            return Err(SimError::BadArgument(format!(
                "f_ctrl = {f_ctrl} is not finite"
            )));
        }
        let preload = match self.params.kind {
            SceneKind::BuckledBeam => 0.0,
            SceneKind::PinnedArch | SceneKind::ClampedArch => self.params.preload,
        };
        self.loads.point_force = preload + f_ctrl;
        self.f_ctrl = f_ctrl;
        let t0 = self.time();
        let mut substeps = self.substeps_for(h);
        if substeps > MAX_SUBSTEPS {
            return Err(SimError::BadArgument(format!(
                "a step of {h} s with dt_max = {} s needs {substeps} sub-steps, more than \
                 {MAX_SUBSTEPS}: raise dt_max or shorten the communication step",
                self.params.dt_max
            )));
        }
        let mut last_failure = None;
        for cuts in 0..=MAX_STEP_CUTS {
            match self.try_substeps(h, substeps) {
                Ok((newton_iterations, factorizations)) => {
                    std::mem::swap(&mut self.state, &mut self.trial);
                    self.energy = self.trial_energy;
                    self.clock = self.clock.with_step(h / substeps as f64);
                    self.clock.count += substeps as u64;
                    self.last_newton_iterations = newton_iterations;
                    return Ok(AdvanceReport {
                        substeps,
                        newton_iterations,
                        factorizations,
                        cuts,
                    });
                }
                Err(e) => last_failure = Some(e),
            }
            substeps = substeps.saturating_mul(2);
            if substeps > MAX_SUBSTEPS {
                break;
            }
        }
        let reason = last_failure.map_or_else(String::new, |e| e.to_string());
        Err(SimError::StepFailed {
            time: t0,
            reason: format!("{reason} (after {MAX_STEP_CUTS} halvings of the sub-step)"),
        })
    }

    /// Returns the corrections and the factorizations summed over the sub-steps.
    fn try_substeps(&mut self, h: f64, substeps: usize) -> Result<(u32, u32), NewtonFailure> {
        self.trial.copy_from(&self.state);
        self.trial_energy = self.energy;
        let dt = h / substeps as f64;
        let clock = self.clock.with_step(dt);
        let (mut iterations, mut factorizations) = (0, 0);
        for k in 0..substeps {
            let t_k = clock.at(k as u64);
            let stats = self
                .integrator
                .step(&self.rod, &self.loads, &mut self.trial, t_k, dt)?;
            iterations += stats.iterations;
            factorizations += stats.factorizations;
            self.book_energy(t_k + 0.5 * dt, dt);
        }
        Ok((iterations, factorizations))
    }

    /// Adds the work and dissipation of the sub-step just taken to the trial ledger.
    fn book_energy(&mut self, t_mid: f64, dt: f64) {
        let du = self.integrator.last_increment();
        let dot = |f: &[f64]| du.iter().zip(f).map(|(a, b)| a * b).sum::<f64>();
        let on_excitation = dot(&self.loads.excitation_shape);
        let on_point = dot(&self.loads.point_shape);
        let ledger = &mut self.trial_energy;
        ledger.external_work += self.loads.excitation(t_mid) * on_excitation
            + (self.loads.point_force - self.f_ctrl) * on_point;
        ledger.control_work += self.f_ctrl * on_point;
        ledger.dissipated += self.rod.dissipation_rate(du) / dt;
    }

    pub fn outputs(&self) -> Outputs {
        let mid = self.rod.midspan();
        let kinetic_energy = self.rod.kinetic_energy(&self.state.v);
        let strain_energy = self.rod.strain_energy(&self.state.u);
        let e = &self.energy;
        Outputs {
            w_mid: self.rod.interpolate(&self.state.u, mid, U2),
            v_mid: self.rod.interpolate(&self.state.v, mid, U2),
            kinetic_energy,
            strain_energy,
            energy: *e,
            energy_error: kinetic_energy + strain_energy
                - e.initial_energy
                - e.external_work
                - e.control_work
                + e.dissipated,
        }
    }

    /// Newton iterations summed over the sub-steps of the last communication step.
    pub fn last_newton_iterations(&self) -> u32 {
        self.last_newton_iterations
    }

    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            version: SNAPSHOT_VERSION,
            kind: self.params.kind,
            elements: self.params.elements,
            time: self.time(),
            displacements: self.state.u.clone(),
            velocities: self.state.v.clone(),
            forcing_amplitude: self.params.forcing_amplitude,
            forcing_frequency: self.params.forcing_frequency,
            last_newton_iterations: self.last_newton_iterations,
            energy: self.energy,
            clock: self.clock,
        }
    }

    /// Continues from a snapshot of a simulation of the same scene and mesh.
    pub fn restore(&mut self, s: &Snapshot) -> Result<(), SimError> {
        let bad = |why: String| Err(SimError::BadSnapshot(why));
        if s.version != SNAPSHOT_VERSION {
            return bad(format!(
                "version {} (this build reads {SNAPSHOT_VERSION})",
                s.version
            ));
        }
        if s.kind != self.params.kind {
            return bad(format!(
                "taken from a {} (this is a {})",
                s.kind, self.params.kind
            ));
        }
        if s.elements != self.params.elements {
            return bad(format!(
                "{} elements (this rod has {})",
                s.elements, self.params.elements
            ));
        }
        let n = self.rod.dofs();
        if s.displacements.len() != n || s.velocities.len() != n {
            return bad(format!("vectors of the wrong length (expected {n})"));
        }
        if !(s.time.is_finite()
            && s.displacements
                .iter()
                .chain(&s.velocities)
                .all(|x| x.is_finite()))
        {
            return bad("non-finite values".to_string());
        }
        self.set_forcing(s.forcing_amplitude, s.forcing_frequency)?;
        self.state.u.copy_from_slice(&s.displacements);
        self.state.v.copy_from_slice(&s.velocities);
        self.clock = s.clock;
        self.last_newton_iterations = s.last_newton_iterations;
        self.energy = s.energy;
        Ok(())
    }

    /// Back to the initial static state at `t = 0`, with the excitation it was built with.
    pub fn reset(&mut self) {
        let (f, omega) = (self.initial_forcing.0, self.initial_forcing.1);
        self.set_forcing(f, omega)
            .expect("the initial forcing was valid");
        self.state.copy_from(&self.initial);
        self.energy = EnergyLedger {
            initial_energy: self.rod.strain_energy(&self.initial.u),
            ..EnergyLedger::default()
        };
        self.clock = Clock::start();
        self.last_newton_iterations = 0;
    }
}
