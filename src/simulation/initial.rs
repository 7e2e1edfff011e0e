//! The initial state of a scene: the undeformed rod, or the static equilibrium under the
//! constant loads and the prescribed displacements, reached by load stepping; with a branch
//! choice, the equilibrium in which the branch sensor has the sign of `well`.
use super::setup::Setup;
use super::SimError;
use crate::integrator::{NewtonFailure, StaticSolver};
use crate::model::{Assembly, Structure};
use crate::scene::{InitialState, ParamValues, Scene};

/// Load steps of the first pass; a step that fails is split in halves, down to
/// `RAMP_STEPS * 2^MAX_REFINE` steps over the whole load.
const RAMP_STEPS: u64 = 20;
const MAX_REFINE: u32 = 12;

/// Size of the branch-selecting imperfection: the load that would deflect a simply supported
/// rod of this length by this fraction of its length (linearly).
const IMPERFECTION: f64 = 1e-3;

/// The prescribed value of every held dof, in the order of `setup.held`: a moving support's
/// input value, else its `displace` value.
fn prescribed(setup: &Setup, values: &ParamValues, inputs: &[f64]) -> Vec<f64> {
    (setup.held.iter())
        .map(|h| h.input.map_or_else(|| h.value.eval(values), |i| inputs[i]))
        .collect()
}

/// The initial displacements of the scene, with the inputs at `inputs`.
pub fn initial_displacements(
    scene: &Scene,
    values: &ParamValues,
    setup: &Setup,
    inputs: &[f64],
) -> Result<Vec<f64>, SimError> {
    let rod = &setup.structure;
    let targets = prescribed(setup, values, inputs);
    let mut u = vec![0.0; rod.dofs()];
    if scene.initial.state == InitialState::Reference {
        for (h, x) in setup.held.iter().zip(&targets) {
            h.set(&mut u, *x);
        }
        rod.make_consistent(&mut u);
        return Ok(u);
    }
    let mut constant = setup.loads.constant_vector().to_vec();
    super::springs::add_static_base_forces(&setup.springs, inputs, &mut constant);
    let fail = |what: &str, e: String| SimError::InitialState(format!("{what}: {e}"));
    let mut solver = StaticSolver::new(rod);
    ramp(&mut solver, setup, &mut u, &constant, &targets).map_err(|e| {
        let e = super::contact::explain_static_failure(scene, setup, e);
        fail("static equilibrium under the constant loads", e)
    })?;
    let Some(branch) = scene.initial.branch else {
        return Ok(u);
    };
    let well = values.get(branch.well_param);
    let probe = setup.sensors[branch.sensor];
    let dof = (scene.sensors[branch.sensor].quantity.displacement_dof())
        .expect("the branch sensor reads a displacement (checked with the scene)");
    let sensor = |u: &[f64]| rod.interpolate(u, probe, dof);
    let stable = |solver: &mut StaticSolver<Structure>, u: &[f64]| {
        solver.negative_eigenvalues(rod, u) == Some(0)
    };
    if sensor(&u) * well > 0.0 && stable(&mut solver, &u) {
        return Ok(u);
    }
    // On the symmetric branch (the sensor exactly 0) and stable: the rod does not buckle at
    // these values, there is no other equilibrium to choose.
    if sensor(&u) == 0.0 && stable(&mut solver, &u) {
        return Ok(u);
    }
    // On the other side, or on an unstable symmetric branch: trace the path again with a load
    // at the sensor along its dof pushing towards the chosen side, then take that load away.
    // The load starts small (it must not change the equilibrium it selects) and grows tenfold
    // while the path ends on the wrong side (the constant loads may push the other way).
    let length = rod.length_scale();
    let ei = match probe {
        crate::model::Place::Member { member, .. } => rod.members[member].rod.section.ei,
        crate::model::Place::Joint(_) | crate::model::Place::Bar { .. } => {
            (rod.members.iter().map(|m| m.rod.section.ei)).fold(f64::INFINITY, f64::min)
        }
    };
    let force = IMPERFECTION * 48.0 * ei / (length * length);
    let unit = if dof == 2 {
        force * length / 4.0
    } else {
        force
    };
    let mut last = format!(
        "the path ended with {} = {:.4e}",
        scene.sensors[branch.sensor].name,
        sensor(&u)
    );
    for growth in [1.0, 10.0, 100.0] {
        let size = well * unit * growth;
        let mut imperfection = vec![0.0; constant.len()];
        rod.add_point_force(&mut imperfection, probe, dof, size);
        u.fill(0.0);
        if let Err(e) = ramp_with(
            &mut solver,
            setup,
            &mut u,
            &constant,
            &targets,
            &imperfection,
        ) {
            last = format!("path with an imperfection of {size:.3e}: {e}");
            continue;
        }
        match unload(&mut solver, rod, &mut u, &constant, &imperfection) {
            Ok(()) if sensor(&u) * well > 0.0 && stable(&mut solver, &u) => return Ok(u),
            Ok(()) => {
                last =
                    format!(
                    "with an imperfection of {size:.3e} the {} equilibrium reached has {} = {:.4e}",
                    if stable(&mut solver, &u) { "stable" } else { "unstable" },
                    scene.sensors[branch.sensor].name,
                    sensor(&u)
                )
            }
            Err(e) => last = format!("removing an imperfection of {size:.3e}: {e}"),
        }
    }
    Err(SimError::InitialState(format!(
        "no equilibrium found with the sensor `{}` of the sign of well = {well} ({last})",
        scene.sensors[branch.sensor].name
    )))
}

/// Takes the branch-selecting `imperfection` away in equal steps (Newton from each state).
fn unload(
    solver: &mut StaticSolver<Structure>,
    rod: &Structure,
    u: &mut [f64],
    constant: &[f64],
    imperfection: &[f64],
) -> Result<(), String> {
    const STEPS: usize = 10;
    let mut f = vec![0.0; constant.len()];
    for k in 1..=STEPS {
        let left = 1.0 - k as f64 / STEPS as f64;
        for ((fi, c), p) in f.iter_mut().zip(constant).zip(imperfection) {
            *fi = c + left * p;
        }
        solver.solve(rod, u, &f).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Steps the constant loads and the prescribed displacements from 0 to their values.
fn ramp(
    solver: &mut StaticSolver<Structure>,
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
    solver: &mut StaticSolver<Structure>,
    setup: &Setup,
    u: &mut [f64],
    load: &[f64],
    targets: &[f64],
    extra: &[f64],
) -> Result<(), String> {
    let rod: &Structure = &setup.structure;
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
            h.set(u, lambda * x);
        }
        rod.make_consistent(u);
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
