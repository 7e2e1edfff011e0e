//! A frame's own terms beside its members' rods: the bars', links' and joint springs' forces
//! and tangents, the bars' and joint masses' inertia and damping, and the frame's graph.
use super::matrix::StructureMatrix;
use super::Structure;
use crate::model::bands::Scaled;
use crate::solver::sparse_blocks::SparseBlocks;
use nalgebra::{Matrix2, Vector2};

impl Structure {
    /// A frame's graph (panics for a single member).
    pub(super) fn graph(&self) -> &super::graph::Graph {
        self.graph.as_ref().expect("a frame")
    }

    /// The matrix of a frame (panics for a single member).
    pub(super) fn graph_matrix(jac: &mut StructureMatrix) -> &mut SparseBlocks {
        match jac {
            StructureMatrix::Graph(m) => m,
            StructureMatrix::Chain(_) => panic!("a frame's matrix is block-sparse"),
        }
    }

    /// Runs `each(member index, rod's slice of x, rod's slice of out)` over the members, after
    /// zeroing the joints' rows of `out` when `overwrite` (the members write their own).
    pub(super) fn for_members(
        &self,
        x: &[f64],
        out: &mut [f64],
        overwrite: bool,
        mut each: impl FnMut(usize, &crate::model::Rod, &[f64], &mut [f64]),
    ) {
        if overwrite {
            out[..3 * self.joints.len()].fill(0.0);
        }
        for (i, m) in self.members.iter().enumerate() {
            let r = m.range();
            each(i, &m.rod, &x[r.clone()], &mut out[r]);
        }
    }

    /// `out += scale * (K_nodal x)`: the joint springs.
    pub(super) fn add_spring_force(&self, x: &[f64], out: &mut [f64], scale: f64) {
        for &(d, k) in &self.nodal.springs {
            out[d] += scale * k * x[d];
        }
    }

    /// `out += M_extra (a x + b y) + c C_extra x`: the bars' mass and damping and the joint
    /// masses and dashpots.
    pub(super) fn add_extra_bracket(
        &self,
        ((a, x), (b, y)): (Scaled, Scaled),
        c: f64,
        out: &mut [f64],
    ) {
        let bracket = |d: usize| a * x[d] + b * y[d];
        for &(d, m) in &self.nodal.masses {
            out[d] += m * bracket(d);
        }
        for &(d, damping) in &self.nodal.dashpots {
            out[d] += c * damping * x[d];
        }
        for bar in &self.axial {
            bar.add_pattern_times(bar.mass, self.lumped, x, out, a);
            bar.add_pattern_times(bar.mass, self.lumped, y, out, b);
            bar.add_pattern_times(bar.damping, self.lumped, x, out, c);
        }
        if let Some((beta, tangents)) = &self.rayleigh {
            self.add_spring_force(x, out, c * beta);
            for (bar, k) in self.axial.iter().zip(tangents) {
                add_block_times(bar.nodes, k, x, out, c * beta);
            }
        }
    }

    pub(super) fn add_extra_mass(&self, jac: &mut SparseBlocks, scale: f64) {
        for &(d, m) in &self.nodal.masses {
            jac.add_diagonal(d, scale * m);
        }
        let g = self.graph();
        for (a, bar) in self.axial.iter().enumerate() {
            g.add_axial_pattern(jac, a, bar.mass, self.lumped, scale);
        }
    }

    pub(super) fn add_extra_damping(&self, jac: &mut SparseBlocks, scale: f64) {
        for &(d, c) in &self.nodal.dashpots {
            jac.add_diagonal(d, scale * c);
        }
        let g = self.graph();
        for (a, bar) in self.axial.iter().enumerate() {
            g.add_axial_pattern(jac, a, bar.damping, self.lumped, scale);
        }
        if let Some((beta, tangents)) = &self.rayleigh {
            for &(d, k) in &self.nodal.springs {
                jac.add_diagonal(d, scale * beta * k);
            }
            for (a, k) in tangents.iter().enumerate() {
                g.add_axial_block(jac, a, k, scale * beta);
            }
        }
    }

    /// The bars', links' and joint springs' force at `u` into `f`, with their tangent into
    /// `jac` (and kept) where given.
    pub(super) fn add_extra_force(
        &self,
        u: &[f64],
        f: &mut [f64],
        mut jac: Option<(&mut SparseBlocks, f64)>,
        mut kept: Option<&mut Vec<Matrix2<f64>>>,
    ) {
        for (i, a) in self.axial.iter().enumerate() {
            let (force, k) = a.force_and_tangent(u);
            a.add_end_force(force, f, 1.0);
            if let Some((m, scale)) = jac.as_mut() {
                self.graph().add_axial_block(m, i, &k, *scale);
            }
            if let Some(kept) = kept.as_mut() {
                kept[i] = k;
            }
        }
        self.add_spring_force(u, f, 1.0);
        if let Some((m, scale)) = jac {
            for &(d, k) in &self.nodal.springs {
                m.add_diagonal(d, scale * k);
            }
        }
    }
}

/// `out += scale * [[K, -K], [-K, K]] x` on the translations of `nodes`.
pub(super) fn add_block_times(
    nodes: [usize; 2],
    k: &Matrix2<f64>,
    x: &[f64],
    out: &mut [f64],
    scale: f64,
) {
    let [a, b] = nodes;
    let d = Vector2::new(x[3 * b] - x[3 * a], x[3 * b + 1] - x[3 * a + 1]);
    let f = scale * (k * d);
    for r in 0..2 {
        out[3 * a + r] -= f[r];
        out[3 * b + r] += f[r];
    }
}
