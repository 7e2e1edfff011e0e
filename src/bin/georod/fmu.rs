//! `georod fmu`: a scene file packaged with the library of every platform at hand.
use crate::args::Options;
use crate::bundle::{self, Bundle};
use georod::packaging::binaries::{Api, Platform};
use georod::packaging::{self, Library};
use georod::scene::Scene;
use std::path::{Path, PathBuf};

/// The platforms with their library files, and the platforms left without one.
type Choice = (Vec<(Platform, PathBuf)>, Vec<Platform>);

/// Where the libraries come from.
enum Source {
    /// `--binary` and `--lib`: only the libraries named.
    Given,
    /// An installed wheel's bundle, beside this executable.
    Bundle(Bundle),
    /// A source checkout's target folder (what scripts/build_fmus built there).
    Target(PathBuf),
}

/// The `--binary` libraries and `--lib` for this platform, by platform.
fn given_libraries(o: &Options) -> Result<Vec<(Platform, PathBuf)>, String> {
    let mut chosen: Vec<(Platform, PathBuf)> = Vec::new();
    for (name, file) in &o.binaries {
        let platform = Platform::from_folder(name).map_err(|e| format!("--binary {e}"))?;
        if chosen.iter().any(|(p, _)| *p == platform) {
            return Err(format!("--binary {platform} given twice"));
        }
        chosen.push((platform, PathBuf::from(file)));
    }
    if let Some(lib) = &o.lib {
        let host = packaging::host_platform()
            .ok_or("--lib: this platform cannot run an FMU; use --binary")?;
        if chosen.iter().any(|(p, _)| *p == host) {
            return Err(format!(
                "--lib and --binary {host}: give the {host} library once"
            ));
        }
        chosen.push((host, PathBuf::from(lib)));
    }
    Ok(chosen)
}

/// The library file of each platform: the given ones (only those: what was asked), otherwise
/// the bundle's (a wheel's), else what scripts/build_fmus built in the target folder (this
/// platform: else the library next to this executable). Platforms with none are returned apart.
fn choose_libraries(given: Vec<(Platform, PathBuf)>, source: &Source) -> Result<Choice, String> {
    let mut chosen = given;
    let mut missing = Vec::new();
    for platform in Platform::ALL {
        if chosen.iter().any(|(p, _)| *p == platform) {
            continue;
        }
        let found = match source {
            Source::Given => None,
            Source::Bundle(bundle) => bundle.library(platform)?,
            Source::Target(target) => {
                let mut candidates: Vec<PathBuf> = platform
                    .built_path()
                    .map(|p| target.join(p))
                    .into_iter()
                    .collect();
                if packaging::host_platform() == Some(platform) {
                    candidates.push(packaging::default_library()?);
                }
                candidates.into_iter().find(|p| p.is_file())
            }
        };
        match found {
            Some(path) => chosen.push((platform, path)),
            None => missing.push(platform),
        }
    }
    chosen.sort();
    Ok((chosen, missing))
}

pub fn package(o: &Options) -> Result<(), String> {
    let [file] = o.positional.as_slice() else {
        return Err("fmu takes one scene file: georod fmu FILE.toml [-o OUT.fmu]".to_string());
    };
    let scene = Scene::load(file).map_err(|e| e.to_string())?;
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let exe_dir = exe.parent().unwrap_or(Path::new("."));
    // An installed georod (a wheel's) has its bundle manifest beside it.
    let installed = exe_dir.join(bundle::MANIFEST).exists();
    let target = exe_dir.parent().unwrap_or(Path::new(".")).to_path_buf();
    let given = given_libraries(o)?;
    let source = if !given.is_empty() {
        Source::Given
    } else if let Some(bundle) = Bundle::beside(exe_dir)? {
        Source::Bundle(bundle)
    } else {
        Source::Target(target.clone())
    };
    let (chosen, missing) = choose_libraries(given, &source)?;
    if chosen.is_empty() {
        return Err(match &source {
            Source::Bundle(bundle) => format!(
                "this installation's {} in {} lists no library: {}",
                bundle::MANIFEST,
                bundle.dir.display(),
                bundle::REPAIR
            ),
            _ => format!(
                "no platform library found: build one (scripts/build_fmus) or pass --binary \
                 PLATFORM=FILE (looked in {}; an installed wheel's georod has its {} beside it)",
                target.display(),
                bundle::MANIFEST
            ),
        });
    }
    let mut libraries = Vec::new();
    for (platform, path) in &chosen {
        let bytes = std::fs::read(path)
            .map_err(|e| format!("cannot read the {platform} library {}: {e}", path.display()))?;
        let api = if o.fmi == 3 { Api::Fmi3 } else { Api::Fmi2 };
        packaging::binaries::check_library(*platform, &bytes, api).map_err(|e| {
            let repair = if matches!(source, Source::Bundle(_)) {
                format!(" (this installation's library: {})", bundle::REPAIR)
            } else {
                String::new()
            };
            format!("{}: {e}{repair}", path.display())
        })?;
        libraries.push(Library {
            platform: *platform,
            bytes,
        });
    }
    let out = match &o.output {
        Some(p) => PathBuf::from(p),
        // An installed georod writes into the working directory, never into its installation.
        None if installed => PathBuf::from(format!("{}.fmu", scene.name)),
        None => {
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
        packaging::fmu3::package3(&scene, &libraries, &out)
    } else {
        packaging::package(&scene, &libraries, &out)
    }
    .map_err(|e| format!("{file}: {e}"))?;
    println!(
        "wrote {} ({} bytes, guid {}, {} variables)",
        p.path.display(),
        p.bytes,
        p.guid,
        p.variables
    );
    for (platform, path) in &chosen {
        let folder = if o.fmi == 3 {
            platform.fmi3_folder()
        } else {
            platform.folder()
        };
        println!("  binaries/{folder}: {}", path.display());
    }
    for platform in missing {
        eprintln!(
            "georod fmu: {}: no {platform} library, binaries/{platform} left out: {}",
            p.path.display(),
            platform.how_to_build()
        );
    }
    Ok(())
}
