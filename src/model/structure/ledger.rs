//! A frame's energies, dissipation, Rayleigh damping, link dashpots and momenta: what the
//! energy ledger and the conservation checks read (a single member's are its rod's).
use super::Structure;
use crate::model::assembly::Assembly;
use crate::model::structure::matrix::StructureMatrix;
use nalgebra::Vector2;

impl Structure {
    /// The members', bars', links', joint springs' and nonlinear items' (stops, cubic springs)
    /// stored energy.
    pub(super) fn frame_strain_energy(&self, u: &[f64]) -> f64 {
        let members: f64 = (self.members.iter())
            .map(|m| m.rod.strain_energy(&u[m.range()]))
            .sum();
        let axial: f64 = self.axial.iter().map(|a| a.strain_energy(u)).sum();
        let springs: f64 = (self.nodal.springs.iter())
            .map(|&(d, k)| 0.5 * k * u[d] * u[d])
            .sum();
        members + axial + springs + self.nonlinear_energy(u)
    }

    /// The members', bars' and joint masses' kinetic energy.
    pub(super) fn frame_kinetic_energy(&self, v: &[f64]) -> f64 {
        let members: f64 = (self.members.iter())
            .map(|m| m.rod.kinetic_energy(&v[m.range()]))
            .sum();
        let bars: f64 = (self.axial.iter())
            .map(|a| a.pattern_form(a.mass, self.lumped, v))
            .sum();
        let masses: f64 = (self.nodal.masses.iter())
            .map(|&(d, m)| m * v[d] * v[d])
            .sum();
        members + 0.5 * (bars + masses)
    }

    /// The power the viscous damping takes at velocity `v`: the members' and bars' material
    /// damping, joint dashpots and Rayleigh's stiffness part (link dashpots: `link_dissipation`).
    pub(super) fn frame_dissipation_rate(&self, v: &[f64]) -> f64 {
        let members: f64 = (self.members.iter())
            .map(|m| m.rod.dissipation_rate(&v[m.range()]))
            .sum();
        let bars: f64 = (self.axial.iter())
            .map(|a| a.pattern_form(a.damping, self.lumped, v))
            .sum();
        let dashpots: f64 = (self.nodal.dashpots.iter())
            .map(|&(d, c)| c * v[d] * v[d])
            .sum();
        let rayleigh = self.rayleigh.as_ref().map_or(0.0, |(beta, tangents)| {
            let springs: f64 = (self.nodal.springs.iter())
                .map(|&(d, k)| k * v[d] * v[d])
                .sum();
            let bars: f64 = (self.axial.iter().zip(tangents))
                .map(|(a, k)| {
                    let [p, q] = a.nodes;
                    let d = Vector2::new(v[3 * q] - v[3 * p], v[3 * q + 1] - v[3 * p + 1]);
                    d.dot(&(k * d))
                })
                .sum();
            beta * (springs + bars)
        });
        members + bars + dashpots + rayleigh
    }
}

impl Structure {
    /// The links with a dashpot.
    pub(super) fn dashpots(&self) -> impl Iterator<Item = &super::Axial> {
        self.axial.iter().filter(|a| a.c > 0.0)
    }

    /// Rayleigh damping `alpha M + beta K0`, `K0` the tangent stiffness at `u0` (the initial
    /// state): each member's own, the bars' and the joint terms'.
    pub fn with_rayleigh(&mut self, alpha: f64, beta: f64, u0: &[f64]) {
        for m in &mut self.members {
            let r = m.range();
            m.rod.with_rayleigh(alpha, beta, &u0[r]);
        }
        if self.is_single() {
            return;
        }
        for a in &mut self.axial {
            a.damping += alpha * a.mass;
        }
        let extra: Vec<(usize, f64)> = (self.nodal.masses.iter())
            .map(|&(d, m)| (d, alpha * m))
            .filter(|&(_, c)| c != 0.0)
            .collect();
        self.nodal.dashpots.extend(extra);
        if beta != 0.0 {
            let tangents = self
                .axial
                .iter()
                .map(|a| a.force_and_tangent(u0).1)
                .collect();
            self.rayleigh = Some((beta, tangents));
        }
    }
}

/// Momenta, and links' dashpots along their current line (see [`Assembly::add_state_damping`]).
impl Structure {
    /// Linear momentum `sum M v` over the translations (members, bars, joint masses).
    pub fn linear_momentum(&self, v: &[f64]) -> nalgebra::Vector2<f64> {
        let mut p = vec![0.0; v.len()];
        self.add_mass_times(v, &mut p, 1.0);
        // Folded: the joints' rows hold their members' ends' share.
        (0..self.nodes())
            .map(|i| Vector2::new(p[3 * i], p[3 * i + 1]))
            .sum()
    }

    /// Angular momentum about the origin, `sum x_i x (M v)_i + (M v)_w`, `x_i` the current
    /// positions of the nodes (the folded product's rows sit at the joints and the members'
    /// own nodes).
    pub fn angular_momentum(&self, u: &[f64], v: &[f64]) -> f64 {
        if self.is_single() {
            return self.rod().angular_momentum(u, v);
        }
        let mut p = vec![0.0; v.len()];
        self.add_mass_times(v, &mut p, 1.0);
        let mut total = 0.0;
        for (j, x0) in self.joints.iter().enumerate() {
            let x = x0 + Vector2::new(u[3 * j], u[3 * j + 1]);
            total += x[0] * p[3 * j + 1] - x[1] * p[3 * j] + p[3 * j + 2];
        }
        for m in &self.members {
            for i in 0..m.rod.nodes() {
                let d = m.offset + 3 * i;
                let x = m.rod.node_position(&u[m.range()], i);
                total += x[0] * p[d + 1] - x[1] * p[d] + p[d + 2];
            }
        }
        total
    }

    pub(super) fn link_damping(
        &self,
        u_n: &[f64],
        du: &[f64],
        dt: f64,
        out: &mut [f64],
        mut jac: Option<&mut StructureMatrix>,
    ) {
        for (i, a) in self.axial.iter().enumerate().filter(|(_, a)| a.c > 0.0) {
            let (stretch, e) = a.stretch_increment(u_n, du, 0.5);
            a.add_end_force(a.c * stretch / dt * e, out, 1.0);
            if let Some(m) = jac.as_deref_mut() {
                // The change of `e` with the increment is left out: its term `e (P d)^T` is not
                // symmetric, and every step factors a symmetric matrix.
                let k = (a.c / dt) * (e * e.transpose());
                self.graph()
                    .add_axial_block(Self::graph_matrix(m), i, &k, 1.0);
            }
        }
    }

    pub(super) fn link_dissipation(&self, u: &[f64], du: &[f64], dt: f64) -> f64 {
        (self.dashpots())
            .map(|a| {
                let (stretch, _) = a.stretch_increment(u, du, -0.5);
                a.c * stretch * stretch / dt
            })
            .sum()
    }
}
