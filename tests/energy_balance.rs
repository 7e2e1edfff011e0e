//! Energy bookkeeping of a forced, damped, controlled run: `E_kin + E_strain - E(0) - W_ext -
//! W_ctrl + E_damped` is round-off for the discrete-gradient scheme (it balances each step
//! exactly) and second order in the step for the midpoint rule.
use georod::scene::{SceneKind, SceneParams};
use georod::simulation::Simulation;

/// The largest |energy balance error| over 10 forcing periods, relative to the largest energy
/// exchanged (the work of the excitation), for a chaotic buckled-beam case with control.
fn balance_error(integrator: f64, dt_max: f64) -> f64 {
    let params = SceneParams::with(
        SceneKind::BuckledBeam,
        [("F", 1.5), ("integrator", integrator), ("dt_max", dt_max)],
    )
    .unwrap();
    let period = 2.0 * std::f64::consts::PI / params.forcing_frequency;
    let mut sim = Simulation::new(params).unwrap();
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for k in 0..500 {
        let f_ctrl = 0.05 * (k as f64 * 0.1).sin();
        sim.advance(period / 50.0, f_ctrl).unwrap();
        let o = sim.outputs();
        worst = worst.max(o.energy_error.abs());
        scale = scale
            .max(o.energy.external_work.abs())
            .max(o.energy.dissipated);
        assert!(o.energy.dissipated >= 0.0);
    }
    assert!(scale > 0.0);
    worst / scale
}

#[test]
fn discrete_gradient_balances_energy_exactly() {
    let error = balance_error(2.0, 1e-5);
    println!("energy-momentum: relative balance error {error:.2e}");
    // Newton's stopping test leaves increments of ~1e-12 in displacements of ~0.4 (see
    // NewtonSettings::tight): relative energy errors of ~1e-10 per step at most.
    assert!(error < 1e-8, "{error}");
}

#[test]
fn midpoint_balance_error_is_second_order() {
    let coarse = balance_error(1.0, 2e-5);
    let fine = balance_error(1.0, 1e-5);
    println!("midpoint: relative balance error {coarse:.2e} (dt 2e-5), {fine:.2e} (dt 1e-5)");
    // Halving the step quarters the error (ratio 4 within 30 %: the run is chaotic, but 10
    // periods stay within the predictable horizon at these steps).
    assert!(
        (2.8..5.2).contains(&(coarse / fine)),
        "ratio {}",
        coarse / fine
    );
}
