//! The system matrix of a structure: a rod's block-tridiagonal matrix, or a frame's block-sparse
//! one on the node graph, and how a member's chain assembles into it (its interior elements by
//! precomputed block slots, its end elements through the ties to their joints).
use super::Structure;
use crate::model::rod::{U1, U2};
use crate::solver::sparse_blocks::{BlockPattern, SparseBlocks};
use crate::solver::{BlockTridiagonal, PairBlocks, PairSink, SingularMatrix, SystemMatrix};
use nalgebra::{Matrix2, Matrix3, Vector3};
use std::sync::Arc;

/// A structure's system matrix.
#[derive(Clone, Debug)]
pub enum StructureMatrix {
    /// One member: its chain's block-tridiagonal matrix.
    Chain(BlockTridiagonal),
    /// A frame: block-sparse on the node graph, ties applied by its solves.
    Graph(SparseBlocks),
}

/// Where a member's elements assemble in a frame's matrix.
#[derive(Clone, Debug)]
pub(super) struct MemberRoute {
    offset: usize,
    dofs: usize,
    /// The global dof of each local dof of the first and of the last node (masters).
    start: [usize; 3],
    end: [usize; 3],
    /// Slots `(aa, ab, ba, bb)` of each element whose dofs are all the member's own.
    pairs: Vec<[usize; 4]>,
}

impl MemberRoute {
    /// The global dof (a master) of the member's local dof `d`.
    fn global(&self, d: usize) -> usize {
        if d < 3 {
            self.start[d]
        } else if d >= self.dofs - 3 {
            self.end[d + 3 - self.dofs]
        } else {
            self.offset + d
        }
    }

    /// Whether element `e` touches an end node (its rows go to masters one by one).
    fn routed(&self, e: usize) -> bool {
        e == 0 || 3 * (e + 2) >= self.dofs
    }
}

/// A frame's pattern and the routes of its members.
#[derive(Clone, Debug)]
pub(super) struct Graph {
    pattern: Arc<BlockPattern>,
    routes: Vec<MemberRoute>,
    ties: Vec<(usize, usize)>,
}

impl Graph {
    /// The node graph of a frame whose members, ties and axial elements are set.
    pub(super) fn new(s: &Structure) -> Graph {
        let master = |d: usize| s.master(d);
        let mut edges = Vec::new();
        let mut routes = Vec::new();
        for m in &s.members {
            let dofs = m.rod.dofs();
            let last = dofs - 3;
            let route = MemberRoute {
                offset: m.offset,
                dofs,
                start: [0, 1, 2].map(|k| master(m.offset + k)),
                end: [0, 1, 2].map(|k| master(m.offset + last + k)),
                pairs: Vec::new(),
            };
            for e in 0..m.rod.elements.len() {
                let nodes: Vec<usize> = (0..6).map(|d| route.global(3 * e + d) / 3).collect();
                for &a in &nodes {
                    for &b in &nodes {
                        if a != b {
                            edges.push((a, b));
                        }
                    }
                }
            }
            routes.push(route);
        }
        for a in &s.axial {
            edges.push((a.nodes[0], a.nodes[1]));
        }
        let pattern = Arc::new(BlockPattern::new(s.dofs / 3, &edges));
        for (route, m) in routes.iter_mut().zip(&s.members) {
            let route: &mut MemberRoute = route;
            let first = m.offset / 3;
            let elements = m.rod.elements.len();
            route.pairs = (0..elements)
                .map(|e| {
                    if route.routed(e) {
                        return [usize::MAX; 4]; // assembled entry by entry
                    }
                    let (a, b) = (first + e, first + e + 1);
                    let slot = |i, j| pattern.slot(i, j).expect("an element's blocks");
                    [slot(a, a), slot(a, b), slot(b, a), slot(b, b)]
                })
                .collect();
        }
        Graph {
            pattern,
            routes,
            ties: s.ties.clone(),
        }
    }

    pub(super) fn new_matrix(&self) -> SparseBlocks {
        SparseBlocks::new(self.pattern.clone()).with_ties(self.ties.clone())
    }

    pub(super) fn route(&self, m: usize) -> &MemberRoute {
        &self.routes[m]
    }
}

/// Member `route`'s chain assembling into a frame's matrix.
pub(super) struct MemberSink<'a> {
    pub(super) matrix: &'a mut SparseBlocks,
    pub(super) route: &'a MemberRoute,
}

impl MemberSink<'_> {
    /// Adds the 6x6 `[[aa, ab], [ab^T, bb]]` of element `e` entry by entry at the masters.
    fn scatter(
        &mut self,
        e: usize,
        (aa, ab, bb): (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>),
        scale: f64,
    ) {
        let block = |r: usize, c: usize| match (r / 3, c / 3) {
            (0, 0) => aa[(r, c)],
            (0, 1) => ab[(r, c - 3)],
            (1, 0) => ab[(c, r - 3)],
            _ => bb[(r - 3, c - 3)],
        };
        for r in 0..6 {
            let row = self.route.global(3 * e + r);
            for c in 0..6 {
                let value = block(r, c);
                if value != 0.0 {
                    let col = self.route.global(3 * e + c);
                    self.matrix.add_entry(row, col, scale * value);
                }
            }
        }
    }
}

impl PairSink for MemberSink<'_> {
    fn add_pair<P: PairBlocks + ?Sized>(&mut self, e: usize, pair: &P, scale: f64) {
        let blocks = pair.blocks();
        if self.route.routed(e) {
            self.scatter(e, blocks, scale);
        } else {
            let (aa, ab, bb) = blocks;
            self.matrix
                .add_pair_slots(self.route.pairs[e], &aa, &ab, &bb, scale);
        }
    }

    fn add_pair_pattern(&mut self, e: usize, coeffs: &Vector3<f64>, scale: f64, lumped: bool) {
        let d = Matrix3::from_diagonal(coeffs);
        let (own, shared) = if lumped { (3.0, 0.0) } else { (2.0, 1.0) };
        self.add_pair(e, &[own * d, shared * d, own * d], scale);
    }

    fn add_diagonal(&mut self, dof: usize, value: f64) {
        self.matrix.add_diagonal(self.route.global(dof), value);
    }
}

/// Adds `scale * [[K, -K], [-K, K]]` of a 2x2 block `K` on the translations of `nodes`.
pub(super) fn add_axial_block(
    matrix: &mut SparseBlocks,
    nodes: [usize; 2],
    k: &Matrix2<f64>,
    scale: f64,
) {
    let [a, b] = nodes;
    for (i, si) in [(a, 1.0), (b, -1.0)] {
        for (j, sj) in [(a, 1.0), (b, -1.0)] {
            for r in 0..2 {
                for c in 0..2 {
                    let value = si * sj * k[(r, c)];
                    if value != 0.0 {
                        matrix.add_entry(3 * i + r, 3 * j + c, scale * value);
                    }
                }
            }
        }
    }
}

/// Adds `scale * c [[2, 1], [1, 2]]` (lumped: `3 c` on the diagonal) on both translations of
/// `nodes` (a bar's consistent mass or damping).
pub(super) fn add_axial_pattern(
    matrix: &mut SparseBlocks,
    nodes: [usize; 2],
    c: f64,
    lumped: bool,
    scale: f64,
) {
    if c == 0.0 {
        return;
    }
    let [a, b] = nodes;
    let (own, shared) = if lumped { (3.0, 0.0) } else { (2.0, 1.0) };
    for k in [U1, U2] {
        matrix.add_diagonal(3 * a + k, scale * own * c);
        matrix.add_diagonal(3 * b + k, scale * own * c);
        if shared != 0.0 {
            matrix.add_entry(3 * a + k, 3 * b + k, scale * shared * c);
            matrix.add_entry(3 * b + k, 3 * a + k, scale * shared * c);
        }
    }
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
