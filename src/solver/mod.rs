//! Linear solvers: the block-tridiagonal system of a rod (3x3 blocks per node), the sparse
//! block system of a frame (3x3 blocks on a node graph), what the integrators ask of any system
//! matrix, and the reductions over dof vectors that the time steps use.
pub mod block_tridiagonal;
pub mod sparse_blocks;
pub mod system;
pub mod vector;

pub use block_tridiagonal::{BlockTridiagonal, PairBlocks, SingularMatrix};
pub use sparse_blocks::{BlockPattern, SparseBlocks};
pub use system::{PairSink, SystemMatrix};
