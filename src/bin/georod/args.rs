//! Command-line options of `georod` and how a `--scene` argument finds its file.
use georod::scene::Scene;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub struct Options {
    pub scene: Option<String>,
    pub overrides: Vec<(String, f64)>,
    pub inputs: Vec<(String, f64)>,
    pub step: Option<f64>,
    pub stop: Option<f64>,
    pub steps: Option<usize>,
    pub output: Option<String>,
    pub lib: Option<String>,
    /// `fmu`: (platform, library file) of each `--binary PLATFORM=FILE`.
    pub binaries: Vec<(String, String)>,
    /// `fmu`: the FMI version, 2 or 3.
    pub fmi: u8,
    /// Positional arguments (the scene file of `fmu` and `check`).
    pub positional: Vec<String>,
    /// `path`: largest arc length as a fraction of the rod length.
    pub max_arc: Option<f64>,
    /// `path`: asymmetric imperfection, a point load `EPS` times the path load at `s = S/4`.
    pub imperfection: f64,
    /// `path`, `modes`: the load whose magnitude the path follows (default: the first point load).
    pub load_name: Option<String>,
    /// `path`, `modes`: the sensor reported along the path (default: the first u2 sensor).
    pub sensor: Option<String>,
    /// `modes`: the load of the equilibria (default: the load at the initial state).
    pub load: Option<f64>,
    /// `modes`: how many modes per equilibrium.
    pub count: usize,
    /// `modes`: also write the equilibria's displacement vectors here.
    pub states: Option<String>,
    /// `simulate`: the outputs written, by name (empty: the default columns).
    pub outputs: Vec<String>,
    pub help: bool,
}

/// A step, time or length: a finite number > 0.
fn positive(flag: &str, v: &str) -> Result<f64, String> {
    match v.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("{flag} {v}: must be a finite number > 0")),
    }
}

pub fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        scene: None,
        overrides: Vec::new(),
        inputs: Vec::new(),
        step: None,
        stop: None,
        steps: None,
        output: None,
        lib: None,
        binaries: Vec::new(),
        fmi: 2,
        positional: Vec::new(),
        max_arc: None,
        imperfection: 0.0,
        load_name: None,
        sensor: None,
        load: None,
        count: 6,
        states: None,
        outputs: Vec::new(),
        help: false,
    };
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{flag} needs a value"));
        let number = |v: &str| {
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{flag} {v}: must be a finite number"))
        };
        let pair = |v: &str| -> Result<(String, f64), String> {
            let (name, x) = v
                .split_once('=')
                .ok_or_else(|| format!("{flag} takes NAME=VALUE, not `{v}`"))?;
            Ok((name.to_string(), number(x)?))
        };
        let count = |v: &str| {
            v.parse::<usize>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| format!("{flag} {v}: must be a whole number > 0"))
        };
        match flag.as_str() {
            "-h" | "--help" => o.help = true,
            "--scene" => o.scene = Some(value()?.clone()),
            "--set" => o.overrides.push(pair(value()?)?),
            "--input" => o.inputs.push(pair(value()?)?),
            "--step" | "--dt" => o.step = Some(positive(flag, value()?)?),
            "--stop" => o.stop = Some(positive(flag, value()?)?),
            "--steps" => o.steps = Some(count(value()?)?),
            "--output" | "-o" => o.output = Some(value()?.clone()),
            "--lib" => o.lib = Some(value()?.clone()),
            "--binary" => {
                let v = value()?;
                let (platform, file) = v.split_once('=').ok_or_else(|| {
                    format!("--binary takes PLATFORM=FILE (linux64, win64, darwin64), not `{v}`")
                })?;
                o.binaries.push((platform.to_string(), file.to_string()));
            }
            "--fmi" => {
                o.fmi = match value()?.as_str() {
                    "2" | "2.0" => 2,
                    "3" | "3.0" => 3,
                    v => return Err(format!("{flag} {v}: the FMI version is 2 or 3")),
                }
            }
            "--max-arc" => o.max_arc = Some(positive(flag, value()?)?),
            "--imperfection" => o.imperfection = number(value()?)?,
            "--load-name" => o.load_name = Some(value()?.clone()),
            "--sensor" => o.sensor = Some(value()?.clone()),
            "--load" => o.load = Some(number(value()?)?),
            "--count" => o.count = count(value()?)?,
            "--states" => o.states = Some(value()?.clone()),
            "--outputs" => o
                .outputs
                .extend(value()?.split(',').map(|n| n.trim().to_string())),
            other if !other.starts_with('-') => o.positional.push(other.to_string()),
            other => return Err(format!("unknown option `{other}`")),
        }
    }
    Ok(o)
}

/// The scene file a `--scene` argument names: a path, or the name of a file in `scenes/`
/// (looked up in the working directory, then in the repository this executable was built in).
pub fn scene_path(arg: &str) -> Result<PathBuf, String> {
    let direct = Path::new(arg);
    if direct.is_file() {
        return Ok(direct.to_path_buf());
    }
    let file = if arg.ends_with(".toml") {
        arg.to_string()
    } else {
        format!("{arg}.toml")
    };
    let mut candidates = vec![Path::new("scenes").join(&file)];
    if let Some(repo) = std::env::current_exe()
        .ok()
        .and_then(|exe| exe.parent()?.parent()?.parent().map(Path::to_path_buf))
    {
        candidates.push(repo.join("scenes").join(&file));
    }
    candidates.into_iter().find(|p| p.is_file()).ok_or_else(|| {
        format!("no scene `{arg}`: not a file, and no scenes/{file} here or in the repository")
    })
}

pub fn load_scene(o: &Options) -> Result<Arc<Scene>, String> {
    let arg = o
        .scene
        .as_deref()
        .ok_or("--scene FILE.toml (or the name of a file in scenes/) is required")?;
    let scene = Scene::load(scene_path(arg)?).map_err(|e| e.to_string())?;
    Ok(Arc::new(scene))
}
