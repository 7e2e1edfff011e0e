//! georod: a geometrically exact planar rod (Cosserat line with shear), discretized by the hybrid
//! two-node element of Sansour, Sansour & Wriggers and integrated by the implicit midpoint rule,
//! exported as FMI 2.0 Co-Simulation FMUs. A rod, its supports, loads, inputs and sensors are a
//! scene file (TOML); one library serves every scene.
//!
//! Layout:
//! - [`model`]: reference geometry, the hybrid element, assembly, loads, mass and damping;
//! - [`solver`]: the block-tridiagonal linear solver (O(elements) per factorization);
//! - [`integrator`]: static Newton, the implicit midpoint rule and the energy-momentum scheme,
//!   arc-length continuation;
//! - [`scene`]: scene files, checked, with their parameters and FMU variables;
//! - [`simulation`]: a scene brought to its initial state and advanced in time (what an FMU runs);
//! - [`packaging`]: a scene packaged as an FMU (modelDescription.xml, documentation, zip);
//! - [`fmi`]: the FMI 2.0 Co-Simulation C API.
pub mod fmi;
pub mod integrator;
pub mod model;
pub mod packaging;
pub mod scene;
pub mod simulation;
pub mod solver;
