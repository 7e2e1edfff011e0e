//! The pattern's order and fill, and the solves against dense LU (nalgebra) and against
//! [`BlockTridiagonal`]; the constraints and ties are in `tests_constraints`, the pivots
//! (singular, inertia) in `tests_inertia`.
//!
//! Tolerances: the test matrices are diagonally dominant by construction ([`case`]) with
//! `cond_inf(A) <= 3`, and both the block LU (no pivoting, stable for diagonally dominant
//! matrices) and the dense LU are backward stable, so the two solutions differ by about
//! `cond * dofs * eps` relative (at most `3 * 45 * 1.1e-16 = 1.5e-14` here); [`SOLVE_TOLERANCE`]
//! leaves a factor 60 of margin.
use super::*;
use crate::solver::{BlockTridiagonal, SingularMatrix};
use nalgebra::{DMatrix, DVector};

/// Relative to the largest entry of the solution: see the module documentation.
pub(super) const SOLVE_TOLERANCE: f64 = 1e-12;

/// A deterministic pseudo-random sequence in `[-1, 1)` (xorshift64*).
pub(super) struct Random(pub(super) u64);

impl Random {
    pub(super) fn value(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        bits as f64 / (1u64 << 52) as f64 - 1.0
    }

    pub(super) fn block(&mut self) -> Matrix3<f64> {
        Matrix3::from_fn(|_, _| self.value())
    }

    pub(super) fn symmetric_block(&mut self) -> Matrix3<f64> {
        let b = self.block();
        0.5 * (b + b.transpose())
    }
}

/// A matrix on a graph and its dense copy, assembled side by side.
#[derive(Clone)]
pub(super) struct Case {
    pub(super) a: SparseBlocks,
    pub(super) dense: DMatrix<f64>,
}

impl Case {
    pub(super) fn add_block(&mut self, i: usize, j: usize, block: &Matrix3<f64>) {
        self.a
            .add_block(self.a.pattern().slot(i, j).unwrap(), block, 1.0);
        let mut view = self.dense.view_mut((3 * i, 3 * j), (3, 3));
        view += block;
    }

    pub(super) fn add_diagonal(&mut self, dof: usize, value: f64) {
        self.a.add_diagonal(dof, value);
        self.dense[(dof, dof)] += value;
    }

    /// The sparse solution of `A x = b` (factored by `factor`) and the dense LU's.
    pub(super) fn solve(
        &mut self,
        b: &[f64],
        factor: fn(&mut SparseBlocks) -> Result<(), SingularMatrix>,
    ) -> (Vec<f64>, Vec<f64>) {
        let want = self
            .dense
            .clone()
            .lu()
            .solve(&DVector::from_column_slice(b));
        factor(&mut self.a).unwrap();
        let mut x = b.to_vec();
        self.a.solve_in_place(&mut x);
        (
            x,
            want.expect("the dense matrix is regular")
                .as_slice()
                .to_vec(),
        )
    }
}

/// A random matrix on `edges` (symmetric or not): element pairs through `add_pair_slots`, a
/// random diagonal block per node and, unless symmetric, a random block on each `(j, i)`; then
/// the diagonal shifted by twice the largest absolute row sum `R` (the diagonal entry
/// included), so every row is dominant by `R` or more and `||A||_inf <= 3 R`: `cond_inf <= 3`.
pub(super) fn case(nodes: usize, edges: &[(usize, usize)], symmetric: bool, seed: u64) -> Case {
    let pattern = Arc::new(BlockPattern::new(nodes, edges));
    let mut case = Case {
        a: SparseBlocks::new(pattern.clone()),
        dense: DMatrix::zeros(3 * nodes, 3 * nodes),
    };
    let mut random = Random(seed);
    for i in 0..nodes {
        let d = random.symmetric_block();
        case.add_block(i, i, &d);
    }
    for &(i, j) in edges {
        let (aa, ab, bb) = (
            random.symmetric_block(),
            random.block(),
            random.symmetric_block(),
        );
        let slots = pattern.pair_slots(i, j).unwrap();
        case.a.add_pair_slots(slots, &aa, &ab, &bb, 0.5);
        for (r, c, block) in [(i, i, aa), (i, j, ab), (j, i, ab.transpose()), (j, j, bb)] {
            let mut view = case.dense.view_mut((3 * r, 3 * c), (3, 3));
            view += 0.5 * block;
        }
        if !symmetric {
            case.add_block(j, i, &random.block());
        }
    }
    let rows = case.dense.row_iter().map(|r| r.abs().sum());
    let shift = 2.0 * rows.fold(0.0, f64::max);
    for dof in 0..3 * nodes {
        case.add_diagonal(dof, shift);
    }
    case
}

pub(super) fn path(n: usize) -> Vec<(usize, usize)> {
    (1..n).map(|i| (i - 1, i)).collect()
}

pub(super) fn cycle(n: usize) -> Vec<(usize, usize)> {
    let mut edges = path(n);
    edges.push((n - 1, 0));
    edges
}

/// A test graph: `(name, nodes, edges)`.
pub(super) type Graph = (&'static str, usize, Vec<(usize, usize)>);

/// The test graphs.
pub(super) fn graphs() -> Vec<Graph> {
    // 11 nodes in the order 3, 10, 6, 2, ... (7 i + 3 mod 11).
    let scrambled = (1..11)
        .map(|i| ((7 * i + 3) % 11, (7 * i - 4) % 11))
        .collect();
    let star = (1..7).map(|i| (0, i)).collect();
    let tree = (1..15).map(|i| ((i - 1) / 2, i)).collect();
    // Two chains of 6 (0..6, 6..12) with rungs, one given twice and reversed.
    let mut ladder: Vec<_> = path(6)
        .into_iter()
        .chain((7..12).map(|i| (i - 1, i)))
        .collect();
    ladder.extend((0..6).map(|i| (i, i + 6)));
    ladder.extend([(8, 2), (2, 8)]);
    let complete = (0..5)
        .flat_map(|i| (i + 1..5).map(move |j| (i, j)))
        .collect();
    vec![
        ("path", 9, path(9)),
        ("scrambled path", 11, scrambled),
        ("star", 7, star),
        ("tree", 15, tree),
        ("cycle", 10, cycle(10)),
        ("ladder", 12, ladder),
        ("complete", 5, complete),
        ("single node", 1, vec![]),
        ("two nodes", 2, path(2)),
    ]
}

pub(super) fn rhs(dofs: usize) -> Vec<f64> {
    (0..dofs).map(|j| (0.7 * j as f64).cos()).collect()
}

pub(super) fn assert_close(got: &[f64], want: &[f64], tolerance: f64, what: &str) {
    let scale = want.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
    for (dof, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= tolerance * scale,
            "{what}, dof {dof}: {g} vs {w}"
        );
    }
}

/// A path in natural order is eliminated from node 0 on, each step coupled to the next node
/// only: no fill, the blocks of a block-tridiagonal matrix, its elimination.
#[test]
fn path_is_eliminated_from_an_end_without_fill() {
    let n = 50;
    let pattern = BlockPattern::new(n, &path(n));
    assert_eq!(pattern.order(), (0..n).collect::<Vec<_>>());
    assert_eq!(
        (pattern.fill_edges(), pattern.blocks()),
        (0, n + 2 * (n - 1))
    );
    for k in 0..n - 1 {
        assert_eq!(pattern.later_of(k), [k + 1]);
        assert_eq!(pattern.slot(k, k + 1), Some(3 * k + 1));
        assert_eq!(pattern.slot(k + 1, k), Some(3 * k + 2));
        assert_eq!(pattern.slot(k + 1, k + 1), Some(3 * k + 3));
    }
    assert_eq!(pattern.slot(0, 2), None);
}

/// A scrambled path starts at one of its ends; a tree is eliminated from its leaves: no fill,
/// one later neighbour per step.
#[test]
fn trees_are_eliminated_from_their_leaves_without_fill() {
    for (name, nodes, edges) in graphs() {
        if matches!(name, "cycle" | "ladder" | "complete") {
            continue;
        }
        let pattern = BlockPattern::new(nodes, &edges);
        assert_eq!(pattern.fill_edges(), 0, "{name}");
        assert_eq!(pattern.edges(), nodes - 1, "{name}");
        for k in 0..nodes {
            assert_eq!(
                pattern.later_of(k).len(),
                usize::from(k + 1 < nodes),
                "{name}"
            );
        }
    }
    let scrambled = BlockPattern::new(11, &graphs()[1].2);
    assert!([3, 7].contains(&scrambled.order()[0]), "starts at an end");
}

/// A cycle stays a cycle one node shorter after each elimination: one fill edge per step until
/// the last triangle, two later neighbours per step before it.
#[test]
fn cycle_gets_one_fill_edge_per_elimination() {
    let n = 10;
    let pattern = BlockPattern::new(n, &cycle(n));
    assert_eq!(pattern.fill_edges(), n - 3);
    for k in 0..n - 2 {
        assert_eq!(pattern.later_of(k).len(), 2);
    }
}

/// Every graph, symmetric or not, factored by each variant that applies: the dense LU's
/// solution (tolerance: module documentation).
#[test]
fn solves_match_dense_lu() {
    type Factor = fn(&mut SparseBlocks) -> Result<(), SingularMatrix>;
    let general: Factor = SparseBlocks::factor;
    let symmetric: Factor = SparseBlocks::factor_symmetric;
    let inertia: Factor = SparseBlocks::factor_with_inertia;
    for (name, nodes, edges) in graphs() {
        let variants = [
            (false, general),
            (true, general),
            (true, symmetric),
            (true, inertia),
        ];
        for (is_symmetric, factor) in variants {
            let mut case = case(nodes, &edges, is_symmetric, 7 + nodes as u64);
            let (x, want) = case.solve(&rhs(3 * nodes), factor);
            assert_close(&x, &want, SOLVE_TOLERANCE, name);
        }
    }
}

/// A pair of right-hand sides solves like each alone, to the bit.
#[test]
fn pairs_solve_like_singles() {
    for (name, nodes, edges) in graphs() {
        let mut a = case(nodes, &edges, false, 3).a;
        a.factor().unwrap();
        let mut x = rhs(3 * nodes);
        let mut y: Vec<f64> = (0..3 * nodes).map(|j| (1.3 * j as f64).sin()).collect();
        let (mut x1, mut y1) = (x.clone(), y.clone());
        a.solve_in_place(&mut x1);
        a.solve_in_place(&mut y1);
        a.solve_pair(&mut x, &mut y);
        assert_eq!((x, y), (x1, y1), "{name}");
    }
}

/// `mul` against the dense matrix assembled beside (the same few products, summed in another
/// order: 1e-14 of the largest entry, a few ulps of sums whose terms are at most 3 times the
/// result: `cond_inf <= 3`), and `row_entries`, the very entries (the same additions).
#[test]
fn products_and_rows_match_dense() {
    for (name, nodes, edges) in graphs() {
        let case = case(nodes, &edges, false, 5);
        let x = rhs(3 * nodes);
        let mut ax = vec![0.0; 3 * nodes];
        case.a.mul(&x, &mut ax);
        let want = &case.dense * DVector::from_column_slice(&x);
        assert_close(&ax, want.as_slice(), 1e-14, name);
        for dof in 0..3 * nodes {
            let entries = case.a.row_entries(dof);
            assert!(
                entries.windows(2).all(|w| w[0].0 < w[1].0),
                "{name}: sorted"
            );
            let mut row = vec![0.0; 3 * nodes];
            entries.iter().for_each(|&(c, value)| row[c] = value);
            assert_eq!(row, case.dense.row(dof).iter().copied().collect::<Vec<_>>());
        }
    }
}

/// The same matrix on a path of `n` nodes as a [`BlockTridiagonal`] and a [`SparseBlocks`]
/// (on `pattern`, or on the path's own): symmetric element pairs (scale 2) and 50 on the
/// diagonal.
pub(super) fn path_pair(
    n: usize,
    seed: u64,
    pattern: Option<BlockPattern>,
) -> (BlockTridiagonal, SparseBlocks) {
    let pattern = pattern.unwrap_or_else(|| BlockPattern::new(n, &path(n)));
    let mut tridiagonal = BlockTridiagonal::new(n);
    let mut sparse = SparseBlocks::new(Arc::new(pattern));
    let mut random = Random(seed);
    for i in 0..n - 1 {
        let (aa, ab, bb) = (
            random.symmetric_block(),
            random.block(),
            random.symmetric_block(),
        );
        tridiagonal.add_pair(i, &[aa, ab, bb], 2.0);
        let slots = sparse.pattern().pair_slots(i, i + 1).unwrap();
        sparse.add_pair_slots(slots, &aa, &ab, &bb, 2.0);
    }
    for dof in 0..3 * n {
        tridiagonal.add_diagonal(dof, 50.0);
        sparse.add_diagonal(dof, 50.0);
    }
    (tridiagonal, sparse)
}

/// On a path in natural order the sparse elimination is the top chain of the twisted
/// block-tridiagonal one: the same solution to round-off, for both factorizations. The pair
/// blocks' entries are below 2 in magnitude, so a row's off-diagonal entries sum to 20 at most
/// and its diagonal entry is 50 +- 4: dominant by 26 with `||A||_inf <= 74`, `cond_inf <= 3`
/// as in [`case`]: [`SOLVE_TOLERANCE`].
#[test]
fn path_solves_like_block_tridiagonal() {
    let n = 12;
    let (tridiagonal, sparse) = path_pair(n, 3, None);
    let x: Vec<f64> = rhs(3 * n);
    for symmetric in [false, true] {
        let (mut t, mut s) = (tridiagonal.clone(), sparse.clone());
        if symmetric {
            t.factor_symmetric().unwrap();
            s.factor_symmetric().unwrap();
        } else {
            t.factor().unwrap();
            s.factor().unwrap();
        }
        let (mut xt, mut xs) = (x.clone(), x.clone());
        t.solve_in_place(&mut xt);
        s.solve_in_place(&mut xs);
        assert_close(&xs, &xt, SOLVE_TOLERANCE, "path");
        assert_eq!(s.negative_pivots(), t.negative_pivots());
    }
}

/// In the twisted order a path's elimination is [`BlockTridiagonal`]'s, operation for
/// operation: the same solutions to the bit, with every factorization, for even and
/// odd sizes (the middle node eliminated last, from one side or both).
#[test]
fn twisted_path_is_block_tridiagonal_to_the_bit() {
    for n in 1..=9 {
        let twisted = BlockPattern::with_order(n, &path(n), &BlockPattern::twisted_order(n));
        assert_eq!(twisted.fill_edges(), 0);
        let (tridiagonal, sparse) = path_pair(n, 5, Some(twisted));
        type Factors = (
            fn(&mut BlockTridiagonal) -> Result<(), SingularMatrix>,
            fn(&mut SparseBlocks) -> Result<(), SingularMatrix>,
        );
        let variants: [Factors; 3] = [
            (BlockTridiagonal::factor, SparseBlocks::factor),
            (
                BlockTridiagonal::factor_symmetric,
                SparseBlocks::factor_symmetric,
            ),
            (
                BlockTridiagonal::factor_with_inertia,
                SparseBlocks::factor_with_inertia,
            ),
        ];
        for (factor_tridiagonal, factor_sparse) in variants {
            let (mut t, mut s) = (tridiagonal.clone(), sparse.clone());
            factor_tridiagonal(&mut t).unwrap();
            factor_sparse(&mut s).unwrap();
            let (mut xt, mut xs) = (rhs(3 * n), rhs(3 * n));
            t.solve_in_place(&mut xt);
            s.solve_in_place(&mut xs);
            assert_eq!(xs, xt, "{n} nodes");
            assert_eq!(s.negative_pivots(), t.negative_pivots());
        }
    }
}
