//! Sparse matrices with 3x3 blocks on a general node graph (a frame: member chains joined at
//! joint nodes, sometimes closed into cycles) and their block LU factorization: the same block
//! arithmetic as [`BlockTridiagonal`](super::BlockTridiagonal), in an elimination order chosen
//! for the graph.
//!
//! [`BlockPattern`] is set up once per graph: the elimination order (minimum degree, `ordering`),
//! the filled pattern and the factorization as flat lists of slots. [`SparseBlocks`] holds the
//! numbers of one matrix on a shared pattern: assembly and constraints (`assemble`), the
//! factorization (`factor`) and the solves (`solve`), none of which allocates.
//!
//! Storage: one block per slot, in elimination order. Step `k` eliminates node `p =
//! order[k]`; its blocks are contiguous from `steps[k].slot`: the pivot `(p, p)`, then for each
//! neighbour `q_a` of `p` eliminated later (in the filled graph, in elimination order) `(p,
//! q_a)` at `slot + 1 + 2 a` and `(q_a, p)` at `slot + 2 + 2 a`. Each block belongs to the
//! step of whichever of its nodes is eliminated first, so a step reads its own blocks and
//! updates only blocks further on: the factorization walks memory forward (on a path, block
//! after block).
//!
//! Cost: the block operations of the block-tridiagonal elimination, per pair of a step's later
//! neighbours. Each step waits for the steps before it that update its pivot: a path in the
//! minimum-degree order (from one end) is a single such chain, and its factorization and solve
//! take about 1.5 times those of [`BlockTridiagonal`](super::BlockTridiagonal), whose twisted
//! order runs two chains side by side; [`BlockPattern::with_order`] with
//! [`BlockPattern::twisted_order`] is that elimination, to the bit.
mod assemble;
mod factor;
mod ordering;
mod solve;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_constraints;
#[cfg(test)]
mod tests_inertia;

use nalgebra::Matrix3;
use std::sync::Arc;

/// The sparsity pattern and its elimination: `nodes` block rows of 3 dofs (global dof `3 i +
/// k`), coupled symmetrically by edges.
#[derive(Clone, Debug)]
pub struct BlockPattern {
    nodes: usize,
    /// `order[k]`: the node eliminated at step `k`.
    order: Vec<usize>,
    /// `position[node]`: the step that eliminates `node`.
    position: Vec<usize>,
    /// One per step, and a sentinel that closes the ranges of the last.
    steps: Vec<Step>,
    /// The later neighbours `q_a` of each step, in elimination order (ranges `steps[k].later..
    /// steps[k + 1].later`).
    later: Vec<usize>,
    /// The Schur complement targets of each step: the slot of `(q_a, q_b)` at `a m + b` of its
    /// range `steps[k].targets..steps[k + 1].targets` (`m` later neighbours).
    targets: Vec<usize>,
    /// The off-diagonal blocks of each node's block row and column (ranges `coupling_start[i]..
    /// coupling_start[i + 1]`): for constraints, products and rows, not for the factorization.
    couplings: Vec<Coupling>,
    coupling_start: Vec<usize>,
    /// Distinct edges given, and edges added by the elimination.
    edges: usize,
    fill_edges: usize,
}

/// One elimination step: its node, its first slot and where its ranges in
/// [`BlockPattern::later`] and [`BlockPattern::targets`] start.
#[derive(Clone, Copy, Debug)]
struct Step {
    node: usize,
    slot: usize,
    later: usize,
    targets: usize,
}

/// Node `i`'s coupling to `node`: the slots of `(i, node)` (`row`) and `(node, i)` (`column`).
#[derive(Clone, Copy, Debug)]
struct Coupling {
    node: usize,
    row: usize,
    column: usize,
}

impl BlockPattern {
    /// The pattern of `nodes` block rows coupled by `edges` (pairs `(i, j)`, `i != j`;
    /// duplicates and both directions allowed, ignored), its elimination order and symbolic
    /// factorization. Setup time: allocates, O(nodes log nodes) on chains and trees.
    pub fn new(nodes: usize, edges: &[(usize, usize)]) -> BlockPattern {
        ordering::symbolic(nodes, edges, None)
    }

    /// [`new`](Self::new) with the elimination order given (`order[k]`: the node eliminated at
    /// step `k`, a permutation), its fill formed as it comes. For a single chain the twisted
    /// order `0, n-1, 1, n-2, ...` (see [`twisted_order`](Self::twisted_order)) is the
    /// elimination of [`BlockTridiagonal`](super::BlockTridiagonal): two independent sweeps
    /// side by side, which the processor overlaps.
    pub fn with_order(nodes: usize, edges: &[(usize, usize)], order: &[usize]) -> BlockPattern {
        ordering::symbolic(nodes, edges, Some(order))
    }

    /// The twisted order of a chain `0 - 1 - ... - (nodes - 1)` from both ends to the middle,
    /// `0, n-1, 1, n-2, ..., n / 2`, as [`BlockTridiagonal`](super::BlockTridiagonal) eliminates.
    pub fn twisted_order(nodes: usize) -> Vec<usize> {
        let middle = nodes / 2;
        let ends =
            (0..middle).flat_map(|k| [k, nodes - 1 - k].into_iter().filter(move |&j| j != middle));
        ends.chain([middle]).collect()
    }

    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// Storage slot of block `(i, j)` (`i == j`: the diagonal block): present for the diagonal,
    /// every edge in both directions and the fill; `None` otherwise. A binary search among the
    /// later neighbours of the first-eliminated node: look slots up at setup, not per step.
    pub fn slot(&self, i: usize, j: usize) -> Option<usize> {
        if i >= self.nodes || j >= self.nodes {
            return None;
        }
        let (pi, pj) = (self.position[i], self.position[j]);
        if i == j {
            return Some(self.steps[pi].slot);
        }
        let (k, other) = if pi < pj { (pi, pj) } else { (pj, pi) };
        let a = (self.later_of(k))
            .binary_search_by_key(&other, |&q| self.position[q])
            .ok()?;
        Some(self.steps[k].slot + 1 + 2 * a + usize::from(pi > pj))
    }

    /// The slots `[ii, ij, ji, jj]` of the coupling of nodes `i` and `j`, as
    /// [`SparseBlocks::add_pair_slots`] takes them; `None` if they are not coupled.
    pub fn pair_slots(&self, i: usize, j: usize) -> Option<[usize; 4]> {
        Some([
            self.slot(i, i)?,
            self.slot(i, j)?,
            self.slot(j, i)?,
            self.slot(j, j)?,
        ])
    }

    /// The elimination order: `order()[k]` is the node eliminated at step `k`.
    pub fn order(&self) -> &[usize] {
        &self.order
    }

    /// The number of stored blocks: `nodes + 2 (edges + fill_edges)`.
    pub fn blocks(&self) -> usize {
        self.steps[self.nodes].slot
    }

    /// Distinct edges given.
    pub fn edges(&self) -> usize {
        self.edges
    }

    /// Edges the elimination adds (the fill): 0 on paths and trees.
    pub fn fill_edges(&self) -> usize {
        self.fill_edges
    }

    /// The later neighbours of step `k`, in elimination order.
    fn later_of(&self, k: usize) -> &[usize] {
        &self.later[self.steps[k].later..self.steps[k + 1].later]
    }

    /// Node `i`'s off-diagonal blocks (filled pattern).
    fn couplings_of(&self, i: usize) -> &[Coupling] {
        &self.couplings[self.coupling_start[i]..self.coupling_start[i + 1]]
    }
}

/// A matrix with the sparsity of a [`BlockPattern`], and after factorization its block LU
/// factors (see `factor`), with optional ties of dofs applied after each solve.
#[derive(Clone, Debug)]
pub struct SparseBlocks {
    pattern: Arc<BlockPattern>,
    /// The blocks by slot.
    blocks: Vec<Matrix3<f64>>,
    /// `(slave, master)` dofs, each master resolved to a dof that is no slave.
    ties: Vec<(usize, usize)>,
    factored: bool,
    /// Number of pivot blocks with negative determinant (after a factorization).
    negative_pivots: usize,
    /// Number of negative eigenvalues of the pivots, when counted
    /// ([`SparseBlocks::factor_with_inertia`]).
    inertia: Option<usize>,
}

impl SparseBlocks {
    /// A zero matrix on `pattern` (allocates its blocks: setup time).
    pub fn new(pattern: Arc<BlockPattern>) -> SparseBlocks {
        SparseBlocks {
            blocks: vec![Matrix3::zeros(); pattern.blocks()],
            pattern,
            ties: Vec::new(),
            factored: false,
            negative_pivots: 0,
            inertia: None,
        }
    }

    /// Ties `(slave_dof, master_dof)`: after every solve `x[slave] = x[master]` (the slave dofs
    /// are constrained by the caller: identity rows, zero right-hand side, and their couplings
    /// assembled into the master's rows). A master may itself be a slave: chains are resolved
    /// here to their last master (a cycle panics), so the order of the ties does not matter.
    pub fn with_ties(mut self, ties: Vec<(usize, usize)>) -> SparseBlocks {
        let dofs = 3 * self.pattern.nodes;
        let mut master_of = std::collections::HashMap::with_capacity(ties.len());
        for &(slave, master) in &ties {
            assert!(
                slave < dofs && master < dofs,
                "tie ({slave}, {master}) of {dofs} dofs"
            );
            let previous = master_of.insert(slave, master);
            assert!(
                previous.is_none_or(|m| m == master),
                "dof {slave} tied to two masters"
            );
        }
        let resolve = |slave: usize| {
            let mut root = slave;
            for _ in 0..=master_of.len() {
                match master_of.get(&root) {
                    Some(&next) => root = next,
                    None => return root,
                }
            }
            panic!("dof {slave} is tied in a cycle")
        };
        self.ties = ties
            .iter()
            .map(|&(slave, _)| (slave, resolve(slave)))
            .collect();
        self
    }

    pub fn pattern(&self) -> &BlockPattern {
        &self.pattern
    }

    pub fn set_zero(&mut self) {
        self.blocks.iter_mut().for_each(|m| m.fill(0.0));
        self.factored = false;
    }

    /// Overwrites `self` with `other` (the same pattern), unfactored; the ties stay `self`'s.
    pub fn copy_from(&mut self, other: &SparseBlocks) {
        debug_assert!(!other.factored);
        debug_assert!(
            Arc::ptr_eq(&self.pattern, &other.pattern) || self.blocks.len() == other.blocks.len()
        );
        self.blocks.copy_from_slice(&other.blocks);
        self.factored = false;
    }
}
