//! What a simulation reports, by output id: sensors and shape samples read from the state with
//! the shape functions, support reactions, energies and the energy ledger.
use super::snapshot::EnergyLedger;
use super::Simulation;
use crate::model::Assembly;
use crate::scene::variables::{OutputId, StandardOutput};

/// Displacements and velocities beyond this have blown up in any unit system; refusing them
/// keeps every output (interpolations, positions, energies) finite.
const BLOWN_UP: f64 = 1e100;

impl Simulation {
    /// The value of an output at the current time.
    pub fn output(&self, id: OutputId) -> f64 {
        match id {
            OutputId::Standard(s) => self.standard_output(s),
            OutputId::Sensor(i) => {
                self.read(self.scene().sensors[i].quantity, self.setup().sensors[i])
            }
            OutputId::Reaction { support, component } => self.reactions()[support][component],
            OutputId::ShapeX(i) => self.shape_point(i)[0],
            OutputId::ShapeY(i) => self.shape_point(i)[1],
            OutputId::ShapeField { field, point } => {
                self.read(self.scene().shape_fields[field], self.setup().shape[point])
            }
            OutputId::Frequency(k) => self.frequency(k),
            OutputId::SpringForce(k) => self.reactions()[self.setup.support_nodes.len() + k][0],
            OutputId::LinkForce(k) => {
                let first = self.setup.support_nodes.len() + self.setup.springs.len();
                self.reactions()[first + k][0]
            }
            OutputId::StopForce(k) | OutputId::StopContact(k) => {
                let first = self.setup.support_nodes.len()
                    + self.setup.springs.len()
                    + self.setup.links.len();
                match id {
                    OutputId::StopForce(_) => self.reactions()[first + k][0],
                    // A sum of sub-step fractions over the step: round-off may pass 1.
                    _ => self.reactions()[first + k][1].clamp(0.0, 1.0),
                }
            }
            OutputId::SupportFrame { support, component } => {
                let [rx, ry, _] = self.reactions()[support];
                let a = self.setup.support_angles[support];
                let (c, s) = (libm::cos(a), libm::sin(a));
                match component {
                    0 => rx * c + ry * s,
                    _ => -rx * s + ry * c,
                }
            }
            OutputId::BarForce { member, .. } => match self.setup.members[member] {
                super::setup::MemberRole::Bar(b) => {
                    self.structure().axial[b].force(&self.state().u)
                }
                super::setup::MemberRole::Rod(_) => unreachable!("bar outputs are trusses'"),
            },
            OutputId::Lyapunov { index, per_period } => self
                .analysis
                .exponent(index, per_period.then_some(self.setup().loads.frequency)),
            OutputId::LyapunovTime => self.analysis.counted_time(),
        }
    }

    /// Current position of shape sample `i`: the reference curve plus the interpolated
    /// displacement.
    pub fn shape_point(&self, i: usize) -> [f64; 2] {
        let probe = self.setup().shape[i];
        let structure = self.structure();
        let x = structure.reference_position(probe);
        let u = &self.state().u;
        [
            x[0] + structure.interpolate(u, probe, 0),
            x[1] + structure.interpolate(u, probe, 1),
        ]
    }

    /// Kinetic and strain energy of the state (computed once after each change).
    fn energies(&self) -> (f64, f64) {
        if let Some(e) = self.energies.get() {
            return e;
        }
        let rod = self.structure();
        let e = (
            rod.kinetic_energy(&self.state().v),
            rod.strain_energy(&self.state().u)
                + super::springs::base_energy(&self.setup.springs, &self.state().u, &self.inputs),
        );
        self.energies.set(Some(e));
        e
    }

    pub fn kinetic_energy(&self) -> f64 {
        self.energies().0
    }

    pub fn strain_energy(&self) -> f64 {
        self.energies().1
    }

    /// `E_kin + E_strain - E(0) - W_ext - W_ctrl - W_supports + E_damped`.
    pub fn energy_error(&self) -> f64 {
        energy_error(self.kinetic_energy(), self.strain_energy(), self.energy())
    }

    fn standard_output(&self, s: StandardOutput) -> f64 {
        let e = self.energy();
        match s {
            StandardOutput::KineticEnergy => self.kinetic_energy(),
            StandardOutput::StrainEnergy => self.strain_energy(),
            StandardOutput::NewtonIterations => f64::from(self.last_newton_iterations()),
            StandardOutput::ExternalWork => e.external_work,
            StandardOutput::InputWork => e.input_work,
            StandardOutput::SupportWork => e.support_work,
            StandardOutput::Dissipated => e.dissipated,
            StandardOutput::EnergyError => self.energy_error(),
        }
    }

    /// The output named like an FMU variable (sensors, reactions, `shape_x[i]`, energies).
    pub fn output_by_name(&self, name: &str) -> Option<f64> {
        crate::scene::variables::variables(self.scene())
            .into_iter()
            .find(|v| v.name == name)
            .and_then(|v| match v.role {
                crate::scene::variables::Role::Output(id) => Some(self.output(id)),
                _ => None,
            })
    }

    /// A converged step can still reach numbers no output can show (overflow on absurd
    /// parameters): the trial state, its ledger and reactions must be finite and not blown up.
    pub(super) fn check_trial(&self) -> Result<(), &'static str> {
        // One sum of magnitudes per vector (cheaper than a test per entry): NaN and infinities
        // propagate into it and fail the comparison, and a sum within 1e100 bounds every entry.
        let bounded = |x: &[f64]| sum_of_magnitudes(x) <= BLOWN_UP;
        if !(bounded(&self.trial.u) && bounded(&self.trial.v)) {
            return Err("or blown-up displacement or velocity");
        }
        if !self.trial_energy.is_finite() {
            return Err("energy ledger");
        }
        if !self.trial_impulses.iter().flatten().all(|x| x.is_finite()) {
            return Err("reaction");
        }
        if !self.analysis.trial_is_finite() {
            return Err("Lyapunov tangent vector");
        }
        Ok(())
    }

    /// The trial's kinetic and strain energy, if they and the energy error are finite.
    pub(super) fn trial_energies(&self) -> Result<(f64, f64), &'static str> {
        let kinetic = self.setup.structure.kinetic_energy(&self.trial.v);
        let strain = self.setup.structure.strain_energy(&self.trial.u)
            + super::springs::base_energy(&self.setup.springs, &self.trial.u, &self.next_inputs);
        finite_energies(kinetic, strain, &self.trial_energy)
    }

    /// Every output finite (checked once, for the initial state: geometry and parameters that
    /// overflow show here).
    pub(super) fn check_outputs(&self) -> Result<(), String> {
        for v in crate::scene::variables::variables(self.scene()) {
            if let crate::scene::variables::Role::Output(id) = v.role {
                let x = self.output(id);
                if !x.is_finite() {
                    return Err(format!("output `{}` = {x}", v.name));
                }
            }
        }
        let blown = |x: &f64| x.abs() > BLOWN_UP;
        if self.state().u.iter().chain(&self.state().v).any(blown) {
            return Err("displacement or velocity (beyond 1e100)".to_string());
        }
        Ok(())
    }
}

/// `E_kin + E_strain - E(0) - W_ext - W_ctrl - W_supports + E_damped`: the `energy_error` output.
fn energy_error(kinetic: f64, strain: f64, e: &EnergyLedger) -> f64 {
    kinetic + strain - e.initial_energy - e.external_work - e.input_work - e.support_work
        + e.dissipated
}

/// The energies after a step, if they are finite and so is the energy error they make with the
/// ledger: a sum of finite terms can still overflow, and no output of a successful step may be
/// infinite.
fn finite_energies(
    kinetic: f64,
    strain: f64,
    ledger: &EnergyLedger,
) -> Result<(f64, f64), &'static str> {
    if !(kinetic.is_finite() && strain.is_finite()) {
        return Err("kinetic or strain energy");
    }
    if !energy_error(kinetic, strain, ledger).is_finite() {
        return Err("energy_error (its finite terms overflow)");
    }
    Ok((kinetic, strain))
}

/// `sum |x_i|` in four independent lanes (vectorizes; NaN and infinities propagate).
fn sum_of_magnitudes(x: &[f64]) -> f64 {
    let mut lanes = [0.0; 4];
    let chunks = x.chunks_exact(4);
    let rest: f64 = chunks.remainder().iter().map(|v| v.abs()).sum();
    for c in chunks {
        for (l, v) in lanes.iter_mut().zip(c) {
            *l += v.abs();
        }
    }
    lanes.iter().sum::<f64>() + rest
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energies_whose_error_overflows_are_refused() {
        let ledger = EnergyLedger {
            external_work: -1e308,
            ..EnergyLedger::default()
        };
        assert_eq!(finite_energies(1.0, 2.0, &ledger), Ok((1.0, 2.0)));
        // Every term finite, the sum is not.
        assert!(energy_error(1e308, 0.0, &ledger).is_infinite());
        assert!(finite_energies(1e308, 0.0, &ledger).is_err());
        assert!(finite_energies(0.9e308, 0.9e308, &EnergyLedger::default()).is_err());
        assert!(finite_energies(f64::INFINITY, 0.0, &EnergyLedger::default()).is_err());
        assert!(finite_energies(0.0, f64::NAN, &EnergyLedger::default()).is_err());
    }
}
