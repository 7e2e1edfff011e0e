//! `georod`: run a scene through the Rust core directly (no FMI).
//!
//! ```text
//! georod demo [--output DIR]
//! georod simulate --scene NAME [--set NAME=VALUE]... --step H --stop T [--output FILE.csv]
//! georod bench-steps --scene NAME [--set NAME=VALUE]... --steps N --dt DT
//! georod path --scene NAME [--set NAME=VALUE]... [--stop MAX_LOAD] [--max-arc FRACTION]
//!             [--imperfection EPS] [--output FILE.csv]
//! georod modes --scene NAME [--set NAME=VALUE]... [--load P] [--count N] [--stop MAX_LOAD]
//!             [--states FILE.csv] [--output FILE.csv]
//! ```
use georod::scene::{SceneKind, SceneParams};
use georod::simulation::Simulation;
use std::fmt::Write as _;
use std::process::ExitCode;
use std::time::Instant;

const USAGE: &str = "usage:
  georod demo [--output DIR]
  georod simulate --scene NAME [--set NAME=VALUE]... --step H --stop T [--output FILE.csv]
  georod bench-steps --scene NAME [--set NAME=VALUE]... --steps N --dt DT
  georod path --scene NAME [--set NAME=VALUE]... [--stop MAX_LOAD] [--max-arc FRACTION]
              [--imperfection EPS] [--output FILE.csv]
  georod modes --scene NAME [--set NAME=VALUE]... [--load P] [--count N] [--stop MAX_LOAD]
              [--states FILE.csv] [--output FILE.csv]
scenes: BuckledBeam, PinnedArch, ClampedArch; parameters: the FMU names (E, nu, F, Omega, ...)";

struct Options {
    scene: SceneKind,
    overrides: Vec<(String, f64)>,
    step: Option<f64>,
    stop: Option<f64>,
    steps: Option<usize>,
    output: Option<String>,
    /// `path`: largest arc length as a fraction of the rod length.
    max_arc: Option<f64>,
    /// `path`: asymmetric imperfection, a point load `EPS` times the crown load at `s = S/4`.
    imperfection: f64,
    /// `modes`: the load of the equilibria (default: the preload `P0`).
    load: Option<f64>,
    /// `modes`: how many modes per equilibrium.
    count: usize,
    /// `modes`: also write the equilibria's displacement vectors here.
    states: Option<String>,
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        scene: SceneKind::BuckledBeam,
        overrides: Vec::new(),
        step: None,
        stop: None,
        steps: None,
        output: None,
        max_arc: None,
        imperfection: 0.0,
        load: None,
        count: 6,
        states: None,
    };
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{flag} needs a value"));
        let number = |v: &str| {
            v.parse::<f64>()
                .map_err(|_| format!("{flag}: `{v}` is not a number"))
        };
        match flag.as_str() {
            "--scene" => {
                let v = value()?;
                o.scene = SceneKind::from_name(v).ok_or_else(|| format!("unknown scene `{v}`"))?;
            }
            "--set" => {
                let v = value()?;
                let (name, x) = v.split_once('=').ok_or("--set takes NAME=VALUE")?;
                o.overrides.push((name.to_string(), number(x)?));
            }
            "--step" | "--dt" => o.step = Some(number(value()?)?),
            "--stop" => o.stop = Some(number(value()?)?),
            "--steps" => o.steps = Some(number(value()?)? as usize),
            "--output" => o.output = Some(value()?.clone()),
            "--max-arc" => o.max_arc = Some(number(value()?)?),
            "--imperfection" => o.imperfection = number(value()?)?,
            "--load" => o.load = Some(number(value()?)?),
            "--count" => o.count = number(value()?)? as usize,
            "--states" => o.states = Some(value()?.clone()),
            other => return Err(format!("unknown option `{other}`")),
        }
    }
    Ok(o)
}

fn simulation(o: &Options) -> Result<Simulation, String> {
    let params = SceneParams::with(o.scene, o.overrides.iter().map(|(k, v)| (k.as_str(), *v)))
        .map_err(|e| e.to_string())?;
    Simulation::new(params).map_err(|e| e.to_string())
}

/// Rows `time,w_mid,v_mid,E_kin,E_strain,newton_iterations` from t = 0 at each step.
fn trajectory(sim: &mut Simulation, step: f64, stop: f64) -> Result<String, String> {
    let mut csv = String::from("time,w_mid,v_mid,E_kin,E_strain,newton_iterations\n");
    let steps = (stop / step).round() as usize;
    let mut row = |sim: &Simulation, t: f64| {
        let o = sim.outputs();
        let _ = writeln!(
            csv,
            "{t:e},{:e},{:e},{:e},{:e},{}",
            o.w_mid,
            o.v_mid,
            o.kinetic_energy,
            o.strain_energy,
            sim.last_newton_iterations()
        );
    };
    row(sim, 0.0);
    for _ in 0..steps {
        sim.advance(step, 0.0).map_err(|e| e.to_string())?;
        row(sim, sim.time());
    }
    Ok(csv)
}

fn run(args: &[String]) -> Result<(), String> {
    let (command, rest) = args.split_first().ok_or(USAGE)?;
    let o = parse(rest)?;
    match command.as_str() {
        "simulate" => {
            let step = o.step.ok_or("simulate needs --step")?;
            let stop = o.stop.ok_or("simulate needs --stop")?;
            let mut sim = simulation(&o)?;
            let csv = trajectory(&mut sim, step, stop)?;
            match &o.output {
                Some(path) => std::fs::write(path, csv).map_err(|e| format!("{path}: {e}"))?,
                None => print!("{csv}"),
            }
        }
        "bench-steps" => {
            let dt = o.step.ok_or("bench-steps needs --dt")?;
            let steps = o.steps.ok_or("bench-steps needs --steps")?;
            let mut sim = simulation(&o)?;
            let (mut corrections, mut factorizations) = (0u64, 0u64);
            let start = Instant::now();
            for _ in 0..steps {
                let report = sim.advance(dt, 0.0).map_err(|e| e.to_string())?;
                corrections += u64::from(report.newton_iterations);
                factorizations += u64::from(report.factorizations);
            }
            let seconds = start.elapsed().as_secs_f64();
            println!("{seconds:.6}");
            let per_step = |x: u64| x as f64 / steps as f64;
            eprintln!(
                "{steps} steps of {dt} s: {seconds:.4} s, {:.2} us/step, {:.2} corrections and \
                 {:.2} factorizations per step",
                1e6 * seconds / steps as f64,
                per_step(corrections),
                per_step(factorizations)
            );
        }
        "path" => {
            let max_load = o.stop.unwrap_or(f64::INFINITY);
            let csv = static_path(&o, max_load)?;
            match &o.output {
                Some(path) => std::fs::write(path, csv).map_err(|e| format!("{path}: {e}"))?,
                None => print!("{csv}"),
            }
        }
        "modes" => {
            let csv = modes(&o)?;
            match &o.output {
                Some(path) => std::fs::write(path, csv).map_err(|e| format!("{path}: {e}"))?,
                None => print!("{csv}"),
            }
        }
        "demo" => demo(o.output.as_deref().unwrap_or("out"))?,
        _ => return Err(USAGE.to_string()),
    }
    Ok(())
}

/// The static path of an arch scene with its critical points and its equilibria at one load.
struct StaticPath {
    rod: georod::model::Rod,
    q: Vec<f64>,
    path: georod::integrator::continuation::Path,
    settings: georod::integrator::continuation::ContinuationSettings,
    /// Index of the starting point (the initial state) in `path`.
    start: usize,
}

/// Arc-length continuation of the crown load from the scene's initial state (the unloaded arch,
/// or its equilibrium under `P0`), both ways, up to `|load| = max_load`.
fn trace(o: &Options, max_load: f64) -> Result<StaticPath, String> {
    use georod::integrator::continuation::{follow_both_ways, ContinuationSettings};
    let params = SceneParams::with(o.scene, o.overrides.iter().map(|(k, v)| (k.as_str(), *v)))
        .map_err(|e| e.to_string())?;
    let (rod, _) = georod::simulation::build_rod(&params);
    let u0 = georod::simulation::initial_displacements(&params, &rod).map_err(|e| e.to_string())?;
    let mut q = vec![0.0; rod.dofs()];
    rod.add_point_transverse_load(&mut q, rod.midspan(), 1.0);
    if o.imperfection != 0.0 {
        let quarter = rod.point_at(0.25 * rod.curve.length());
        rod.add_point_transverse_load(&mut q, quarter, o.imperfection);
    }
    let mut settings = ContinuationSettings::for_rod(&rod, max_load);
    if let Some(f) = o.max_arc {
        settings.max_arc_length = f * rod.curve.length();
        settings.arc_length = settings.arc_length.min(settings.max_arc_length);
    }
    settings.max_points = 20_000;
    settings.max_displacement = 4.0 * params.rise.max(params.pre_shortening);
    let (path, start) = follow_both_ways(&rod, &u0, params.preload, &q, &settings);
    Ok(StaticPath {
        rod,
        q,
        path,
        settings,
        start,
    })
}

/// Labels `z1, z2, ...` of equilibria in order of decreasing `w_mid`.
fn equilibria(
    sp: &StaticPath,
    load: f64,
) -> Vec<(String, f64, georod::integrator::continuation::Equilibrium)> {
    use georod::integrator::continuation::equilibria_at_load;
    let mid = sp.rod.midspan();
    let mut found: Vec<_> = equilibria_at_load(&sp.rod, &sp.q, &sp.path, load, &sp.settings)
        .into_iter()
        .map(|e| (sp.rod.interpolate(&e.u, mid, georod::model::rod::U2), e))
        .collect();
    found.sort_by(|a, b| b.0.total_cmp(&a.0));
    // The same equilibrium reached twice (e.g. at the start and by the path) counts once.
    found.dedup_by(|a, b| (a.0 - b.0).abs() <= 1e-8 * sp.rod.curve.length());
    found
        .into_iter()
        .enumerate()
        .map(|(k, (w, e))| (format!("z{}", k + 1), w, e))
        .collect()
}

/// The static crown-load path of an arch scene, traced both ways from the initial state: rows
/// `load,w_mid,stable,negative_eigenvalues` in path order, then comment lines
/// `# critical,KIND,load,w_mid,negative_before,negative_after` (located by bisection),
/// `# equilibrium,zK,load,w_mid,negative_eigenvalues` (the path's equilibria at zero load, `z1`
/// highest) and `# start,INDEX` and `# stopped: ...`.
fn static_path(o: &Options, max_load: f64) -> Result<String, String> {
    use georod::integrator::continuation::refine_critical_points;
    let sp = trace(o, max_load)?;
    let (rod, path) = (&sp.rod, &sp.path);
    let mut csv = String::from("load,w_mid,stable,negative_eigenvalues\n");
    let mid = rod.midspan();
    let w_mid = |u: &[f64]| rod.interpolate(u, mid, georod::model::rod::U2);
    for p in &path.points {
        let _ = writeln!(
            csv,
            "{:e},{:e},{},{}",
            p.load,
            w_mid(&p.u),
            p.negative_eigenvalues == 0,
            p.negative_eigenvalues
        );
    }
    for c in refine_critical_points(rod, &sp.q, path, &sp.settings) {
        let _ = writeln!(
            csv,
            "# critical,{:?},{:.10e},{:.10e},{},{}",
            c.kind,
            c.load,
            w_mid(&c.u),
            c.negative_before,
            c.negative_after
        );
    }
    for (name, w, e) in equilibria(&sp, 0.0) {
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
        path.stop_reason,
        path.points.len()
    );
    Ok(csv)
}

/// The lowest natural frequencies about every equilibrium of the static path at one load (the
/// preload `P0` unless `--load`): rows
/// `equilibrium,w_mid,negative_eigenvalues,mode,omega_squared,omega,hertz,symmetric`.
fn modes(o: &Options) -> Result<String, String> {
    use georod::model::modal::modes;
    let sp = trace(o, o.stop.unwrap_or(100.0))?;
    let load = o.load.unwrap_or(sp.path.points[sp.start].load);
    let mut csv = String::from(
        "equilibrium,w_mid,negative_eigenvalues,mode,omega_squared,omega,hertz,symmetric\n",
    );
    let found = equilibria(&sp, load);
    if let Some(path) = &o.states {
        // One row per equilibrium: name, w_mid, negative eigenvalues, then every dof.
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
        for (k, m) in modes(&sp.rod, &e.u).iter().take(o.count).enumerate() {
            let _ = writeln!(
                csv,
                "{name},{w:.8e},{},{},{:.8e},{:.8e},{:.8e},{}",
                e.negative_eigenvalues,
                k + 1,
                m.omega_squared,
                m.omega(),
                m.hertz(),
                m.symmetric
            );
        }
    }
    Ok(csv)
}

/// The default BuckledBeam through the core: static buckled state and a few forcing periods.
fn demo(dir: &str) -> Result<(), String> {
    let params = SceneParams::defaults(SceneKind::BuckledBeam);
    let start = Instant::now();
    let mut sim = Simulation::new(params.clone()).map_err(|e| e.to_string())?;
    let w0 = sim.outputs().w_mid;
    let period = 2.0 * std::f64::consts::PI / params.forcing_frequency;
    let step = period / 50.0;
    let csv = trajectory(&mut sim, step, 20.0 * period)?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{dir}: {e}"))?;
    let path = format!("{dir}/demo_core_buckled_beam.csv");
    std::fs::write(&path, &csv).map_err(|e| format!("{path}: {e}"))?;
    println!(
        "BuckledBeam, {} elements, pre_shortening {}, well {:+}",
        params.elements, params.pre_shortening, params.well
    );
    println!("  static buckled midspan deflection w_mid = {w0:.6}");
    println!(
        "  F = {}, Omega = {} rad/s, period T = {:.4e} s, dt_max = {:e}",
        params.forcing_amplitude, params.forcing_frequency, period, params.dt_max
    );
    println!("  w_mid at the end of each forcing period:");
    for (k, line) in csv.lines().skip(1).step_by(50).enumerate() {
        let w: f64 = line
            .split(',')
            .nth(1)
            .and_then(|x| x.parse().ok())
            .unwrap_or(f64::NAN);
        println!("    t = {:2} T   w_mid = {w:+.6}", k);
    }
    println!("  wrote {path} ({:.2} s)", start.elapsed().as_secs_f64());
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("georod: {e}");
            ExitCode::FAILURE
        }
    }
}
