//! The system matrix of a structure: a rod's block-tridiagonal matrix, or a frame's block-sparse
//! one on the node graph (`graph.rs` says where a frame's elements go in it).
use crate::solver::sparse_blocks::SparseBlocks;
use crate::solver::{BlockTridiagonal, SingularMatrix, SystemMatrix};

/// A structure's system matrix.
#[derive(Clone, Debug)]
pub enum StructureMatrix {
    /// One member: its chain's block-tridiagonal matrix.
    Chain(BlockTridiagonal),
    /// A frame: block-sparse on the node graph, ties applied by its solves.
    Graph(SparseBlocks),
}

impl StructureMatrix {
    /// Removes a held direction `n` of `node`'s translation.
    pub(super) fn constrain_direction(&mut self, node: usize, n: [f64; 2]) {
        match self {
            StructureMatrix::Chain(m) => m.constrain_direction(node, n),
            StructureMatrix::Graph(m) => m.constrain_direction(node, n),
        }
    }
}

impl SystemMatrix for StructureMatrix {
    fn set_zero(&mut self) {
        match self {
            StructureMatrix::Chain(m) => m.set_zero(),
            StructureMatrix::Graph(m) => m.set_zero(),
        }
    }

    fn copy_from(&mut self, other: &Self) {
        match (self, other) {
            (StructureMatrix::Chain(m), StructureMatrix::Chain(o)) => m.copy_from(o),
            (StructureMatrix::Graph(m), StructureMatrix::Graph(o)) => m.copy_from(o),
            _ => panic!("copy between matrices of different structures"),
        }
    }

    fn add_diagonal(&mut self, dof: usize, value: f64) {
        match self {
            StructureMatrix::Chain(m) => m.add_diagonal(dof, value),
            StructureMatrix::Graph(m) => m.add_diagonal(dof, value),
        }
    }

    fn constrain(&mut self, dofs: &[usize]) {
        match self {
            StructureMatrix::Chain(m) => m.constrain(dofs),
            StructureMatrix::Graph(m) => m.constrain(dofs),
        }
    }

    fn factor(&mut self) -> Result<(), SingularMatrix> {
        match self {
            StructureMatrix::Chain(m) => m.factor(),
            StructureMatrix::Graph(m) => m.factor(),
        }
    }

    fn factor_symmetric(&mut self) -> Result<(), SingularMatrix> {
        match self {
            StructureMatrix::Chain(m) => m.factor_symmetric(),
            StructureMatrix::Graph(m) => m.factor_symmetric(),
        }
    }

    fn factor_with_inertia(&mut self) -> Result<(), SingularMatrix> {
        match self {
            StructureMatrix::Chain(m) => m.factor_with_inertia(),
            StructureMatrix::Graph(m) => m.factor_with_inertia(),
        }
    }

    fn negative_eigenvalues(&self) -> usize {
        match self {
            StructureMatrix::Chain(m) => m.negative_eigenvalues(),
            StructureMatrix::Graph(m) => m.negative_eigenvalues(),
        }
    }

    fn solve_in_place(&self, x: &mut [f64]) {
        match self {
            StructureMatrix::Chain(m) => m.solve_in_place(x),
            StructureMatrix::Graph(m) => m.solve_in_place(x),
        }
    }

    fn solve_pair(&self, a: &mut [f64], b: &mut [f64]) {
        match self {
            StructureMatrix::Chain(m) => m.solve_pair(a, b),
            StructureMatrix::Graph(m) => m.solve_pair(a, b),
        }
    }

    fn mul(&self, x: &[f64], out: &mut [f64]) {
        match self {
            StructureMatrix::Chain(m) => m.mul(x, out),
            StructureMatrix::Graph(m) => m.mul(x, out),
        }
    }

    fn row_entries(&self, dof: usize) -> Vec<(usize, f64)> {
        match self {
            StructureMatrix::Chain(m) => SystemMatrix::row_entries(m, dof),
            StructureMatrix::Graph(m) => m.row_entries(dof),
        }
    }
}
