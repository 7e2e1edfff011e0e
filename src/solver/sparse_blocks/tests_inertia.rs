//! The pivots: singular ones reported, the inertia and the determinant's sign against the dense
//! symmetric eigenvalues (nalgebra), and near a zero eigenvalue against [`BlockTridiagonal`].
use super::tests::{case, graphs, path_pair};
use super::*;
use crate::solver::{BlockTridiagonal, SingularMatrix};
use nalgebra::DMatrix;

fn sorted_eigenvalues(a: &DMatrix<f64>) -> Vec<f64> {
    let mut eigenvalues = a.clone().symmetric_eigenvalues().as_slice().to_vec();
    eigenvalues.sort_by(f64::total_cmp);
    eigenvalues
}

/// Each graph's symmetric matrix shifted to the midpoint between two consecutive eigenvalues
/// (so every eigenvalue is half a gap from zero, far above the dense eigenvalues' round-off,
/// which is near `dofs * eps * ||A||`): the count of negative eigenvalues and the parity of the
/// negative pivots. Without pivoting an indefinite matrix may meet a singular pivot; those
/// shifts are skipped, and enough must remain.
#[test]
fn pivots_give_the_inertia_and_the_determinant_sign() {
    let mut checked = 0;
    for (name, nodes, edges) in graphs() {
        let base = case(nodes, &edges, true, 41);
        let eigenvalues = sorted_eigenvalues(&base.dense);
        let largest = eigenvalues[eigenvalues.len() - 1];
        for (j, pair) in eigenvalues.windows(2).enumerate() {
            if pair[1] - pair[0] < 1e-6 * largest {
                continue;
            }
            let mut a = base.a.clone();
            for dof in 0..3 * nodes {
                a.add_diagonal(dof, -0.5 * (pair[0] + pair[1]));
            }
            if a.factor_with_inertia().is_err() {
                continue;
            }
            assert_eq!(a.negative_eigenvalues(), j + 1, "{name}, shift {j}");
            assert_eq!(a.negative_pivots() % 2, (j + 1) % 2, "{name}, shift {j}");
            checked += 1;
        }
    }
    assert!(checked >= 100, "only {checked} shifts checked");
}

/// Near a zero eigenvalue (shifted to `1e-11 ||A||` on either side of each eigenvalue of a
/// path's matrix: the pivot that carries it is singular to 1e-11, not to working precision,
/// and the dense eigenvalues are exact to about `dofs * eps ||A|| = 3e-15 ||A||`): counted
/// from the pivots before their inversion, as the block-tridiagonal factorization counts,
/// and as the dense eigenvalues say.
#[test]
fn inertia_near_a_zero_eigenvalue_matches_block_tridiagonal() {
    let n = 8;
    let (tridiagonal, sparse) = path_pair(n, 43, None);
    let mut dense = DMatrix::zeros(3 * n, 3 * n);
    for j in 0..3 * n {
        let mut e = vec![0.0; 3 * n];
        e[j] = 1.0;
        sparse.mul(&e, dense.column_mut(j).as_mut_slice());
    }
    let eigenvalues = sorted_eigenvalues(&dense);
    let largest = eigenvalues[3 * n - 1];
    for (j, &eigenvalue) in eigenvalues.iter().enumerate() {
        for side in [-1.0, 1.0] {
            let shift = eigenvalue + side * 1e-11 * largest;
            let (mut t, mut s) = (tridiagonal.clone(), sparse.clone());
            for dof in 0..3 * n {
                t.add_diagonal(dof, -shift);
                s.add_diagonal(dof, -shift);
            }
            let want = j + usize::from(side > 0.0);
            s.factor_with_inertia().unwrap();
            t.factor_with_inertia().unwrap();
            assert_eq!(
                s.negative_eigenvalues(),
                want,
                "eigenvalue {j}, side {side}"
            );
            assert_eq!(
                t.negative_eigenvalues(),
                want,
                "eigenvalue {j}, side {side}"
            );
        }
    }
}

/// An exactly zero eigenvalue (a dof with a zero row and column) is a singular pivot at its
/// node for both factorizations.
#[test]
fn zero_eigenvalue_is_a_singular_pivot() {
    let (mut t, mut s): (BlockTridiagonal, SparseBlocks) = path_pair(6, 47, None);
    let w = 3 * 3 + 2;
    t.constrain(&[w]);
    s.constrain(&[w]);
    t.add_diagonal(w, -1.0);
    s.add_diagonal(w, -1.0);
    assert_eq!(s.factor_with_inertia(), Err(SingularMatrix { block: 3 }));
    assert_eq!(t.factor_with_inertia(), Err(SingularMatrix { block: 3 }));
}

/// A pivot singular to working precision is reported with its node: a leaf's own block, and
/// the last pivot of a star whose Schur complement vanishes (`3 I - 3 (I I^-1 I)`: leaves 1
/// and 2, then the center, of degree one then, and leaf 3).
#[test]
fn singular_pivot_is_reported_with_its_node() {
    let star: Vec<_> = (1..4).map(|i| (0, i)).collect();
    let pattern = Arc::new(BlockPattern::new(4, &star));
    let mut a = SparseBlocks::new(pattern.clone());
    for i in 1..4 {
        let slots = pattern.pair_slots(0, i).unwrap();
        let identity = Matrix3::identity();
        a.add_pair_slots(slots, &identity, &identity, &identity, 1.0);
    }
    let mut leaf = a.clone();
    assert_eq!(pattern.order(), [1, 2, 0, 3]);
    assert_eq!(a.factor(), Err(SingularMatrix { block: 3 }));
    let dependent = Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0);
    leaf.add_block(pattern.slot(2, 2).unwrap(), &dependent, 1.0);
    leaf.add_block(pattern.slot(2, 2).unwrap(), &Matrix3::identity(), -1.0);
    assert_eq!(leaf.factor(), Err(SingularMatrix { block: 2 }));
}
