//! The force outputs of a frame's links (`<link>_force`, tension positive): each sub-step's
//! impulse of the spring at the midpoint state and of the dashpot over the step, averaged over
//! the communication step like a reaction; before the first step the static force.
use super::Simulation;
use crate::model::Structure;

/// Each link's static force at `u` (first component), after the supports' and springs'
/// reactions.
pub fn static_forces<'a>(
    structure: &'a Structure,
    links: &'a [usize],
    u: &'a [f64],
) -> impl Iterator<Item = [f64; 3]> + 'a {
    links
        .iter()
        .map(move |&a| [structure.axial[a].force(u), 0.0, 0.0])
}

impl Simulation {
    /// After a sub-step of size `dt`: adds each link's impulse, `dt k (l_mid - rest) + c (e .
    /// d)` (`d` the increment of its ends' separation, `e` its direction at the midpoint), to
    /// its entry after the supports' and springs'.
    pub(super) fn book_links(&mut self, dt: f64) {
        if self.setup.links.is_empty() {
            return;
        }
        let first = self.setup.support_nodes.len() + self.setup.springs.len();
        let du = self.integrator.last_increment();
        let u = &self.trial.u;
        let structure = &self.setup.structure;
        for (j, &a) in self.trial_impulses[first..]
            .iter_mut()
            .zip(&self.setup.links)
        {
            let link = &structure.axial[a];
            let [p, q] = link.nodes;
            // The midpoint chord: the end state's minus half the increment.
            let mut r = link.chord(u);
            r[0] -= 0.5 * (du[3 * q] - du[3 * p]);
            r[1] -= 0.5 * (du[3 * q + 1] - du[3 * p + 1]);
            let d = nalgebra::Vector2::new(du[3 * q] - du[3 * p], du[3 * q + 1] - du[3 * p + 1]);
            let l = r.norm();
            j[0] += dt * link.k * (l - link.rest) + link.c * (r / l).dot(&d);
        }
    }
}
