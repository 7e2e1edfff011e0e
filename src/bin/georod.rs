//! `georod`: run a scene through the Rust core directly (no FMI).
//!
//! ```text
//! georod demo [--output DIR]
//! georod simulate --scene NAME [--set NAME=VALUE]... --step H --stop T [--output FILE.csv]
//! georod bench-steps --scene NAME [--set NAME=VALUE]... --steps N --dt DT
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
scenes: BuckledBeam, PinnedArch, ClampedArch; parameters: the FMU names (E, nu, F, Omega, ...)";

struct Options {
    scene: SceneKind,
    overrides: Vec<(String, f64)>,
    step: Option<f64>,
    stop: Option<f64>,
    steps: Option<usize>,
    output: Option<String>,
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        scene: SceneKind::BuckledBeam,
        overrides: Vec::new(),
        step: None,
        stop: None,
        steps: None,
        output: None,
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
            let start = Instant::now();
            for _ in 0..steps {
                sim.advance(dt, 0.0).map_err(|e| e.to_string())?;
            }
            let seconds = start.elapsed().as_secs_f64();
            println!("{seconds:.6}");
            eprintln!(
                "{steps} steps of {dt} s: {seconds:.4} s, {:.2} us/step",
                1e6 * seconds / steps as f64
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
        "demo" => demo(o.output.as_deref().unwrap_or("out"))?,
        _ => return Err(USAGE.to_string()),
    }
    Ok(())
}

/// The static crown-load path of an arch scene (arc-length continuation from the unloaded arch):
/// rows `load,w_mid,stable,negative_eigenvalues`, then the critical points as comment lines.
fn static_path(o: &Options, max_load: f64) -> Result<String, String> {
    use georod::integrator::continuation::{critical_points, follow_path, ContinuationSettings};
    let params = SceneParams::with(o.scene, o.overrides.iter().map(|(k, v)| (k.as_str(), *v)))
        .map_err(|e| e.to_string())?;
    let (rod, _) = georod::simulation::build_rod(&params);
    let u0 = georod::simulation::initial_displacements(&params, &rod).map_err(|e| e.to_string())?;
    let mut q = vec![0.0; rod.dofs()];
    rod.add_point_transverse_load(&mut q, rod.midspan(), 1.0);
    let mut settings = ContinuationSettings::for_rod(&rod, max_load);
    settings.max_displacement = 4.0 * params.rise.max(params.pre_shortening);
    let path = follow_path(&rod, &u0, params.preload, &q, &settings);
    let mut csv = String::from("load,w_mid,stable,negative_eigenvalues\n");
    let mid = rod.midspan();
    for p in &path.points {
        let w = rod.interpolate(&p.u, mid, georod::model::rod::U2);
        let _ = writeln!(
            csv,
            "{:e},{w:e},{},{}",
            p.load,
            p.negative_eigenvalues == 0,
            p.negative_eigenvalues
        );
    }
    for c in critical_points(&path) {
        let w = rod.interpolate(&path.points[c.index].u, mid, georod::model::rod::U2);
        let _ = writeln!(
            csv,
            "# {:?} at load {:.6e} (w_mid about {w:.4e})",
            c.kind, c.load
        );
    }
    let _ = writeln!(
        csv,
        "# stopped: {} ({} points)",
        path.stop_reason,
        path.points.len()
    );
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
