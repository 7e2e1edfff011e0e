//! A meshed rod: elements along the reference curve, constrained dofs, and the global vectors and
//! matrices (internal force, tangent, mass, damping, loads). Global dof `3 i + k` is `u1`, `u2`,
//! `w` (k = 0, 1, 2) of node `i`; element `e` joins nodes `e` and `e + 1`, so its six dofs are
//! contiguous and the matrices are block tridiagonal.
use super::attachments::Attachments;
use super::bands::{Bands, Scaled};
use super::element::{
    gauss_trig, shape_functions, Element, ElementInertia, ElementTangent, GaussTrig, Vector6,
    GAUSS_POINTS,
};
use super::geometry::{Placement, ReferenceCurve};
use super::rayleigh::StiffnessDamping;
use super::section::Section;
#[cfg(test)]
use crate::solver::BlockTridiagonal;
use crate::solver::PairSink;
use nalgebra::Vector2;

#[path = "rod_attachments.rs"]
mod rod_attachments;
#[path = "rod_energy.rs"]
mod rod_energy;
#[path = "rod_points.rs"]
mod rod_points;
#[path = "rod_tangent.rs"]
mod rod_tangent;

/// Dof index within a node.
pub const U1: usize = 0;
pub const U2: usize = 1;
pub const ROTATION: usize = 2;

/// A point of the rod given by the element that holds it and the shape-function weights there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointOnRod {
    pub element: usize,
    pub weights: (f64, f64),
}

#[derive(Clone, Debug)]
pub struct Rod {
    pub curve: ReferenceCurve,
    /// Where the curve lies (`None`: as it is, from the origin along `e1`).
    pub placement: Option<Placement>,
    pub section: Section,
    /// Viscous damping per unit length on the translations.
    pub damping: f64,
    pub elements: Vec<Element>,
    inertia: Vec<ElementInertia>,
    /// The mass and damping matrices as bands of the dof vector (see [`Bands`]).
    mass_bands: Bands,
    damping_bands: Bands,
    /// Arc length of each node.
    pub node_s: Vec<f64>,
    /// Equal elements (points are found by division instead of a search).
    uniform: bool,
    /// Constrained (fixed or prescribed) dofs, per global dof ([`Rod::fix`]).
    pub fixed: Vec<bool>,
    /// The constrained dofs in increasing order.
    constrained: Vec<usize>,
    /// Lumped (diagonal) instead of consistent mass and damping matrices.
    pub lumped: bool,
    /// `beta K0` of Rayleigh damping, part of the damping matrix (none: no cost).
    stiffness_damping: Option<StiffnessDamping>,
    /// Point masses, springs, dashpots, foundations (in the bands), and the stiffness they add.
    attachments: Attachments,
    attached_stiffness: Option<Bands>,
}

impl Rod {
    /// `n` equal elements along `curve`; no dof constrained.
    pub fn new(curve: ReferenceCurve, section: Section, damping: f64, n: usize) -> Rod {
        assert!(n >= 1, "a rod needs at least one element");
        let length = curve.length() / n as f64;
        let node_s: Vec<f64> = (0..=n)
            .map(|i| curve.length() * i as f64 / n as f64)
            .collect();
        Rod::build(curve, section, damping, node_s, vec![length; n], true)
    }

    /// Elements between the nodes at `fractions` of the arc length (increasing, from 0 to 1);
    /// no dof constrained.
    pub fn with_nodes(
        curve: ReferenceCurve,
        section: Section,
        damping: f64,
        fractions: &[f64],
    ) -> Rod {
        assert!(fractions.len() >= 2, "a rod needs at least one element");
        let total = curve.length();
        let node_s: Vec<f64> = fractions.iter().map(|f| total * f).collect();
        let lengths = node_s.windows(2).map(|w| w[1] - w[0]).collect();
        Rod::build(curve, section, damping, node_s, lengths, false)
    }

    fn build(
        curve: ReferenceCurve,
        section: Section,
        damping: f64,
        node_s: Vec<f64>,
        lengths: Vec<f64>,
        uniform: bool,
    ) -> Rod {
        let n = lengths.len();
        let elements = (0..n)
            .map(|e| {
                let alpha = GAUSS_POINTS.map(|xi| {
                    let (_, nb) = shape_functions(xi);
                    curve.tangent_angle(node_s[e] + nb * lengths[e])
                });
                Element::new(lengths[e], alpha)
            })
            .collect();
        let mut rod = Rod {
            curve,
            placement: None,
            section,
            damping,
            elements,
            inertia: (lengths.iter())
                .map(|&l| ElementInertia::new(&section, damping, l))
                .collect(),
            mass_bands: Bands::default(),
            damping_bands: Bands::default(),
            node_s,
            uniform,
            fixed: vec![false; 3 * (n + 1)],
            constrained: Vec::new(),
            lumped: false,
            stiffness_damping: None,
            attachments: Attachments::default(),
            attached_stiffness: None,
        };
        rod.update_bands();
        rod
    }

    /// The same rod with its curve placed in the plane (its elements' reference angles turned
    /// with it).
    pub fn with_placement(mut self, placement: Placement) -> Rod {
        for (e, el) in self.elements.iter_mut().enumerate() {
            let (a, l) = (self.node_s[e], el.length);
            let alpha = GAUSS_POINTS.map(|xi| {
                let (_, nb) = shape_functions(xi);
                placement.turn(self.curve.tangent_angle(a + nb * l))
            });
            *el = Element::new(l, alpha);
        }
        self.placement = Some(placement);
        self
    }

    /// The reference position `X(s)` in the plane.
    pub fn reference_position(&self, s: f64) -> Vector2<f64> {
        let x = self.curve.position(s);
        self.placement.map_or(x, |p| p.place(x))
    }

    /// The reference tangent angle `alpha(s)` in the plane.
    pub fn reference_angle(&self, s: f64) -> f64 {
        let alpha = self.curve.tangent_angle(s);
        self.placement.map_or(alpha, |p| p.turn(alpha))
    }

    /// The bands of the mass and damping matrices from the element coefficients.
    fn update_bands(&mut self) {
        let coefficients = |damping: bool| {
            let c: Vec<[f64; 3]> = (self.inertia.iter())
                .map(|m| m.coefficients(damping).into())
                .collect();
            Bands::consistent(&c, self.lumped)
        };
        self.mass_bands = coefficients(false);
        self.damping_bands = coefficients(true);
        (self.attachments).add_to_bands(&mut self.mass_bands, &mut self.damping_bands);
    }

    /// The same rod with lumped (diagonal, row-sum) mass and damping matrices instead of the
    /// consistent ones: an option for studies, not the model of `docs/model.md`.
    pub fn with_lumped_mass(mut self) -> Rod {
        self.lumped = true;
        self.update_bands();
        self
    }

    /// The same rod with a viscous damping `d_w` per unit length on the rotations too (the
    /// model damps translations only): an option for studies.
    pub fn with_rotational_damping(mut self, d_w: f64) -> Rod {
        for (m, el) in self.inertia.iter_mut().zip(&self.elements) {
            m.rotational_damping = d_w * el.length / 6.0;
        }
        self.update_bands();
        self
    }

    pub fn nodes(&self) -> usize {
        self.node_s.len()
    }

    pub fn dofs(&self) -> usize {
        3 * self.nodes()
    }

    pub fn last_node(&self) -> usize {
        self.nodes() - 1
    }

    /// Constrains dof `k` (`U1`, `U2`, `ROTATION`) of `node`.
    pub fn fix(&mut self, node: usize, k: usize) {
        let dof = 3 * node + k;
        self.fixed[dof] = true;
        if let Err(at) = self.constrained.binary_search(&dof) {
            self.constrained.insert(at, dof);
        }
    }

    /// The six dofs of element `e` in a nodal vector.
    pub fn element_dofs(x: &[f64], e: usize) -> Vector6 {
        Vector6::from_column_slice(&x[3 * e..3 * e + 6])
    }

    /// The elements that hold node `i` (one at an end, two inside), with the offset of the
    /// node's dofs in the element's six.
    pub fn elements_at(&self, i: usize) -> impl Iterator<Item = (usize, usize)> {
        let before = i.checked_sub(1).map(|e| (e, 3));
        let after = (i < self.elements.len()).then_some((i, 0));
        before.into_iter().chain(after)
    }

    /// Element `e`'s internal force on its six dofs.
    pub fn element_internal_force(&self, e: usize, ue: &Vector6) -> Vector6 {
        self.elements[e].internal_force(&self.section, ue)
    }

    /// The rows of node `i` of `f_int(u)`: O(1).
    pub fn node_internal_force(&self, u: &[f64], i: usize) -> [f64; 3] {
        let mut rows = [0.0; 3];
        for (e, offset) in self.elements_at(i) {
            let f = self.element_internal_force(e, &Self::element_dofs(u, e));
            for (k, r) in rows.iter_mut().enumerate() {
                *r += f[offset + k];
            }
        }
        if let Some(k) = &self.attached_stiffness {
            for (j, r) in rows.iter_mut().enumerate() {
                *r += k.row_times(u, 3 * i + j);
            }
        }
        rows
    }

    /// `f = f_int(u)` (overwrites `f`).
    pub fn internal_force(&self, u: &[f64], f: &mut [f64]) {
        assemble(f, &self.elements, u, |_, el, ue, trig| {
            el.internal_force_with(&self.section, ue, trig)
        });
        self.add_attached_force(u, f);
    }

    /// `f =` the energy-momentum discrete gradient between `ua` and `ub` (overwrites).
    pub fn discrete_gradient(&self, ua: &[f64], ub: &[f64], f: &mut [f64]) {
        f.fill(0.0);
        for (e, el) in self.elements.iter().enumerate() {
            let (a, b) = (Self::element_dofs(ua, e), Self::element_dofs(ub, e));
            add_element_vector(f, e, &el.discrete_gradient(&self.section, &a, &b));
        }
        self.add_attached_midpoint_force(ua, ub, f);
    }

    /// `f =` the energy-momentum discrete gradient between `ua` and `ub` (overwrites), and
    /// `jac += scale * K_T((ua + ub) / 2)`, its derivative up to `O(|ub - ua|)`.
    pub fn discrete_gradient_and_tangent(
        &self,
        ua: &[f64],
        ub: &[f64],
        f: &mut [f64],
        jac: &mut impl PairSink,
        scale: f64,
    ) {
        f.fill(0.0);
        for (e, el) in self.elements.iter().enumerate() {
            let (a, b) = (Self::element_dofs(ua, e), Self::element_dofs(ub, e));
            let fe = el.discrete_gradient(&self.section, &a, &b);
            let (mut ke, mid) = (ElementTangent::default(), 0.5 * (a + b));
            let trig = gauss_trig(&mid);
            el.force_and_tangent_into(&self.section, &mid, &trig, &mut Vector6::zeros(), &mut ke);
            add_element_vector(f, e, &fe);
            jac.add_pair(e, &ke, scale);
        }
        self.add_attached_midpoint_force(ua, ub, f);
        self.attachments.add_stiffness(jac, scale);
    }

    /// `jac += scale * M`.
    pub fn add_mass(&self, jac: &mut impl PairSink, scale: f64) {
        for (e, m) in self.inertia.iter().enumerate() {
            jac.add_pair_pattern(e, &m.coefficients(false), scale, self.lumped);
        }
        self.attachments.add_mass(jac, scale);
    }

    /// `jac += scale * C` (damping).
    pub fn add_damping(&self, jac: &mut impl PairSink, scale: f64) {
        for (e, m) in self.inertia.iter().enumerate() {
            jac.add_pair_pattern(e, &m.coefficients(true), scale, self.lumped);
        }
        self.attachments.add_damping(jac, scale);
        if let Some(k0) = &self.stiffness_damping {
            k0.add_to(self, jac, scale);
        }
    }

    /// `out += scale * M x`.
    pub fn add_mass_times(&self, x: &[f64], out: &mut [f64], scale: f64) {
        self.mass_bands.add_times(x, out, scale);
    }

    /// `out += scale * C x` (damping).
    pub fn add_damping_times(&self, x: &[f64], out: &mut [f64], scale: f64) {
        self.damping_bands.add_times(x, out, scale);
        if let Some(k0) = &self.stiffness_damping {
            k0.add_times(x, out, scale);
        }
    }

    /// `out += mass_scale * M x + damping_scale * C y` in one pass.
    pub fn add_mass_and_damping_times(
        &self,
        (x, mass_scale): (&[f64], f64),
        (y, damping_scale): (&[f64], f64),
        out: &mut [f64],
    ) {
        self.mass_bands.add_times(x, out, mass_scale);
        self.damping_bands.add_times(y, out, damping_scale);
        if let Some(k0) = &self.stiffness_damping {
            k0.add_times(y, out, damping_scale);
        }
    }

    /// `out += M (a x + b y) + c C x + z`: the linear part of the midpoint rule's residual and
    /// of its tangent map, with the bracket formed before the product (see
    /// [`Bands::add_bracket_times`]).
    pub fn add_bracket_times(
        &self,
        bracket: (Scaled, Scaled),
        c: f64,
        z: Option<&[f64]>,
        out: &mut [f64],
    ) {
        self.mass_bands
            .add_bracket_times(&self.damping_bands, bracket, c, z, out);
        if let Some(k0) = &self.stiffness_damping {
            let ((_, x), _) = bracket;
            k0.add_times(x, out, c);
        }
    }

    /// Current position of node `i`.
    pub fn node_position(&self, u: &[f64], i: usize) -> Vector2<f64> {
        self.reference_position(self.node_s[i]) + Vector2::new(u[3 * i + U1], u[3 * i + U2])
    }

    /// Sets constrained entries of `x` to zero.
    pub fn zero_constrained(&self, x: &mut [f64]) {
        for &dof in &self.constrained {
            x[dof] = 0.0;
        }
    }

    /// The constrained dofs in increasing order.
    pub fn constrained(&self) -> &[usize] {
        &self.constrained
    }
}

/// Elements evaluated together: the sines and cosines of their Gauss points first, all
/// independent, so that the processor overlaps them (computed element by element, each waited
/// on its element's arithmetic: 3 % of a step), then their arithmetic.
const BLOCK: usize = 16;

/// `f =` the sum of the element vectors `element_vector(e, element, ue, trig)` at the dofs `u`
/// (overwrites, with no zeroing pass of its own: an element's second node is first touched by
/// it), `trig` the sines and cosines of the element's Gauss points.
fn assemble(
    f: &mut [f64],
    elements: &[Element],
    u: &[f64],
    mut element_vector: impl FnMut(usize, &Element, &Vector6, &GaussTrig) -> Vector6,
) {
    f[..3].fill(0.0);
    let mut trig = [[(0.0, 1.0); 2]; BLOCK];
    for (b, block) in elements.chunks(BLOCK).enumerate() {
        let first = b * BLOCK;
        for (t, e) in trig.iter_mut().zip(first..first + block.len()) {
            *t = gauss_trig(&Rod::element_dofs(u, e));
        }
        for (i, el) in block.iter().enumerate() {
            let e = first + i;
            let fe = element_vector(e, el, &Rod::element_dofs(u, e), &trig[i]);
            let (first, second) = f[3 * e..3 * e + 6].split_at_mut(3);
            for k in 0..3 {
                first[k] += fe[k];
                second[k] = fe[3 + k];
            }
        }
    }
}

fn add_element_vector(out: &mut [f64], e: usize, fe: &Vector6) {
    for (o, f) in out[3 * e..3 * e + 6].iter_mut().zip(fe.iter()) {
        *o += f;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The matrix-free products `M x` and `C x` equal the assembled block-tridiagonal matrices
    /// times `x` (consistent and lumped, rotational damping on so every coefficient counts).
    #[test]
    fn mass_and_damping_products_match_the_assembled_matrices() {
        let section = Section::rectangular(1.2e4, 0.3, 1e-6, 1.0, 0.2);
        let consistent = Rod::new(ReferenceCurve::Straight { length: 3.0 }, section, 0.7, 5)
            .with_rotational_damping(0.05);
        for rod in [consistent.clone(), consistent.with_lumped_mass()] {
            let x: Vec<f64> = (0..rod.dofs()).map(|i| (i as f64 * 0.37).sin()).collect();
            for damping in [false, true] {
                let mut matrix = BlockTridiagonal::new(rod.nodes());
                let mut product = vec![0.5; rod.dofs()];
                if damping {
                    rod.add_damping(&mut matrix, 2.0);
                    rod.add_damping_times(&x, &mut product, 2.0);
                } else {
                    rod.add_mass(&mut matrix, 2.0);
                    rod.add_mass_times(&x, &mut product, 2.0);
                }
                let mut expected = vec![0.0; rod.dofs()];
                matrix.mul(&x, &mut expected);
                for (p, e) in product.iter().zip(&expected) {
                    // Round-off of a few products of O(1) numbers.
                    assert!(
                        (p - 0.5 - e).abs() < 1e-14,
                        "lumped {}: {p} vs {e}",
                        rod.lumped
                    );
                }
            }
        }
    }
}
