//! The scalar laws of the nonlinear supports (docs/model.md, section 14): a one-sided penalty on
//! the positive part of a penetration `p` (a stop, a cable's stretch) and the cubic part of a
//! hardening or softening spring, each with its energy, force, stiffness and the exact
//! discrete gradient the energy-momentum scheme applies (`(V(b) - V(a)) / (b - a)`, in closed
//! forms that never divide by a small difference).
//!
//! **One-sided penalty.** `V(p) = k/2 max(0, p)^2`: the force `k max(0, p)` is continuous and
//! Lipschitz in `p` (the motion it drives is well posed, and a Newton iteration on it is
//! semi-smooth); its stiffness jumps from 0 to `k` at `p = 0`, taken as `k` from `p = 0` on (a
//! stop that just touches, a cable at its length, stiffens the static tangent).
//!
//! **A contact dashpot** acts on the rate of the positive part `p+ = max(0, p)`: over a step from
//! `p_a` to `p_b`, `q = p_b+ - p_a+`, the force `c q / dt` (in continuous time `c dp/dt` while in
//! contact, nothing outside), added to the spring's force `F_s >= 0` and cut at zero so that the
//! stop never pulls: `F = max(0, F_s + c q / dt)`. The dashpot's part `F_d = F - F_s` does the
//! work `F_d (p_b - p_a) >= 0` on the step: where the cut is inactive it is `c q (p_b - p_a) / dt`
//! and `q` has the sign of `p_b - p_a` (`p+` does not decrease with `p`); where the cut is active,
//! `F_s + c q / dt < 0` needs `q < 0`, so `p_b < p_a`, and `F_d = -F_s <= 0`. `q` is continuous
//! in the state (a step that enters contact sees only the penetration reached), so the step's
//! residual has no jump at the instant of contact.
//!
//! **Cubic spring part.** `V(r) = k3/4 r^4`, force `k3 r^3`, stiffness `3 k3 r^2`, discrete
//! gradient `k3/4 (a + b) (a^2 + b^2)` (`= k3/4 (a^3 + a^2 b + a b^2 + b^3)`).

/// `k/2 max(0, p)^2`.
pub fn one_sided_energy(k: f64, p: f64) -> f64 {
    let p = p.max(0.0);
    0.5 * k * p * p
}

/// `k max(0, p)`.
pub fn one_sided_force(k: f64, p: f64) -> f64 {
    k * p.max(0.0)
}

/// `k` from `p = 0` on, else 0 (the semi-smooth Newton's choice at the kink).
pub fn one_sided_stiffness(k: f64, p: f64) -> f64 {
    if p >= 0.0 {
        k
    } else {
        0.0
    }
}

/// The discrete gradient `(V(p_b) - V(p_a)) / (p_b - p_a)` of the one-sided energy (its
/// derivative where `p_a = p_b`). Across the kink the difference in the denominator is at least
/// the positive one of `p_a`, `p_b`, so nothing small divides.
pub fn one_sided_gradient(k: f64, pa: f64, pb: f64) -> f64 {
    match (pa > 0.0, pb > 0.0) {
        (false, false) => 0.0,
        (true, true) => 0.5 * k * (pa + pb),
        (false, true) => 0.5 * k * pb * pb / (pb - pa),
        (true, false) => 0.5 * k * pa * pa / (pa - pb),
    }
}

/// The derivative of [`one_sided_gradient`] with respect to `p_b`.
pub fn one_sided_gradient_slope(k: f64, pa: f64, pb: f64) -> f64 {
    match (pa > 0.0, pb > 0.0) {
        (false, false) => 0.0,
        (true, true) => 0.5 * k,
        (false, true) => {
            let d = pb - pa;
            0.5 * k * pb * (pb - 2.0 * pa) / (d * d)
        }
        (true, false) => {
            let d = pa - pb;
            0.5 * k * pa * pa / (d * d)
        }
    }
}

/// The fraction of a step over which `p`, linear from `p_a` to `p_b`, is positive.
pub fn positive_fraction(pa: f64, pb: f64) -> f64 {
    match (pa > 0.0, pb > 0.0) {
        (false, false) => 0.0,
        (true, true) => 1.0,
        (false, true) => pb / (pb - pa),
        (true, false) => pa / (pa - pb),
    }
}

/// A contact dashpot over a step (see the module doc): with the spring's force `spring >= 0`,
/// the penetrations `p_a`, `p_b` at the step's ends and its size `dt`, the dashpot's part
/// `F_d = max(0, spring + c q / dt) - spring` of the total force, `q = p_b+ - p_a+`, and
/// whether the cut at zero is active.
pub fn dashpot(c: f64, spring: f64, pa: f64, pb: f64, dt: f64) -> (f64, bool) {
    let q = pb.max(0.0) - pa.max(0.0);
    let total = spring + c * q / dt;
    if total > 0.0 {
        (c * q / dt, false)
    } else {
        (-spring, true)
    }
}

/// `k3/4 r^4`.
pub fn cubic_energy(k3: f64, r: f64) -> f64 {
    let r2 = r * r;
    0.25 * k3 * r2 * r2
}

/// `k3 r^3`.
pub fn cubic_force(k3: f64, r: f64) -> f64 {
    k3 * r * r * r
}

/// `3 k3 r^2`.
pub fn cubic_stiffness(k3: f64, r: f64) -> f64 {
    3.0 * k3 * r * r
}

/// `(V(b) - V(a)) / (b - a) = k3/4 (a + b) (a^2 + b^2)`.
pub fn cubic_gradient(k3: f64, a: f64, b: f64) -> f64 {
    0.25 * k3 * (a + b) * (a * a + b * b)
}

/// The derivative of [`cubic_gradient`] with respect to `b`: `k3/4 (a^2 + 2 a b + 3 b^2)`.
pub fn cubic_gradient_slope(k3: f64, a: f64, b: f64) -> f64 {
    0.25 * k3 * (a * a + 2.0 * a * b + 3.0 * b * b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The discrete gradients' work is the change of energy to round-off (1e-14 of the
    /// energies, a few operations each), across the kink and on either side of it; their slopes
    /// are the derivatives (central differences, step 1e-6: O(h^2) = 1e-12, checked at 1e-8).
    #[test]
    fn gradients_are_exact_and_slopes_their_derivatives() {
        let k = 3.0e5;
        let pairs = [
            (-0.2, 0.3),
            (0.3, -0.2),
            (0.1, 0.4),
            (-0.4, -0.1),
            (1e-9, 0.5),
            (-1e-12, 2e-12),
            (0.7, 0.7),
        ];
        for (pa, pb) in pairs {
            let dv = one_sided_energy(k, pb) - one_sided_energy(k, pa);
            let work = one_sided_gradient(k, pa, pb) * (pb - pa);
            let scale = one_sided_energy(k, pa.abs().max(pb.abs()));
            assert!(
                (work - dv).abs() <= 1e-14 * scale,
                "{pa} {pb}: {work} vs {dv}"
            );
            let k3 = -2.5e7;
            let dv = cubic_energy(k3, pb) - cubic_energy(k3, pa);
            let work = cubic_gradient(k3, pa, pb) * (pb - pa);
            let scale = cubic_energy(k3, pa.abs().max(pb.abs())).abs();
            assert!((work - dv).abs() <= 1e-14 * scale, "cubic {pa} {pb}");
        }
        // At equal states the gradient is the force.
        assert_eq!(one_sided_gradient(k, 0.7, 0.7), one_sided_force(k, 0.7));
        assert_eq!(cubic_gradient(2.0, 0.3, 0.3), cubic_force(2.0, 0.3));
        let h = 1e-6;
        for (pa, pb) in [(-0.2, 0.3), (0.3, -0.2), (0.1, 0.4), (0.5, 0.2)] {
            let fd =
                (one_sided_gradient(k, pa, pb + h) - one_sided_gradient(k, pa, pb - h)) / (2.0 * h);
            let exact = one_sided_gradient_slope(k, pa, pb);
            assert!((fd - exact).abs() <= 1e-8 * k, "{pa} {pb}: {fd} vs {exact}");
            let fd =
                (cubic_gradient(7.0, pa, pb + h) - cubic_gradient(7.0, pa, pb - h)) / (2.0 * h);
            assert!((fd - cubic_gradient_slope(7.0, pa, pb)).abs() <= 1e-8);
        }
    }

    /// The contact fraction of a linear penetration, and the dashpot's work never negative
    /// over every sign pattern of the step (the module doc's argument).
    #[test]
    fn fraction_and_dashpot_dissipate() {
        assert_eq!(positive_fraction(-1.0, 3.0), 0.75);
        assert_eq!(positive_fraction(3.0, -1.0), 0.75);
        assert_eq!(positive_fraction(-1.0, -3.0), 0.0);
        assert_eq!(positive_fraction(1.0, 3.0), 1.0);
        let (k, c, dt) = (1e4, 50.0, 1e-3);
        for pa in [-2e-3, -1e-4, 0.0, 1e-4, 2e-3] {
            for pb in [-2e-3, -1e-4, 0.0, 1e-4, 2e-3] {
                let spring = one_sided_gradient(k, pa, pb);
                let (fd, cut) = dashpot(c, spring, pa, pb, dt);
                assert!(fd * (pb - pa) >= 0.0, "{pa} {pb}");
                assert!(spring + fd >= 0.0, "never pulls");
                if cut {
                    assert_eq!(spring + fd, 0.0);
                }
            }
        }
    }
}
