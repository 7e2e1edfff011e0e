//! Points of a rod: where an arc length falls (element and shape-function weights), the node
//! nearest to it, and the nodal forces of simple loads there.
use super::{PointOnRod, Rod, U2};

impl Rod {
    /// The point at arc length `s` (clamped to the rod).
    pub fn point_at(&self, s: f64) -> PointOnRod {
        let n = self.elements.len();
        if !self.uniform {
            let s = s.clamp(0.0, self.curve.length());
            let element = self.node_s.partition_point(|&x| x <= s).clamp(1, n) - 1;
            let (a, b) = (self.node_s[element], self.node_s[element + 1]);
            let local = ((s - a) / (b - a)).clamp(0.0, 1.0);
            return PointOnRod {
                element,
                weights: (1.0 - local, local),
            };
        }
        let total = self.curve.length();
        let x = (s / total * n as f64).clamp(0.0, n as f64);
        let element = (x.floor() as usize).min(n - 1);
        let local = x - element as f64;
        PointOnRod {
            element,
            weights: (1.0 - local, local),
        }
    }

    /// The node nearest to arc length `s`.
    pub fn node_at(&self, s: f64) -> usize {
        let after = self
            .node_s
            .partition_point(|&x| x < s)
            .min(self.last_node());
        match after.checked_sub(1) {
            Some(before) if s - self.node_s[before] < self.node_s[after] - s => before,
            _ => after,
        }
    }

    /// The point `s = S/2`, where the crown load acts and the outputs are taken.
    pub fn midspan(&self) -> PointOnRod {
        self.point_at(0.5 * self.curve.length())
    }

    /// Dof `k` of a nodal vector interpolated at `p`.
    pub fn interpolate(&self, x: &[f64], p: PointOnRod, k: usize) -> f64 {
        let (na, nb) = p.weights;
        na * x[3 * p.element + k] + nb * x[3 * p.element + 3 + k]
    }

    /// Nodal forces of a unit uniform load per unit length along `-e2` (fixed direction).
    pub fn add_uniform_transverse_load(&self, out: &mut [f64], magnitude: f64) {
        for (e, el) in self.elements.iter().enumerate() {
            let half = 0.5 * magnitude * el.length;
            out[3 * e + U2] -= half;
            out[3 * (e + 1) + U2] -= half;
        }
    }

    /// Nodal forces of a point force of `magnitude` along `-e2` at `p`.
    pub fn add_point_transverse_load(&self, out: &mut [f64], p: PointOnRod, magnitude: f64) {
        let (na, nb) = p.weights;
        out[3 * p.element + U2] -= na * magnitude;
        out[3 * (p.element + 1) + U2] -= nb * magnitude;
    }
}
