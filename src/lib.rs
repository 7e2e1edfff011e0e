//! georod: a geometrically exact planar rod (Cosserat line with shear), discretized by the hybrid
//! two-node element of Sansour, Sansour & Wriggers and integrated by the implicit midpoint rule,
//! exported as FMI 2.0 Co-Simulation FMUs.
//!
//! Layout:
//! - [`model`]: reference geometry, the hybrid element, assembly, loads, mass and damping;
//! - [`solver`]: the block-tridiagonal linear solver (O(elements) per factorization);
//! - [`integrator`]: static Newton with ramping, and the implicit midpoint rule;
//! - [`scene`]: the three scenes of `model.md` as validated data;
//! - [`simulation`]: a scene brought to its initial state and advanced in time (what an FMU runs);
//! - [`variables`]: the FMU variable table generated from `modelDescription/`;
//! - [`fmi`]: the FMI 2.0 Co-Simulation C API.
pub mod fmi;
pub mod integrator;
pub mod model;
pub mod scene;
pub mod simulation;
pub mod solver;
pub mod variables;
