//! A beam that heaves as a rigid body (the contact tests: a stiff beam on springs and stops):
//! its release from a displaced state and the times it crosses a level.
use georod::simulation::Simulation;

/// Moves every node along e2 by `du` at the speed `v` (a rigid heave), as the state at t = 0,
/// with the energy ledger starting there.
pub fn release(sim: &mut Simulation, du: f64, v: f64) {
    let mut s = sim.snapshot();
    for i in 0..s.displacements.len() / 3 {
        s.displacements[3 * i + 1] += du;
        s.velocities[3 * i + 1] = v;
    }
    sim.restore(&s).expect("a state of the beam");
    s.energy.initial_energy = sim.kinetic_energy() + sim.strain_energy();
    sim.restore(&s).expect("with its ledger");
}

/// The times at which `x` crosses `level` upwards, linearly interpolated between samples.
pub fn up_crossings(t: &[f64], x: &[f64], level: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 1..t.len() {
        let (a, b) = (x[i - 1] - level, x[i] - level);
        if a < 0.0 && b >= 0.0 {
            out.push(t[i - 1] + (t[i] - t[i - 1]) * a / (a - b));
        }
    }
    out
}

/// The mean period between the first and the last of the crossings.
pub fn mean_period(crossings: &[f64]) -> f64 {
    (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64
}
