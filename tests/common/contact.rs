//! Helpers of the contact tests (`tests/contact_*.rs`): a stiff beam that heaves as a rigid body
//! on springs and stops (its release from a displaced state, the times it crosses a level), the
//! example `ImpactingCantilever` with its stop's dashpot set, and the largest Lyapunov exponent
//! by two nearby trajectories.
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

/// The example `examples/ImpactingCantilever.toml` with its stop's dashpot `c` and parameters
/// overridden by name; a refusal as its message.
pub fn impacting_cantilever(overrides: &[(&str, f64)], c: f64) -> Result<Simulation, String> {
    let path = format!(
        "{}/examples/ImpactingCantilever.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).expect("the example");
    assert!(text.contains("c = 0.0 "), "the example's stop has c = 0.0");
    let text = text.replace("c = 0.0 ", &format!("c = {c} "));
    let scene = georod::scene::Scene::parse(&text, "ImpactingCantilever.toml").unwrap();
    let values = scene
        .values_with(overrides.iter().copied())
        .map_err(|e| e.to_string())?;
    Simulation::new(std::sync::Arc::new(scene), values).map_err(|e| e.to_string())
}

/// The largest Lyapunov exponent per period `2 pi / omega` by two trajectories (Benettin):
/// `twin` (a copy of `reference`) starts `d0` away along `reference`'s first tangent vector's
/// initial direction and is pulled back to `d0` along its separation after every period
/// (through snapshots), in the core's norm `|du|^2 + |dv / omega|^2` over the `free` dofs; the
/// growth is averaged after `skip` periods.
pub fn twin_exponent(
    reference: &mut Simulation,
    twin: &mut Simulation,
    free: &[usize],
    omega: f64,
    (periods, skip): (usize, usize),
    d0: f64,
) -> f64 {
    let period = 2.0 * std::f64::consts::PI / omega;
    let direction = reference.snapshot().lyapunov.expect("tangent vectors");
    let place = |twin: &mut Simulation, reference: &Simulation, du: &[f64], dv: &[f64], s| {
        let mut state = reference.snapshot();
        for &i in free {
            state.displacements[i] += s * du[i];
            state.velocities[i] += s * dv[i];
        }
        twin.restore(&state).unwrap();
    };
    place(twin, reference, &direction.du, &direction.dv, d0);
    let mut growth = 0.0;
    for p in 0..periods {
        reference.advance(period).unwrap();
        twin.advance(period).unwrap();
        let (r, t) = (reference.state(), twin.state());
        let du: Vec<f64> = (0..r.u.len()).map(|i| t.u[i] - r.u[i]).collect();
        let dv: Vec<f64> = (0..r.v.len()).map(|i| t.v[i] - r.v[i]).collect();
        let d = (free.iter())
            .map(|&i| du[i] * du[i] + (dv[i] / omega).powi(2))
            .sum::<f64>()
            .sqrt();
        if p >= skip {
            growth += (d / d0).ln();
        }
        place(twin, reference, &du, &dv, d0 / d);
    }
    growth / (periods - skip) as f64
}

/// A 1 m beam 1e5 times as stiff as steel (it heaves as a rigid body: tests/suite/contact_stops.rs),
/// guided along e2 at its middle, steps of `dt`, scheme `integrator`: the start of the scenes
/// that put springs and stops under it.
pub fn guided_block(name: &str, dt: f64, integrator: f64) -> String {
    format!(
        r#"
name = "{name}"
[defaults]
E = 2.1e16
nu = 0.3
rho = 7850.0
d = 0.0
elements = 10
dt_max = {dt}
integrator = {integrator}
[section]
b = 0.1
h = 0.1
[geometry]
shape = "straight"
L = 1.0
[[support]]
name = "guide"
at = 0.5
fix = ["u1"]
"#
    )
}
