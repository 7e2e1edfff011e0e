//! FMI 2.0 and FMI 3.0 Co-Simulation C APIs.
//!
//! One binary serves every scene and both versions: `fmi2Instantiate` (or
//! `fmi3InstantiateCoSimulation`) reads the scene file from the FMU's
//! `resources/`, checks it, and compares the GUID of the modelDescription.xml it generates with
//! the host's ([`interface`]). Each instance is a boxed [`instance::Instance`] behind the opaque
//! `fmi2Component`; there is no global state and no thread, so instances may live on different
//! threads at once. This layer knows no physics: it maps value references to the scene's
//! parameters, inputs and outputs and drives a [`crate::simulation::Simulation`].
//!
//! - [`types`], [`types3`]: the C types of the FMI 2.0 and FMI 3.0 headers;
//! - [`logging`]: log categories ([`logging::LOG_CATEGORIES`], also used for the XML) and the
//!   per-instance logger;
//! - [`interface`]: the scene of an FMU and its variables;
//! - [`state_machine`]: the FMI states, the states each call is allowed in, how a call is
//!   refused ([`state_machine::FmiResult`]);
//! - [`experiment`]: what `fmi2SetupExperiment` said;
//! - [`state_data`]: what an FMU state holds;
//! - [`instance`]: one instance: life cycle, values, stepping, FMU states (testable Rust);
//! - [`values`]: getting and setting variables;
//! - [`fmu_state`]: FMU state snapshots and their serialized, self-checking form;
//! - [`state_check`]: field checks of a deserialized state;
//! - [`state_registry`]: the state handles an instance gave out (opaque tokens, never reused,
//!   checked before any use);
//! - [`ffi`]: what the C shims of both versions share (the call wrapper with `catch_unwind`,
//!   pointer checks); [`ffi_states`]: FMU states through the C API, for both versions;
//! - [`api`]: the exported FMI 2.0 `extern "C"` functions, by concern (life cycle, values, FMU
//!   states, stepping); [`api3`]: the FMI 3.0 ones (arrays mapped to the instance's scalars,
//!   the functions of unsupported features refused); only these two differ between versions;
//! - [`uri`]: `fmuResourceLocation` parsing.
pub mod api;
pub mod api3;
pub mod experiment;
pub mod ffi;
pub mod ffi_states;
pub mod fmu_state;
pub mod instance;
pub mod interface;
pub mod logging;
pub mod state_check;
pub mod state_data;
pub mod state_machine;
pub mod state_registry;
pub mod types;
pub mod types3;
pub mod uri;
pub mod values;
