//! `georod`: package a scene file into an FMU, or run a scene through the Rust core directly.
mod args;
mod bundle;
mod fmu;
mod modal;
mod report;
mod statics;

use args::{load_scene, Options};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

/// Every command: (name, synopsis and what it does).
const COMMANDS: [(&str, &str); 7] = [
    (
        "fmu",
        "fmu FILE.toml [-o OUT.fmu] [--fmi 2|3] [--lib LIB] [--binary PLATFORM=FILE]...
    package a scene file into an FMI 2.0 (default) or 3.0 Co-Simulation FMU (default OUT:
    <target>/fmu/<name>.fmu, or fmu3/ for FMI 3.0, beside this executable's target folder; an
    installed georod (pip): <name>.fmu in the working directory) with a library for each
    platform (linux64, win64, darwin64; one library exports both versions' functions): FILE,
    else the installation's (bundle.toml beside an installed georod lists them), else the one
    scripts/build_fmus built in that target folder (LIB or the library next to this executable
    for this platform); each is checked (format, architecture, every FMI function exported)
    and a platform left out is named with how to build it; a bad scene file is refused with
    the file, the key and what is allowed, and nothing is written",
    ),
    (
        "check",
        "check FILE.toml
    check a scene file (and its initial state) and list the FMU variables it declares (an array
    such as shape_x[1..21] on one line), then the initial state's support reactions, sensor
    values, strain energy and natural frequencies",
    ),
    (
        "simulate",
        "simulate --scene SCENE [--set NAME=VALUE]... [--input NAME=VALUE]... --step H --stop T
         [--outputs NAME,NAME,...] [--output FILE.csv]
    time and, at each step, the outputs named (any FMU output: sensors, reactions, shape_M[3],
    frequency[1], energy_error, ...; default: every sensor, every support reaction, E_kin,
    E_strain, newton_iterations) as CSV",
    ),
    (
        "bench-steps",
        "bench-steps --scene SCENE [--set NAME=VALUE]... --steps N --dt DT
    time N steps of DT through the core (prints seconds)",
    ),
    (
        "path",
        "path --scene SCENE [--set ...] [--load-name LOAD] [--sensor NAME] [--stop MAX_LOAD]
     [--max-arc FRACTION] [--imperfection EPS] [--output FILE.csv]
    static path of one point load's magnitude through limit points (arc-length continuation)",
    ),
    (
        "modes",
        "modes FILE.toml [--set ...] [--count N] [--output SHAPES.csv]
    natural frequencies of any scene's initial state (constant loads on, harmonic and input
    loads off), printed; the mode shapes written to SHAPES.csv (default <name>_modes.csv, or
    <name>_modes-2.csv, ... where that exists) and drawn in SHAPES.svg
  modes --scene SCENE [--set ...] [--load-name LOAD] [--sensor NAME] [--load P] [--count N]
      [--stop MAX_LOAD] [--states FILE.csv] [--output FILE.csv]
    natural frequencies about every equilibrium of one point load's static path at one load",
    ),
    (
        "demo",
        "demo [--output DIR]
    the default BuckledBeam through the core",
    ),
];

const NOTES: &str = "SCENE is a scene file, or the name of one in scenes/ (BuckledBeam, PinnedArch,
ClampedArch, ...). Parameters and inputs are named as in the FMU (E, nu, F, Omega,
pre_shortening, f_ctrl, ...). Steps, times, lengths (H, T, DT, MAX_LOAD, FRACTION) are finite
numbers > 0, counts (N) whole numbers > 0. Exit status: 0 done, 1 failed, 2 a bad command line.";

fn usage() -> String {
    let mut u = String::from(
        "usage: georod COMMAND [OPTIONS]   (georod COMMAND --help for one; georod --version)\n\n",
    );
    for (_, help) in COMMANDS {
        let _ = writeln!(u, "  {}\n", help.replace('\n', "\n  "));
    }
    u + NOTES
}

fn simulation(o: &Options) -> Result<Simulation, String> {
    let scene = load_scene(o)?;
    let values = scene
        .values_with(o.overrides.iter().map(|(k, v)| (k.as_str(), *v)))
        .map_err(|e| e.to_string())?;
    let mut sim = Simulation::new(scene.clone(), values).map_err(|e| e.to_string())?;
    for (name, value) in &o.inputs {
        let i = scene
            .inputs
            .iter()
            .position(|input| &input.name == name)
            .ok_or_else(|| format!("--input: `{name}` is not an input of {}", scene.name))?;
        sim.set_input(i, *value).map_err(|e| e.to_string())?;
    }
    Ok(sim)
}

fn write_or_print(output: Option<&str>, text: &str) -> Result<(), String> {
    match output {
        Some(path) => std::fs::write(path, text).map_err(|e| format!("{path}: {e}")),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

fn check(o: &Options) -> Result<(), String> {
    let [file] = o.positional.as_slice() else {
        return Err("check takes one scene file: georod check FILE.toml".to_string());
    };
    let scene = Arc::new(Scene::load(file).map_err(|e| e.to_string())?);
    let sim = Simulation::new(scene.clone(), scene.defaults())
        .map_err(|e| format!("{file}: {}: with its default parameters: {e}", scene.name))?;
    println!("{file}: scene {} is valid", scene.name);
    print!("{}", report::listing(&scene, &sim));
    Ok(())
}

fn bench_steps(o: &Options) -> Result<(), String> {
    let dt = o.step.ok_or("bench-steps needs --dt")?;
    let steps = o.steps.ok_or("bench-steps needs --steps")?;
    let mut sim = simulation(o)?;
    let (mut corrections, mut factorizations) = (0u64, 0u64);
    let start = Instant::now();
    for _ in 0..steps {
        let report = sim.advance(dt).map_err(|e| e.to_string())?;
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
    Ok(())
}

/// The default BuckledBeam through the core: static buckled state and a few forcing periods.
fn demo(dir: &str) -> Result<(), String> {
    let o = Options {
        scene: Some("BuckledBeam".into()),
        ..args::parse(&[])?
    };
    let start = Instant::now();
    let mut sim = simulation(&o)?;
    let scene: Arc<Scene> = sim.scene().clone();
    let values = sim.values().clone();
    let value = |name: &str| scene.param_index(name).map_or(f64::NAN, |i| values.get(i));
    let (omega, f) = (value("Omega"), value("F"));
    let w0 = sim.output_by_name("w_mid").unwrap_or(f64::NAN);
    let period = 2.0 * std::f64::consts::PI / omega;
    let step = period / 50.0;
    let columns = report::columns(&scene, &["w_mid".into(), "v_mid".into()])?;
    let csv = report::trajectory(&mut sim, &columns, step, 20.0 * period)?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{dir}: {e}"))?;
    let path = format!("{dir}/demo_core_buckled_beam.csv");
    std::fs::write(&path, &csv).map_err(|e| format!("{path}: {e}"))?;
    println!(
        "BuckledBeam, {} elements, pre_shortening {}, well {:+}",
        sim.values().elements(),
        value("pre_shortening"),
        value("well")
    );
    println!("  static buckled midspan deflection w_mid = {w0:.6}");
    println!(
        "  F = {f}, Omega = {omega} rad/s, period T = {period:.4e} s, dt_max = {:e}",
        sim.values().dt_max()
    );
    println!("  w_mid at the end of each forcing period:");
    for (k, line) in csv.lines().skip(1).step_by(50).enumerate() {
        let w: f64 = line
            .split(',')
            .nth(1)
            .and_then(|x| x.parse().ok())
            .unwrap_or(f64::NAN);
        println!("    t = {k:2} T   w_mid = {w:+.6}");
    }
    println!("  wrote {path} ({:.2} s)", start.elapsed().as_secs_f64());
    Ok(())
}

/// Why `georod` stopped: a bad command line (exit status 2, like the Python tools' argparse),
/// or a failure while doing what it was asked (1).
enum Failure {
    Usage(String),
    Run(String),
}

impl From<String> for Failure {
    fn from(message: String) -> Failure {
        Failure::Run(message)
    }
}

/// The most communication steps `simulate` takes (a guard against a typo in --stop or --step).
const MAX_STEPS: f64 = 1e9;

/// What the command line of `command` must have, checked before anything is read or run.
fn check_command_line(command: &str, o: &Options) -> Result<(), String> {
    let one_file = matches!(command, "fmu" | "check");
    if one_file && o.positional.len() != 1 {
        return Err(format!(
            "{command} takes one scene file: georod {command} FILE.toml"
        ));
    }
    let modal = command == "modes" && o.scene.is_none();
    if modal && o.positional.len() != 1 {
        return Err(
            "modes takes one scene file (georod modes FILE.toml), or --scene for the \
             path-following form"
                .to_string(),
        );
    }
    if let (false, false, Some(extra)) = (one_file, modal, o.positional.first()) {
        return Err(format!(
            "unexpected argument `{extra}` ({command} takes options only)"
        ));
    }
    match command {
        "simulate" => {
            let step = o.step.ok_or("simulate needs --step H")?;
            let stop = o.stop.ok_or("simulate needs --stop T")?;
            let steps = (stop / step).round();
            if steps < 1.0 {
                return Err(format!(
                    "--stop {stop} is less than half of --step {step}: there is no step to take"
                ));
            }
            if steps > MAX_STEPS {
                return Err(format!(
                    "--stop {stop} / --step {step} = {steps:e} steps: at most {MAX_STEPS:e}"
                ));
            }
        }
        "bench-steps" => {
            o.step.ok_or("bench-steps needs --dt DT")?;
            o.steps.ok_or("bench-steps needs --steps N")?;
        }
        _ => {}
    }
    Ok(())
}

fn run(args: &[String]) -> Result<(), Failure> {
    let Some((command, rest)) = args.split_first() else {
        return Err(Failure::Usage(usage()));
    };
    if matches!(command.as_str(), "-h" | "--help" | "help") {
        println!("{}", usage());
        return Ok(());
    }
    if matches!(command.as_str(), "-V" | "--version") {
        println!("georod {}", env!("CARGO_PKG_VERSION"));
        return Ok(());
    }
    let Some((_, help)) = COMMANDS.iter().find(|(name, _)| name == command) else {
        return Err(Failure::Usage(format!(
            "unknown command `{command}`\n{}",
            usage()
        )));
    };
    let usage_error = |e: String| Failure::Usage(format!("{e}\nusage: georod {help}"));
    let o = args::parse(rest).map_err(usage_error)?;
    if o.help {
        println!("usage: georod {help}\n\n{NOTES}");
        return Ok(());
    }
    check_command_line(command, &o).map_err(usage_error)?;
    match command.as_str() {
        "fmu" => fmu::package(&o)?,
        "check" => check(&o)?,
        "simulate" => {
            let (step, stop) = (o.step.unwrap_or_default(), o.stop.unwrap_or_default());
            let mut sim = simulation(&o)?;
            let columns = report::columns(&sim.scene().clone(), &o.outputs)?;
            let csv = report::trajectory(&mut sim, &columns, step, stop)?;
            write_or_print(o.output.as_deref(), &csv)?
        }
        "bench-steps" => bench_steps(&o)?,
        "path" => {
            let csv = statics::static_path(&o)?;
            write_or_print(o.output.as_deref(), &csv)?
        }
        "modes" if o.scene.is_none() => {
            let file = &o.positional[0];
            let report = modal::modes_of_scene(file, &o)?;
            let stem = Path::new(file)
                .file_stem()
                .map_or("scene".into(), |s| s.to_string_lossy());
            // The default never replaces an earlier run's files: <name>_modes-2.csv, ...
            let default = (1..)
                .map(|k| match k {
                    1 => format!("{stem}_modes.csv"),
                    k => format!("{stem}_modes-{k}.csv"),
                })
                .find(|csv| {
                    let csv = Path::new(csv);
                    !csv.exists() && !csv.with_extension("svg").exists()
                })
                .expect("some free name");
            let csv = o.output.clone().unwrap_or(default);
            let svg = Path::new(&csv).with_extension("svg");
            std::fs::write(&csv, report.csv).map_err(|e| format!("{csv}: {e}"))?;
            std::fs::write(&svg, report.svg).map_err(|e| format!("{}: {e}", svg.display()))?;
            print!("{}", report.text);
            println!("wrote the mode shapes to {csv} and {}", svg.display());
        }
        "modes" => {
            let csv = statics::modes(&o)?;
            write_or_print(o.output.as_deref(), &csv)?
        }
        "demo" => demo(o.output.as_deref().unwrap_or("out"))?,
        other => unreachable!("`{other}` is in COMMANDS but has no arm"),
    }
    Ok(())
}

fn main() -> ExitCode {
    // A reader that stops early (`georod check FILE | head`) ends the process quietly, as it
    // does any Unix filter; Rust ignores SIGPIPE by default and `println!` would then panic.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of one signal before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(e)) => {
            eprintln!("georod: {e}");
            ExitCode::from(2)
        }
        Err(Failure::Run(e)) => {
            eprintln!("georod: {e}");
            ExitCode::FAILURE
        }
    }
}
