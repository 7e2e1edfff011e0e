//! The implicit midpoint rule (paper eqs. 38-43, model.md):
//! `R(du) = M (2/dt^2 du - 2/dt v_n) + C du/dt + f_int(u_n + du/2) - f_ext(t_n + dt/2) = 0`,
//! solved by Newton with the exact Jacobian `2/dt^2 M + C/dt + K_T(u_n + du/2)/2`; then
//! `u_(n+1) = u_n + du`, `v_(n+1) = 2 du/dt - v_n`. Constrained dofs keep their values.
//! With [`Scheme::EnergyMomentum`] the internal force `f_int(u_n + du/2)` is replaced by the
//! discrete gradient of the element energies between `u_n` and `u_n + du`
//! ([`crate::model::Element::discrete_gradient`]): the step then conserves the energy of an
//! undamped, unforced rod and its linear and angular momentum exactly (to solver tolerance),
//! with rotations advanced by the Cayley rule: the angular velocity averaged over a step is
//! `2 tan(dw/2) / dt` instead of `dw / dt` (both second order; with the angle itself, exact energy
//! and exact angular momentum exclude each other: the director chord carries `sin(dw/2)` where
//! the rotation of the mid configuration carries `cos(dw/2)`, and `tan` reconciles them).
//! Newton uses the midpoint Jacobian (exact up to `O(du)`), so it converges fast but linearly.
//! All buffers live in [`Midpoint`]: a step allocates nothing.
mod residual;

use super::newton::{
    chord_correction, newton_correction, Factorization, NewtonFailure, NewtonSettings, NewtonStats,
};
use super::tangent_map::TangentMap;
use crate::model::{Assembly, LoadSet};
use crate::solver::vector::update_and_norm;
use residual::{motion, Tangent};
use serde::{Deserialize, Serialize};

/// Displacements and velocities of every dof (constrained ones included).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DynamicState {
    pub u: Vec<f64>,
    pub v: Vec<f64>,
}

impl DynamicState {
    pub fn at_rest(u: Vec<f64>) -> DynamicState {
        let v = vec![0.0; u.len()];
        DynamicState { u, v }
    }

    pub fn copy_from(&mut self, other: &DynamicState) {
        self.u.copy_from_slice(&other.u);
        self.v.copy_from_slice(&other.v);
    }
}

/// The time integration scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Scheme {
    /// The implicit midpoint rule of the paper (symplectic, conserves momenta).
    #[default]
    Midpoint,
    /// The energy-momentum scheme (discrete gradient, Cayley rotations): conserves energy,
    /// linear and angular momentum.
    EnergyMomentum,
}

/// A chord correction (old factorization) is kept, and the factorization reused, when it is at
/// most this fraction of the correction before it: it costs about a third of a Newton
/// correction (no tangent, no factorization) and must gain at least two decades for that.
const CHORD_CONTRACTION: f64 = 0.01;
/// Safety factor on the estimated error left after a correction (see [`error_after`]): the
/// estimate must pass the convergence test a hundred times over (with ten, the midpoint rule's
/// momenta on a stiff spinning rod, tests/suite/energy_momentum.rs, drift by 4e-10 in 300 steps
/// instead of staying at 1e-10).
const ESTIMATE_MARGIN: f64 = 0.01;

/// The error left in the iterate after applying the correction `c` that followed the
/// correction `previous`, for the midpoint rule's quadratically converging Newton. A converging
/// iteration contracts its error by about `rho = c / previous` per correction (quadratic Newton:
/// faster still), so after `c` about `rho / (1 - rho) c` is left (the geometric tail); this
/// estimate with the margin [`ESTIMATE_MARGIN`], but never more than `c` itself (the plain
/// test: a correction below the tolerance ends the iteration). Without a contraction
/// (`rho >= 1`, or no previous correction) it is `c`. At the sweeps' steps this ends most steps
/// one correction earlier than testing `c` itself, with an estimated error of 1e-17 of the
/// increment or less, against the tolerance of 1e-10.
fn error_after(c: f64, previous: Option<f64>) -> f64 {
    match previous {
        Some(p) if c < p => {
            let rho = c / p;
            (rho / (1.0 - rho) * c / ESTIMATE_MARGIN).min(c)
        }
        _ => c,
    }
}

#[derive(Clone, Debug)]
pub struct Midpoint<A: Assembly = crate::model::Rod> {
    pub settings: NewtonSettings,
    pub scheme: Scheme,
    /// Reuse the last factorized Jacobian for further corrections while they contract fast
    /// (see [`Midpoint::step`]); `false` gives plain Newton, one factorization per correction.
    pub reuse_factorization: bool,
    /// The Jacobian of the Newton corrections (and of the chord corrections that reuse it).
    jac: A::Matrix,
    /// The tangent map's systems that a step solves besides its own (Lyapunov exponents; see
    /// [`Midpoint::tangent_map_mut`]). Solving them does not change the step's result.
    tangents: TangentMap<A>,
    /// The Jacobian at the last chord correction's iterate, where the tangent map's
    /// refinement cannot be trusted ([`TangentMap::refine`]).
    linear: A::Matrix,
    /// `2/dt^2 M + C/dt` for `dynamic_dt`: the constant part of the Jacobian.
    dynamic_part: A::Matrix,
    dynamic_dt: f64,
    du: Vec<f64>,
    /// The state at which the residual was last evaluated.
    u_mid: Vec<f64>,
    /// Scratch: the energy-momentum scheme's inertia bracket.
    bracket: Vec<f64>,
    residual: Vec<f64>,
    /// What the residual's linear part takes from the start of the step: the inertia of the
    /// old velocity in the bracket, `-2/dt v_n`, and the loads at the midpoint, `-f_ext`.
    inertia: Vec<f64>,
    load: Vec<f64>,
    /// Held dofs whose rows of the equation of motion each step keeps, and those rows.
    held: Vec<usize>,
    held_rows: Vec<f64>,
    /// Rows of `dynamic_part` at the held dofs: (column, entry) pairs.
    held_stencils: Vec<Vec<(usize, f64)>>,
}

impl<A: Assembly> Midpoint<A> {
    pub fn new(rod: &A) -> Midpoint<A> {
        let n = rod.dofs();
        Midpoint {
            settings: NewtonSettings::tight(rod.length_scale()),
            scheme: Scheme::Midpoint,
            reuse_factorization: true,
            jac: rod.new_matrix(),
            tangents: TangentMap::default(),
            linear: rod.new_matrix(),
            dynamic_part: rod.new_matrix(),
            dynamic_dt: f64::NAN,
            du: vec![0.0; n],
            u_mid: vec![0.0; n],
            bracket: vec![0.0; n],
            residual: vec![0.0; n],
            inertia: vec![0.0; n],
            load: vec![0.0; n],
            held: Vec::new(),
            held_rows: Vec::new(),
            held_stencils: Vec::new(),
        }
    }

    /// Keep the rows of these (held) dofs of each step's equation of motion: see
    /// [`Midpoint::held_rows`].
    pub fn keep_rows(&mut self, dofs: &[usize]) {
        self.held = dofs.to_vec();
        self.held_rows = vec![0.0; dofs.len()];
        self.held_stencils = vec![Vec::new(); dofs.len()];
    }

    /// The rows of the kept dofs of the equation of motion `M (v_(n+1) - v_n)/dt + C du/dt +
    /// f(u) - f_ext(t_mid)` at the step just taken (`f` the scheme's internal force): on a held
    /// dof, the force its support exerts on the rod, averaged over the step. Newton's last
    /// residual (at the iterate before the last correction `c`, which leaves held rows
    /// unsolved) gives them but for `c`: its linear part `(2/dt^2 M + C/dt) c` is added; the
    /// internal force's part, about `K c / 2`, is left out. `c` passed the convergence test, so
    /// the rows hold to the solver's tolerance, like every other result of the step, at no cost
    /// (evaluating the internal force again at the held nodes would add 5-8 % to a step of a
    /// 10-element rod).
    pub fn held_rows(&self) -> &[f64] {
        &self.held_rows
    }

    /// One step of size `dt` from `t_n`. On failure `state` is untouched. `rod` must be the rod
    /// given to [`Midpoint::new`] (its mass and damping are cached per step size). Constrained
    /// dofs move by the increments in `prescribed` (`(dof, increment)`; dofs not listed stay).
    ///
    /// Newton with the exact Jacobian; after each Newton correction the next residual is first
    /// solved with the same factorization (a chord correction: a residual evaluation and two
    /// triangular sweeps, no tangent and no factorization). The chord correction is applied when
    /// it is at most [`CHORD_CONTRACTION`] of the correction before it (and the factorization is
    /// reused again); otherwise it is dropped and a Newton correction is computed at the same
    /// iterate. Right after a Newton correction `c` the Jacobian is off by `O(c)`, so the chord
    /// correction is the Newton correction up to `O(c^2)`. The iteration ends when the error
    /// left after a correction passes the convergence test: for the midpoint rule estimated from
    /// the contraction of the corrections ([`error_after`]), so at small steps one Newton and
    /// one chord correction are typical (measured: BuckledBeam, T/180, two corrections per
    /// step where testing the last correction itself took three).
    pub fn step(
        &mut self,
        rod: &A,
        loads: &LoadSet,
        state: &mut DynamicState,
        t_n: f64,
        dt: f64,
        prescribed: &[(usize, f64)],
    ) -> Result<NewtonStats, NewtonFailure> {
        debug_assert_eq!(
            rod.dofs(),
            self.du.len(),
            "a Midpoint serves the rod it was made for"
        );
        self.prepare(rod, loads, state, t_n, dt, prescribed);
        let mut stats = NewtonStats::default();
        let tangents = self.tangents.count() > 0;
        debug_assert!(
            !tangents || self.scheme == Scheme::Midpoint,
            "the tangent map is the midpoint rule's"
        );
        // The last correction applied, and whether the current factorization may be reused.
        let mut previous: Option<f64> = None;
        let mut reusable = false;
        // Forces with a kink (stops): a correction that takes one across is tested itself.
        let kinks = rod.has_kinks();
        // Whether the iteration ended on a Newton correction (the factorization is then at
        // the iterate before the last correction, the converged step to the solver's
        // tolerance) rather than a chord correction.
        let ended_on_newton;
        loop {
            if let (true, Some(last)) = (reusable, previous) {
                // With the tangent map, its element products at this iterate too (the same
                // residual bits).
                let tangent = if tangents {
                    Tangent::Elements
                } else {
                    Tangent::Skip
                };
                self.residual(rod, state, dt, tangent);
                // The tangent map's first refinement solved with the chord correction.
                let refinement = if tangents {
                    self.tangents.paired_refinement(rod)
                } else {
                    None
                };
                let (residual_norm, chord) =
                    chord_correction(rod, &self.jac, &mut self.residual, refinement).ok_or(
                        NewtonFailure::NonFinite {
                            iteration: stats.iterations,
                        },
                    )?;
                if chord <= CHORD_CONTRACTION * last {
                    let increment = self.apply_correction();
                    let mut error = self.error_after(chord, previous, true);
                    if kinks && self.crossed_kink(rod, state) {
                        error = error.max(chord);
                    }
                    let converged = self.settings.converged(error, increment);
                    stats.record(residual_norm, chord);
                    if converged {
                        ended_on_newton = false;
                        break;
                    }
                    previous = Some(chord);
                    self.check_iteration_limit(&stats, chord)?;
                    continue;
                }
            }
            self.residual(rod, state, dt, Tangent::Iteration);
            // The tangent map's first solve with the Newton correction (one system: paired).
            let first = if tangents {
                self.tangents.paired_first_solve()
            } else {
                None
            };
            let paired = first.is_some();
            let (residual_norm, correction) = newton_correction(
                rod,
                &mut self.jac,
                &mut self.residual,
                first,
                stats.iterations,
                Factorization::Symmetric,
            )?;
            if tangents {
                self.tangents.solved_first(&self.jac, paired);
            }
            let increment = self.apply_correction();
            stats.record(residual_norm, correction);
            stats.factorizations += 1;
            let mut error = self.error_after(correction, previous, false);
            if kinks && self.crossed_kink(rod, state) {
                error = error.max(correction);
            }
            if self.settings.converged(error, increment) {
                ended_on_newton = true;
                break;
            }
            self.check_iteration_limit(&stats, correction)?;
            previous = Some(correction);
            reusable = self.reuse_factorization;
        }
        self.update_held_rows();
        // Ended on a Newton correction, the factorization is at the iterate before it, which
        // passed the convergence test: the tangent map's first solve was exact.
        let exact = self.tangents.exact();
        if tangents && ended_on_newton && exact {
            self.tangents.solve(&self.jac);
        } else if tangents && !ended_on_newton && (exact || !self.tangents.refine(rod, &self.jac)) {
            self.tangents
                .solve_exactly(rod, &self.dynamic_part, &mut self.linear)?;
            stats.factorizations += 1;
            stats.tangent_factorizations += 1;
        }
        let dofs = state.u.iter_mut().zip(state.v.iter_mut()).zip(&self.du);
        match self.scheme {
            Scheme::Midpoint => {
                let rate = 2.0 / dt;
                for ((u, v), d) in dofs {
                    *u += d;
                    *v = rate * d - *v;
                }
            }
            Scheme::EnergyMomentum => {
                for (i, ((u, v), d)) in dofs.enumerate() {
                    *u += d;
                    *v = 2.0 * motion(self.scheme, i, *d) / dt - *v;
                }
            }
        }
        Ok(stats)
    }

    /// The error left after the correction `c` (a chord correction if `chord`), for the
    /// convergence test. The midpoint rule: estimated from the contraction ([`error_after`]).
    /// The energy-momentum scheme iterates with the midpoint Jacobian, so its Newton converges
    /// only linearly, and its point is an energy balance to round-off: there the correction
    /// itself must pass (a chord correction ten times over), which leaves errors at round-off.
    fn error_after(&self, c: f64, previous: Option<f64>, chord: bool) -> f64 {
        match (self.scheme, chord) {
            (Scheme::Midpoint, _) => error_after(c, previous),
            (Scheme::EnergyMomentum, true) => c / ESTIMATE_MARGIN,
            (Scheme::EnergyMomentum, false) => c,
        }
    }

    /// Whether the correction just applied (still in `residual`) took a kinked force across its
    /// kink, at the state where the scheme evaluates it (the midpoint, or the step's end).
    fn crossed_kink(&self, rod: &A, state: &DynamicState) -> bool {
        let w = match self.scheme {
            Scheme::Midpoint => 0.5,
            Scheme::EnergyMomentum => 1.0,
        };
        rod.crosses_kink(&state.u, &self.du, &self.residual[..self.du.len()], w)
    }

    fn check_iteration_limit(
        &self,
        stats: &NewtonStats,
        correction: f64,
    ) -> Result<(), NewtonFailure> {
        if stats.iterations >= self.settings.max_iterations || !correction.is_finite() {
            return Err(NewtonFailure::NotConverged {
                iterations: stats.iterations,
                correction,
            });
        }
        Ok(())
    }

    /// The tangent map's systems that the next steps solve besides their own (reserve them
    /// first with [`Midpoint::reserve_tangents`]); their solutions after a step.
    pub fn tangent_map_mut(&mut self) -> &mut TangentMap<A> {
        &mut self.tangents
    }

    pub fn tangent_map(&self) -> &TangentMap<A> {
        &self.tangents
    }

    /// Room for `count` tangent-map systems (allocates: call before stepping).
    pub fn reserve_tangents(&mut self, count: usize, rod: &A) {
        self.tangents.reserve(count, rod);
    }

    /// Adds the correction in `residual` to `du`; returns `|du|_inf` after it (NaN-aware).
    fn apply_correction(&mut self) -> f64 {
        let r = &self.residual[..self.du.len()];
        update_and_norm(&mut self.du, |i, d| d + r[i])
    }

    /// The displacement increment `du` of the last successful step.
    pub fn last_increment(&self) -> &[f64] {
        &self.du
    }

    /// Brings the kept rows from the last residual evaluation to the converged step: adds the
    /// linear part `(2/dt^2 M + C/dt) c` of the last correction `c` (in `residual`), from the
    /// rows of the cached `dynamic_part`.
    fn update_held_rows(&mut self) {
        for (row, entries) in self.held_rows.iter_mut().zip(&self.held_stencils) {
            let c = &self.residual;
            *row += entries.iter().map(|&(j, a)| a * c[j]).sum::<f64>();
        }
    }
}
