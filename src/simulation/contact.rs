//! A scene's stops and cubic springs in a simulation (docs/model.md, section 14): placed on the
//! structure's master dofs, their outputs booked per sub-step like reactions (`<stop>_force`:
//! the impulse of the spring and dashpot the step applied; `<stop>_contact`: the time in contact,
//! the penetration taken linear over each sub-step), the cubic springs' moving bases, and the
//! check that a softening spring has not passed the peak of its force.
use super::setup::{MemberRole, Setup, SpringOnRod};
use super::Simulation;
use crate::model::structure::{CubicSpring, Stop};
use crate::model::{Place, Structure};
use crate::scene::{Scene, Station};

/// The place of a station that is a node of the structure.
fn node_place(setup: &Setup, station: Station) -> Place {
    match station {
        Station::Joint(j) => Place::Joint(j),
        Station::On { member, at } => match setup.members[member] {
            MemberRole::Rod(r) => {
                let length = setup.structure.members[r].rod.curve.length();
                setup.structure.member_place(r, at * length)
            }
            MemberRole::Bar(_) => unreachable!("nothing sits inside a truss bar (checked)"),
        },
    }
}

/// Adds the scene's stops and the cubic parts of its springs to the structure (the bases at 0).
pub(super) fn attach(scene: &Scene, setup: &mut Setup) {
    let stops = (scene.stops.iter())
        .map(|s| Stop {
            dof: setup.structure.node_dof(node_place(setup, s.at), s.dof),
            sign: s.sign,
            gap: s.gap,
            k: s.k,
            c: s.c,
        })
        .collect();
    let cubic = (setup.springs.iter().enumerate())
        .filter(|(_, s)| s.k3 != 0.0)
        .map(|(i, s)| CubicSpring {
            spring: i,
            dof: setup.structure.master(s.dof),
            k: s.k,
            k3: s.k3,
            base: [0.0; 2],
        })
        .collect();
    setup.structure.nonlinear.stops = stops;
    setup.structure.nonlinear.cubic = cubic;
}

/// Where a spring's base is with the inputs at `inputs` (0 for a fixed base).
fn base(spring: &SpringOnRod, inputs: &[f64]) -> f64 {
    spring.base.map_or(0.0, |i| inputs[i])
}

/// Sets every cubic spring's base at rest where the inputs put it.
pub(super) fn rest_bases(structure: &mut Structure, springs: &[SpringOnRod], inputs: &[f64]) {
    for i in 0..structure.nonlinear.cubic.len() {
        let spring = &springs[structure.nonlinear.cubic[i].spring];
        if spring.base.is_some() {
            let b = base(spring, inputs);
            structure.set_cubic_base(i, b, b);
        }
    }
}

/// The static force of each stop on the structure at `u` (first component) and whether it
/// touches (second), after the supports', springs' and links' reactions.
pub fn static_forces<'a>(
    structure: &'a Structure,
    u: &'a [f64],
) -> impl Iterator<Item = [f64; 3]> + 'a {
    structure.nonlinear.stops.iter().map(move |s| {
        let p = s.penetration(u);
        let force = -s.sign * crate::model::contact::one_sided_force(s.k, p);
        [force, if p > 0.0 { 1.0 } else { 0.0 }, 0.0]
    })
}

/// Why a softening spring at the state `u` (its base where the structure has it) is past the
/// peak of its force, if one is.
pub(super) fn past_peak(scene: &Scene, structure: &Structure, u: &[f64]) -> Option<String> {
    structure.nonlinear.cubic.iter().find_map(|c| {
        let r = u[c.dof] - c.base[1];
        let stiffness = c.stiffness(r);
        (stiffness <= 0.0).then(|| {
            let name = &scene.springs[c.spring].name;
            let key = crate::scene::stops::entry_key("spring", c.spring, name, "k3");
            let peak = (c.k / (-3.0 * c.k3)).sqrt();
            format!(
                "{key}: spring `{name}` is past the peak of its force: its stiffness \
                 k + 3 k3 (u - b)^2 is {stiffness:.4e} at u - b = {r:.4e}; with k3 = {} < 0 it \
                 carries at most {:.4e} (at |u - b| = {peak:.4e}): a softening spring must stay \
                 below its peak (lower the load, raise k, or make k3 smaller in magnitude)",
                c.k3,
                2.0 / 3.0 * c.k * peak
            )
        })
    })
}

/// Why a static state may not have been found (`why`): what the one-sided supports and the
/// softening springs can carry.
pub(super) fn explain_static_failure(scene: &Scene, setup: &Setup, why: String) -> String {
    let mut out = why;
    if !scene.stops.is_empty() {
        let names: Vec<&str> = scene.stops.iter().map(|s| s.name.as_str()).collect();
        out += &format!(
            ". The stops ({}) hold only where the loads press the structure onto them: if the \
             loads pull it off them, what else holds it must (add a support or a spring), or \
             start from [initial] state = \"reference\"",
            names.join(", ")
        );
    }
    if let Some(limits) = softening_limits(scene, &setup.structure) {
        out += &format!(". A softening spring cannot carry more than its peak force: {limits}");
    }
    out
}

/// In a static state `u`: a joint of a frame that only cables hold (no rod or truss member,
/// support, spring, stop or link there) whose cables are all slack: nothing holds it (its
/// position is not determined), refused with the key of its first cable.
pub(super) fn slack_joint(scene: &Scene, setup: &Setup, u: &[f64]) -> Option<String> {
    let frame = scene.frame.as_ref()?;
    let at = |j: usize, s: &Station| *s == Station::Joint(j);
    (0..frame.joints.len()).find_map(|j| {
        let members: Vec<usize> = (0..frame.members.len())
            .filter(|&m| frame.members[m].from == j || frame.members[m].to == j)
            .collect();
        let held = scene.supports.iter().any(|s| at(j, &s.at))
            || scene.springs.iter().any(|s| at(j, &s.at))
            || scene.stops.iter().any(|s| at(j, &s.at))
            || (frame.links.iter()).any(|l| l.ends.iter().any(|e| at(j, e)));
        let slack = |m: usize| match setup.members[m] {
            MemberRole::Bar(b) => {
                let a = &setup.structure.axial[b];
                a.tension_only && a.chord(u).norm() < a.rest * (1.0 - 1e-12)
            }
            MemberRole::Rod(_) => false,
        };
        if held || members.is_empty() || !members.iter().all(|&m| slack(m)) {
            return None;
        }
        let names: Vec<&str> = members
            .iter()
            .map(|&m| frame.members[m].name.as_str())
            .collect();
        let first = members[0];
        let key =
            crate::scene::stops::entry_key("member", first, &frame.members[first].name, "kind");
        Some(format!(
            "{key}: in the static state every cable at joint `{}` ({}) is slack and nothing else \
             holds the joint: a cable carries tension only (hold the joint with a rod or truss \
             member, a support or a spring, or load it so that its cables pull)",
            frame.joints[j].name,
            names.join(", ")
        ))
    })
}

/// The most each softening spring of the scene can carry, for a static state that was not found.
fn softening_limits(scene: &Scene, structure: &Structure) -> Option<String> {
    let limits: Vec<String> = (structure.nonlinear.cubic.iter())
        .filter(|c| c.k3 < 0.0)
        .map(|c| {
            let peak = (c.k / (-3.0 * c.k3)).sqrt();
            format!(
                "spring `{}` (k3 < 0) carries at most {:.4e}, at |u - b| = {peak:.4e}",
                scene.springs[c.spring].name,
                2.0 / 3.0 * c.k * peak
            )
        })
        .collect();
    (!limits.is_empty()).then(|| limits.join("; "))
}

impl Simulation {
    /// Before sub-step `k` of `n`: each moving cubic spring's base at its start and end.
    pub(super) fn set_cubic_bases(&mut self, k: usize, n: usize) {
        let structure = &mut self.setup.structure;
        for i in 0..structure.nonlinear.cubic.len() {
            let spring = &self.setup.springs[structure.nonlinear.cubic[i].spring];
            if let Some(input) = spring.base {
                let (from, to) = (self.inputs[input], self.next_inputs[input]);
                let at = |j: usize| match j {
                    j if j == n => to,
                    j => from + (to - from) * (j as f64 / n as f64),
                };
                structure.set_cubic_base(i, at(k), at(k + 1));
            }
        }
    }

    /// Outside a step: every cubic spring's base where the held inputs put it.
    pub(super) fn rest_cubic_bases(&mut self) {
        rest_bases(&mut self.setup.structure, &self.setup.springs, &self.inputs);
    }

    /// After a sub-step of size `dt`: adds each stop's impulse on the structure and its time in
    /// contact to its entry after the supports', springs' and links'.
    pub(super) fn book_stops(&mut self, dt: f64) {
        let nonlinear = &self.setup.structure.nonlinear;
        if nonlinear.stops.is_empty() {
            return;
        }
        let first =
            self.setup.support_nodes.len() + self.setup.springs.len() + self.setup.links.len();
        let du = self.integrator.last_increment();
        let u = &self.trial.u;
        for (j, s) in self.trial_impulses[first..]
            .iter_mut()
            .zip(&nonlinear.stops)
        {
            let step = nonlinear.stop_step(s, u, du, dt);
            j[0] -= s.sign * (step.spring + step.dashpot) * dt;
            j[1] += step.contact * dt;
        }
    }

    /// After a sub-step: an error naming the softening spring the step took past its peak.
    pub(super) fn check_softening(&self) -> Result<(), String> {
        if self.setup.structure.nonlinear.cubic.is_empty() {
            return Ok(());
        }
        match past_peak(&self.scene, &self.setup.structure, &self.trial.u) {
            None => Ok(()),
            Some(why) => Err(why),
        }
    }
}
