//! What `fmi2SetupExperiment` said: kept by an instance and in its FMU states. A leaf: it names
//! nothing else of `fmi`.
use serde::{Deserialize, Serialize};

/// What `fmi2SetupExperiment` said.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Experiment {
    pub tolerance: Option<f64>,
    pub start_time: f64,
    pub stop_time: Option<f64>,
}

impl Default for Experiment {
    fn default() -> Self {
        Experiment {
            tolerance: None,
            start_time: 0.0,
            stop_time: None,
        }
    }
}
