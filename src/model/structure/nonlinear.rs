//! The nonlinear terms on single dofs of a structure (docs/model.md, section 14): stops
//! (one-sided penalty supports with a contact dashpot) and the cubic parts of hardening and
//! softening springs, with the scalar laws of [`crate::model::contact`]. They sit on master dofs
//! (a joint's, or a member's own node), so their rows are added to the folded vectors and their
//! stiffness to the diagonal of any system matrix. A structure without them skips them (an empty
//! list: no pass over anything, the same bits).
use crate::model::contact::{
    cubic_energy, cubic_force, cubic_gradient, cubic_gradient_slope, cubic_stiffness, dashpot,
    one_sided_energy, one_sided_force, one_sided_gradient, one_sided_gradient_slope,
    one_sided_stiffness, positive_fraction,
};
use crate::solver::sparse_blocks::SparseBlocks;
use crate::solver::BlockTridiagonal;

/// A matrix the nodal terms add their stiffness to, on its diagonal.
pub trait Diagonal {
    fn add_to_diagonal(&mut self, dof: usize, value: f64);
}

impl Diagonal for BlockTridiagonal {
    fn add_to_diagonal(&mut self, dof: usize, value: f64) {
        self.add_diagonal(dof, value);
    }
}

impl Diagonal for SparseBlocks {
    fn add_to_diagonal(&mut self, dof: usize, value: f64) {
        self.add_diagonal(dof, value);
    }
}

impl Diagonal for super::StructureMatrix {
    fn add_to_diagonal(&mut self, dof: usize, value: f64) {
        crate::solver::SystemMatrix::add_diagonal(self, dof, value);
    }
}

/// The fraction of a stop's stiffness its open state keeps in a static Newton iteration's
/// Jacobian (never in a residual): a part held only by stops that are open in the current
/// iterate (a beam above a stop, settling onto it under its weight) then has a regular
/// Jacobian, whose correction moves it towards the stop; the correction is cut where the stop
/// is reached ([`Nonlinear::static_step_limit`]).
pub const OPEN_STIFFNESS: f64 = 1e-6;

/// A one-sided support on one dof: penetration `p = sign u - gap`, stored energy
/// `k/2 max(0, p)^2`, a dashpot `c` on the rate of `max(0, p)`, its total force cut at zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stop {
    pub dof: usize,
    /// +1: the stop is on the positive side of the dof (touched at `u = gap`), -1: the negative.
    pub sign: f64,
    pub gap: f64,
    pub k: f64,
    pub c: f64,
}

impl Stop {
    pub fn penetration(&self, u: &[f64]) -> f64 {
        self.sign * u[self.dof] - self.gap
    }
}

/// The cubic part `k3 (u - b)^3` of a spring on `dof`, `b` its base (at the start and the end of
/// the current step; both the same outside a step); `k` its linear part (for the check that
/// its stiffness stays positive).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicSpring {
    /// The caller's index of the spring it is part of.
    pub spring: usize,
    pub dof: usize,
    pub k: f64,
    pub k3: f64,
    pub base: [f64; 2],
}

impl CubicSpring {
    /// The stretch `u - b` at state `u` with the base at `b`.
    fn stretch(&self, u: &[f64], b: f64) -> f64 {
        u[self.dof] - b
    }

    /// The base at the step's midpoint.
    fn mid_base(&self) -> f64 {
        0.5 * (self.base[0] + self.base[1])
    }

    /// Its stiffness `k + 3 k3 r^2` at the stretch `r`.
    pub fn stiffness(&self, r: f64) -> f64 {
        self.k + cubic_stiffness(self.k3, r)
    }
}

/// What a stop did over a step: the spring's and the dashpot's force (along `sign`, >= 0 in
/// total) and the fraction of the step in contact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StopStep {
    pub spring: f64,
    pub dashpot: f64,
    pub contact: f64,
}

/// A structure's stops and cubic springs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Nonlinear {
    pub stops: Vec<Stop>,
    pub cubic: Vec<CubicSpring>,
    /// Whether the steps apply the discrete gradient (energy-momentum scheme): a contact
    /// dashpot cuts the total force of the spring force the step applies.
    pub energy_momentum: bool,
    /// The axial elements that are cables (tension only: a kink where they tighten).
    pub cables: Vec<usize>,
}

impl Nonlinear {
    pub fn is_empty(&self) -> bool {
        self.stops.is_empty() && self.cubic.is_empty()
    }

    /// How many tangents a residual evaluation keeps (one per stop, then per cubic spring).
    pub fn len(&self) -> usize {
        self.stops.len() + self.cubic.len()
    }

    pub fn has_dashpots(&self) -> bool {
        self.stops.iter().any(|s| s.c > 0.0)
    }

    /// Whether any term has a kink (a stop, a cable).
    pub fn has_kinks(&self) -> bool {
        !self.stops.is_empty() || !self.cables.is_empty()
    }

    /// Adds the forces at `u` (cubic springs: with the base at the step's midpoint) to `f`, their
    /// stiffness times `scale` to `jac` and into `kept` where given.
    pub fn add_force<M: Diagonal>(
        &self,
        u: &[f64],
        f: &mut [f64],
        mut jac: Option<(&mut M, f64)>,
        mut kept: Option<&mut [f64]>,
    ) {
        for (i, s) in self.stops.iter().enumerate() {
            let p = s.penetration(u);
            let k = one_sided_stiffness(s.k, p);
            if p > 0.0 {
                f[s.dof] += s.sign * one_sided_force(s.k, p);
            }
            if let Some((m, scale)) = jac.as_mut() {
                if k != 0.0 {
                    m.add_to_diagonal(s.dof, *scale * k);
                }
            }
            if let Some(kept) = kept.as_deref_mut() {
                kept[i] = k;
            }
        }
        let first = self.stops.len();
        for (i, s) in self.cubic.iter().enumerate() {
            let r = s.stretch(u, s.mid_base());
            f[s.dof] += cubic_force(s.k3, r);
            let k = cubic_stiffness(s.k3, r);
            if let Some((m, scale)) = jac.as_mut() {
                m.add_to_diagonal(s.dof, *scale * k);
            }
            if let Some(kept) = kept.as_deref_mut() {
                kept[first + i] = k;
            }
        }
    }

    /// Adds the discrete gradient between `ua` and `ub` (cubic springs: the stretches with the
    /// base at the step's start and end) to `f`, and `2 scale` times its derivative with respect
    /// to `ub` to `jac` where given (the structure's convention: `scale` multiplies half a
    /// tangent).
    pub fn add_gradient<M: Diagonal>(
        &self,
        ua: &[f64],
        ub: &[f64],
        f: &mut [f64],
        mut jac: Option<(&mut M, f64)>,
    ) {
        for s in &self.stops {
            let (pa, pb) = (s.penetration(ua), s.penetration(ub));
            if pa <= 0.0 && pb <= 0.0 {
                continue;
            }
            f[s.dof] += s.sign * one_sided_gradient(s.k, pa, pb);
            if let Some((m, scale)) = jac.as_mut() {
                m.add_to_diagonal(s.dof, 2.0 * *scale * one_sided_gradient_slope(s.k, pa, pb));
            }
        }
        for s in &self.cubic {
            let (a, b) = (s.stretch(ua, s.base[0]), s.stretch(ub, s.base[1]));
            f[s.dof] += cubic_gradient(s.k3, a, b);
            if let Some((m, scale)) = jac.as_mut() {
                m.add_to_diagonal(s.dof, 2.0 * *scale * cubic_gradient_slope(s.k3, a, b));
            }
        }
    }

    /// Their stored energy at `u` (cubic springs: with the base at the end of the step).
    pub fn energy(&self, u: &[f64]) -> f64 {
        let stops: f64 = (self.stops.iter())
            .map(|s| one_sided_energy(s.k, s.penetration(u)))
            .sum();
        let cubic: f64 = (self.cubic.iter())
            .map(|s| cubic_energy(s.k3, s.stretch(u, s.base[1])))
            .sum();
        stops + cubic
    }

    /// `out += scale (K1 - K0) y` from two sets of kept tangents.
    pub fn add_tangent_change(
        &self,
        (k1, k0): (&[f64], &[f64]),
        y: &[f64],
        out: &mut [f64],
        scale: f64,
    ) {
        for ((d, a), b) in self.dofs().zip(k1).zip(k0) {
            if a != b {
                out[d] += scale * (a - b) * y[d];
            }
        }
    }

    /// `jac += scale K` from kept tangents.
    pub fn add_kept<M: Diagonal>(&self, jac: &mut M, kept: &[f64], scale: f64) {
        for (d, &k) in self.dofs().zip(kept) {
            if k != 0.0 {
                jac.add_to_diagonal(d, scale * k);
            }
        }
    }

    /// The dof of each kept tangent.
    fn dofs(&self) -> impl Iterator<Item = usize> + '_ {
        (self.stops.iter().map(|s| s.dof)).chain(self.cubic.iter().map(|s| s.dof))
    }

    /// The spring force a step from `ua` to `ub` applies on a stop (the scheme's: at the
    /// midpoint, or the discrete gradient), along its sign.
    fn spring_force(&self, s: &Stop, pa: f64, pb: f64) -> f64 {
        if self.energy_momentum {
            one_sided_gradient(s.k, pa, pb)
        } else {
            one_sided_force(s.k, 0.5 * (pa + pb))
        }
    }

    /// Its derivative with respect to `pb`.
    fn spring_slope(&self, s: &Stop, pa: f64, pb: f64) -> f64 {
        if self.energy_momentum {
            one_sided_gradient_slope(s.k, pa, pb)
        } else {
            0.5 * one_sided_stiffness(s.k, 0.5 * (pa + pb))
        }
    }

    /// The contact dashpots of a step of size `dt` from `u_n` by `du` (see
    /// [`crate::model::contact::dashpot`]): their forces into `out`, their derivatives into `jac`.
    pub fn add_damping<M: Diagonal>(
        &self,
        u_n: &[f64],
        du: &[f64],
        dt: f64,
        out: &mut [f64],
        mut jac: Option<&mut M>,
    ) {
        for s in self.stops.iter().filter(|s| s.c > 0.0) {
            let pa = s.penetration(u_n);
            let pb = pa + s.sign * du[s.dof];
            if pa <= 0.0 && pb <= 0.0 {
                continue;
            }
            let (fd, cut) = dashpot(s.c, self.spring_force(s, pa, pb), pa, pb, dt);
            out[s.dof] += s.sign * fd;
            if let Some(m) = jac.as_deref_mut() {
                let slope = if cut {
                    -self.spring_slope(s, pa, pb)
                } else if pb > 0.0 {
                    s.c / dt
                } else {
                    0.0
                };
                if slope != 0.0 {
                    m.add_to_diagonal(s.dof, slope);
                }
            }
        }
    }

    /// What a stop did over the step that ended at `u` with the increment `du` and size `dt`.
    pub fn stop_step(&self, s: &Stop, u: &[f64], du: &[f64], dt: f64) -> StopStep {
        let pb = s.penetration(u);
        let pa = pb - s.sign * du[s.dof];
        if pa <= 0.0 && pb <= 0.0 {
            return StopStep::default();
        }
        let spring = self.spring_force(s, pa, pb);
        let dashpot = if s.c > 0.0 {
            dashpot(s.c, spring, pa, pb, dt).0
        } else {
            0.0
        };
        StopStep {
            spring,
            dashpot,
            contact: positive_fraction(pa, pb),
        }
    }

    /// What the contact dashpots dissipated over that step: `F_d (p_b - p_a) >= 0` each.
    pub fn dissipation(&self, u: &[f64], du: &[f64], dt: f64) -> f64 {
        (self.stops.iter().filter(|s| s.c > 0.0))
            .map(|s| self.stop_step(s, u, du, dt).dashpot * s.sign * du[s.dof])
            .sum()
    }

    /// Whether a stop is on the other side of its kink at `u + w du` than at `u + w (du - c)`:
    /// the iterate before the correction `c` and after it.
    pub fn crosses_kink(&self, u: &[f64], du: &[f64], c: &[f64], w: f64) -> bool {
        self.stops.iter().any(|s| {
            let after = s.sign * (u[s.dof] + w * du[s.dof]) - s.gap;
            let before = after - s.sign * w * c[s.dof];
            (after >= 0.0) != (before >= 0.0)
        })
    }

    /// A static Newton iteration's Jacobian at `u`: the open stops' [`OPEN_STIFFNESS`].
    pub fn add_static_regularization<M: Diagonal>(&self, u: &[f64], jac: &mut M) {
        for s in self.stops.iter().filter(|s| s.penetration(u) < 0.0) {
            jac.add_to_diagonal(s.dof, OPEN_STIFFNESS * s.k);
        }
    }

    /// The fraction of a static Newton correction `delta` from `u` that reaches the first open
    /// stop it would close (1 when it closes none).
    pub fn static_step_limit(&self, u: &[f64], delta: &[f64]) -> f64 {
        let mut t: f64 = 1.0;
        for s in &self.stops {
            let p = s.penetration(u);
            let dp = s.sign * delta[s.dof];
            if p < 0.0 && p + dp > 0.0 {
                // Just past the kink (by 1e-6 of the way there): the next iteration sees the
                // stop closed.
                t = t.min(-p / dp * (1.0 + 1e-6));
            }
        }
        t
    }
}

/// The structure's calls into its nonlinear terms, each skipped when there are none.
impl super::Structure {
    pub(super) fn add_nonlinear_force<M: Diagonal>(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: Option<(&mut M, f64)>,
        kept: Option<&mut [f64]>,
    ) {
        if !self.nonlinear.is_empty() {
            self.nonlinear.add_force(u, f, jac, kept);
        }
    }

    pub(super) fn add_nonlinear_gradient<M: Diagonal>(
        &self,
        ua: &[f64],
        ub: &[f64],
        f: &mut [f64],
        jac: Option<(&mut M, f64)>,
    ) {
        if !self.nonlinear.is_empty() {
            self.nonlinear.add_gradient(ua, ub, f, jac);
        }
    }

    pub(super) fn add_nonlinear_change(
        &self,
        (k1, k0): (&[f64], &[f64]),
        y: &[f64],
        out: &mut [f64],
        scale: f64,
    ) {
        if !self.nonlinear.is_empty() {
            self.nonlinear.add_tangent_change((k1, k0), y, out, scale);
        }
    }

    pub(super) fn nonlinear_energy(&self, u: &[f64]) -> f64 {
        if self.nonlinear.is_empty() {
            0.0
        } else {
            self.nonlinear.energy(u)
        }
    }

    /// Sets whether the steps apply the discrete gradient (the energy-momentum scheme), which
    /// the contact dashpots' cut refers to.
    pub fn set_energy_momentum(&mut self, on: bool) {
        self.nonlinear.energy_momentum = on;
    }

    /// Sets the base of cubic spring `i` at the start and the end of the next step.
    pub fn set_cubic_base(&mut self, i: usize, start: f64, end: f64) {
        self.nonlinear.cubic[i].base = [start, end];
    }
}
