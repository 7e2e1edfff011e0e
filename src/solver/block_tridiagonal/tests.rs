use super::factor::adjugate_and_determinant;
use super::*;

/// Each row stencil times `x` is that row of `A x`, at the ends and inside.
#[test]
fn row_stencils_are_the_rows_of_the_product() {
    let blocks = 4;
    let mut a = BlockTridiagonal::new(blocks);
    let fill = |m: &mut Matrix3<f64>, seed: f64| {
        for (n, x) in m.iter_mut().enumerate() {
            *x = (seed + n as f64).sin();
        }
    };
    for i in 0..blocks {
        fill(&mut a.diag[i], i as f64);
    }
    for i in 0..blocks - 1 {
        fill(&mut a.upper[i], 10.0 + i as f64);
        fill(&mut a.lower[i], 20.0 + i as f64);
    }
    let x: Vec<f64> = (0..3 * blocks).map(|j| (0.3 * j as f64).cos()).collect();
    let mut ax = vec![0.0; 3 * blocks];
    a.mul(&x, &mut ax);
    for (dof, want) in ax.iter().enumerate() {
        let (first, entries) = a.row_stencil(dof);
        let got: f64 = entries.iter().zip(&x[first..]).map(|(e, v)| e * v).sum();
        assert!((got - want).abs() <= 1e-14, "row {dof}: {got} vs {want}");
    }
}

/// `add_pair` with plain blocks `[aa, ab, bb]` adds `scale * [[aa, ab], [ab^T, bb]]` at block
/// rows `i`, `i + 1` and nothing elsewhere; two pairs sharing a block row add up there.
#[test]
fn add_pair_adds_the_scaled_blocks_and_the_transpose() {
    let block = |seed: f64| Matrix3::from_fn(|r, c| (seed + (3 * r + c) as f64).sin());
    let (aa, ab, bb) = (block(0.0), block(10.0), block(20.0));
    let mut a = BlockTridiagonal::new(4);
    a.add_pair(1, &[aa, ab, bb], 2.0);
    a.add_pair(2, &[aa, ab, bb], -0.5);
    assert_eq!(a.diag[0], Matrix3::zeros());
    assert_eq!(a.diag[1], 2.0 * aa);
    assert_eq!(a.diag[2], 2.0 * bb + -0.5 * aa);
    assert_eq!(a.diag[3], -0.5 * bb);
    assert_eq!(
        (a.upper[0], a.lower[0]),
        (Matrix3::zeros(), Matrix3::zeros())
    );
    assert_eq!((a.upper[1], a.lower[1]), (2.0 * ab, 2.0 * ab.transpose()));
    assert_eq!((a.upper[2], a.lower[2]), (-0.5 * ab, -0.5 * ab.transpose()));
}

#[test]
fn adjugate_inverse_matches_nalgebra() {
    let m = Matrix3::new(4.0, -1.5, 0.3, 2.0, 7.0, -0.25, 1e-3, 0.5, 3e-4);
    let (adjugate, det) = adjugate_and_determinant(&m);
    let inverse = adjugate / det;
    assert!((det - m.determinant()).abs() <= 1e-14 * det.abs());
    let reference = m.try_inverse().unwrap();
    assert!((inverse - reference).norm() <= 1e-13 * reference.norm());
    assert!((inverse * m - Matrix3::identity()).norm() <= 1e-13);
}

/// A diagonally dominant matrix of `blocks` blocks, non-symmetric unless `symmetric`.
fn test_matrix(blocks: usize, symmetric: bool, shift: f64) -> BlockTridiagonal {
    let mut a = BlockTridiagonal::new(blocks);
    for i in 0..blocks {
        for (n, x) in a.diag[i].iter_mut().enumerate() {
            *x = (1.7 * (i * 9 + n) as f64).sin();
        }
        a.diag[i] += Matrix3::identity() * shift;
    }
    for i in 0..blocks - 1 {
        for (n, x) in a.upper[i].iter_mut().enumerate() {
            *x = (0.9 * (i * 9 + n) as f64 + 1.0).cos();
        }
        for (n, x) in a.lower[i].iter_mut().enumerate() {
            *x = (1.3 * (i * 9 + n) as f64 + 2.0).sin();
        }
    }
    if symmetric {
        for i in 0..blocks {
            a.diag[i] = 0.5 * (a.diag[i] + a.diag[i].transpose());
        }
        for i in 0..blocks - 1 {
            a.lower[i] = a.upper[i].transpose();
        }
    }
    a
}

/// The dense form of `a` (before factorization).
fn dense(a: &BlockTridiagonal) -> nalgebra::DMatrix<f64> {
    let n = 3 * a.blocks();
    let mut d = nalgebra::DMatrix::zeros(n, n);
    for j in 0..n {
        let mut e = vec![0.0; n];
        e[j] = 1.0;
        let mut col = vec![0.0; n];
        a.mul(&e, &mut col);
        for i in 0..n {
            d[(i, j)] = col[i];
        }
    }
    d
}

/// `solve_in_place` inverts `mul` for every size from one block (the middle block alone)
/// to eight (both chains, with one or two blocks more on the top chain): residual at
/// round-off of a well-conditioned system.
#[test]
fn solve_inverts_the_product() {
    for blocks in 1..=8 {
        let mut a = test_matrix(blocks, false, 6.0);
        let x: Vec<f64> = (0..3 * blocks).map(|j| (0.7 * j as f64).cos()).collect();
        let mut ax = vec![0.0; 3 * blocks];
        a.mul(&x, &mut ax);
        a.factor().unwrap();
        a.solve_in_place(&mut ax);
        for (got, want) in ax.iter().zip(&x) {
            assert!(
                (got - want).abs() <= 1e-14,
                "{blocks} blocks: {got} vs {want}"
            );
        }
    }
}

/// A pair of right-hand sides solves like each alone, to the bit.
#[test]
fn pairs_solve_like_singles() {
    let mut a = test_matrix(7, false, 6.0);
    a.factor().unwrap();
    let mut x: Vec<f64> = (0..21).map(|j| (0.7 * j as f64).cos()).collect();
    let mut y: Vec<f64> = (0..21).map(|j| (1.3 * j as f64).sin()).collect();
    let (mut x1, mut y1) = (x.clone(), y.clone());
    a.solve_in_place(&mut x1);
    a.solve_in_place(&mut y1);
    a.solve_pair(&mut x, &mut y);
    assert_eq!((x, y), (x1, y1));
}

/// The symmetric factorization of a symmetric matrix solves like the general one.
#[test]
fn symmetric_factorization_solves() {
    for blocks in 1..=8 {
        let mut a = test_matrix(blocks, true, 6.0);
        let mut general = a.clone();
        let x: Vec<f64> = (0..3 * blocks).map(|j| (0.7 * j as f64).cos()).collect();
        let mut ax = vec![0.0; 3 * blocks];
        a.mul(&x, &mut ax);
        let mut ax_general = ax.clone();
        a.factor_symmetric().unwrap();
        general.factor().unwrap();
        a.solve_in_place(&mut ax);
        general.solve_in_place(&mut ax_general);
        for ((got, general), want) in ax.iter().zip(&ax_general).zip(&x) {
            assert!(
                (got - want).abs() <= 1e-14,
                "{blocks} blocks: {got} vs {want}"
            );
            assert!(
                (got - general).abs() <= 1e-14,
                "{blocks} blocks: {got} vs {general}"
            );
        }
    }
}

/// The determinant's sign and the inertia of a symmetric indefinite matrix from the pivots
/// equal those of its dense eigenvalues.
#[test]
fn pivots_give_the_determinant_sign_and_the_inertia() {
    let mut checked = 0;
    for blocks in 1..=7 {
        for shift in [-1.5, 0.3, 2.5] {
            let mut a = test_matrix(blocks, true, shift);
            let d = dense(&a);
            let eigenvalues = d.clone().symmetric_eigenvalues();
            let negative = eigenvalues.iter().filter(|&&l| l < 0.0).count();
            if eigenvalues.iter().any(|l| l.abs() < 1e-6) || a.factor_with_inertia().is_err() {
                continue;
            }
            assert_eq!(
                a.negative_eigenvalues(),
                negative,
                "{blocks} blocks, {shift}"
            );
            let sign = if a.negative_pivots() % 2 == 0 {
                1.0
            } else {
                -1.0
            };
            assert_eq!(sign, d.determinant().signum(), "{blocks} blocks, {shift}");
            checked += 1;
        }
    }
    assert!(checked >= 15, "only {checked} matrices checked");
}

#[test]
fn singular_pivot_is_reported() {
    let mut a = BlockTridiagonal::new(2);
    a.diag[0] = Matrix3::identity();
    a.diag[1] = Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0);
    assert_eq!(a.factor(), Err(SingularMatrix { block: 1 }));
}
