//! Two-node elements that carry a force along the current line between their nodes: truss bars
//! (`kind = "truss"`: the exact axial strain, so a shallow bar pair snaps through) and links
//! (a spring between two points of a structure). Both store `k / 2 (l - rest)^2`, `l` the
//! current distance of the nodes: a bar with `k = EA / L` and `rest = L` has the normal force
//! `N = EA (l / L - 1)`, exact for any rotation. A bar also has mass (the consistent mass of its
//! linear displacement field) and the material's viscous damping; a link may have a dashpot
//! along its current line (a force of the rate of its length, applied through
//! `Structure::add_state_damping`).
//!
//! Discrete gradient: with `r` the vector from the first node to the second and `V(l)`
//! quadratic in `l`, `f_b = k (l_a + l_b - 2 rest) / (l_a + l_b) (r_a + r_b) / 2` (and `-f_b`
//! on the first node) gives `f . (x_b - x_a) = V(l_b) - V(l_a)` exactly, since
//! `(r_a + r_b) . (r_b - r_a) = l_b^2 - l_a^2`: no division by a small difference.
//!
//! A cable (`kind = "cable"`, [`Axial::tension_only`]) stores `k / 2 max(0, l - rest)^2`: no
//! force while slack, the bar's force and tangent while taut (from `l = rest` on, its tangent
//! `k e e^T`). Its discrete gradient is `f_b = 2 G / (l_a + l_b) (r_a + r_b) / 2` with
//! `G = (V(l_b) - V(l_a)) / (l_b - l_a)` the one-sided energy's scalar discrete gradient
//! ([`crate::model::contact::one_sided_gradient`], in closed forms that never divide by a small
//! difference): its work is `G (l_b^2 - l_a^2) / (l_a + l_b) = V(l_b) - V(l_a)` exactly (for the
//! bar, `G = k (l_a + l_b - 2 rest) / 2`: the same formula).
use nalgebra::{Matrix2, Vector2};

/// A two-node axial element between the translations of two nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axial {
    /// The global node indices of its ends (their `u1`, `u2` dofs).
    pub nodes: [usize; 2],
    /// The reference positions of its ends.
    pub reference: [Vector2<f64>; 2],
    /// Axial stiffness `k` (a bar: `EA / L`).
    pub k: f64,
    /// Length at which it carries no force.
    pub rest: f64,
    /// Dashpot along its line (links), N s/m.
    pub c: f64,
    /// Mass per unit length and viscous damping per unit length (bars), times the reference
    /// length over 6: the coefficients of the consistent pattern `[[2, 1], [1, 2]]`.
    pub mass: f64,
    pub damping: f64,
    /// A cable: tension only (slack, no force, while shorter than `rest`).
    pub tension_only: bool,
}

impl Axial {
    /// A truss bar between `reference` positions: `k = EA / L`, `rest = L`, mass `rho A` and
    /// damping `d` per unit length.
    pub fn bar(
        nodes: [usize; 2],
        reference: [Vector2<f64>; 2],
        ea: f64,
        rho_a: f64,
        d: f64,
    ) -> Axial {
        let length = (reference[1] - reference[0]).norm();
        Axial {
            nodes,
            reference,
            k: ea / length,
            rest: length,
            c: 0.0,
            mass: rho_a * length / 6.0,
            damping: d * length / 6.0,
            tension_only: false,
        }
    }

    /// A massless link of stiffness `k` and dashpot `c`, free of force at the distance `rest`.
    pub fn link(
        nodes: [usize; 2],
        reference: [Vector2<f64>; 2],
        k: f64,
        c: f64,
        rest: f64,
    ) -> Axial {
        Axial {
            nodes,
            reference,
            k,
            rest,
            c,
            mass: 0.0,
            damping: 0.0,
            tension_only: false,
        }
    }

    /// This element as a cable: it carries tension only.
    pub fn cable(self) -> Axial {
        Axial {
            tension_only: true,
            ..self
        }
    }

    /// Its axial force for the stretch `l - rest` (tension positive): `k (l - rest)`, a cable's
    /// cut at zero.
    fn axial_force(&self, stretch: f64) -> f64 {
        if self.tension_only {
            crate::model::contact::one_sided_force(self.k, stretch)
        } else {
            self.k * stretch
        }
    }

    /// The vector from the first end to the second with the displacements `u`.
    pub fn chord(&self, u: &[f64]) -> Vector2<f64> {
        let [a, b] = self.nodes;
        self.reference[1] - self.reference[0]
            + Vector2::new(u[3 * b] - u[3 * a], u[3 * b + 1] - u[3 * a + 1])
    }

    /// The force along the line, tension positive: `k (l - rest)`.
    pub fn force(&self, u: &[f64]) -> f64 {
        self.axial_force(self.chord(u).norm() - self.rest)
    }

    pub fn strain_energy(&self, u: &[f64]) -> f64 {
        let stretch = self.chord(u).norm() - self.rest;
        if self.tension_only {
            return crate::model::contact::one_sided_energy(self.k, stretch);
        }
        0.5 * self.k * stretch * stretch
    }

    /// The force on its second end (the first gets the opposite): `N r / l`.
    pub fn end_force(&self, u: &[f64]) -> Vector2<f64> {
        let r = self.chord(u);
        let l = r.norm();
        self.axial_force(l - self.rest) / l * r
    }

    /// The force on the second end and the tangent block `K = k e e^T + N / l (I - e e^T)`
    /// (the element's tangent is `[[K, -K], [-K, K]]` on the two ends' translations).
    pub fn force_and_tangent(&self, u: &[f64]) -> (Vector2<f64>, Matrix2<f64>) {
        let r = self.chord(u);
        let l = r.norm();
        let e = r / l;
        if self.tension_only && l < self.rest {
            return (Vector2::zeros(), Matrix2::zeros());
        }
        let n = self.axial_force(l - self.rest);
        let outer = e * e.transpose();
        let tangent = self.k * outer + (n / l) * (Matrix2::identity() - outer);
        (n * e, tangent)
    }

    /// The discrete gradient between the states `ua` and `ub`: the force on the second end.
    pub fn discrete_gradient(&self, ua: &[f64], ub: &[f64]) -> Vector2<f64> {
        let (ra, rb) = (self.chord(ua), self.chord(ub));
        let (la, lb) = (ra.norm(), rb.norm());
        let factor = if self.tension_only {
            let (pa, pb) = (la - self.rest, lb - self.rest);
            2.0 * crate::model::contact::one_sided_gradient(self.k, pa, pb) / (la + lb)
        } else {
            self.k * (la + lb - 2.0 * self.rest) / (la + lb)
        };
        factor * 0.5 * (ra + rb)
    }

    /// Adds `scale` times the force `f` on the second end (and `-f` on the first) to `out`.
    pub fn add_end_force(&self, f: Vector2<f64>, out: &mut [f64], scale: f64) {
        let [a, b] = self.nodes;
        for k in 0..2 {
            out[3 * a + k] -= scale * f[k];
            out[3 * b + k] += scale * f[k];
        }
    }

    /// `out += scale * P x` for the consistent pattern `c [[2, 1], [1, 2]]` on both
    /// translations (`c` its mass or damping coefficient), or lumped `3 c` on the diagonal.
    pub fn add_pattern_times(&self, c: f64, lumped: bool, x: &[f64], out: &mut [f64], scale: f64) {
        if c == 0.0 {
            return;
        }
        let [a, b] = self.nodes;
        let (own, shared) = if lumped { (3.0, 0.0) } else { (2.0, 1.0) };
        for k in 0..2 {
            let (xa, xb) = (x[3 * a + k], x[3 * b + k]);
            out[3 * a + k] += scale * c * (own * xa + shared * xb);
            out[3 * b + k] += scale * c * (shared * xa + own * xb);
        }
    }

    /// `x^T P x` for that pattern.
    pub fn pattern_form(&self, c: f64, lumped: bool, x: &[f64]) -> f64 {
        if c == 0.0 {
            return 0.0;
        }
        let [a, b] = self.nodes;
        let (own, shared) = if lumped { (3.0, 0.0) } else { (2.0, 1.0) };
        (0..2)
            .map(|k| {
                let (xa, xb) = (x[3 * a + k], x[3 * b + k]);
                c * (own * (xa * xa + xb * xb) + 2.0 * shared * xa * xb)
            })
            .sum()
    }

    /// The rate of its length times the step: `e . (du_b - du_a)` with `e` the direction at
    /// the step's midpoint `u + towards du` (from the start `u_n`: `towards = 1/2`; from the
    /// end: `-1/2`), and that direction (for its dashpot over a step).
    pub fn stretch_increment(&self, u: &[f64], du: &[f64], towards: f64) -> (f64, Vector2<f64>) {
        let [a, b] = self.nodes;
        let d = Vector2::new(du[3 * b] - du[3 * a], du[3 * b + 1] - du[3 * a + 1]);
        let r = self.chord(u) + towards * d;
        let e = r / r.norm();
        (e.dot(&d), e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bar() -> Axial {
        Axial::bar(
            [0, 1],
            [Vector2::new(0.0, 0.0), Vector2::new(3.0, 0.4)],
            2.0e3,
            1.5,
            0.1,
        )
    }

    /// The force is the derivative of the energy and the tangent the derivative of the force
    /// (central differences, step 1e-6 of the length: errors O(h^2) ~ 1e-12 relative, checked
    /// at 1e-7 to leave room for round-off of the differences).
    #[test]
    fn force_and_tangent_are_derivatives() {
        let b = bar();
        let u = [0.1, -0.2, 0.0, 0.35, 0.05, 0.0];
        let (f, k) = b.force_and_tangent(&u);
        let h = 1e-6 * b.rest;
        for j in 0..2 {
            let (mut plus, mut minus) = (u, u);
            plus[3 + j] += h;
            minus[3 + j] -= h;
            let de = (b.strain_energy(&plus) - b.strain_energy(&minus)) / (2.0 * h);
            assert!((de - f[j]).abs() <= 1e-7 * f.norm(), "force {j}");
            let df = (b.force_and_tangent(&plus).0 - b.force_and_tangent(&minus).0) / (2.0 * h);
            for i in 0..2 {
                assert!(
                    (df[i] - k[(i, j)]).abs() <= 1e-7 * k.norm(),
                    "tangent {i} {j}"
                );
            }
        }
    }

    /// The discrete gradient's work over any increment is the change of energy (round-off of
    /// energies of size ~1e2: 1e-11), and it is the force at the midpoint to second order.
    #[test]
    fn discrete_gradient_is_exact() {
        let b = bar();
        let ua = [0.1, -0.2, 0.0, 0.35, 0.05, 0.0];
        let ub = [-0.4, 0.3, 0.0, 0.9, -0.6, 0.0];
        let f = b.discrete_gradient(&ua, &ub);
        let work =
            f[0] * ((ub[3] - ub[0]) - (ua[3] - ua[0])) + f[1] * ((ub[4] - ub[1]) - (ua[4] - ua[1]));
        let change = b.strain_energy(&ub) - b.strain_energy(&ua);
        assert!(
            (work - change).abs() <= 1e-11 * change.abs().max(1.0),
            "{work} vs {change}"
        );
        let tiny: Vec<f64> = ua
            .iter()
            .zip(&ub)
            .map(|(a, b)| a + 1e-5 * (b - a))
            .collect();
        let mid: Vec<f64> = ua.iter().zip(&tiny).map(|(a, b)| 0.5 * (a + b)).collect();
        let g = b.discrete_gradient(&ua, &tiny);
        assert!((g - b.end_force(&mid)).norm() <= 1e-8 * g.norm());
    }

    /// A cable: no force while slack, the bar's while taut; its discrete gradient's work is the
    /// change of its energy to round-off across the slack-taut kink (both ways), and within the
    /// taut range it is the bar's.
    #[test]
    fn a_cable_carries_tension_only() {
        let c = bar().cable();
        let slack = [0.1, -0.2, 0.0, 0.0, -0.2, 0.0];
        assert_eq!(c.force(&slack), 0.0);
        assert_eq!(c.strain_energy(&slack), 0.0);
        assert_eq!(
            c.force_and_tangent(&slack),
            (Vector2::zeros(), Matrix2::zeros())
        );
        let taut = [-0.4, 0.3, 0.0, 0.9, -0.6, 0.0];
        assert_eq!(c.force_and_tangent(&taut), bar().force_and_tangent(&taut));
        for (ua, ub) in [(slack, taut), (taut, slack)] {
            let f = c.discrete_gradient(&ua, &ub);
            let work = f[0] * ((ub[3] - ub[0]) - (ua[3] - ua[0]))
                + f[1] * ((ub[4] - ub[1]) - (ua[4] - ua[1]));
            let change = c.strain_energy(&ub) - c.strain_energy(&ua);
            assert!(
                (work - change).abs() <= 1e-11 * change.abs(),
                "{work} vs {change}"
            );
        }
        let tauter = [-0.5, 0.3, 0.0, 1.0, -0.6, 0.0];
        let (g, h) = (
            c.discrete_gradient(&taut, &tauter),
            bar().discrete_gradient(&taut, &tauter),
        );
        assert!((g - h).norm() <= 1e-12 * h.norm());
    }
}
