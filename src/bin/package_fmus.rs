//! `package-fmus`: packs each scene into an FMI 2.0 Co-Simulation FMU.
//!
//! ```text
//! package-fmus [--lib PATH] [--out DIR]
//! ```
//!
//! For every scene it writes `<DIR>/<Scene>.fmu` (default `DIR`: `target/fmu`, next to the
//! `target/release/` directory this executable lives in) holding
//! - `modelDescription.xml`: exactly the document the library was built with
//!   (`georod::variables::MODEL_DESCRIPTIONS`, so the GUIDs match);
//! - `binaries/linux64/<Scene>.so`: a copy of the release cdylib (default: `libgeorod.so` next to
//!   this executable);
//! - `documentation/index.html`: the scene, its variables and a short fmpy example.
//!
//! The archives are reproducible: fixed entry order and timestamps (1980-01-01).
use georod::variables::{
    Causality, VarType, Variability, Variable, GUIDS, MODEL_DESCRIPTIONS,
    SCENE_DEFAULT_EXPERIMENTS, SCENE_DESCRIPTIONS, SCENE_NAMES, VARIABLES, VARIABLE_UNITS,
};
use std::fmt::Write as _;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

const USAGE: &str = "usage: package-fmus [--lib PATH] [--out DIR]
  --lib PATH  the cdylib to ship (default: libgeorod.so next to this executable)
  --out DIR   where to write <Scene>.fmu (default: target/fmu)";

struct Options {
    lib: PathBuf,
    out: PathBuf,
}

fn parse(args: &[String]) -> Result<Options, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot locate this executable: {e}"))?;
    let exe_dir = exe
        .parent()
        .ok_or("executable without a directory")?
        .to_path_buf();
    // target/release/package-fmus -> target/
    let target_dir = exe_dir
        .parent()
        .map_or_else(|| exe_dir.clone(), Path::to_path_buf);
    let mut o = Options {
        lib: exe_dir.join("libgeorod.so"),
        out: target_dir.join("fmu"),
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || {
            it.next()
                .cloned()
                .ok_or_else(|| format!("{a} needs a value\n{USAGE}"))
        };
        match a.as_str() {
            "--lib" => o.lib = PathBuf::from(value()?),
            "--out" => o.out = PathBuf::from(value()?),
            "-h" | "--help" => {
                println!("{USAGE}");
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument `{other}`\n{USAGE}")),
        }
    }
    Ok(o)
}

fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn causality_text(v: &Variable) -> &'static str {
    match (v.causality, v.variability) {
        (Causality::Parameter, Variability::Fixed) => "parameter / fixed",
        (Causality::Parameter, Variability::Tunable) => "parameter / tunable",
        (Causality::Input, _) => "input / continuous",
        (Causality::Output, Variability::Discrete) => "output / discrete",
        (Causality::Output, _) => "output / continuous",
        (Causality::Parameter, _) => "parameter",
    }
}

/// A start value as the host sees it (integers without a decimal point).
fn value_text(v: &Variable, x: f64) -> String {
    match v.var_type {
        VarType::Integer | VarType::Enumeration => format!("{}", x as i64),
        VarType::Real => format!("{x}"),
    }
}

/// The variables of scene `k`, in modelDescription order, with their unit.
fn scene_variables(k: usize) -> impl Iterator<Item = (&'static Variable, Option<&'static str>)> {
    VARIABLES
        .iter()
        .zip(VARIABLE_UNITS)
        .filter(move |(v, _)| v.scenes[k])
        .map(move |(v, u)| (v, u[k]))
}

/// `documentation/index.html` of scene `k`.
fn documentation(k: usize) -> String {
    let name = SCENE_NAMES[k];
    let [_, stop, step] = SCENE_DEFAULT_EXPERIMENTS[k];
    let mut h = String::new();
    let _ = writeln!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{name} (georod FMU)</title>\n<style>\n\
         body {{ font-family: sans-serif; max-width: 60em; margin: 2em auto; line-height: 1.4; }}\n\
         table {{ border-collapse: collapse; }}\n\
         th, td {{ border: 1px solid #bbb; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }}\n\
         th {{ background: #eee; }}\n\
         code, pre {{ background: #f4f4f4; }}\n</style>\n</head>\n<body>"
    );
    let _ = writeln!(h, "<h1>{name}</h1>");
    let _ = writeln!(h, "<p>{}</p>", html_escape(SCENE_DESCRIPTIONS[k]));
    let _ = writeln!(
        h,
        "<p>A geometrically exact planar rod (Cosserat line with shear) discretized by the hybrid \
         two-node element of Sansour, Sansour &amp; Wriggers and integrated by the implicit \
         midpoint rule, as an FMI 2.0 Co-Simulation FMU (<code>modelIdentifier=\"{name}\"</code>, \
         GUID <code>{guid}</code>). The state at <i>t</i> = 0 is the static equilibrium of the \
         scene with zero velocity. Each communication step is cut into the fewest equal \
         sub-steps no longer than <code>dt_max</code>; a step whose Newton iteration fails even \
         after cutting returns <code>fmi2Discard</code> and leaves the state unchanged. The FMU \
         can get, set and serialize its state, and several instances may run at once.</p>",
        guid = html_escape(GUIDS[k]),
    );
    let _ = writeln!(
        h,
        "<p>Default experiment: stop time {stop} s, communication step {step} s. Parameters \
         outside their range are refused when set, with a message that names the variable.</p>"
    );
    let _ = writeln!(h, "<h2>Variables</h2>\n<table>");
    let _ = writeln!(
        h,
        "<tr><th>name</th><th>causality / variability</th><th>type</th><th>unit</th>\
         <th>start</th><th>range</th><th>description</th></tr>"
    );
    for (v, unit) in scene_variables(k) {
        let start = v.start[k].map_or(String::new(), |x| value_text(v, x));
        let range = v.range_text().unwrap_or_default();
        let _ = writeln!(
            h,
            "<tr><td><code>{}</code></td><td>{}</td><td>{:?}</td><td>{}</td><td>{}</td>\
             <td>{}</td><td>{}</td></tr>",
            html_escape(v.name),
            causality_text(v),
            v.var_type,
            html_escape(unit.unwrap_or("")),
            html_escape(&start),
            html_escape(&range),
            html_escape(v.description),
        );
    }
    let _ = writeln!(h, "</table>");
    let outputs: Vec<String> = scene_variables(k)
        .filter(|(v, _)| v.causality == Causality::Output)
        .map(|(v, _)| format!("\"{}\"", v.name))
        .collect();
    let tunable: Vec<String> = scene_variables(k)
        .filter(|(v, _)| v.variability == Variability::Tunable)
        .filter_map(|(v, _)| v.start[k].map(|x| format!("\"{}\": {x:?}", v.name)))
        .collect();
    let _ = write!(h, "<h2>Use from Python (fmpy)</h2>\n<pre><code>");
    let snippet = format!(
        r#"from fmpy import dump, simulate_fmu

dump("{name}.fmu")  # variables, units, default experiment
result = simulate_fmu(
    "{name}.fmu",
    start_values={{{tunable}}},
    stop_time={stop},
    output_interval={step},
    output=[{outputs}],
)
print(result["time"][-1], result["w_mid"][-1])"#,
        tunable = tunable.join(", "),
        outputs = outputs.join(", "),
    );
    let _ = writeln!(h, "{}</code></pre>", html_escape(&snippet));
    let _ = writeln!(
        h,
        "<p>The input <code>f_ctrl</code> (a control force at mid-span) is held over each \
         communication step; with <code>fmpy.fmi2.FMU2Slave</code> a controller sets it between \
         <code>doStep</code> calls.</p>\n</body>\n</html>"
    );
    h
}

/// Writes `<out>/<Scene>.fmu` for scene `k`; returns its path and size.
fn package(k: usize, lib: &[u8], out: &Path) -> Result<(PathBuf, u64), String> {
    let name = SCENE_NAMES[k];
    let path = out.join(format!("{name}.fmu"));
    let tmp = out.join(format!(".{name}.fmu.tmp"));
    let io = |e: std::io::Error| format!("{}: {e}", tmp.display());
    let zerr = |e: zip::result::ZipError| format!("{}: {e}", tmp.display());
    let file = fs::File::create(&tmp).map_err(io)?;
    let mut zip = ZipWriter::new(file);
    let text = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .unix_permissions(0o644);
    let binary = text.unix_permissions(0o755);
    let doc = documentation(k);
    let entries: [(String, &[u8], SimpleFileOptions); 3] = [
        (
            "modelDescription.xml".into(),
            MODEL_DESCRIPTIONS[k].as_bytes(),
            text,
        ),
        (format!("binaries/linux64/{name}.so"), lib, binary),
        ("documentation/index.html".into(), doc.as_bytes(), text),
    ];
    for (entry, bytes, options) in entries {
        zip.start_file(entry, options).map_err(zerr)?;
        zip.write_all(bytes).map_err(io)?;
    }
    zip.finish().map_err(zerr)?;
    fs::rename(&tmp, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    let size = fs::metadata(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok((path, size.len()))
}

fn run(args: &[String]) -> Result<(), String> {
    let o = parse(args)?;
    let lib = fs::read(&o.lib).map_err(|e| {
        format!(
            "cannot read the FMU library {}: {e}\n\
             build it first with `cargo build --release --lib`, or pass --lib PATH",
            o.lib.display()
        )
    })?;
    if !lib.starts_with(b"\x7fELF") {
        return Err(format!("{} is not an ELF shared library", o.lib.display()));
    }
    let contains = |needle: &[u8]| lib.windows(needle.len()).any(|w| w == needle);
    if !contains(b"fmi2Instantiate\0") {
        eprintln!(
            "warning: {} does not export fmi2Instantiate: the FMUs will not load in a host",
            o.lib.display()
        );
    } else if let Some(g) = GUIDS.iter().find(|g| !contains(g.as_bytes())) {
        // The FMI layer matches the GUID passed to fmi2Instantiate against its own table.
        return Err(format!(
            "{} does not contain the GUID {g}: it was built from another modelDescription/ than \
             this packager; rebuild both with scripts/build_fmus",
            o.lib.display()
        ));
    }
    fs::create_dir_all(&o.out).map_err(|e| format!("{}: {e}", o.out.display()))?;
    println!("library: {} ({} bytes)", o.lib.display(), lib.len());
    for (k, guid) in GUIDS.iter().enumerate() {
        let (path, size) = package(k, &lib, &o.out)?;
        println!(
            "wrote {} ({size} bytes, guid {guid}, {} variables)",
            path.display(),
            scene_variables(k).count()
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("package-fmus: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use georod::variables::XML_LOG_CATEGORIES;

    #[test]
    fn model_descriptions_match_the_tables() {
        for (k, scene) in SCENE_NAMES.iter().enumerate() {
            let xml = MODEL_DESCRIPTIONS[k];
            assert!(xml.contains(&format!("guid=\"{}\"", GUIDS[k])), "{scene}");
            assert!(xml.contains(&format!("modelIdentifier=\"{scene}\"")));
            assert!(xml.contains(&format!("modelName=\"{scene}\"")));
            for v in VARIABLES {
                let decl = format!("name=\"{}\" valueReference=\"{}\"", v.name, v.vr);
                assert_eq!(xml.contains(&decl), v.scenes[k], "{scene}: {}", v.name);
            }
            for (name, _) in XML_LOG_CATEGORIES {
                assert!(xml.contains(&format!("<Category name=\"{name}\"")));
            }
        }
    }

    #[test]
    fn guids_are_distinct_and_well_formed() {
        for (i, g) in GUIDS.iter().enumerate() {
            assert_eq!(g.len(), 38, "{g}");
            assert!(g.starts_with('{') && g.ends_with('}'));
            let groups: Vec<usize> = g[1..37].split('-').map(str::len).collect();
            assert_eq!(groups, [8, 4, 4, 4, 12]);
            assert!(GUIDS[..i].iter().all(|h| h != g));
        }
    }

    #[test]
    fn documentation_lists_the_scene_variables() {
        for k in 0..SCENE_NAMES.len() {
            let doc = documentation(k);
            for v in VARIABLES {
                let cell = format!("<td><code>{}</code></td>", v.name);
                assert_eq!(doc.contains(&cell), v.scenes[k], "{}", v.name);
            }
        }
    }
}
