//! The initial state of a scene: the undeformed rod, or the static equilibrium under the
//! constant loads and the prescribed displacements, reached by load stepping; with a branch
//! choice, the equilibrium in which the branch sensor has the sign of `well`.
use super::setup::Setup;
use super::SimError;
use crate::integrator::{NewtonFailure, StaticSolver};
use crate::model::Rod;
use crate::scene::{InitialState, ParamValues, Scene};

/// Load steps of the first pass; a step that fails is split in halves, down to
/// `RAMP_STEPS * 2^MAX_REFINE` steps over the whole load.
const RAMP_STEPS: u64 = 20;
const MAX_REFINE: u32 = 12;

/// Size of the branch-selecting imperfection: the load that would deflect a simply supported
/// rod of this length by this fraction of its length (linearly).
const IMPERFECTION: f64 = 1e-3;

/// The prescribed value of every held dof, in the order of `setup.held`.
fn prescribed(setup: &Setup, values: &ParamValues) -> Vec<f64> {
    setup.held.iter().map(|h| h.value.eval(values)).collect()
}

/// The initial displacements of the scene.
pub fn initial_displacements(
    scene: &Scene,
    values: &ParamValues,
    setup: &Setup,
) -> Result<Vec<f64>, SimError> {
    let rod = &setup.rod;
    let targets = prescribed(setup, values);
    let mut u = vec![0.0; rod.dofs()];
    if scene.initial.state == InitialState::Reference {
        for (h, x) in setup.held.iter().zip(&targets) {
            u[h.dof] = *x;
        }
        return Ok(u);
    }
    let constant = setup.loads.constant_vector().to_vec();
    let fail = |what: &str, e: String| SimError::InitialState(format!("{what}: {e}"));
    let mut solver = StaticSolver::new(rod);
    ramp(&mut solver, setup, &mut u, &constant, &targets)
        .map_err(|e| fail("static equilibrium under the constant loads", e))?;
    let Some(branch) = scene.initial.branch else {
        return Ok(u);
    };
    let well = values.get(branch.well_param);
    let probe = setup.sensors[branch.sensor];
    let (dof, _) = scene.sensors[branch.sensor].quantity.dof();
    let sensor = |u: &[f64]| rod.interpolate(u, probe.point, dof);
    if sensor(&u) * well > 0.0 {
        return Ok(u);
    }
    // The equilibrium found is on the other side or on the symmetric branch. If it is stable,
    // there is no other (the rod does not buckle at these values); otherwise push it into the
    // chosen well with a small load at the sensor along its dof, then take the load away.
    if solver.factored_tangent().negative_pivots() == 0 {
        return Ok(u);
    }
    let length = rod.curve.length();
    let ei = rod.section.ei;
    let force = IMPERFECTION * 48.0 * ei / (length * length);
    let size = if dof == 2 {
        force * length / 4.0
    } else {
        force
    };
    let mut imperfect = constant.clone();
    let (na, nb) = probe.point.weights;
    imperfect[3 * probe.point.element + dof] += well * size * na;
    imperfect[3 * (probe.point.element + 1) + dof] += well * size * nb;
    u.fill(0.0);
    ramp_with(&mut solver, setup, &mut u, &constant, &targets, &imperfect)
        .map_err(|e| fail("path with a branch-selecting imperfection", e))?;
    solver
        .solve(rod, &mut u, &constant)
        .map_err(|e| fail("equilibrium after removing the imperfection", e.to_string()))?;
    if sensor(&u) * well <= 0.0 {
        return Err(SimError::InitialState(format!(
            "no equilibrium found with the sensor `{}` = {:.4e} of the sign of well = {well}",
            scene.sensors[branch.sensor].name,
            sensor(&u)
        )));
    }
    Ok(u)
}

/// Steps the constant loads and the prescribed displacements from 0 to their values.
fn ramp(
    solver: &mut StaticSolver,
    setup: &Setup,
    u: &mut [f64],
    load: &[f64],
    targets: &[f64],
) -> Result<(), String> {
    if load.iter().all(|&f| f == 0.0) && targets.iter().all(|&x| x == 0.0) {
        return Ok(()); // the reference state is the equilibrium
    }
    ramp_with(solver, setup, u, load, targets, &vec![0.0; load.len()])
}

/// Steps `lambda` from 0 to 1 with the loads `lambda * load + extra` and the held dofs at
/// `lambda * targets`; a failing step is split in halves (up to [`MAX_REFINE`] times).
fn ramp_with(
    solver: &mut StaticSolver,
    setup: &Setup,
    u: &mut [f64],
    load: &[f64],
    targets: &[f64],
    extra: &[f64],
) -> Result<(), String> {
    let rod: &Rod = &setup.rod;
    let mut f = vec![0.0; load.len()];
    // lambda = num / den exactly, so the first pass takes the loads k / 20 of the full ones.
    let (mut num, mut den, mut refine) = (0u64, RAMP_STEPS, 0u32);
    let mut last: Option<NewtonFailure> = None;
    while num < den {
        let lambda = (num + 1) as f64 / den as f64;
        for ((fi, l), e) in f.iter_mut().zip(load).zip(extra) {
            *fi = lambda * l + e;
        }
        let before = u.to_vec();
        for (h, x) in setup.held.iter().zip(targets) {
            u[h.dof] = lambda * x;
        }
        match solver.solve(rod, u, &f) {
            Ok(_) => {
                num += 1;
                last = None;
            }
            Err(e) => {
                u.copy_from_slice(&before);
                if refine == MAX_REFINE {
                    return Err(format!(
                        "{e} at load factor {lambda:.6} (after {MAX_REFINE} halvings of the load step)"
                    ));
                }
                last = Some(e);
                num *= 2;
                den *= 2;
                refine += 1;
            }
        }
    }
    debug_assert!(last.is_none());
    Ok(())
}
