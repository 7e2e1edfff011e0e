//! Stress resultants of the cross-section along the rod, from the elements' own strains and
//! resultants (docs/model.md, "Section quantities"): only when read, never in the time step.
//!
//! Inside an element: its eliminated forces `(S1, S2)` (constant per element, normal and shear
//! force in the section's frame) and its bending moment `EI (wb - wa) / l`. At a node: the force
//! and moment each element transmits to it (the node's rows of its internal force, as the part
//! of the rod beyond the node acts on the part before it), the force rotated into the node's
//! section frame; at a node shared by two elements the mean of the two, at an end node the one
//! element's (which balances the reaction or the end load exactly).
use super::rod::{Rod, ROTATION, U1, U2};

/// Normal force `n`, shear force `q` (components of the section force along the directors `d1`,
/// `d2`) and bending moment `m` (counter-clockwise), as the part of the rod beyond the section
/// (larger arc length) acts on the part before it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SectionForces {
    pub n: f64,
    pub q: f64,
    pub m: f64,
}

impl SectionForces {
    fn mean(a: SectionForces, b: SectionForces) -> SectionForces {
        SectionForces {
            n: 0.5 * (a.n + b.n),
            q: 0.5 * (a.q + b.q),
            m: 0.5 * (a.m + b.m),
        }
    }
}

/// Stations closer to a node than this (in element lengths) read the node's value.
const NODE_TOLERANCE: f64 = 1e-9;

impl Rod {
    /// Element `e`'s own resultants: `(S1, S2) = C b / l` and `EI (wb - wa) / l`.
    pub fn element_section_forces(&self, u: &[f64], e: usize) -> SectionForces {
        let ue = Self::element_dofs(u, e);
        let el = &self.elements[e];
        let s = el.stress_resultants(&self.section, &ue);
        SectionForces {
            n: s[0],
            q: s[1],
            m: self.section.ei * (ue[5] - ue[2]) / el.length,
        }
    }

    /// The force and moment element `e` transmits to its node `end` (0: first, 1: second), in
    /// the node's section frame (`d1` at the angle `alpha + w` of the node). The element's
    /// internal force rows are what the node exerts on it; beyond its second node the rod acts
    /// on the element with them, before its first node with their opposite.
    pub fn element_node_forces(&self, u: &[f64], e: usize, end: usize) -> SectionForces {
        let f = self.element_internal_force(e, &Self::element_dofs(u, e));
        let (offset, sign) = if end == 0 { (0, -1.0) } else { (3, 1.0) };
        let node = e + end;
        let (fx, fy) = (sign * f[offset + U1], sign * f[offset + U2]);
        let beta = self.reference_angle(self.node_s[node]) + u[3 * node + ROTATION];
        let (sin, cos) = libm::sincos(beta);
        SectionForces {
            n: fx * cos + fy * sin,
            q: -fx * sin + fy * cos,
            m: sign * f[offset + ROTATION],
        }
    }

    /// The section forces at arc length `s` (clamped to the rod): the element's own inside an
    /// element, at a node the mean of what its elements transmit to it.
    pub fn section_forces_at(&self, u: &[f64], s: f64) -> SectionForces {
        let n = self.elements.len();
        let point = self.point_at(s);
        let local = point.weights.1;
        // The arc length's round-off in element units grows with the element count.
        let tolerance = NODE_TOLERANCE * n as f64;
        let node = if local <= tolerance {
            point.element
        } else if local >= 1.0 - tolerance {
            point.element + 1
        } else {
            return self.element_section_forces(u, point.element);
        };
        match node {
            0 => self.element_node_forces(u, 0, 0),
            i if i == n => self.element_node_forces(u, n - 1, 1),
            i => SectionForces::mean(
                self.element_node_forces(u, i - 1, 1),
                self.element_node_forces(u, i, 0),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ReferenceCurve, Section};

    /// A straight rod stretched uniformly: `N = EA eps` inside the elements, at the interior
    /// nodes and at the ends; no shear force, no moment (round-off).
    #[test]
    fn uniform_stretch_reads_the_same_everywhere() {
        let section = Section::rectangular(2.0e5, 0.3, 1.0, 0.1, 0.2);
        let rod = Rod::new(ReferenceCurve::Straight { length: 2.0 }, section, 0.0, 4);
        let strain = 1e-3;
        let mut u = vec![0.0; rod.dofs()];
        for i in 0..rod.nodes() {
            u[3 * i + U1] = strain * rod.node_s[i];
        }
        for s in [0.0, 0.25, 0.5, 0.9, 1.0, 2.0] {
            let f = rod.section_forces_at(&u, s);
            let expected = section.ea * strain;
            assert!((f.n - expected).abs() < 1e-12 * expected, "{s}: {f:?}");
            assert!(f.q.abs() < 1e-12 * expected && f.m.abs() < 1e-12 * expected);
        }
    }

    /// A mesh of unequal elements (nodes at 0, 0.3, 0.5, 1.4, 2 of a rod of length 2), each
    /// stretched by its own strain: a station inside an element reads that element's `EA eps`,
    /// a station on an interior node the mean of its two elements'.
    #[test]
    fn unequal_elements_read_the_element_that_holds_the_station() {
        let section = Section::rectangular(2.0e5, 0.3, 1.0, 0.1, 0.2);
        let fractions = [0.0, 0.15, 0.25, 0.7, 1.0];
        let curve = ReferenceCurve::Straight { length: 2.0 };
        let rod = Rod::with_nodes(curve, section, 0.0, &fractions);
        let strains = [1e-3, 2e-3, 3e-3, 4e-3];
        let mut u = vec![0.0; rod.dofs()];
        for e in 0..4 {
            let length = rod.node_s[e + 1] - rod.node_s[e];
            u[3 * (e + 1) + U1] = u[3 * e + U1] + strains[e] * length;
        }
        let inside = [(0.1, 0), (0.4, 1), (1.0, 2), (1.9, 3)];
        for (s, e) in inside {
            let got = rod.section_forces_at(&u, s).n;
            let want = section.ea * strains[e];
            assert!(
                (got - want).abs() < 1e-9 * want,
                "s = {s}: {got} instead of {want}"
            );
        }
        let got = rod.section_forces_at(&u, 1.0 + 0.4).n;
        let want = section.ea * 0.5 * (strains[2] + strains[3]);
        assert!(
            (got - want).abs() < 1e-9 * want,
            "node at 1.4: {got} instead of {want}"
        );
    }

    /// Pure bending of a straight rod into a circle of curvature `k` (exact: nodes on the circle,
    /// rotations `k s`): the moment is `EI k` inside the elements and at the nodes (the nodal
    /// balance carries no moment jump without a nodal load), to round-off.
    #[test]
    fn pure_bending_moment_is_ei_kappa_everywhere() {
        let section = Section::rectangular(1.0e4, 0.2, 1.0, 1.0, 0.5);
        let n = 8;
        let rod = Rod::new(ReferenceCurve::Straight { length: 4.0 }, section, 0.0, n);
        let k = 0.3;
        let mut u = vec![0.0; rod.dofs()];
        for i in 0..rod.nodes() {
            let s = rod.node_s[i];
            u[3 * i + U1] = (k * s).sin() / k - s;
            u[3 * i + U2] = (1.0 - (k * s).cos()) / k;
            u[3 * i + ROTATION] = k * s;
        }
        let m = section.ei * k;
        for e in 0..n {
            let f = rod.element_section_forces(&u, e);
            assert!((f.m - m).abs() < 1e-12 * m, "element {e}: {f:?}");
        }
        // The chord of an element is shorter than its arc and turned by half the rotation
        // change: small membrane and shear forces of order (k l)^2 that the moment at a node
        // also carries through the nodal balance; relative 1e-2 at k l = 0.15.
        for s in [0.0, 1.0, 2.0, 4.0] {
            let f = rod.section_forces_at(&u, s);
            assert!((f.m - m).abs() < 1e-2 * m, "node at {s}: {f:?}");
        }
    }
}
