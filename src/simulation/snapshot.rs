//! The simulation clock, the energy ledger, and snapshots: everything needed to continue a
//! simulation exactly.
use super::{SimError, Simulation};
use crate::model::Assembly;
use crate::scene::Variability;
use serde::{Deserialize, Serialize};

/// Version of [`Snapshot`]'s layout; bump it when the fields change.
pub const SNAPSHOT_VERSION: u32 = 5;

/// Simulation time as a step counter (model: `t_n = n dt`, not a running sum): while
/// communication steps keep the same sub-step `step`, sub-step `n` starts at
/// `origin + n * step`; a different sub-step size restarts the count at the current time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Clock {
    pub origin: f64,
    pub step: f64,
    pub count: u64,
}

impl Clock {
    pub fn start() -> Clock {
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
    pub fn with_step(self, step: f64) -> Clock {
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
    pub fn at(&self, k: u64) -> f64 {
        self.origin + (self.count + k) as f64 * self.step
    }

    pub fn is_finite(&self) -> bool {
        self.origin.is_finite() && self.step.is_finite() && self.step >= 0.0
    }
}

/// Energy bookkeeping since `t = 0`: with `du` a sub-step's increment, the work of the loads
/// held at the sub-step's midpoint is `du . f`, the dissipated energy `du . C du / dt`, the work
/// of the supports `du . R` over the held dofs (plus the work of the impulse when a moving
/// support changes speed). The discrete-gradient scheme balances these exactly; the midpoint
/// rule up to `O(dt^2)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EnergyLedger {
    /// Work of the constant and harmonic loads.
    pub external_work: f64,
    /// Work of the input loads.
    pub input_work: f64,
    /// Work of the supports on the rod.
    pub support_work: f64,
    pub dissipated: f64,
    /// `E_kin + E_strain` at `t = 0`.
    pub initial_energy: f64,
}

impl EnergyLedger {
    pub fn is_finite(&self) -> bool {
        [
            self.external_work,
            self.input_work,
            self.support_work,
            self.dissipated,
            self.initial_energy,
        ]
        .iter()
        .all(|x| x.is_finite())
    }
}

/// Everything needed to continue a simulation exactly: self-contained, versioned.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    pub version: u32,
    pub scene: String,
    pub elements: usize,
    pub time: f64,
    pub displacements: Vec<f64>,
    pub velocities: Vec<f64>,
    /// The values of every parameter (the tunable ones may have changed during the run).
    pub values: Vec<f64>,
    /// The inputs held over the last communication step.
    pub inputs: Vec<f64>,
    /// The reactions reported by the last step, per support.
    pub reactions: Vec<[f64; 3]>,
    pub last_newton_iterations: u32,
    pub energy: EnergyLedger,
    pub clock: Clock,
    /// Tangent vectors and growth of the Lyapunov exponents (when `lyapunov` > 0).
    pub lyapunov: Option<super::analysis::LyapunovSnapshot>,
    /// Accelerations of the last sub-step (empty unless an output reads them).
    pub accelerations: Vec<f64>,
}

impl Simulation {
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            version: SNAPSHOT_VERSION,
            scene: self.scene.name.clone(),
            elements: self.values.elements(),
            time: self.time(),
            displacements: self.state.u.clone(),
            velocities: self.state.v.clone(),
            values: self.values.0.clone(),
            inputs: self.inputs.clone(),
            reactions: self.reactions.clone(),
            last_newton_iterations: self.last_newton_iterations,
            energy: self.energy,
            clock: self.clock,
            lyapunov: self.analysis.snapshot(),
            accelerations: self.readouts.accelerations().to_vec(),
        }
    }

    /// Continues from a snapshot of a simulation of the same scene and fixed parameters. On an
    /// error the simulation may be partly changed: restore a snapshot of its own (as the FMU
    /// does) or drop it.
    pub fn restore(&mut self, s: &Snapshot) -> Result<(), SimError> {
        let bad = |why: String| Err(SimError::BadSnapshot(why));
        if s.version != SNAPSHOT_VERSION {
            return bad(format!(
                "version {} (this build reads {SNAPSHOT_VERSION})",
                s.version
            ));
        }
        if s.scene != self.scene.name {
            return bad(format!(
                "taken from a {} (this is a {})",
                s.scene, self.scene.name
            ));
        }
        if s.elements != self.values.elements() {
            return bad(format!(
                "{} elements (this rod has {})",
                s.elements,
                self.values.elements()
            ));
        }
        let n = self.setup.structure.dofs();
        if s.displacements.len() != n
            || s.velocities.len() != n
            || s.values.len() != self.values.0.len()
            || s.inputs.len() != self.inputs.len()
            || s.reactions.len() != self.reactions.len()
        {
            return bad("vectors of the wrong length".to_string());
        }
        let numbers = s
            .displacements
            .iter()
            .chain(&s.velocities)
            .chain(&s.values)
            .chain(&s.inputs);
        if !(s.time.is_finite()
            && numbers
                .chain(s.reactions.iter().flatten())
                .all(|x| x.is_finite())
            && s.energy.is_finite()
            && s.clock.is_finite())
        {
            return bad("non-finite values".to_string());
        }
        // A frame member's end repeats its joint: a state where they differ is no state of it.
        let ties = self.setup.structure.ties();
        if (ties.iter()).any(|&(a, b)| {
            s.displacements[a] != s.displacements[b] || s.velocities[a] != s.velocities[b]
        }) {
            return bad("a member's end differs from its joint".to_string());
        }
        self.analysis
            .check(s.lyapunov.as_ref())
            .map_err(SimError::BadSnapshot)?;
        if let Some(l) = &s.lyapunov {
            let n = self.setup.structure.dofs();
            let blocks = l.du.chunks(n).chain(l.dv.chunks(n));
            if blocks
                .into_iter()
                .any(|x| ties.iter().any(|&(a, b)| x[a] != x[b]))
            {
                return bad("a tangent vector's member end differs from its joint".to_string());
            }
        }
        if !self.readouts.fits(&s.accelerations) {
            return bad("accelerations of the wrong length or not finite".to_string());
        }
        let mut values = self.values.clone();
        for (i, &x) in s.values.iter().enumerate() {
            let p = &self.scene.params[i];
            if p.variability == Variability::Fixed && x != self.values.get(i) {
                return bad(format!(
                    "the fixed parameter `{}` differs ({x}, here {})",
                    p.name,
                    self.values.get(i)
                ));
            }
            p.check(x).map_err(SimError::Param)?;
            values.0[i] = x;
        }
        for i in 0..values.0.len() {
            self.set_param(i, values.get(i))?;
        }
        self.state.u.copy_from_slice(&s.displacements);
        self.state.v.copy_from_slice(&s.velocities);
        self.inputs.copy_from_slice(&s.inputs);
        self.next_inputs.copy_from_slice(&s.inputs);
        self.rest_cubic_bases();
        self.input_derivatives.fill(None);
        self.loads_stale = true;
        self.reactions.copy_from_slice(&s.reactions);
        self.clock = s.clock;
        self.last_newton_iterations = s.last_newton_iterations;
        self.energy = s.energy;
        self.energies.set(None);
        self.analysis.restore(&self.values, s.lyapunov.as_ref());
        self.readouts.restore(&s.accelerations);
        // Finite numbers can still make outputs that are not (a huge velocity, a ledger whose
        // sum overflows): such a snapshot is refused like a non-finite one.
        self.check_outputs()
            .map_err(|what| SimError::BadSnapshot(format!("it gives a non-finite {what}")))
    }

    /// Back to the initial state at `t = 0`, with the values and inputs it was built with.
    pub fn reset(&mut self) {
        let values = self.initial_values.clone();
        for i in 0..values.0.len() {
            self.set_param(i, values.get(i))
                .expect("the initial values were valid");
        }
        self.state.copy_from(&self.initial);
        self.inputs.clone_from(&self.initial_inputs);
        self.next_inputs.clone_from(&self.inputs);
        self.rest_cubic_bases();
        self.input_derivatives.fill(None);
        self.loads_stale = true;
        self.energy = EnergyLedger {
            initial_energy: self.setup.structure.strain_energy(&self.initial.u)
                + super::springs::base_energy(&self.setup.springs, &self.initial.u, &self.inputs),
            ..EnergyLedger::default()
        };
        self.reactions.clone_from(&self.static_reactions);
        self.energies.set(Some((0.0, self.energy.initial_energy)));
        self.clock = Clock::start();
        self.last_newton_iterations = 0;
        self.analysis.reset(&self.values);
        self.readouts.reset();
    }
}
