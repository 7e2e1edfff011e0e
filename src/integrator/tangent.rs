//! Lyapunov exponents from the exact tangent map of the midpoint rule.
//!
//! A midpoint step is a map `z_n = (u_n, v_n) -> z_(n+1)` defined by `R(du; u_n, v_n) = 0` with
//! `R = M (2/dt^2 du - 2/dt v_n) + C du/dt + f_int(u_n + du/2) - f_ext`. Differentiating at the
//! converged step, with `J = dR/d(du) = A + K/2`, `A = 2/dt^2 M + C/dt`, `K` the tangent
//! stiffness at the midpoint:
//!
//! `J d(du) = -K du_n + 2/dt M dv_n`, and `K = 2 (J - A)` gives
//! `du_(n+1) = J^-1 (2 A du_n + 2/dt M dv_n) - du_n`, `dv_(n+1) = 2/dt (du_(n+1) - du_n) - dv_n`:
//!
//! one system with the converged step's Jacobian per tangent vector, which the step solves
//! along with its own (`tangent_map.rs`: with one vector, the Jacobian of its Newton iteration
//! and one or two refinements; with more, the converged Jacobian factored once; exact to about
//! 1e-12). Held dofs are not part of the state (their motion is
//! prescribed): their components stay zero.
//!
//! `k` tangent vectors are advanced together and re-orthonormalized after every sub-step
//! (modified Gram-Schmidt, i.e. a QR decomposition, in the norm
//! `|z|^2 = |du|^2 + tau^2 |dv|^2`); the logarithms of the diagonal of `R` summed over time are
//! the leading `k` exponents times the time (Benettin et al.). Renormalizing every sub-step
//! keeps the vectors bounded whatever the communication step, and makes the estimate
//! independent of how sub-steps are grouped into communication steps.
use super::tangent_map::TangentMap;
use crate::model::Assembly;
use crate::solver::vector::dot;

/// The most exponents one simulation estimates.
pub const MAX_EXPONENTS: usize = 4;

/// `k` tangent vectors and their accumulated growth. Plain data: copying it restores it.
#[derive(Clone, Debug, PartialEq)]
pub struct Lyapunov {
    /// Displacement and velocity parts of the vectors, `k` blocks of `dofs` each.
    du: Vec<f64>,
    dv: Vec<f64>,
    /// Weight of the velocities in the norm (a time).
    tau: f64,
    /// Sub-steps starting at or after this time count towards the exponents.
    count_from: f64,
    /// Sum of `ln |R_jj|` over the counted sub-steps, per exponent.
    log_growth: Vec<f64>,
    /// Time covered by the counted sub-steps.
    counted_time: f64,
    /// The dofs the norm leaves out (see [`Assembly::duplicates`]).
    duplicates: Vec<usize>,
}

/// A deterministic pseudo-random direction over the free dofs (splitmix64), unit in the norm
/// with weight `tau`: the same for every run of the same rod.
pub fn seeded_direction<A: Assembly>(rod: &A, seed: u64, tau: f64) -> (Vec<f64>, Vec<f64>) {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let n = rod.dofs();
    let mut du: Vec<f64> = (0..n).map(|_| next()).collect();
    let mut dv: Vec<f64> = (0..n).map(|_| next() / tau).collect();
    rod.zero_constrained(&mut du);
    rod.zero_constrained(&mut dv);
    rod.make_consistent(&mut du);
    rod.make_consistent(&mut dv);
    let norm = weighted_norm(&du, &dv, tau, rod.duplicates());
    du.iter_mut().chain(dv.iter_mut()).for_each(|x| *x /= norm);
    (du, dv)
}

fn weighted_norm(du: &[f64], dv: &[f64], tau: f64, duplicates: &[usize]) -> f64 {
    weighted_dot((du, dv), (du, dv), tau, duplicates).sqrt()
}

/// `|z|^2 = du . du + tau^2 dv . dv`, each physical dof once: the `duplicates` (a frame member's
/// ends, which repeat their joints) left out.
fn weighted_dot(
    (au, av): (&[f64], &[f64]),
    (bu, bv): (&[f64], &[f64]),
    tau: f64,
    duplicates: &[usize],
) -> f64 {
    let mut d = dot(au, bu) + tau * tau * dot(av, bv);
    for &i in duplicates {
        d -= au[i] * bu[i] + tau * tau * (av[i] * bv[i]);
    }
    d
}

impl Lyapunov {
    /// `k` (1..=[`MAX_EXPONENTS`]) orthonormal vectors from seeded directions; the growth
    /// counts from time `count_from` on; `tau` weighs the velocities in the norm.
    pub fn new<A: Assembly>(rod: &A, k: usize, tau: f64, count_from: f64) -> Lyapunov {
        assert!((1..=MAX_EXPONENTS).contains(&k) && tau > 0.0);
        let n = rod.dofs();
        let mut l = Lyapunov {
            du: Vec::with_capacity(k * n),
            dv: Vec::with_capacity(k * n),
            tau,
            count_from,
            log_growth: vec![0.0; k],
            counted_time: 0.0,
            duplicates: rod.duplicates().to_vec(),
        };
        for j in 0..k {
            let (du, dv) = seeded_direction(rod, j as u64 + 1, tau);
            l.du.extend(du);
            l.dv.extend(dv);
        }
        l.orthonormalize(false);
        l
    }

    pub fn count(&self) -> usize {
        self.log_growth.len()
    }

    fn dofs(&self) -> usize {
        self.du.len() / self.count()
    }

    pub fn copy_from(&mut self, other: &Lyapunov) {
        self.du.copy_from_slice(&other.du);
        self.dv.copy_from_slice(&other.dv);
        self.tau = other.tau;
        self.count_from = other.count_from;
        self.log_growth.copy_from_slice(&other.log_growth);
        self.counted_time = other.counted_time;
    }

    /// The running estimates of the exponents (1/s): the summed growth over the counted time,
    /// or 0 before any sub-step counted.
    pub fn exponent(&self, j: usize) -> f64 {
        if self.counted_time > 0.0 {
            self.log_growth[j] / self.counted_time
        } else {
            0.0
        }
    }

    pub fn counted_time(&self) -> f64 {
        self.counted_time
    }

    /// Sets the tangent map's systems of the sub-step of size `dt` about to be taken: one per
    /// vector, `rhs = 2 A du + 2/dt M dv = M (4/dt^2 du + 2/dt dv) + C (2/dt du)` (`map` must
    /// have room for [`Lyapunov::count`] of them).
    pub fn prepare<A: Assembly>(&self, rod: &A, dt: f64, map: &mut TangentMap<A>) {
        let n = self.dofs();
        map.set_count(self.count());
        for j in 0..self.count() {
            let du = &self.du[j * n..(j + 1) * n];
            let dv = &self.dv[j * n..(j + 1) * n];
            let rhs = map.rhs_mut(j);
            rhs.fill(0.0);
            let bracket = ((4.0 / (dt * dt), du), (2.0 / dt, dv));
            rod.add_bracket_times(bracket, 2.0 / dt, None, rhs);
            rod.zero_constrained(rhs);
        }
    }

    /// Advances the vectors over the sub-step `[t_n, t_n + dt]` just taken, from the solutions
    /// of the systems that [`Lyapunov::prepare`] set, then re-orthonormalizes them and books
    /// the growth if `t_n` counts.
    pub fn advance<A: Assembly>(&mut self, rod: &A, map: &TangentMap<A>, t_n: f64, dt: f64) {
        let n = self.dofs();
        for j in 0..self.count() {
            let du = &mut self.du[j * n..(j + 1) * n];
            let dv = &mut self.dv[j * n..(j + 1) * n];
            for ((u, v), x) in du.iter_mut().zip(dv.iter_mut()).zip(map.solution(j)) {
                let du_next = x - *u;
                *v = 2.0 / dt * (du_next - *u) - *v;
                *u = du_next;
            }
            rod.zero_constrained(du);
            rod.zero_constrained(dv);
        }
        let counts = t_n >= self.count_from;
        self.orthonormalize(counts);
        if counts {
            self.counted_time += dt;
        }
    }

    /// Modified Gram-Schmidt in the weighted norm; with `book`, adds `ln |R_jj|` to the growth.
    fn orthonormalize(&mut self, book: bool) {
        let n = self.dofs();
        for j in 0..self.count() {
            let (done_u, rest_u) = self.du.split_at_mut(j * n);
            let (done_v, rest_v) = self.dv.split_at_mut(j * n);
            let (u, v) = (&mut rest_u[..n], &mut rest_v[..n]);
            for i in 0..j {
                let (qu, qv) = (&done_u[i * n..(i + 1) * n], &done_v[i * n..(i + 1) * n]);
                let p = weighted_dot((u, v), (qu, qv), self.tau, &self.duplicates);
                u.iter_mut().zip(qu).for_each(|(x, q)| *x -= p * q);
                v.iter_mut().zip(qv).for_each(|(x, q)| *x -= p * q);
            }
            let r = weighted_norm(u, v, self.tau, &self.duplicates);
            let inverse = 1.0 / r;
            u.iter_mut().chain(v.iter_mut()).for_each(|x| *x *= inverse);
            if book {
                self.log_growth[j] += libm::log(r);
            }
        }
    }

    /// Everything that defines the estimate, for snapshots: (vectors u, vectors v, growth,
    /// counted time).
    pub fn parts(&self) -> (&[f64], &[f64], &[f64], f64) {
        (&self.du, &self.dv, &self.log_growth, self.counted_time)
    }

    /// Restores what [`Lyapunov::parts`] gave (same `k` and dofs; checked by the caller).
    pub fn set_parts(&mut self, du: &[f64], dv: &[f64], log_growth: &[f64], counted_time: f64) {
        self.du.copy_from_slice(du);
        self.dv.copy_from_slice(dv);
        self.log_growth.copy_from_slice(log_growth);
        self.counted_time = counted_time;
    }

    /// Whether every number is finite (a blown-up tangent means a non-finite exponent).
    pub fn is_finite(&self) -> bool {
        self.du
            .iter()
            .chain(&self.dv)
            .chain(&self.log_growth)
            .all(|x| x.is_finite())
            && self.counted_time.is_finite()
    }
}
