//! The structure as the integrators see it ([`Assembly`]): a single member hands every call to
//! its rod (the same code as a lone rod's); a frame runs each member's rod on its slice of the
//! vectors, adds the bars, links and joint terms, and folds the slaves' rows into their joints'.
use super::frame_terms::add_block_times;
use super::matrix::StructureMatrix;
use super::{Structure, StructureTangents};
use crate::model::assembly::Assembly;
use crate::model::bands::Scaled;
use crate::model::element::ElementTangent;
use crate::solver::SystemMatrix;
use nalgebra::{Matrix2, Vector2};

impl Assembly for Structure {
    type Matrix = StructureMatrix;
    type Tangents = StructureTangents;

    fn dofs(&self) -> usize {
        self.dofs
    }

    fn new_matrix(&self) -> StructureMatrix {
        match &self.graph {
            None => StructureMatrix::Chain(self.rod().new_matrix()),
            Some(g) => StructureMatrix::Graph(g.new_matrix()),
        }
    }

    fn new_tangents(&self) -> StructureTangents {
        StructureTangents {
            members: (self.members.iter())
                .map(|m| vec![ElementTangent::default(); m.rod.elements.len()])
                .collect(),
            axial: vec![Matrix2::zeros(); self.axial.len()],
            nodal: vec![0.0; self.nonlinear.len()],
        }
    }

    fn length_scale(&self) -> f64 {
        if self.is_single() {
            return self.rod().curve.length();
        }
        // The largest extent of the structure's reference state.
        let points = (self.joints.iter().copied()).chain(self.members.iter().flat_map(|m| {
            (0..m.rod.nodes()).map(move |i| m.rod.reference_position(m.rod.node_s[i]))
        }));
        let (mut lo, mut hi) = (
            Vector2::repeat(f64::INFINITY),
            Vector2::repeat(f64::NEG_INFINITY),
        );
        for p in points {
            lo = lo.inf(&p);
            hi = hi.sup(&p);
        }
        (hi - lo).norm()
    }

    fn bending_scale(&self) -> f64 {
        if self.is_single() {
            return self.rod().bending_scale();
        }
        // The softest member's (bars: their axial `E / (rho L^2)`): the scale of the lowest
        // eigenvalues.
        let members = self.members.iter().map(|m| m.rod.bending_scale());
        let bars = (self.axial.iter())
            .filter(|a| a.mass > 0.0)
            .map(|a| a.k / (6.0 * a.mass));
        members.chain(bars).fold(f64::INFINITY, f64::min)
    }

    fn constrained(&self) -> &[usize] {
        &self.eliminated
    }

    fn zero_constrained(&self, x: &mut [f64]) {
        self.zero_held(x);
    }

    fn make_consistent(&self, x: &mut [f64]) {
        self.expand(x);
    }

    fn duplicates(&self) -> &[usize] {
        &self.slaves
    }

    fn constrain(&self, jac: &mut StructureMatrix) {
        jac.constrain(&self.eliminated);
        for &(node, n) in &self.directions {
            jac.constrain_direction(node, n);
        }
    }

    fn internal_force(&self, u: &[f64], f: &mut [f64]) {
        if self.is_single() {
            self.rod().internal_force(u, f);
            return self.add_nonlinear_force::<StructureMatrix>(u, f, None, None);
        }
        self.for_members(u, f, true, |_, rod, u, f| rod.internal_force(u, f));
        self.add_extra_force(u, f, None, None);
        self.fold(f);
        self.add_nonlinear_force::<StructureMatrix>(u, f, None, None);
    }

    fn internal_force_and_tangent(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: &mut StructureMatrix,
        scale: f64,
    ) {
        if let StructureMatrix::Chain(m) = jac {
            self.rod().internal_force_and_tangent(u, f, m, scale);
            return self.add_nonlinear_force(u, f, Some((m, scale)), None);
        }
        let g = self.graph.as_ref().expect("a frame");
        let matrix = Self::graph_matrix(jac);
        self.for_members(u, f, true, |i, rod, u, f| {
            let mut sink = g.member(matrix, i);
            rod.internal_force_and_tangent(u, f, &mut sink, scale);
        });
        self.add_extra_force(u, f, Some((matrix, scale)), None);
        self.fold(f);
        self.add_nonlinear_force(u, f, Some((matrix, scale)), None);
    }

    fn internal_force_and_tangent_kept(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: &mut StructureMatrix,
        scale: f64,
        kept: &mut StructureTangents,
    ) {
        if let StructureMatrix::Chain(m) = jac {
            let rod = self.rod();
            rod.internal_force_and_tangent_kept(u, f, m, scale, &mut kept.members[0]);
            return self.add_nonlinear_force(u, f, Some((m, scale)), Some(&mut kept.nodal));
        }
        let g = self.graph.as_ref().expect("a frame");
        let matrix = Self::graph_matrix(jac);
        let members = &mut kept.members;
        self.for_members(u, f, true, |i, rod, u, f| {
            let mut sink = g.member(matrix, i);
            rod.internal_force_and_tangent_kept(u, f, &mut sink, scale, &mut members[i]);
        });
        self.add_extra_force(u, f, Some((matrix, scale)), Some(&mut kept.axial));
        self.fold(f);
        self.add_nonlinear_force(u, f, Some((matrix, scale)), Some(&mut kept.nodal));
    }

    fn internal_force_and_element_tangents(
        &self,
        u: &[f64],
        f: &mut [f64],
        kept: &mut StructureTangents,
    ) {
        if self.is_single() {
            let rod = self.rod();
            rod.internal_force_and_element_tangents(u, f, &mut kept.members[0]);
            let nodal = Some(&mut kept.nodal[..]);
            return self.add_nonlinear_force::<StructureMatrix>(u, f, None, nodal);
        }
        let members = &mut kept.members;
        self.for_members(u, f, true, |i, rod, u, f| {
            rod.internal_force_and_element_tangents(u, f, &mut members[i]);
        });
        self.add_extra_force(u, f, None, Some(&mut kept.axial));
        self.fold(f);
        let nodal = Some(&mut kept.nodal[..]);
        self.add_nonlinear_force::<StructureMatrix>(u, f, None, nodal);
    }

    fn tangent_change_times(
        &self,
        (k1, k0): (&StructureTangents, &StructureTangents),
        y: &[f64],
        out: &mut [f64],
        scale: f64,
    ) {
        if self.is_single() {
            let pair = (&k1.members[0][..], &k0.members[0][..]);
            self.rod().tangent_change_times(pair, y, out, scale);
            return self.add_nonlinear_change((&k1.nodal, &k0.nodal), y, out, scale);
        }
        self.for_members(y, out, true, |i, rod, y, out| {
            rod.tangent_change_times((&k1.members[i], &k0.members[i]), y, out, scale);
        });
        for ((a, t1), t0) in self.axial.iter().zip(&k1.axial).zip(&k0.axial) {
            add_block_times(a.nodes, &(t1 - t0), y, out, scale);
        }
        self.fold(out);
        self.add_nonlinear_change((&k1.nodal, &k0.nodal), y, out, scale);
    }

    fn add_kept_tangents(&self, jac: &mut StructureMatrix, kept: &StructureTangents, scale: f64) {
        if !self.nonlinear.is_empty() {
            self.nonlinear.add_kept(jac, &kept.nodal, scale);
        }
        if let StructureMatrix::Chain(m) = jac {
            return self.rod().add_kept_tangents(m, &kept.members[0], scale);
        }
        let g = self.graph.as_ref().expect("a frame");
        let matrix = Self::graph_matrix(jac);
        for (i, m) in self.members.iter().enumerate() {
            let mut sink = g.member(matrix, i);
            for (e, ke) in kept.members[i].iter().enumerate() {
                crate::solver::PairSink::add_pair(&mut sink, e, ke, scale);
            }
            m.rod.add_attached_stiffness(&mut sink, scale);
        }
        for (a, k) in kept.axial.iter().enumerate() {
            g.add_axial_block(matrix, a, k, scale);
        }
        for &(d, k) in &self.nodal.springs {
            matrix.add_diagonal(d, scale * k);
        }
    }

    fn discrete_gradient(&self, ua: &[f64], ub: &[f64], f: &mut [f64]) {
        if self.is_single() {
            self.rod().discrete_gradient(ua, ub, f);
            return self.add_nonlinear_gradient::<StructureMatrix>(ua, ub, f, None);
        }
        f[..3 * self.joints.len()].fill(0.0);
        for m in &self.members {
            let r = m.range();
            m.rod
                .discrete_gradient(&ua[r.clone()], &ub[r.clone()], &mut f[r]);
        }
        for a in &self.axial {
            a.add_end_force(a.discrete_gradient(ua, ub), f, 1.0);
        }
        self.add_spring_force(ua, f, 0.5);
        self.add_spring_force(ub, f, 0.5);
        self.fold(f);
        self.add_nonlinear_gradient::<StructureMatrix>(ua, ub, f, None);
    }

    fn discrete_gradient_and_tangent(
        &self,
        ua: &[f64],
        ub: &[f64],
        f: &mut [f64],
        jac: &mut StructureMatrix,
        scale: f64,
    ) {
        if let StructureMatrix::Chain(m) = jac {
            self.rod()
                .discrete_gradient_and_tangent(ua, ub, f, m, scale);
            return self.add_nonlinear_gradient(ua, ub, f, Some((m, scale)));
        }
        let g = self.graph.as_ref().expect("a frame");
        let matrix = Self::graph_matrix(jac);
        f[..3 * self.joints.len()].fill(0.0);
        for (i, m) in self.members.iter().enumerate() {
            let r = m.range();
            let mut sink = g.member(matrix, i);
            m.rod.discrete_gradient_and_tangent(
                &ua[r.clone()],
                &ub[r.clone()],
                &mut f[r],
                &mut sink,
                scale,
            );
        }
        let mid: Vec<f64> = ua.iter().zip(ub).map(|(a, b)| 0.5 * (a + b)).collect();
        for (i, a) in self.axial.iter().enumerate() {
            a.add_end_force(a.discrete_gradient(ua, ub), f, 1.0);
            g.add_axial_block(matrix, i, &a.force_and_tangent(&mid).1, scale);
        }
        self.add_spring_force(ua, f, 0.5);
        self.add_spring_force(ub, f, 0.5);
        for &(d, k) in &self.nodal.springs {
            matrix.add_diagonal(d, scale * k);
        }
        self.fold(f);
        self.add_nonlinear_gradient(ua, ub, f, Some((matrix, scale)));
    }

    fn add_mass(&self, jac: &mut StructureMatrix, scale: f64) {
        if let StructureMatrix::Chain(m) = jac {
            return self.rod().add_mass(m, scale);
        }
        let g = self.graph.as_ref().expect("a frame");
        let matrix = Self::graph_matrix(jac);
        for (i, m) in self.members.iter().enumerate() {
            m.rod.add_mass(&mut g.member(matrix, i), scale);
        }
        self.add_extra_mass(matrix, scale);
    }

    fn add_damping(&self, jac: &mut StructureMatrix, scale: f64) {
        if let StructureMatrix::Chain(m) = jac {
            return self.rod().add_damping(m, scale);
        }
        let g = self.graph.as_ref().expect("a frame");
        let matrix = Self::graph_matrix(jac);
        for (i, m) in self.members.iter().enumerate() {
            m.rod.add_damping(&mut g.member(matrix, i), scale);
        }
        self.add_extra_damping(matrix, scale);
    }

    fn add_mass_times(&self, x: &[f64], out: &mut [f64], scale: f64) {
        if self.is_single() {
            return self.rod().add_mass_times(x, out, scale);
        }
        self.for_members(x, out, false, |_, rod, x, out| {
            rod.add_mass_times(x, out, scale)
        });
        self.add_extra_bracket(((scale, x), (0.0, x)), 0.0, out);
        self.fold(out);
    }

    fn add_mass_and_damping_times(
        &self,
        (x, ms): (&[f64], f64),
        (y, ds): (&[f64], f64),
        out: &mut [f64],
    ) {
        if self.is_single() {
            return self.rod().add_mass_and_damping_times((x, ms), (y, ds), out);
        }
        for m in &self.members {
            let r = m.range();
            m.rod
                .add_mass_and_damping_times((&x[r.clone()], ms), (&y[r.clone()], ds), &mut out[r]);
        }
        // M (ms x) + C (ds y): the bracket's `a x` with c = ds on `y` needs y as the damped one.
        self.add_extra_bracket(((ms, x), (0.0, x)), 0.0, out);
        self.add_extra_bracket(((0.0, y), (0.0, y)), ds, out);
        self.fold(out);
    }

    fn add_bracket_times(
        &self,
        bracket: (Scaled, Scaled),
        c: f64,
        z: Option<&[f64]>,
        out: &mut [f64],
    ) {
        if self.is_single() {
            return self.rod().add_bracket_times(bracket, c, z, out);
        }
        let ((a, x), (b, y)) = bracket;
        for m in &self.members {
            let r = m.range();
            let pair = ((a, &x[r.clone()]), (b, &y[r.clone()]));
            m.rod
                .add_bracket_times(pair, c, z.map(|z| &z[r.clone()]), &mut out[r]);
        }
        if let Some(z) = z {
            let joints = 3 * self.joints.len();
            for (o, z) in out[..joints].iter_mut().zip(&z[..joints]) {
                *o += z;
            }
        }
        self.add_extra_bracket(bracket, c, out);
        self.fold(out);
    }

    fn has_state_damping(&self) -> bool {
        self.dashpots().next().is_some() || self.nonlinear.has_dashpots()
    }

    fn add_state_damping(
        &self,
        u_n: &[f64],
        du: &[f64],
        dt: f64,
        out: &mut [f64],
        mut jac: Option<&mut StructureMatrix>,
    ) {
        self.link_damping(u_n, du, dt, out, jac.as_deref_mut());
        self.nonlinear.add_damping(u_n, du, dt, out, jac);
    }

    fn state_damping_dissipation(&self, u: &[f64], du: &[f64], dt: f64) -> f64 {
        self.link_dissipation(u, du, dt) + self.nonlinear.dissipation(u, du, dt)
    }

    fn has_kinks(&self) -> bool {
        self.nonlinear.has_kinks()
    }

    fn crosses_kink(&self, u: &[f64], du: &[f64], c: &[f64], w: f64) -> bool {
        self.kink_crossed(u, du, c, w)
    }

    fn add_static_regularization(&self, u: &[f64], jac: &mut StructureMatrix) {
        self.regularize_statics(u, jac);
    }

    fn static_step_limit(&self, u: &[f64], delta: &[f64]) -> f64 {
        self.static_limit(u, delta)
    }

    fn strain_energy(&self, u: &[f64]) -> f64 {
        if self.is_single() {
            return self.rod().strain_energy(u) + self.nonlinear_energy(u);
        }
        self.frame_strain_energy(u)
    }

    fn kinetic_energy(&self, v: &[f64]) -> f64 {
        if self.is_single() {
            return self.rod().kinetic_energy(v);
        }
        self.frame_kinetic_energy(v)
    }

    fn dissipation_rate(&self, v: &[f64]) -> f64 {
        if self.is_single() {
            return self.rod().dissipation_rate(v);
        }
        self.frame_dissipation_rate(v)
    }
}
