//! How a frame assembles into its block-sparse matrix: the node graph (each member a chain of
//! nodes, its end elements coupled to its joints through the ties, bars and links between
//! their nodes), and where each element's entries go, looked up once: a member's interior
//! elements by their four block slots (the hot path, as a lone rod's), its end elements and the
//! axial elements entry by entry through precomputed tables.
use super::Structure;
use crate::solver::sparse_blocks::{BlockPattern, SparseBlocks};
use crate::solver::{PairBlocks, PairSink};
use nalgebra::{Matrix2, Matrix3, Vector3};
use std::sync::Arc;

/// Where an entry goes: the slot of its block and its row and column there.
#[derive(Clone, Copy, Debug, Default)]
struct Entry {
    slot: usize,
    r: u8,
    c: u8,
}

impl Entry {
    /// The entry `(row, col)` (dofs) of the matrix of `pattern`.
    fn of(pattern: &BlockPattern, row: usize, col: usize) -> Entry {
        Entry {
            slot: (pattern.slot(row / 3, col / 3)).expect("an entry of the pattern"),
            r: (row % 3) as u8,
            c: (col % 3) as u8,
        }
    }

    fn add(&self, m: &mut SparseBlocks, value: f64) {
        m.add_slot_entry(self.slot, self.r as usize, self.c as usize, value);
    }
}

/// Where a member's elements assemble in a frame's matrix.
#[derive(Clone, Debug)]
pub(super) struct MemberRoute {
    offset: usize,
    dofs: usize,
    /// The global dof of each local dof of the first and of the last node (masters).
    start: [usize; 3],
    end: [usize; 3],
    /// Slots `(aa, ab, ba, bb)` of each element whose dofs are all the member's own (unused
    /// for the routed ones).
    pairs: Vec<[usize; 4]>,
    /// The elements at the member's ends, whose rows and columns go to their joints' one by
    /// one: where each of their 36 entries goes.
    routed: Vec<(usize, [Entry; 36])>,
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

    /// Whether element `e` must go to its masters entry by entry: it touches an end node
    /// whose three dofs are not one node's (a hinged end: its translations are the joint's,
    /// its rotation its own). A rigid end's node is wholly its joint's: the element then
    /// assembles by blocks at the joint's node.
    fn is_routed(&self, e: usize) -> bool {
        let split = |dofs: &[usize; 3]| dofs[1] != dofs[0] + 1 || dofs[2] != dofs[0] + 2;
        (e == 0 && split(&self.start)) || (3 * (e + 2) >= self.dofs && split(&self.end))
    }

    /// The node of the member's local node `i` in the matrix (a rigid end's: its joint's).
    fn node(&self, i: usize) -> usize {
        self.global(3 * i) / 3
    }
}

/// A frame's pattern, the routes of its members and the tables of its axial elements.
#[derive(Clone, Debug)]
pub(super) struct Graph {
    pattern: Arc<BlockPattern>,
    routes: Vec<MemberRoute>,
    /// Where each axial element's 4x4 entries (both ends' translations) go.
    axial: Vec<[Entry; 16]>,
    ties: Vec<(usize, usize)>,
}

impl Graph {
    /// The node graph of a frame whose members, ties and axial elements are set.
    pub(super) fn new(s: &Structure) -> Graph {
        let mut edges = Vec::new();
        let mut routes: Vec<MemberRoute> = Vec::new();
        for m in &s.members {
            let dofs = m.rod.dofs();
            let route = MemberRoute {
                offset: m.offset,
                dofs,
                start: [0, 1, 2].map(|k| s.master(m.offset + k)),
                end: [0, 1, 2].map(|k| s.master(m.offset + dofs - 3 + k)),
                pairs: Vec::new(),
                routed: Vec::new(),
            };
            for e in 0..m.rod.elements.len() {
                let nodes: Vec<usize> = (0..6).map(|d| route.global(3 * e + d) / 3).collect();
                for &a in &nodes {
                    edges.extend(nodes.iter().filter(|&&b| b != a).map(|&b| (a, b)));
                }
            }
            routes.push(route);
        }
        for a in &s.axial {
            edges.push((a.nodes[0], a.nodes[1]));
        }
        let nodes = s.dofs / 3;
        let pattern = Arc::new(match twisted(nodes, &edges) {
            Some(order) => BlockPattern::with_order(nodes, &edges, &order),
            None => BlockPattern::new(nodes, &edges),
        });
        for (route, m) in routes.iter_mut().zip(&s.members) {
            let elements = m.rod.elements.len();
            route.routed = (0..elements)
                .filter(|&e| route.is_routed(e))
                .map(|e| {
                    let mut table = [Entry::default(); 36];
                    for (k, entry) in table.iter_mut().enumerate() {
                        let (r, c) = (route.global(3 * e + k / 6), route.global(3 * e + k % 6));
                        *entry = Entry::of(&pattern, r, c);
                    }
                    (e, table)
                })
                .collect();
            route.pairs = (0..elements)
                .map(|e| match route.is_routed(e) {
                    true => [usize::MAX; 4],
                    false => {
                        let (a, b) = (route.node(e), route.node(e + 1));
                        (pattern.pair_slots(a, b)).expect("an element's blocks")
                    }
                })
                .collect();
        }
        let axial = (s.axial.iter())
            .map(|a| {
                let [p, q] = a.nodes;
                let dofs = [3 * p, 3 * p + 1, 3 * q, 3 * q + 1];
                let mut table = [Entry::default(); 16];
                for (k, entry) in table.iter_mut().enumerate() {
                    *entry = Entry::of(&pattern, dofs[k / 4], dofs[k % 4]);
                }
                table
            })
            .collect();
        Graph {
            pattern,
            routes,
            axial,
            ties: s.ties.clone(),
        }
    }

    pub(super) fn new_matrix(&self) -> SparseBlocks {
        SparseBlocks::new(self.pattern.clone()).with_ties(self.ties.clone())
    }

    /// Member `m`'s chain assembling into `matrix`.
    pub(super) fn member<'a>(&'a self, matrix: &'a mut SparseBlocks, m: usize) -> MemberSink<'a> {
        MemberSink {
            matrix,
            route: &self.routes[m],
        }
    }

    /// Adds `scale * [[K, -K], [-K, K]]` of a 2x2 block `K` on axial element `a`'s
    /// translations.
    pub(super) fn add_axial_block(
        &self,
        m: &mut SparseBlocks,
        a: usize,
        k: &Matrix2<f64>,
        scale: f64,
    ) {
        for (i, entry) in self.axial[a].iter().enumerate() {
            let (r, c) = (i / 4, i % 4);
            let sign = if (r < 2) == (c < 2) { 1.0 } else { -1.0 };
            let value = sign * k[(r % 2, c % 2)];
            if value != 0.0 {
                entry.add(m, scale * value);
            }
        }
    }

    /// Adds `scale * c [[2, 1], [1, 2]]` (lumped: `3 c` on the diagonal) on both translations
    /// of axial element `a` (a bar's consistent mass or damping).
    pub(super) fn add_axial_pattern(
        &self,
        m: &mut SparseBlocks,
        a: usize,
        c: f64,
        lumped: bool,
        scale: f64,
    ) {
        if c == 0.0 {
            return;
        }
        let (own, shared) = if lumped { (3.0, 0.0) } else { (2.0, 1.0) };
        for (i, entry) in self.axial[a].iter().enumerate() {
            let (r, col) = (i / 4, i % 4);
            let value = match (r == col, r % 2 == col % 2) {
                (true, _) => own,
                (false, true) => shared,
                (false, false) => 0.0,
            };
            if value != 0.0 {
                entry.add(m, scale * value * c);
            }
        }
    }
}

/// A twisted elimination order where the coupled nodes form one path or one loop (a portal
/// frame, a closed frame; the isolated nodes, fully tied member ends, first): from both ends
/// of the path to its middle, as a lone rod's block-tridiagonal elimination runs, so the
/// processor overlaps the two sweeps (a loop: the path left by one of its nodes, that node
/// last). `None` for any other graph: the minimum-degree order then.
fn twisted(nodes: usize, edges: &[(usize, usize)]) -> Option<Vec<usize>> {
    let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); nodes];
    for &(a, b) in edges {
        adjacent[a].push(b);
        adjacent[b].push(a);
    }
    for list in &mut adjacent {
        list.sort_unstable();
        list.dedup();
    }
    if adjacent.iter().any(|a| a.len() > 2) {
        return None;
    }
    let live: Vec<usize> = (0..nodes).filter(|&i| !adjacent[i].is_empty()).collect();
    let &first = live.first()?;
    // A path starts at a node with one neighbour; a loop anywhere, that node left for last.
    let (start, last) = match live.iter().find(|&&i| adjacent[i].len() == 1) {
        Some(&end) => (end, None),
        None => (adjacent[first][0], Some(first)),
    };
    let mut visited = vec![false; nodes];
    if let Some(c) = last {
        visited[c] = true;
    }
    let mut walk = Vec::with_capacity(live.len());
    let mut at = Some(start);
    while let Some(i) = at {
        visited[i] = true;
        walk.push(i);
        at = adjacent[i].iter().copied().find(|&n| !visited[n]);
    }
    if walk.len() + usize::from(last.is_some()) != live.len() {
        return None; // more than one path or loop
    }
    let mut order: Vec<usize> = (0..nodes).filter(|&i| adjacent[i].is_empty()).collect();
    order.extend(
        BlockPattern::twisted_order(walk.len())
            .into_iter()
            .map(|k| walk[k]),
    );
    order.extend(last);
    Some(order)
}

/// A member's chain assembling into a frame's matrix.
pub(super) struct MemberSink<'a> {
    matrix: &'a mut SparseBlocks,
    route: &'a MemberRoute,
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
        let (_, table) = (self.route.routed.iter())
            .find(|(element, _)| *element == e)
            .expect("a routed element's table");
        for (k, entry) in table.iter().enumerate() {
            let value = block(k / 6, k % 6);
            if value != 0.0 {
                entry.add(self.matrix, scale * value);
            }
        }
    }
}

impl PairSink for MemberSink<'_> {
    fn add_pair<P: PairBlocks + ?Sized>(&mut self, e: usize, pair: &P, scale: f64) {
        let blocks = pair.blocks();
        if self.route.is_routed(e) {
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
