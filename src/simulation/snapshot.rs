//! The simulation clock, the energy ledger, and snapshots: everything needed to continue a
//! simulation exactly.
use serde::{Deserialize, Serialize};

/// Version of [`Snapshot`]'s layout; bump it when the fields change.
pub const SNAPSHOT_VERSION: u32 = 3;

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
}
