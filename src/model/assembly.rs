//! What the integrators (time steps, statics, continuation, modes, tangent map) ask of a
//! discretized model: its global dof vector, the internal force with its tangent, the
//! energy-momentum discrete gradient, the mass and damping matrices, the held dofs. A
//! [`Rod`] is one chain of elements with a block-tridiagonal matrix; a
//! [`Structure`](super::structure::Structure) is members joined at joints, a rod when it has one
//! member. The integrators are generic over it, so a rod's step is the same code as before
//! frames existed (the same bits and cost).
use super::bands::Scaled;
use super::element::ElementTangent;
use super::rod::Rod;
use crate::solver::{BlockTridiagonal, SystemMatrix};

pub trait Assembly {
    /// Its system matrices (Jacobians, tangents, mass).
    type Matrix: SystemMatrix;
    /// Each element's tangent, kept by a residual evaluation for the tangent map.
    type Tangents: Clone + std::fmt::Debug + Default;

    fn dofs(&self) -> usize;
    /// A zero matrix of its pattern.
    fn new_matrix(&self) -> Self::Matrix;
    /// Storage for every element's tangent.
    fn new_tangents(&self) -> Self::Tangents;
    /// A length of the model (its size: for tolerances on positions and arc lengths).
    fn length_scale(&self) -> f64;
    /// `EI / (rho A S^4)`: the scale of its lowest bending eigenvalues `omega^2`.
    fn bending_scale(&self) -> f64;

    /// The dofs removed from every system (identity rows and columns).
    fn constrained(&self) -> &[usize];
    /// Sets the held entries of a vector to zero (a correction, a right-hand side, a velocity).
    fn zero_constrained(&self, x: &mut [f64]);
    /// Makes a vector of displacements or velocities consistent: every dof that stands for
    /// another (a frame member's end, tied to its joint) takes its value. A vector made any
    /// other way than by the model's own solves (a seeded direction) must be, or the step
    /// carries the difference along forever.
    fn make_consistent(&self, _x: &mut [f64]) {}

    /// The dofs that repeat another (a frame member's end, tied to its joint): norms of state
    /// vectors count each physical dof once by leaving these out.
    fn duplicates(&self) -> &[usize] {
        &[]
    }

    /// Removes the constrained dofs from a matrix.
    fn constrain(&self, jac: &mut Self::Matrix) {
        jac.constrain(self.constrained());
    }

    /// `f = f_int(u)` (overwrites).
    fn internal_force(&self, u: &[f64], f: &mut [f64]);
    /// `f = f_int(u)` (overwrites) and `jac += scale * K_T(u)`.
    fn internal_force_and_tangent(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: &mut Self::Matrix,
        scale: f64,
    );
    /// [`Assembly::internal_force_and_tangent`] that also keeps each element's tangent.
    fn internal_force_and_tangent_kept(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: &mut Self::Matrix,
        scale: f64,
        kept: &mut Self::Tangents,
    );
    /// `f = f_int(u)` (overwrites) and each element's tangent into `kept`, not assembled.
    fn internal_force_and_element_tangents(
        &self,
        u: &[f64],
        f: &mut [f64],
        kept: &mut Self::Tangents,
    );
    /// `out = scale * (K1 - K0) y` (overwrites) from kept element tangents.
    fn tangent_change_times(
        &self,
        tangents: (&Self::Tangents, &Self::Tangents),
        y: &[f64],
        out: &mut [f64],
        scale: f64,
    );
    /// `jac += scale * K`, `K` assembled from the kept element tangents and the constant
    /// stiffness of the attachments.
    fn add_kept_tangents(&self, jac: &mut Self::Matrix, kept: &Self::Tangents, scale: f64);

    /// `f =` the energy-momentum discrete gradient between `ua` and `ub` (overwrites).
    fn discrete_gradient(&self, ua: &[f64], ub: &[f64], f: &mut [f64]);
    /// [`Assembly::discrete_gradient`] and `jac += scale * K_T((ua + ub) / 2)`.
    fn discrete_gradient_and_tangent(
        &self,
        ua: &[f64],
        ub: &[f64],
        f: &mut [f64],
        jac: &mut Self::Matrix,
        scale: f64,
    );

    /// `jac += scale * M`.
    fn add_mass(&self, jac: &mut Self::Matrix, scale: f64);
    /// `jac += scale * C`.
    fn add_damping(&self, jac: &mut Self::Matrix, scale: f64);
    /// `out += scale * M x`.
    fn add_mass_times(&self, x: &[f64], out: &mut [f64], scale: f64);
    /// `out += mass_scale * M x + damping_scale * C y`.
    fn add_mass_and_damping_times(
        &self,
        mass: (&[f64], f64),
        damping: (&[f64], f64),
        out: &mut [f64],
    );
    /// `out += M (a x + b y) + c C x + z` (see [`Rod::add_bracket_times`]).
    fn add_bracket_times(
        &self,
        bracket: (Scaled, Scaled),
        c: f64,
        z: Option<&[f64]>,
        out: &mut [f64],
    );

    /// Whether it has forces of the state and the step's rate (a link's dashpot along its
    /// current line): [`Assembly::add_state_damping`].
    fn has_state_damping(&self) -> bool {
        false
    }
    /// Adds to a step's residual the forces that depend on the state and on the step's rate
    /// (dashpots along a current direction: `c (e . d) / dt e`, `d` the increment of the
    /// dashpot's stretch, `e` its direction at the midpoint `u_n + du / 2`), and to `jac` their
    /// derivative along that direction (the change of `e` left out: Newton then converges
    /// linearly in them).
    fn add_state_damping(
        &self,
        _u_n: &[f64],
        _du: &[f64],
        _dt: f64,
        _out: &mut [f64],
        _jac: Option<&mut Self::Matrix>,
    ) {
    }
    /// What those forces dissipate over a step that ended at `u` with the increment `du`:
    /// `sum c (e . d)^2 / dt`.
    fn state_damping_dissipation(&self, _u: &[f64], _du: &[f64], _dt: f64) -> f64 {
        0.0
    }

    /// Whether it has forces with a kink (stops, cables: the stiffness jumps where they touch or
    /// tighten): [`Assembly::crosses_kink`].
    fn has_kinks(&self) -> bool {
        false
    }
    /// Whether such a force is on the other side of its kink at `u + w du` than at
    /// `u + w (du - c)` (the iterates after and before a Newton correction `c`): the
    /// correction's error is then not estimated from the contraction of the corrections.
    fn crosses_kink(&self, _u: &[f64], _du: &[f64], _c: &[f64], _w: f64) -> bool {
        false
    }
    /// Adds to a static Newton iteration's Jacobian at `u` a small stiffness of the open stops
    /// and slack cables (the residual keeps none): a part held only by them stays regular.
    fn add_static_regularization(&self, _u: &[f64], _jac: &mut Self::Matrix) {}
    /// The fraction of a static Newton correction `delta` from `u` to take: up to just past the
    /// first open stop or slack cable it closes (1 when none).
    fn static_step_limit(&self, _u: &[f64], _delta: &[f64]) -> f64 {
        1.0
    }

    /// The stored energy (elements and attachments).
    fn strain_energy(&self, u: &[f64]) -> f64;
    /// `v^T M v / 2`.
    fn kinetic_energy(&self, v: &[f64]) -> f64;
    /// `v^T C v`.
    fn dissipation_rate(&self, v: &[f64]) -> f64;
}

impl Assembly for Rod {
    type Matrix = BlockTridiagonal;
    type Tangents = Vec<ElementTangent>;

    fn dofs(&self) -> usize {
        Rod::dofs(self)
    }

    fn new_matrix(&self) -> BlockTridiagonal {
        BlockTridiagonal::new(self.nodes())
    }

    fn new_tangents(&self) -> Vec<ElementTangent> {
        vec![ElementTangent::default(); self.elements.len()]
    }

    fn length_scale(&self) -> f64 {
        self.curve.length()
    }

    fn bending_scale(&self) -> f64 {
        let c = &self.section;
        c.ei / (c.rho_a * self.curve.length().powi(4))
    }

    fn constrained(&self) -> &[usize] {
        Rod::constrained(self)
    }

    fn zero_constrained(&self, x: &mut [f64]) {
        Rod::zero_constrained(self, x);
    }

    fn internal_force(&self, u: &[f64], f: &mut [f64]) {
        Rod::internal_force(self, u, f);
    }

    fn internal_force_and_tangent(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: &mut BlockTridiagonal,
        scale: f64,
    ) {
        Rod::internal_force_and_tangent(self, u, f, jac, scale);
    }

    fn internal_force_and_tangent_kept(
        &self,
        u: &[f64],
        f: &mut [f64],
        jac: &mut BlockTridiagonal,
        scale: f64,
        kept: &mut Vec<ElementTangent>,
    ) {
        Rod::internal_force_and_tangent_kept(self, u, f, jac, scale, kept);
    }

    fn internal_force_and_element_tangents(
        &self,
        u: &[f64],
        f: &mut [f64],
        kept: &mut Vec<ElementTangent>,
    ) {
        Rod::internal_force_and_element_tangents(self, u, f, kept);
    }

    fn tangent_change_times(
        &self,
        (k1, k0): (&Vec<ElementTangent>, &Vec<ElementTangent>),
        y: &[f64],
        out: &mut [f64],
        scale: f64,
    ) {
        Rod::tangent_change_times(self, (k1, k0), y, out, scale);
    }

    fn add_kept_tangents(
        &self,
        jac: &mut BlockTridiagonal,
        kept: &Vec<ElementTangent>,
        scale: f64,
    ) {
        for (e, ke) in kept.iter().enumerate() {
            jac.add_pair(e, ke, scale);
        }
        self.add_attached_stiffness(jac, scale);
    }

    fn discrete_gradient(&self, ua: &[f64], ub: &[f64], f: &mut [f64]) {
        Rod::discrete_gradient(self, ua, ub, f);
    }

    fn discrete_gradient_and_tangent(
        &self,
        ua: &[f64],
        ub: &[f64],
        f: &mut [f64],
        jac: &mut BlockTridiagonal,
        scale: f64,
    ) {
        Rod::discrete_gradient_and_tangent(self, ua, ub, f, jac, scale);
    }

    fn add_mass(&self, jac: &mut BlockTridiagonal, scale: f64) {
        Rod::add_mass(self, jac, scale);
    }

    fn add_damping(&self, jac: &mut BlockTridiagonal, scale: f64) {
        Rod::add_damping(self, jac, scale);
    }

    fn add_mass_times(&self, x: &[f64], out: &mut [f64], scale: f64) {
        Rod::add_mass_times(self, x, out, scale);
    }

    fn add_mass_and_damping_times(
        &self,
        mass: (&[f64], f64),
        damping: (&[f64], f64),
        out: &mut [f64],
    ) {
        Rod::add_mass_and_damping_times(self, mass, damping, out);
    }

    fn add_bracket_times(
        &self,
        bracket: (Scaled, Scaled),
        c: f64,
        z: Option<&[f64]>,
        out: &mut [f64],
    ) {
        Rod::add_bracket_times(self, bracket, c, z, out);
    }

    fn strain_energy(&self, u: &[f64]) -> f64 {
        Rod::strain_energy(self, u)
    }

    fn kinetic_energy(&self, v: &[f64]) -> f64 {
        Rod::kinetic_energy(self, v)
    }

    fn dissipation_rate(&self, v: &[f64]) -> f64 {
        Rod::dissipation_rate(self, v)
    }
}
