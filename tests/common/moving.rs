//! The modal series of a constant force crossing a simply supported Euler-Bernoulli beam
//! (Fryba), undamped, from rest.

use std::f64::consts::PI;

/// A simply supported beam of span `length`, bending stiffness `ei`, mass per length `mu`,
/// crossed by the force `force` (along -e2) at `speed`.
pub struct Crossing {
    pub length: f64,
    pub ei: f64,
    pub mu: f64,
    pub force: f64,
    pub speed: f64,
}

impl Crossing {
    /// The deflection (along e2) at `x` a time `t` after the force entered, summed over 60
    /// modes: `q_j'' + omega_j^2 q_j = 2 P sin(W_j t) / (mu L)`, `W_j = j pi v / L`, from rest:
    /// `q_j = 2 P / (mu L) (sin(W_j t) - W_j / omega_j sin(omega_j t)) / (omega_j^2 - W_j^2)`.
    pub fn deflection(&self, x: f64, t: f64) -> f64 {
        (1..=60)
            .map(|j| {
                let k = j as f64 * PI / self.length;
                let omega = k * k * (self.ei / self.mu).sqrt();
                let w = k * self.speed;
                let q = 2.0 * self.force / (self.mu * self.length)
                    * ((w * t).sin() - w / omega * (omega * t).sin())
                    / (omega * omega - w * w);
                -q * (k * x).sin()
            })
            .sum()
    }
}
