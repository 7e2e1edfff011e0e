//! `georod`: package a scene file into an FMU, or run a scene through the Rust core directly.
mod args;
mod statics;

use args::{load_scene, Options};
use georod::packaging;
use georod::scene::variables::{self, Causality, Role};
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

/// Every command: (name, synopsis and what it does).
const COMMANDS: [(&str, &str); 7] = [
    (
        "fmu",
        "fmu FILE.toml [-o OUT.fmu] [--lib LIB] [--fmi 2|3]
    package a scene file into an FMI 2.0 (default) or 3.0 Co-Simulation FMU (default OUT:
    <target>/fmu/<name>.fmu, or fmu3/ for FMI 3.0, beside this executable's target folder; LIB:
    the georod library next to this executable, which exports both versions' functions);
    a bad scene file is refused with the file, the key and what is allowed, and nothing is written",
    ),
    (
        "check",
        "check FILE.toml
    check a scene file (and its initial state) and list the FMU variables it declares",
    ),
    (
        "simulate",
        "simulate --scene SCENE [--set NAME=VALUE]... [--input NAME=VALUE]... --step H --stop T
         [--output FILE.csv]
    time, every sensor, E_kin, E_strain, newton_iterations at each step (CSV)",
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
        "modes --scene SCENE [--set ...] [--load-name LOAD] [--sensor NAME] [--load P] [--count N]
      [--stop MAX_LOAD] [--states FILE.csv] [--output FILE.csv]
    natural frequencies about every equilibrium of that path at one load",
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
    let mut u =
        String::from("usage: georod COMMAND [OPTIONS]   (georod COMMAND --help for one)\n\n");
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

/// Rows `time,<sensors>,E_kin,E_strain,newton_iterations` from t = 0 at each step.
fn trajectory(sim: &mut Simulation, step: f64, stop: f64) -> Result<String, String> {
    let scene = sim.scene().clone();
    let mut csv = String::from("time");
    for s in &scene.sensors {
        let _ = write!(csv, ",{}", s.name);
    }
    csv.push_str(",E_kin,E_strain,newton_iterations\n");
    let steps = (stop / step).round() as usize;
    let row = |sim: &Simulation, t: f64, csv: &mut String| {
        let _ = write!(csv, "{t:e}");
        for i in 0..scene.sensors.len() {
            let _ = write!(csv, ",{:e}", sim.output(variables::OutputId::Sensor(i)));
        }
        let _ = writeln!(
            csv,
            ",{:e},{:e},{}",
            sim.kinetic_energy(),
            sim.strain_energy(),
            sim.last_newton_iterations()
        );
    };
    row(sim, 0.0, &mut csv);
    for _ in 0..steps {
        sim.advance(step).map_err(|e| e.to_string())?;
        row(sim, sim.time(), &mut csv);
    }
    Ok(csv)
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

fn package(o: &Options) -> Result<(), String> {
    let [file] = o.positional.as_slice() else {
        return Err("fmu takes one scene file: georod fmu FILE.toml [-o OUT.fmu]".to_string());
    };
    let scene = Scene::load(file).map_err(|e| e.to_string())?;
    let lib_path = match &o.lib {
        Some(p) => PathBuf::from(p),
        None => packaging::default_library()?,
    };
    let lib = std::fs::read(&lib_path).map_err(|e| {
        format!(
            "cannot read the FMU library {}: {e} (build it with `cargo build --release --lib`, \
             or pass --lib PATH)",
            lib_path.display()
        )
    })?;
    let out = match &o.output {
        Some(p) => PathBuf::from(p),
        None => {
            let exe = std::env::current_exe().map_err(|e| e.to_string())?;
            let target = exe
                .parent()
                .and_then(Path::parent)
                .unwrap_or(Path::new("."));
            let folder = if o.fmi == 3 { "fmu3" } else { "fmu" };
            target.join(folder).join(format!("{}.fmu", scene.name))
        }
    };
    if out.extension().is_none_or(|e| e != "fmu") {
        return Err(format!(
            "-o {}: the output must be a .fmu file",
            out.display()
        ));
    }
    let p = if o.fmi == 3 {
        packaging::fmu3::package3(&scene, &[(packaging::platform(), &lib)], &out)
    } else {
        packaging::package(&scene, &lib, &out)
    }
    .map_err(|e| format!("{file}: {e}"))?;
    println!(
        "wrote {} ({} bytes, guid {}, {} variables)",
        p.path.display(),
        p.bytes,
        p.guid,
        p.variables
    );
    Ok(())
}

fn check(o: &Options) -> Result<(), String> {
    let [file] = o.positional.as_slice() else {
        return Err("check takes one scene file: georod check FILE.toml".to_string());
    };
    let scene = Scene::load(file).map_err(|e| e.to_string())?;
    packaging::check_initial_state(&scene)?;
    println!("{file}: scene {} is valid", scene.name);
    for v in variables::variables(&scene) {
        let kind = match (v.causality, v.role) {
            (Causality::Parameter, _) => "parameter",
            (Causality::Input, _) => "input",
            (_, Role::Output(_)) => "output",
            _ => "",
        };
        println!("  {kind:9} {:24} {}", v.name, v.description);
    }
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
    let csv = trajectory(&mut sim, step, 20.0 * period)?;
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
    if let (false, Some(extra)) = (one_file, o.positional.first()) {
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
        "fmu" => package(&o)?,
        "check" => check(&o)?,
        "simulate" => {
            let (step, stop) = (o.step.unwrap_or_default(), o.stop.unwrap_or_default());
            let mut sim = simulation(&o)?;
            let csv = trajectory(&mut sim, step, stop)?;
            write_or_print(o.output.as_deref(), &csv)?
        }
        "bench-steps" => bench_steps(&o)?,
        "path" => {
            let csv = statics::static_path(&o)?;
            write_or_print(o.output.as_deref(), &csv)?
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
