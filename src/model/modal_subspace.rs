//! The lowest natural frequencies of a rod of any size: subspace iteration with the shifted
//! tangent `A = K_T(u) + s M` factored once as a block-tridiagonal matrix (`O(n)` per solve), and
//! a Rayleigh-Ritz step on `K phi = lambda M phi` in the iterated subspace after each pass
//! (`lambda = omega^2`). For a few modes of a long rod this costs `O(n)` where the dense
//! eigenproblem of [`super::modal`] costs `O(n^3)`.
use super::assembly::Assembly;
use crate::solver::SystemMatrix;
use nalgebra::DMatrix;

/// Most passes of the subspace iteration before it is given up.
const MAX_PASSES: usize = 500;
/// The wanted `lambda` have converged when no pass changes them by more than this (relative to
/// the largest wanted `|lambda| + s`): the Ritz values converge with the square of the vectors'
/// error, so the vectors are then within about 1e-7.
const TOLERANCE: f64 = 1e-13;
/// ... or when the changes have stopped falling while below this (relative to each
/// `|lambda| + s`): the Ritz values then sit at their round-off floor. The Rayleigh quotients
/// are sums of the rod's stiff axial and shear terms, which cancel for its softest modes (a rod
/// on springs, a heavy tip mass): their floor can be 1e-8 of `lambda`, far above `TOLERANCE`.
const FLOOR: f64 = 1e-6;

/// A mode: `lambda = omega^2` and its shape on every dof (zero on the held ones), with
/// `phi^T M phi = 1`.
pub type Mode = (f64, Vec<f64>);

/// The `count` lowest modes of `K_T(u) phi = lambda M phi` on the free dofs of `rod`, ascending;
/// an error if the iteration does not converge (or no shift makes `A` positive definite).
pub fn lowest_modes<A: Assembly>(rod: &A, u: &[f64], count: usize) -> Result<Vec<Mode>, String> {
    let n = rod.dofs();
    let free = n - rod.constrained().len();
    let width = (2 * count).max(count + 8).min(free);
    if count == 0 || count > free {
        return Err(format!("{count} modes of a rod with {free} free dofs"));
    }
    let mut k = rod.new_matrix();
    rod.internal_force_and_tangent(u, &mut vec![0.0; n], &mut k, 1.0);
    rod.constrain(&mut k);
    let (a, shift) = shifted_factor(rod, &k)?;
    // Deterministic start vectors (a fixed pseudo-random sequence), zero on the held dofs.
    let mut state = 0x9E37_79B9_7F4A_7C15_u64;
    let mut x: Vec<Vec<f64>> = (0..width)
        .map(|_| {
            let mut v: Vec<f64> = (0..n)
                .map(|_| {
                    state = state
                        .wrapping_mul(6_364_136_223_846_793_005)
                        .wrapping_add(1);
                    (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
                })
                .collect();
            rod.zero_constrained(&mut v);
            v
        })
        .collect();
    let mut previous = vec![f64::INFINITY; count];
    let mut last_change = vec![f64::INFINITY; count];
    let mut mass_times = vec![0.0; n];
    for _ in 0..MAX_PASSES {
        // Y = A^-1 M X.
        for v in &mut x {
            mass_times.fill(0.0);
            rod.add_mass_times(v, &mut mass_times, 1.0);
            rod.zero_constrained(&mut mass_times);
            a.solve_in_place(&mut mass_times);
            v.copy_from_slice(&mass_times);
        }
        let (lambda, vectors) = rayleigh_ritz(rod, &k, &mut x)?;
        x = combine(&x, &vectors);
        let scale = lambda[count - 1].abs() + shift;
        let change: Vec<f64> = (lambda[..count].iter().zip(&previous))
            .map(|(l, p)| (l - p).abs())
            .collect();
        let converged = change.iter().all(|&d| d <= TOLERANCE * scale);
        let at_floor = (change.iter().zip(&last_change).zip(&lambda[..count]))
            .all(|((&d, &last), l)| d <= FLOOR * (l.abs() + shift) && d >= 0.5 * last);
        previous.copy_from_slice(&lambda[..count]);
        last_change = change;
        if converged || at_floor {
            return Ok(previous.into_iter().zip(x).collect());
        }
    }
    Err(format!(
        "the subspace iteration for {count} modes did not converge in {MAX_PASSES} passes"
    ))
}

/// `A = K + s M` factored, with the smallest shift `s` tried (`1e-3` of the rod's bending scale
/// `EI / (rho A S^4)`, then ten times more up to twenty times) that makes it positive definite:
/// the wanted `lambda` (the lowest, possibly negative or zero) are then the largest
/// `1 / (lambda + s)`.
fn shifted_factor<A: Assembly>(rod: &A, k: &A::Matrix) -> Result<(A::Matrix, f64), String> {
    let mut shift = 1e-3 * rod.bending_scale();
    for _ in 0..20 {
        let mut a = rod.new_matrix();
        a.copy_from(k);
        rod.add_mass(&mut a, shift);
        rod.constrain(&mut a);
        if a.factor_with_inertia().is_ok() && a.negative_eigenvalues() == 0 {
            return Ok((a, shift));
        }
        shift *= 10.0;
    }
    Err("no shift makes the tangent positive definite".to_string())
}

/// The Ritz values (ascending) and vectors (columns) of `K`, `M` in the span of `y`, after `y`
/// is made `M`-orthonormal (the passes make its columns nearly parallel: the lowest modes
/// dominate every one of them).
fn rayleigh_ritz<A: Assembly>(
    rod: &A,
    k: &A::Matrix,
    y: &mut [Vec<f64>],
) -> Result<(Vec<f64>, DMatrix<f64>), String> {
    m_orthonormalize(rod, y)?;
    let p = y.len();
    let mut ky = vec![vec![0.0; rod.dofs()]; p];
    for j in 0..p {
        k.mul(&y[j], &mut ky[j]);
    }
    let kr = DMatrix::from_fn(p, p, |i, j| 0.5 * (dot(&y[i], &ky[j]) + dot(&y[j], &ky[i])));
    let eig = kr.symmetric_eigen();
    let mut order: Vec<usize> = (0..p).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    let lambda = order.iter().map(|&i| eig.eigenvalues[i]).collect();
    let vectors = DMatrix::from_fn(p, p, |r, c| eig.eigenvectors[(r, order[c])]);
    Ok((lambda, vectors))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Modified Gram-Schmidt in the `M` inner product, each vector twice against the ones before it
/// (once is not enough for nearly parallel vectors).
fn m_orthonormalize<A: Assembly>(rod: &A, y: &mut [Vec<f64>]) -> Result<(), String> {
    let n = rod.dofs();
    let mut my: Vec<Vec<f64>> = Vec::with_capacity(y.len());
    for j in 0..y.len() {
        for _ in 0..2 {
            for (i, mi) in my.iter().enumerate() {
                let c = dot(mi, &y[j]);
                let (before, rest) = y.split_at_mut(j);
                rest[0]
                    .iter_mut()
                    .zip(&before[i])
                    .for_each(|(a, b)| *a -= c * b);
            }
        }
        let mut m = vec![0.0; n];
        rod.add_mass_times(&y[j], &mut m, 1.0);
        rod.zero_constrained(&mut m);
        let norm = dot(&y[j], &m).sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return Err("the iterated vectors became dependent".to_string());
        }
        y[j].iter_mut().for_each(|a| *a /= norm);
        m.iter_mut().for_each(|a| *a /= norm);
        my.push(m);
    }
    Ok(())
}

/// The columns `y phi` for each column of `phi`.
fn combine(y: &[Vec<f64>], phi: &DMatrix<f64>) -> Vec<Vec<f64>> {
    (0..phi.ncols())
        .map(|c| {
            let mut v = vec![0.0; y[0].len()];
            for (r, yr) in y.iter().enumerate() {
                let w = phi[(r, c)];
                v.iter_mut().zip(yr).for_each(|(a, b)| *a += w * b);
            }
            v
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ReferenceCurve, Rod, Section};

    /// Against the dense eigenproblem: a pinned-pinned rod, a free rod (three rigid motions at
    /// zero) and a compressed rod past its buckling load (a negative `lambda`), to 1e-9 relative
    /// to the largest of the wanted `|lambda|`.
    #[test]
    fn agrees_with_the_dense_eigenproblem() {
        let section = Section::rectangular(2.0e5, 0.3, 1.0, 1.0, 0.2);
        let make = |fix: &[(usize, usize)]| {
            let mut rod = Rod::new(ReferenceCurve::Straight { length: 5.0 }, section, 0.0, 24);
            for &(node, dof) in fix {
                rod.fix(node, dof);
            }
            rod
        };
        let pinned = make(&[(0, 0), (0, 1), (24, 1)]);
        let free = make(&[]);
        let held = make(&[(0, 0), (0, 1), (24, 0), (24, 1)]);
        let mut compressed = vec![0.0; held.dofs()];
        for i in 0..held.nodes() {
            compressed[3 * i] = -0.01 * held.node_s[i] / 5.0; // far past Euler's shortening
        }
        for (rod, u) in [
            (&pinned, vec![0.0; pinned.dofs()]),
            (&free, vec![0.0; free.dofs()]),
            (&held, compressed),
        ] {
            let dense: Vec<f64> = crate::model::modal::modes(rod, &u)
                .iter()
                .map(|m| m.omega_squared)
                .collect();
            let fast: Vec<f64> = lowest_modes(rod, &u, 5)
                .unwrap()
                .into_iter()
                .map(|(lambda, _)| lambda)
                .collect();
            let scale = dense[4].abs().max(dense[0].abs());
            for (a, b) in fast.iter().zip(&dense) {
                assert!(
                    (a - b).abs() <= 1e-9 * scale,
                    "{fast:?} vs {:?}",
                    &dense[..5]
                );
            }
        }
    }
}
