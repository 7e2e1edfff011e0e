//! Held dofs and directions, and ties (a pin joint built with them), against dense systems.
//!
//! Tolerances: the solves are compared at [`SOLVE_TOLERANCE`] (see `tests`); each test says why
//! its system is as well conditioned as the plain test matrices.
use super::tests::{assert_close, case, graphs, path, rhs, Random, SOLVE_TOLERANCE};
use super::*;
use crate::solver::SingularMatrix;
use nalgebra::{DMatrix, DVector};

/// The factorization of a matrix known to be symmetric or not.
fn factor_for(symmetric: bool) -> fn(&mut SparseBlocks) -> Result<(), SingularMatrix> {
    if symmetric {
        SparseBlocks::factor_symmetric
    } else {
        SparseBlocks::factor
    }
}

/// Held dofs: the dense system with their rows and columns replaced by the identity's and a
/// zero right-hand side (removing dofs of a matrix with `cond_inf <= 3` leaves a diagonally
/// dominant one, as well conditioned); the held dofs come out exactly zero, a symmetric matrix
/// stays symmetric.
#[test]
fn held_dofs_match_the_dense_reduced_system() {
    for (name, nodes, edges) in graphs() {
        for symmetric in [false, true] {
            let mut case = case(nodes, &edges, symmetric, 17);
            let held = [0, 4 % (3 * nodes), 3 * nodes - 1];
            case.a.constrain(&held);
            let mut b = rhs(3 * nodes);
            for &dof in &held {
                case.dense.row_mut(dof).fill(0.0);
                case.dense.column_mut(dof).fill(0.0);
                case.dense[(dof, dof)] = 1.0;
                b[dof] = 0.0;
            }
            assert!(case.a.is_symmetric() || !symmetric, "{name}");
            let (x, want) = case.solve(&b, factor_for(symmetric));
            assert_close(&x, &want, SOLVE_TOLERANCE, name);
            assert!(held.iter().all(|&dof| x[dof] == 0.0), "{name}");
        }
    }
}

/// A held direction at a node with couplings: the solution has no component along `n` there,
/// the projected equations hold and it is the solution of the dense `P A P + N` (with `P`, `N`
/// the block-diagonal projector and `n n^T` at the node). That matrix decouples the motion
/// along `n` (eigenvalue 1) from the rest, the compression of `A` to the other directions, whose
/// eigenvalues (symmetric case) lie within `A`'s: conditioned as `A` on each part.
#[test]
fn held_direction_matches_the_dense_projected_system() {
    let (c, s) = (0.7f64.cos(), 0.7f64.sin());
    for (name, nodes, edges) in graphs() {
        for symmetric in [false, true] {
            let node = nodes / 2;
            let mut case = case(nodes, &edges, symmetric, 23);
            let original = case.dense.clone();
            case.a.constrain_direction(node, [c, s]);
            let mut projector = DMatrix::identity(3 * nodes, 3 * nodes);
            let mut along = DMatrix::zeros(3 * nodes, 3 * nodes);
            let n = nalgebra::Vector3::new(c, s, 0.0);
            let nn = n * n.transpose();
            let mut block = projector.view_mut((3 * node, 3 * node), (3, 3));
            block -= nn;
            along.view_mut((3 * node, 3 * node), (3, 3)).copy_from(&nn);
            case.dense = &projector * &original * &projector + along;
            let mut b = rhs(3 * nodes);
            let bn = c * b[3 * node] + s * b[3 * node + 1];
            b[3 * node] -= bn * c;
            b[3 * node + 1] -= bn * s;
            assert!(case.a.is_symmetric() || !symmetric, "{name}: to the bit");
            let (x, want) = case.solve(&b, factor_for(symmetric));
            assert_close(&x, &want, SOLVE_TOLERANCE, name);
            let scale = x.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
            let xn = c * x[3 * node] + s * x[3 * node + 1];
            assert!(xn.abs() <= SOLVE_TOLERANCE * scale, "{name}: along n {xn}");
            // The equations of the original matrix, projected: `P (A x - b) = 0`, relative to
            // the terms of `A x` (`||A||_inf ||x||_inf`).
            let x = DVector::from_column_slice(&x);
            let residual = &projector * (&original * &x - DVector::from_column_slice(&b));
            let norm = original
                .row_iter()
                .map(|r| r.abs().sum())
                .fold(0.0, f64::max);
            assert!(
                residual.amax() <= SOLVE_TOLERANCE * norm * scale,
                "{name}: residual {}",
                residual.amax()
            );
        }
    }
}

/// Ties copy the master's value into the slave after each solve, exactly, for one or two
/// right-hand sides; a chain of ties (`4 -> 10 -> 1`) resolves to its last master.
#[test]
fn ties_copy_the_master_into_the_slave() {
    let mut case = case(6, &path(6), true, 29);
    let ties = vec![(4, 10), (10, 1), (17, 0)];
    case.a = case.a.clone().with_ties(ties);
    case.a.constrain(&[4, 10, 17]);
    case.a.factor_symmetric().unwrap();
    let mut x = rhs(18);
    let mut y: Vec<f64> = (0..18).map(|j| (1.3 * j as f64).sin()).collect();
    for dof in [4, 10, 17] {
        (x[dof], y[dof]) = (0.0, 0.0);
    }
    let mut single = x.clone();
    case.a.solve_in_place(&mut single);
    case.a.solve_pair(&mut x, &mut y);
    assert_eq!(single, x);
    for v in [&x, &y] {
        assert_eq!([v[4], v[10], v[17]], [v[1], v[1], v[0]]);
        assert_ne!(v[1], 0.0);
    }
}

#[test]
#[should_panic(expected = "cycle")]
fn a_cycle_of_ties_is_refused() {
    let a = SparseBlocks::new(Arc::new(BlockPattern::new(2, &path(2))));
    let _ = a.with_ties(vec![(0, 3), (3, 0)]);
}

/// The recipe for a pin joint: member A is nodes 0-1-2 (2 the joint), member B nodes 3-4-5
/// whose end node 3 shares the joint's translations (`u1`, `u2` tied to node 2's) and keeps its
/// own rotation. Every entry of B's first element is routed (a slave dof to its master), so the
/// pattern holds the edges `(3, 4)`, `(2, 4)` and `(2, 3)` besides the members' chains. The
/// result is the dense system with the tie substituted, `T^T K T y = T^T b`, `x = T y` (`T`
/// keeps each dof, the slaves taking the masters' columns): `K` is symmetric and dominant
/// (eigenvalues in `[R, 3 R]`) and `T`'s singular values are 1 and `sqrt 2`, so `T^T K T` has
/// a condition number of 6 at most.
#[test]
fn pin_joint_by_routing_matches_the_dense_substitution() {
    let edges = [(0, 1), (1, 2), (3, 4), (4, 5), (2, 4), (2, 3)];
    let elements = [(0, 1), (1, 2), (3, 4), (4, 5)];
    let ties = [(9, 6), (10, 7)];
    let route = |dof: usize| ties.iter().find(|t| t.0 == dof).map_or(dof, |t| t.1);
    let pattern = Arc::new(BlockPattern::new(6, &edges));
    let mut a = SparseBlocks::new(pattern).with_ties(ties.to_vec());
    let mut k = DMatrix::zeros(18, 18);
    let mut random = Random(31);
    for &(i, j) in &elements {
        let (aa, ab, bb) = (
            random.symmetric_block(),
            random.block(),
            random.symmetric_block(),
        );
        for (bi, bj, block) in [(i, i, aa), (i, j, ab), (j, i, ab.transpose()), (j, j, bb)] {
            for (r, c) in (0..3).flat_map(|r| (0..3).map(move |c| (r, c))) {
                let (row, column) = (3 * bi + r, 3 * bj + c);
                k[(row, column)] += block[(r, c)];
                a.add_entry(route(row), route(column), block[(r, c)]);
            }
        }
    }
    let shift = 2.0 * k.row_iter().map(|r| r.abs().sum()).fold(0.0, f64::max);
    for dof in 0..18 {
        k[(dof, dof)] += shift;
        a.add_diagonal(route(dof), shift);
    }
    a.constrain(&[9, 10]);
    assert!(a.is_symmetric(), "routed symmetrically, to the bit");
    let mut t = DMatrix::zeros(18, 16);
    let reduced = |dof: usize| dof - usize::from(dof > 10) * 2;
    for dof in 0..18 {
        t[(dof, reduced(route(dof)))] = 1.0;
    }
    let b = DVector::from_column_slice(&rhs(18));
    let y = (t.transpose() * &k * &t).lu().solve(&(t.transpose() * &b));
    let want = &t * y.expect("regular");
    let mut x = (t.transpose() * &b).as_slice().to_vec();
    for (dof, value) in [(9, 0.0), (10, 0.0)] {
        x.insert(dof, value);
    }
    a.factor_symmetric().unwrap();
    a.solve_in_place(&mut x);
    assert_close(&x, want.as_slice(), SOLVE_TOLERANCE, "pin joint");
}
