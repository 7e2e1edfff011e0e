//! Solvers in time and for equilibrium: Newton settings, static Newton, the implicit midpoint rule.
pub mod continuation;
pub mod midpoint;
pub mod newton;
pub mod statics;
pub mod tangent;
pub mod tangent_map;

pub use midpoint::{DynamicState, Midpoint, Scheme};
pub use newton::{NewtonFailure, NewtonSettings, NewtonStats};
pub use statics::StaticSolver;
