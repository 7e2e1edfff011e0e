//! `georod path` and `georod modes`: the static path of one point load of a scene (its
//! magnitude as the path parameter, the other loads held), its critical points, the
//! equilibria at one load, and the natural frequencies about them.
use crate::args::{load_scene, Options};
use georod::integrator::continuation::{
    equilibria_at_load, follow_both_ways, refine_critical_points, ContinuationSettings,
    Equilibrium, Path,
};
use georod::model::loads::LoadShape;
use georod::model::modal::modes as natural_modes;
use georod::model::modal_subspace::lowest_modes;
use georod::model::{Assembly, Place, Structure};
use georod::scene::{LoadKind, Scene, TimeLaw};
use georod::simulation::{initial, setup};
use std::fmt::Write as _;

/// The static path of a scene with its critical points and its equilibria at one load.
struct StaticPath {
    rod: Structure,
    q: Vec<f64>,
    path: Path,
    settings: ContinuationSettings,
    /// Index of the starting point (the initial state) in `path`.
    start: usize,
    /// Where the reported sensor reads, and its dof.
    sensor: (String, Place, usize),
}

/// The load the path follows: `--load-name`, or the first point load.
fn path_load(scene: &Scene, o: &Options) -> Result<usize, String> {
    let found = match &o.load_name {
        Some(name) => scene.loads.iter().position(|l| &l.name == name),
        None => scene
            .loads
            .iter()
            .position(|l| matches!(l.kind, LoadKind::Point { .. })),
    };
    found.ok_or_else(|| {
        let names: Vec<&str> = scene.loads.iter().map(|l| l.name.as_str()).collect();
        format!(
            "--load-name: pick one of the loads of {} ({})",
            scene.name,
            names.join(", ")
        )
    })
}

/// Arc-length continuation of one load's magnitude from the scene's initial state, both ways,
/// up to `|load| = max_load`. The constant loads with the same nodal vector as the path load
/// (a preload at the same point) give the starting load; any other constant load must be zero.
fn trace(o: &Options, max_load: f64) -> Result<StaticPath, String> {
    let scene = load_scene(o)?;
    let values = scene
        .values_with(o.overrides.iter().map(|(k, v)| (k.as_str(), *v)))
        .map_err(|e| e.to_string())?;
    let mut s = setup::setup(&scene, &values);
    let inputs: Vec<f64> = (0..scene.inputs.len())
        .map(|i| georod::scene::variables::input_start(&scene, i, &values))
        .collect();
    let u0 =
        initial::initial_displacements(&scene, &values, &s, &inputs).map_err(|e| e.to_string())?;
    let index = path_load(&scene, o)?;
    let load = &scene.loads[index];
    if matches!(load.kind, LoadKind::Moving { .. }) {
        return Err(format!(
            "--load-name: `{}` moves; a static path follows a load that stays",
            load.name
        ));
    }
    // The path load's nodal vector: the load set with that load alone at magnitude 1, at t = 0.
    let mut unit = vec![0.0; s.loads.len()];
    unit[index] = 1.0;
    s.loads.set_magnitudes(&unit);
    s.loads.frequency = 0.0;
    let mut q = vec![0.0; s.structure.dofs()];
    s.loads.add_to(0.0, &mut q, 1.0);
    let sensor = sensor(&scene, o, &s)?;
    let rod = s.structure;
    let length = rod.length_scale();
    let mut load0 = 0.0;
    for l in scene.loads.iter().filter(|l| l.time == TimeLaw::Constant) {
        let magnitude = l.value.eval(&values);
        if magnitude == 0.0 {
            continue;
        }
        if l.kind == load.kind && l.direction == load.direction {
            load0 += magnitude;
        } else {
            return Err(format!(
                "the constant load `{}` acts elsewhere than the path load `{}`: set it to 0",
                l.name, load.name
            ));
        }
    }
    if o.imperfection != 0.0 {
        if !rod.is_single() {
            return Err(
                "--imperfection: a quarter-span load is a single rod's; on a frame add a \
                        small [[load]] where the imperfection belongs"
                    .to_string(),
            );
        }
        let quarter = LoadShape::Point {
            s: 0.25 * length,
            component: load.direction.component,
            sign: load.direction.sign,
        };
        for (a, b) in q.iter_mut().zip(quarter.nodal_vector(rod.rod())) {
            *a += o.imperfection * b;
        }
    }
    let mut settings = ContinuationSettings::for_rod(&rod, max_load);
    if let Some(f) = o.max_arc {
        settings.max_arc_length = f * length;
        settings.arc_length = settings.arc_length.min(settings.max_arc_length);
    }
    settings.max_points = 20_000;
    settings.max_displacement = match scene.param_index("H") {
        Some(i) => 4.0 * values.get(i),
        // A frame's snap-backs (Lee's) run to displacements of the order of its size.
        None if !rod.is_single() => length,
        None => 0.4 * length,
    };
    let (path, start) = follow_both_ways(&rod, &u0, load0, &q, &settings);
    Ok(StaticPath {
        rod,
        q,
        path,
        settings,
        start,
        sensor,
    })
}

/// The displacement sensor reported along the path: `--sensor`, or the first `u2` sensor.
fn sensor(scene: &Scene, o: &Options, s: &setup::Setup) -> Result<(String, Place, usize), String> {
    let index = match &o.sensor {
        Some(name) => scene.sensors.iter().position(|s| &s.name == name),
        None => scene
            .sensors
            .iter()
            .position(|s| s.quantity.displacement_dof() == Some(1)),
    };
    let (i, dof) = index
        .and_then(|i| Some((i, scene.sensors[i].quantity.displacement_dof()?)))
        .ok_or("--sensor: name a displacement sensor of the scene")?;
    Ok((scene.sensors[i].name.clone(), s.sensors[i], dof))
}

impl StaticPath {
    fn read(&self, u: &[f64]) -> f64 {
        self.rod.interpolate(u, self.sensor.1, self.sensor.2)
    }

    /// Labels `z1, z2, ...` of equilibria in order of decreasing sensor value.
    fn equilibria(&self, load: f64) -> Vec<(String, f64, Equilibrium)> {
        let mut found: Vec<_> =
            equilibria_at_load(&self.rod, &self.q, &self.path, load, &self.settings)
                .into_iter()
                .map(|e| (self.read(&e.u), e))
                .collect();
        found.sort_by(|a, b| b.0.total_cmp(&a.0));
        // The same equilibrium reached twice (e.g. at the start and by the path) counts once.
        let length = self.rod.length_scale();
        found.dedup_by(|a, b| (a.0 - b.0).abs() <= 1e-8 * length);
        found
            .into_iter()
            .enumerate()
            .map(|(k, (w, e))| (format!("z{}", k + 1), w, e))
            .collect()
    }
}

/// Rows `load,<sensor>,stable,negative_eigenvalues` in path order, then comment lines
/// `# critical,KIND,load,<sensor>,negative_before,negative_after` (located by bisection),
/// `# equilibrium,zK,load,<sensor>,negative_eigenvalues` (the path's equilibria at zero load,
/// `z1` highest) and `# start,INDEX` and `# stopped: ...`.
pub fn static_path(o: &Options) -> Result<String, String> {
    let sp = trace(o, o.stop.unwrap_or(f64::INFINITY))?;
    let mut csv = format!("load,{},stable,negative_eigenvalues\n", sp.sensor.0);
    for p in &sp.path.points {
        let n = p.negative_eigenvalues;
        let _ = writeln!(csv, "{:e},{:e},{},{n}", p.load, sp.read(&p.u), n == 0);
    }
    for c in refine_critical_points(&sp.rod, &sp.q, &sp.path, &sp.settings) {
        let _ = writeln!(
            csv,
            "# critical,{:?},{:.10e},{:.10e},{},{}",
            c.kind,
            c.load,
            sp.read(&c.u),
            c.negative_before,
            c.negative_after
        );
    }
    for (name, w, e) in sp.equilibria(0.0) {
        let _ = writeln!(
            csv,
            "# equilibrium,{name},{:e},{w:.10e},{}",
            e.load, e.negative_eigenvalues
        );
    }
    let _ = writeln!(csv, "# start,{}", sp.start);
    let _ = writeln!(
        csv,
        "# stopped: {} ({} points)",
        sp.path.stop_reason,
        sp.path.points.len()
    );
    Ok(csv)
}

/// The lowest natural frequencies about every equilibrium of the static path at one load (the
/// initial state's load unless `--load`): rows
/// `equilibrium,<sensor>,negative_eigenvalues,mode,omega_squared,omega,hertz,symmetric`.
pub fn modes(o: &Options) -> Result<String, String> {
    let sp = trace(o, o.stop.unwrap_or(100.0))?;
    let load = o.load.unwrap_or(sp.path.points[sp.start].load);
    let mut csv = format!(
        "equilibrium,{},negative_eigenvalues,mode,omega_squared,omega,hertz,symmetric\n",
        sp.sensor.0
    );
    let found = sp.equilibria(load);
    if let Some(path) = &o.states {
        // One row per equilibrium: name, sensor, negative eigenvalues, then every dof.
        let mut rows = String::new();
        for (name, w, e) in &found {
            let _ = write!(rows, "{name},{w:.17e},{}", e.negative_eigenvalues);
            for x in &e.u {
                let _ = write!(rows, ",{x:.17e}");
            }
            rows.push('\n');
        }
        std::fs::write(path, rows).map_err(|e| format!("{path}: {e}"))?;
    }
    for (name, w, e) in found {
        // A rod: the dense eigenproblem, which also tells symmetric modes; a frame: the lowest
        // modes by subspace iteration.
        let modes: Vec<(f64, String)> = if sp.rod.is_single() {
            (natural_modes(sp.rod.rod(), &e.u).iter().take(o.count))
                .map(|m| (m.omega_squared, m.symmetric.to_string()))
                .collect()
        } else {
            let count = o.count.min(sp.rod.dofs() - sp.rod.constrained().len());
            (lowest_modes(&sp.rod, &e.u, count).map_err(|why| format!("modes: {why}"))?)
                .into_iter()
                .map(|(lambda, _)| (lambda, String::new()))
                .collect()
        };
        for (k, (lambda, symmetric)) in modes.iter().enumerate() {
            let omega = lambda.signum() * lambda.abs().sqrt();
            let _ = writeln!(
                csv,
                "{name},{w:.8e},{},{},{:.8e},{:.8e},{:.8e},{symmetric}",
                e.negative_eigenvalues,
                k + 1,
                lambda,
                omega,
                omega / std::f64::consts::TAU,
            );
        }
    }
    Ok(csv)
}
