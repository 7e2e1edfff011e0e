//! What sensors and shape fields read beyond displacements and velocities: accelerations over
//! the last sub-step, and the section quantities (strains, stress resultants, fiber stresses)
//! from the elements' own strains and resultants. Section quantities are computed when read
//! (an element or two per reading); accelerations cost one copy of the velocities per
//! communication step, and only in scenes that read them.
use super::setup::Setup;
use super::{SimError, Simulation};
use crate::model::{Place, Structure};
use crate::scene::{ParamValues, Quantity, Reading, Scene, SectionQuantity};

/// The section's geometry for fiber stresses: area, second moment of area, depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fibers {
    pub area: f64,
    pub inertia: f64,
    /// Distance between the top (`+d2`) and the bottom (`-d2`) fiber.
    pub depth: f64,
}

impl Fibers {
    /// The scene's section (`[section]`, the `b x h` rectangle by default). A section without a
    /// depth (a general one that gives none) has NaN: the scene checker refuses fiber stresses
    /// there, so no output reads it.
    pub fn of(scene: &Scene, values: &ParamValues) -> Fibers {
        let properties = scene.section.properties(values);
        Fibers {
            area: properties.area,
            inertia: properties.inertia,
            depth: scene.section.depth(values).unwrap_or(f64::NAN),
        }
    }

    /// Per member of the scene: its own section's, or the scene's.
    pub fn of_members(scene: &Scene, values: &ParamValues) -> Vec<Fibers> {
        let Some(frame) = &scene.frame else {
            return vec![Fibers::of(scene, values)];
        };
        (frame.members.iter())
            .map(|m| match &m.section {
                None => Fibers::of(scene, values),
                Some(own) => {
                    let p = own.properties(values);
                    Fibers {
                        area: p.area,
                        inertia: p.inertia,
                        depth: own.depth(values).unwrap_or(f64::NAN),
                    }
                }
            })
            .collect()
    }
}

/// Accelerations of the last sub-step and the section's fiber geometry.
pub(super) struct Readouts {
    /// `(v_(n+1) - v_n) / dt` of the last sub-step of the last communication step, per dof;
    /// empty when no output reads accelerations (nothing is then copied in a step).
    accelerations: Vec<f64>,
    trial_accelerations: Vec<f64>,
    /// The trial's velocities before its last sub-step.
    velocity_before: Vec<f64>,
    /// Per member of the structure (rods), and per truss bar (axial elements in order).
    fibers: Vec<Fibers>,
    bar_fibers: Vec<Fibers>,
    /// `frequency[k]` in Hz (`[modes] count` of them).
    frequencies: Vec<f64>,
}

/// Whether any output of the scene reads an acceleration.
fn reads_accelerations(scene: &Scene) -> bool {
    let sensors = scene.sensors.iter().map(|s| s.quantity);
    sensors
        .chain(scene.shape_fields.iter().copied())
        .any(Quantity::is_acceleration)
}

impl Readouts {
    /// The readouts of a simulation whose initial displacements are `initial` (its natural
    /// frequencies are computed here, once).
    pub(super) fn new(
        scene: &Scene,
        values: &ParamValues,
        setup: &Setup,
        initial: &[f64],
    ) -> Result<Readouts, SimError> {
        let n = if reads_accelerations(scene) {
            setup.structure.dofs()
        } else {
            0
        };
        Ok(Readouts {
            accelerations: vec![0.0; n],
            trial_accelerations: vec![0.0; n],
            velocity_before: vec![0.0; n],
            fibers: member_fibers(scene, values, setup, false),
            bar_fibers: member_fibers(scene, values, setup, true),
            frequencies: natural_frequencies(&setup.structure, initial, scene.modes)?,
        })
    }

    /// Called before the last sub-step of an attempt, with the trial's velocities.
    pub(super) fn before_last_substep(&mut self, v: &[f64]) {
        if !self.velocity_before.is_empty() {
            self.velocity_before.copy_from_slice(v);
        }
    }

    /// Called after the last sub-step (of size `dt`) of an attempt.
    pub(super) fn after_last_substep(&mut self, v: &[f64], dt: f64) {
        for ((a, after), before) in self
            .trial_accelerations
            .iter_mut()
            .zip(v)
            .zip(&self.velocity_before)
        {
            *a = (after - before) / dt;
        }
    }

    /// The attempt succeeded: its accelerations are the state's.
    pub(super) fn commit(&mut self) {
        std::mem::swap(&mut self.accelerations, &mut self.trial_accelerations);
    }

    /// Back to rest (before the first step no sub-step has been taken: 0).
    pub(super) fn reset(&mut self) {
        self.accelerations.fill(0.0);
    }

    /// The accelerations for a snapshot (empty when the scene reads none).
    pub(super) fn accelerations(&self) -> &[f64] {
        &self.accelerations
    }

    /// Whether a snapshot's accelerations fit this scene (and are finite).
    pub(super) fn fits(&self, a: &[f64]) -> bool {
        a.len() == self.accelerations.len() && a.iter().all(|x| x.is_finite())
    }

    /// Restores the accelerations of a snapshot that [`Readouts::fits`].
    pub(super) fn restore(&mut self, a: &[f64]) {
        self.accelerations.copy_from_slice(a);
    }
}

/// The fiber geometry of each rod member of the structure (or of each bar, with `bars`).
fn member_fibers(scene: &Scene, values: &ParamValues, setup: &Setup, bars: bool) -> Vec<Fibers> {
    let all = Fibers::of_members(scene, values);
    (setup.members.iter().zip(all))
        .filter(|(role, _)| matches!(role, super::setup::MemberRole::Bar(_)) == bars)
        .map(|(_, f)| f)
        .collect()
}

/// The `count` lowest natural frequencies (Hz) of the rod about `u` (undamped, the tangent
/// stiffness at `u` with the held dofs removed, the mass matrix of the model); an unstable
/// direction (`omega^2 < 0`) gives `-sqrt(-omega^2) / (2 pi)`.
pub fn natural_frequencies(rod: &Structure, u: &[f64], count: usize) -> Result<Vec<f64>, SimError> {
    if count == 0 {
        return Ok(Vec::new());
    }
    let modes = crate::model::modal_subspace::lowest_modes(rod, u, count)
        .map_err(|why| SimError::BadArgument(format!("[modes] count = {count}: {why}")))?;
    Ok(modes.iter().map(|(lambda, _)| hertz(*lambda)).collect())
}

/// `omega / (2 pi)` of `lambda = omega^2`, signed: `-sqrt(-lambda) / (2 pi)` when negative.
pub fn hertz(lambda: f64) -> f64 {
    lambda.signum() * lambda.abs().sqrt() / std::f64::consts::TAU
}

impl Simulation {
    /// `frequency[k + 1]` (Hz) of the initial state.
    pub fn frequency(&self, k: usize) -> f64 {
        self.readouts.frequencies[k]
    }

    /// `quantity` at arc length `s` (a sensor's or a shape sample's point `point`).
    pub fn read(&self, quantity: Quantity, point: super::setup::Probe) -> f64 {
        match quantity.reading() {
            Reading::Nodal { dof, order } => {
                let x = match order {
                    0 => &self.state().u,
                    1 => &self.state().v,
                    _ => &self.readouts.accelerations,
                };
                self.structure().interpolate(x, point, dof)
            }
            Reading::Section(q) => self.section_quantity(q, point),
        }
    }

    /// A section quantity of a truss bar: its normal force, constant along it (no shear, no
    /// moment).
    fn bar_quantity(&self, q: SectionQuantity, bar: usize) -> f64 {
        let b = &self.structure().axial[bar];
        let n = b.force(&self.state().u);
        let area = self.readouts.bar_fibers[bar].area;
        match q {
            SectionQuantity::N => n,
            SectionQuantity::Eps => n / (b.k * b.rest),
            SectionQuantity::SigmaTop | SectionQuantity::SigmaBottom => n / area,
            SectionQuantity::Q
            | SectionQuantity::M
            | SectionQuantity::Gamma
            | SectionQuantity::Kappa => 0.0,
        }
    }

    /// A section quantity at a place of a member (docs/model.md, "Section quantities"; a
    /// joint has no section: the scene names the member there).
    pub fn section_quantity(&self, q: SectionQuantity, place: Place) -> f64 {
        let (member, s) = match place {
            Place::Member { member, s, .. } => (member, s),
            Place::Bar { bar, .. } => return self.bar_quantity(q, bar),
            Place::Joint(_) => {
                unreachable!("a section quantity is read on a member (checked with the scene)")
            }
        };
        let m = &self.structure().members[member];
        let rod = &m.rod;
        let f = rod.section_forces_at(&self.state().u[m.range()], s);
        let c = &rod.section;
        let Fibers {
            area,
            inertia,
            depth,
        } = self.readouts.fibers[member];
        match q {
            SectionQuantity::N => f.n,
            SectionQuantity::Q => f.q,
            SectionQuantity::M => f.m,
            SectionQuantity::Eps => f.n / c.ea,
            SectionQuantity::Gamma => f.q / c.ga,
            SectionQuantity::Kappa => f.m / c.ei,
            SectionQuantity::SigmaTop => f.n / area - f.m * depth / (2.0 * inertia),
            SectionQuantity::SigmaBottom => f.n / area + f.m * depth / (2.0 * inertia),
        }
    }
}
