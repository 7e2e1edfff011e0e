//! A structure: members joined at joints. Each member is a [`Rod`] (a chain of elements along
//! its own reference curve, with its own section and mesh); truss bars and links ([`Axial`])
//! join two nodes; masses, springs and dashpots may sit on a joint's dofs. A scene with one
//! member (every `[geometry]` scene) is a structure whose one rod is the whole model: it keeps
//! the rod's block-tridiagonal matrix and its step is the rod's own (same bits, same cost).
//!
//! **Dof vector.** Joints come first (joint `j` is node `j`, dofs `3 j + k`), then each member's
//! nodes in order (member `m` from `offset[m]`), so a member's dofs are one contiguous slice and
//! its elements run over it exactly as a lone rod's do. A member's end nodes duplicate its joints:
//! their translations (and rotation, unless the end is hinged) are **tied** to the joint's
//! (slave dof, master dof). Vectors of displacements and velocities keep every slave equal to its
//! master; vectors of forces are **folded**: a slave's row is added to its master's and set to
//! zero. Every product and force of a structure returns folded vectors, every solve returns
//! consistent ones (the solver copies masters to slaves), so the integrators never see a tie.
//! A hinged end keeps its own rotation, free of the joint's; a joint that no rigid member end
//! reaches has no rotation (its `w` is held at zero: "dead").
//!
//! The matrices of a frame are block-sparse on the node graph (`matrix.rs`): each member a chain,
//! coupled at the joints; their elimination follows the chains (see `crate::solver::sparse_blocks`).
mod assembly;
mod axial;
mod frame_terms;
mod graph;
mod kinks;
mod ledger;
mod matrix;
pub mod nonlinear;
mod points;
mod topology;

pub use axial::Axial;
pub use matrix::StructureMatrix;
pub use nonlinear::{CubicSpring, Nonlinear, Stop};
pub use points::Place;

use super::element::ElementTangent;
use super::rod::Rod;
use nalgebra::{Matrix2, Vector2};

/// Where a member ends: its joint, and whether the end is hinged there (a pin: the member's end
/// rotates freely of the joint).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemberEnd {
    pub joint: usize,
    pub hinged: bool,
}

/// A member: a rod whose dofs start at `offset` in the structure's vectors.
#[derive(Clone, Debug)]
pub struct Member {
    pub rod: Rod,
    pub offset: usize,
    /// Its two ends (none for the one member of a scene without joints).
    pub ends: Option<[MemberEnd; 2]>,
}

impl Member {
    /// The member's dofs in the structure's vectors.
    pub fn range(&self) -> std::ops::Range<usize> {
        self.offset..self.offset + self.rod.dofs()
    }
}

/// Constant terms on single dofs of the structure (at joints): point masses, springs, dashpots.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodalTerms {
    pub masses: Vec<(usize, f64)>,
    pub springs: Vec<(usize, f64)>,
    pub dashpots: Vec<(usize, f64)>,
}

/// Every element tangent of a structure, kept by a residual evaluation (the tangent map).
#[derive(Clone, Debug, Default)]
pub struct StructureTangents {
    pub members: Vec<Vec<ElementTangent>>,
    pub axial: Vec<Matrix2<f64>>,
    /// The stops' and cubic springs' stiffness (see [`Nonlinear::len`]).
    pub nodal: Vec<f64>,
}

#[derive(Clone, Debug)]
pub struct Structure {
    pub members: Vec<Member>,
    /// Reference position of each joint.
    pub joints: Vec<Vector2<f64>>,
    pub axial: Vec<Axial>,
    pub nodal: NodalTerms,
    /// Stops and cubic springs (on master dofs; empty: skipped).
    pub nonlinear: Nonlinear,
    dofs: usize,
    /// `(slave, master)` dof pairs, and the slaves alone.
    ties: Vec<(usize, usize)>,
    slaves: Vec<usize>,
    /// Held by a support (fixed or prescribed), per dof.
    held: Vec<bool>,
    /// Joint rotations that no rigid member end reaches.
    dead: Vec<usize>,
    /// Supports that hold a node along one direction only: `(node, unit vector)`.
    directions: Vec<(usize, [f64; 2])>,
    /// Set to zero in vectors: held and dead dofs and their slaves, in increasing order.
    zeroed: Vec<usize>,
    /// Removed from the systems: the zeroed dofs and every slave.
    eliminated: Vec<usize>,
    /// Nodes whose translation a direction holds, with the slaves of theirs: projected in vectors.
    projected: Vec<(usize, [f64; 2])>,
    /// The frame's block-sparse pattern and where each element assembles (`None`: one member,
    /// a block-tridiagonal matrix).
    graph: Option<graph::Graph>,
    /// Lumped mass and damping (of the members and bars).
    pub lumped: bool,
    /// Stiffness-proportional Rayleigh damping of the bars and joint springs: `beta` and the
    /// bars' tangents of the initial state.
    rayleigh: Option<(f64, Vec<Matrix2<f64>>)>,
}

impl Structure {
    /// The one-member structure of a rod (its held dofs are the rod's).
    pub fn single(rod: Rod) -> Structure {
        let dofs = rod.dofs();
        let held: Vec<usize> = rod.constrained().to_vec();
        let lumped = rod.lumped;
        let mut s = Structure {
            members: vec![Member {
                rod,
                offset: 0,
                ends: None,
            }],
            joints: Vec::new(),
            axial: Vec::new(),
            nodal: NodalTerms::default(),
            nonlinear: Nonlinear::default(),
            dofs,
            ties: Vec::new(),
            slaves: Vec::new(),
            held: vec![false; dofs],
            dead: Vec::new(),
            directions: Vec::new(),
            zeroed: Vec::new(),
            eliminated: Vec::new(),
            projected: Vec::new(),
            graph: None,
            lumped,
            rayleigh: None,
        };
        for dof in held {
            s.held[dof] = true;
        }
        s.update_constraints();
        s
    }

    /// Whether this is one rod (no joints): its matrices are block tridiagonal.
    pub fn is_single(&self) -> bool {
        self.graph.is_none()
    }

    /// The one rod of a single-member structure, or the first member.
    pub fn rod(&self) -> &Rod {
        &self.members[0].rod
    }

    pub fn dofs(&self) -> usize {
        self.dofs
    }

    pub fn nodes(&self) -> usize {
        self.dofs / 3
    }

    /// Holds `dof` (a support: fixed or prescribed).
    pub fn hold(&mut self, dof: usize) {
        self.held[dof] = true;
        self.update_constraints();
    }

    /// Holds the translation of `node` along the unit vector `n` only (a roller on an incline).
    pub fn hold_direction(&mut self, node: usize, n: [f64; 2]) {
        self.directions.push((node, n));
        self.update_constraints();
    }

    /// Whether a support holds `dof`.
    pub fn is_held(&self, dof: usize) -> bool {
        self.held[dof]
    }

    /// The directions held at nodes (supports at an angle that hold one translation).
    pub fn held_directions(&self) -> &[(usize, [f64; 2])] {
        &self.directions
    }

    /// The master of every dof: itself, or the joint dof it is tied to.
    pub fn master(&self, dof: usize) -> usize {
        (self.ties.iter())
            .find(|&&(s, _)| s == dof)
            .map_or(dof, |&(_, m)| m)
    }

    /// Whether `dof` is a joint rotation that no rigid member end reaches.
    pub fn is_dead(&self, dof: usize) -> bool {
        self.dead.contains(&dof)
    }

    /// Adds each slave's row to its master's and zeroes it (a force vector made of the
    /// members' own rows).
    pub fn fold(&self, x: &mut [f64]) {
        for &(s, m) in &self.ties {
            x[m] += x[s];
            x[s] = 0.0;
        }
    }

    /// Copies every master into its slaves (a displacement or velocity vector).
    pub fn expand(&self, x: &mut [f64]) {
        for &(s, m) in &self.ties {
            x[s] = x[m];
        }
    }

    /// The rows of the folded force vector at a node's three dofs, from a full vector `f`.
    pub fn node_rows(f: &[f64], node: usize) -> [f64; 3] {
        [f[3 * node], f[3 * node + 1], f[3 * node + 2]]
    }
}
