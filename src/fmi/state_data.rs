//! What an FMU state holds ([`StateData`]): taken and restored by an instance, kept by its state
//! registry, serialized and checked by [`super::fmu_state`] and [`super::state_check`]. It names
//! only the leaves [`super::state_machine`] and [`super::experiment`] of `fmi`.
use super::experiment::Experiment;
use super::state_machine::FmiState;
use crate::scene::ParamValues;
use crate::simulation::Snapshot;

/// What an FMU state holds.
#[derive(Clone, Debug, PartialEq)]
pub struct StateData {
    /// The scene's name.
    pub scene: String,
    pub fmi_state: FmiState,
    pub experiment: Experiment,
    pub params: ParamValues,
    /// The inputs the host set (`None`: the start value).
    pub inputs: Vec<Option<f64>>,
    /// The simulation state; `None` before `fmi2ExitInitializationMode` (nothing simulated yet).
    pub snapshot: Option<Snapshot>,
}
