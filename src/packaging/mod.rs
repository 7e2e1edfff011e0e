//! Packaging a scene into an FMI 2.0 Co-Simulation FMU: `modelDescription.xml` (generated from
//! the scene), `binaries/linux64/<name>.so` (the one georod cdylib, whatever the scene),
//! `resources/scene.toml` (the scene file, read again by the binary at instantiation) and
//! `documentation/index.html`. Archives are reproducible: fixed entry order and timestamps.
pub mod documentation;
pub mod fmu3;
pub mod model_description;
pub mod model_description3;
pub mod variables3;

use crate::scene::Scene;
use crate::simulation::Simulation;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

/// Where the scene file lies inside an FMU.
pub const SCENE_RESOURCE: &str = "scene.toml";

/// The platform folder of `binaries/` for this build.
pub fn platform() -> &'static str {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("windows", "x86_64") => "win64",
        ("windows", _) => "win32",
        ("macos", _) => "darwin64",
        ("linux", "x86_64") => "linux64",
        _ => "linux32",
    }
}

/// What [`package`] wrote.
pub struct Packaged {
    pub path: PathBuf,
    pub bytes: u64,
    pub guid: String,
    pub variables: usize,
}

/// Checks that the scene has an initial state with its default parameters (a scene whose
/// static equilibrium cannot be found is refused here rather than at every instantiation).
pub fn check_initial_state(scene: &Scene) -> Result<(), String> {
    let scene = Arc::new(scene.clone());
    Simulation::new(scene.clone(), scene.defaults())
        .map(|_| ())
        .map_err(|e| format!("{}: with its default parameters: {e}", scene.name))
}

/// Writes the FMU of `scene` to `out` (through a temporary file: on error nothing is left).
pub fn package(scene: &Scene, lib: &[u8], out: &Path) -> Result<Packaged, String> {
    check_library(lib)?;
    check_initial_state(scene)?;
    let md = model_description::model_description(scene);
    let doc = documentation::documentation(scene, &md.guid);
    let bytes = write_atomically(out, |tmp| write_zip(tmp, scene, lib, &md.xml, &doc))?;
    Ok(Packaged {
        path: out.to_path_buf(),
        bytes,
        guid: md.guid,
        variables: crate::scene::variables::variables(scene).len(),
    })
}

/// Writes `out` through a temporary file beside it, filled by `write` (on error nothing is
/// left); returns the size written.
pub(crate) fn write_atomically(
    out: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<u64, String> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let file_name = out
        .file_name()
        .ok_or_else(|| format!("{}: not a file path", out.display()))?;
    let tmp = out.with_file_name(format!(".{}.tmp", file_name.to_string_lossy()));
    if let Err(e) = write(&tmp) {
        let _ = fs::remove_file(&tmp);
        return Err(e);
    }
    fs::rename(&tmp, out).map_err(|e| format!("{}: {e}", out.display()))?;
    Ok(fs::metadata(out)
        .map_err(|e| format!("{}: {e}", out.display()))?
        .len())
}

fn write_zip(tmp: &Path, scene: &Scene, lib: &[u8], xml: &str, doc: &str) -> Result<(), String> {
    let library = format!(
        "binaries/{}/{}{}",
        platform(),
        scene.name,
        std::env::consts::DLL_SUFFIX
    );
    let resource = format!("resources/{SCENE_RESOURCE}");
    write_archive(
        tmp,
        &[
            ("modelDescription.xml", xml.as_bytes(), false),
            (&library, lib, true),
            (&resource, scene.source.as_bytes(), false),
            ("documentation/index.html", doc.as_bytes(), false),
        ],
    )
}

/// A zip of `(path, bytes, executable)` entries, in this order, with fixed timestamps.
pub(crate) fn write_archive(tmp: &Path, entries: &[(&str, &[u8], bool)]) -> Result<(), String> {
    let io = |e: std::io::Error| format!("{}: {e}", tmp.display());
    let zerr = |e: zip::result::ZipError| format!("{}: {e}", tmp.display());
    let mut zip = ZipWriter::new(fs::File::create(tmp).map_err(io)?);
    let text = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .unix_permissions(0o644);
    for &(path, bytes, executable) in entries {
        let options = if executable {
            text.unix_permissions(0o755)
        } else {
            text
        };
        zip.start_file(path, options).map_err(zerr)?;
        zip.write_all(bytes).map_err(io)?;
    }
    zip.finish().map_err(zerr)?;
    Ok(())
}

/// The library must be a shared library exporting the FMI functions.
fn check_library(lib: &[u8]) -> Result<(), String> {
    check_exports(lib, "fmi2Instantiate")
}

/// `lib` must be a shared library (ELF, PE or Mach-O) whose symbols include `entry`.
pub(crate) fn check_exports(lib: &[u8], entry: &str) -> Result<(), String> {
    let shared =
        lib.starts_with(b"\x7fELF") || lib.starts_with(b"MZ") || lib.starts_with(&[0xcf, 0xfa]);
    if !shared {
        return Err("the FMU library is not a shared library".to_string());
    }
    let symbol = format!("{entry}\0");
    if !lib.windows(symbol.len()).any(|w| w == symbol.as_bytes()) {
        return Err(format!("the FMU library does not export {entry}"));
    }
    Ok(())
}

/// The georod cdylib next to the running executable (`target/release/libgeorod.so` beside
/// `target/release/georod`).
pub fn default_library() -> Result<PathBuf, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot locate this executable: {e}"))?;
    let dir = exe.parent().ok_or("executable without a directory")?;
    let name = format!(
        "{}georod{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    );
    Ok(dir.join(name))
}
