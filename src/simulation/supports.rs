//! What the supports do during a communication step: moving supports follow their inputs
//! (linearly over the step), a change of their speed is an impulse on the rod, and every held
//! dof's reaction is accumulated as an impulse so that the step reports its average.
//!
//! A support's speed jumps at a communication point when its input path changes slope. With the
//! consistent mass, the free dofs next to it must then change speed too, so that the impulse
//! acts on the held dofs only: `M_ff dv_f = -M_fc dv_c`. The impulse `J = (M dv)_c` is part of
//! the step's reaction (`J / h` of the average), and its work `J . (v_c- + v_c+) / 2` is part
//! of the supports' work (it is exactly the kinetic energy it adds).
use super::setup::{Held, Setup};
use super::snapshot::EnergyLedger;
use super::Simulation;

/// The path of a moving held dof over one communication step of length `h`: linear from
/// `start` to `end` (the value set for its input), or, when the host gave the input's
/// derivatives, their polynomial from where the support is: `start + d1 t + d2 t^2 / 2`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MotionPath {
    start: f64,
    end: f64,
    derivatives: Option<[f64; 2]>,
    h: f64,
}

impl MotionPath {
    /// The position after the fraction `f` (0..=1) of the step.
    pub fn position(&self, f: f64) -> f64 {
        match self.derivatives {
            None if f == 1.0 => self.end,
            None => self.start + (self.end - self.start) * f,
            Some([d1, d2]) => {
                let t = f * self.h;
                self.start + d1 * t + 0.5 * d2 * t * t
            }
        }
    }

    /// The speed at the start of the step.
    pub fn initial_speed(&self) -> f64 {
        match self.derivatives {
            None => (self.end - self.start) / self.h,
            Some([d1, _]) => d1,
        }
    }
}
use crate::integrator::{DynamicState, Midpoint};
use crate::model::{Assembly, Structure};
use crate::solver::SystemMatrix;

/// The mass matrix with the held dofs removed, factored, and scratch vectors (made once).
pub struct MotionSolver<A: Assembly> {
    mass: A::Matrix,
    dv: Vec<f64>,
    impulse: Vec<f64>,
}

impl<A: Assembly> MotionSolver<A> {
    /// Fails when the mass matrix cannot be factored (a density or section so small that the
    /// masses underflow).
    pub fn new(rod: &A) -> Result<MotionSolver<A>, String> {
        let mut mass = rod.new_matrix();
        rod.add_mass(&mut mass, 1.0);
        rod.constrain(&mut mass);
        mass.factor().map_err(|e| {
            format!("the mass matrix has a {e}: rho A or rho I too small to be represented")
        })?;
        Ok(MotionSolver {
            mass,
            dv: vec![0.0; rod.dofs()],
            impulse: vec![0.0; rod.dofs()],
        })
    }

    /// Sets the held dofs' velocities to `speeds` (one per entry of `held` with an input;
    /// others stay at rest), with the impulse that does it. Books the impulse per support in
    /// `impulses` and its work in `ledger`.
    pub fn change_speeds(
        &mut self,
        rod: &A,
        held: &[Held],
        speeds: &[f64],
        state: &mut DynamicState,
        impulses: &mut [[f64; 3]],
        ledger: &mut EnergyLedger,
    ) {
        self.dv.fill(0.0);
        let mut any = false;
        for (h, &speed) in held.iter().filter(|h| h.input.is_some()).zip(speeds) {
            self.dv[h.dof] = speed - state.v[h.dof];
            any |= self.dv[h.dof] != 0.0;
        }
        if !any {
            return;
        }
        // A frame's member ends at a moving joint change speed with it.
        rod.make_consistent(&mut self.dv);
        self.impulse.fill(0.0);
        rod.add_mass_times(&self.dv, &mut self.impulse, -1.0);
        rod.zero_constrained(&mut self.impulse);
        self.mass.solve_in_place(&mut self.impulse);
        // `impulse` now holds dv_f (zero on the held dofs); add the held part back.
        for (d, f) in self.dv.iter_mut().zip(&self.impulse) {
            *d += f;
        }
        self.impulse.fill(0.0);
        rod.add_mass_times(&self.dv, &mut self.impulse, 1.0);
        for h in held {
            let j = self.impulse[h.dof];
            let v_before = state.v[h.dof];
            let v_after = v_before + self.dv[h.dof];
            impulses[h.support][h.component] += j;
            ledger.support_work += 0.5 * j * (v_before + v_after);
        }
        for (v, d) in state.v.iter_mut().zip(&self.dv) {
            *v += d;
        }
    }
}

/// Adds the reaction impulses of the sub-step just taken (`dt` times the held dofs' rows of the
/// equation of motion, see `Midpoint::held_rows`) and the supports' work over it.
pub fn book_reactions(
    setup: &Setup,
    integrator: &Midpoint<Structure>,
    dt: f64,
    impulses: &mut [[f64; 3]],
    ledger: &mut EnergyLedger,
) {
    let du = integrator.last_increment();
    let mut rows = integrator.held_rows().iter();
    for h in &setup.held {
        match h.direction {
            None => {
                let r = *rows.next().expect("a row per held dof");
                impulses[h.support][h.component] += dt * r;
                ledger.support_work += r * du[h.dof];
            }
            Some([n1, n2]) => {
                // The support pushes along its direction only: the rows' component along it.
                let (rx, ry) = (*rows.next().expect("u1"), *rows.next().expect("u2"));
                let along = n1 * rx + n2 * ry;
                impulses[h.support][0] += dt * along * n1;
                impulses[h.support][1] += dt * along * n2;
                ledger.support_work += along * (n1 * du[h.dof] + n2 * du[h.dof + 1]);
            }
        }
    }
}

/// The static reactions of an equilibrium `u` under the constant loads: `f_int - f_const` on
/// the held dofs (they balance the loads exactly up to round-off).
///
/// After the supports, one entry per spring: its static force on the rod `-k (u - b)` (first
/// component, the bases at `inputs`), booked like a reaction over the steps (see
/// `Simulation::book_springs`).
pub fn static_reactions(setup: &Setup, u: &[f64], inputs: &[f64]) -> Vec<[f64; 3]> {
    let rod = &setup.structure;
    // A frame's rows are its members' folded: the whole internal force, once.
    let full = (!rod.is_single()).then(|| {
        let mut f = vec![0.0; rod.dofs()];
        rod.internal_force(u, &mut f);
        f
    });
    let supports = setup.support_nodes.iter().map(|&node| {
        let f = match &full {
            None => rod.rod().node_internal_force(u, node),
            Some(f) => Structure::node_rows(f, node),
        };
        let mut r = [0.0; 3];
        let along_direction = rod.held_directions().iter().any(|&(n, _)| n == node);
        for c in 0..3 {
            if rod.is_held(3 * node + c) || (along_direction && c < 2) {
                r[c] = f[c] - setup.loads.constant_at(3 * node + c);
            }
        }
        r
    });
    let springs = super::springs::static_forces(&setup.springs, u, inputs);
    let links = super::links::static_forces(&setup.structure, &setup.links, u);
    let stops = super::contact::static_forces(&setup.structure, u);
    supports.chain(springs).chain(links).chain(stops).collect()
}

impl Simulation {
    /// Sets up the moving supports' paths over a step of `h` and their speed change.
    pub(super) fn start_motion(&mut self, h: f64) {
        let Some(motion) = self.motion.as_mut() else {
            return;
        };
        let moving = self
            .setup
            .held
            .iter()
            .filter_map(|h| h.input.map(|i| (h.dof, i)));
        let paths = self
            .motion_path
            .iter_mut()
            .zip(self.motion_speeds.iter_mut());
        for ((dof, input), (path, speed)) in moving.zip(paths) {
            *path = MotionPath {
                start: self.trial.u[dof],
                end: self.next_inputs[input],
                derivatives: self.input_derivatives[input],
                h,
            };
            *speed = path.initial_speed();
        }
        motion.change_speeds(
            &self.setup.structure,
            &self.setup.held,
            &self.motion_speeds,
            &mut self.trial,
            &mut self.trial_impulses,
            &mut self.trial_energy,
        );
    }

    /// The increments of the moving held dofs over sub-step `k` of `n`.
    pub(super) fn motion_increments(&mut self, k: usize, n: usize) {
        if self.motion_path.is_empty() {
            return; // no moving support: `prescribed` stays empty
        }
        self.prescribed.clear();
        let moving = self.setup.held.iter().filter(|h| h.input.is_some());
        for (h, path) in moving.zip(&self.motion_path) {
            let at = |j: usize| path.position(j as f64 / n as f64);
            self.prescribed.push((h.dof, at(k + 1) - at(k)));
        }
    }

    /// Load inputs with derivatives follow their polynomial over the step: their magnitudes at
    /// the sub-step's midpoint `t` (from the start of the step) rebuild the load set.
    pub(super) fn interpolate_load_inputs(&mut self, t: f64) {
        if !self.input_derivatives.iter().any(Option::is_some) {
            return;
        }
        let mut changed = false;
        for (l, m) in self.scene.loads.iter().zip(self.magnitudes.iter_mut()) {
            if let crate::scene::TimeLaw::Input(i) = l.time {
                if let Some([d1, d2]) = self.input_derivatives[i] {
                    *m = self.next_inputs[i] + d1 * t + 0.5 * d2 * t * t;
                    changed = true;
                }
            }
        }
        if changed {
            self.setup.loads.set_magnitudes(&self.magnitudes);
        }
    }
}
