//! Linear solvers: the block-tridiagonal system of a rod (3x3 blocks per node).
pub mod block_tridiagonal;

pub use block_tridiagonal::{BlockTridiagonal, SingularMatrix};
