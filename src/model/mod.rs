//! The rod model of `docs/model.md` (sections 1 to 5): reference geometry, section, the hybrid
//! element and the assembled rod with its constraints, loads, mass and damping.
pub mod assembly;
pub mod attachments;
pub mod bands;
pub mod contact;
pub mod element;
pub mod geometry;
pub mod loads;
pub mod mesh;
pub mod modal;
pub mod modal_subspace;
pub mod moving_loads;
pub mod rayleigh;
pub mod rod;
pub mod section;
pub mod section_forces;
pub mod structure;

pub use assembly::Assembly;
pub use element::Element;
pub use geometry::{Placement, ReferenceCurve};
pub use loads::{LoadSet, LoadShape, LoadTime};
pub use rod::{PointOnRod, Rod};
pub use section::Section;
pub use section_forces::SectionForces;
pub use structure::{Place, Structure};
