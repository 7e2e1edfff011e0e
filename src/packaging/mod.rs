//! Packaging a scene into an FMI 2.0 Co-Simulation FMU: `modelDescription.xml` (generated from
//! the scene), `binaries/<platform>/<name><suffix>` (the one georod cdylib of each platform,
//! whatever the scene: linux64, win64, darwin64, see [`binaries`]),
//! `resources/scene.toml` (the scene file, read again by the binary at instantiation) and
//! `documentation/index.html`; or into an FMI 3.0 one ([`fmu3`]) with the same libraries.
//! Archives are reproducible: fixed entry order and timestamps, no path or date of the build
//! ([`write_archive`]).
pub mod binaries;
pub mod documentation;
pub mod fmu3;
pub mod model_description;
pub mod model_description3;
pub mod variables3;

use crate::scene::Scene;
use crate::simulation::Simulation;
use binaries::Platform;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

/// Where the scene file lies inside an FMU.
pub const SCENE_RESOURCE: &str = "scene.toml";

/// The platform of this build (where `georod fmu` runs), if an FMU can carry its library.
pub fn host_platform() -> Option<Platform> {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("windows", "x86_64") => Some(Platform::Win64),
        ("macos", "x86_64" | "aarch64") => Some(Platform::Darwin64),
        ("linux", "x86_64") => Some(Platform::Linux64),
        _ => None,
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

/// A platform's library to pack.
pub struct Library {
    pub platform: Platform,
    pub bytes: Vec<u8>,
}

/// Checks `libraries`: at least one, one per platform, each a library of its platform that
/// exports every function of `api`.
pub(crate) fn check_libraries(libraries: &[Library], api: binaries::Api) -> Result<(), String> {
    if libraries.is_empty() {
        return Err("no platform library to pack".to_string());
    }
    for (i, lib) in libraries.iter().enumerate() {
        if libraries[..i].iter().any(|l| l.platform == lib.platform) {
            return Err(format!("two {} libraries given", lib.platform));
        }
        binaries::check_library(lib.platform, &lib.bytes, api)?;
    }
    Ok(())
}

/// Writes the FMU of `scene` with `libraries` (at least one, one per platform) to `out`
/// (through a temporary file: on error nothing is left).
pub fn package(scene: &Scene, libraries: &[Library], out: &Path) -> Result<Packaged, String> {
    check_libraries(libraries, binaries::Api::Fmi2)?;
    check_initial_state(scene)?;
    let md = model_description::model_description(scene);
    let doc = documentation::documentation(scene, &md.guid);
    let bytes = write_fmu(out, scene, libraries, Platform::folder, &md.xml, &doc)?;
    Ok(Packaged {
        path: out.to_path_buf(),
        bytes,
        guid: md.guid,
        variables: crate::scene::variables::variables(scene).len(),
    })
}

/// The archive of an FMU at `out`: `xml`, each library under `binaries/<folder>/`, the scene
/// file, the documentation page `doc`; returns its size.
pub(crate) fn write_fmu(
    out: &Path,
    scene: &Scene,
    libraries: &[Library],
    folder: fn(Platform) -> &'static str,
    xml: &str,
    doc: &str,
) -> Result<u64, String> {
    // Fixed order (platforms sorted) for reproducible archives.
    let mut sorted: Vec<&Library> = libraries.iter().collect();
    sorted.sort_by_key(|l| l.platform);
    let paths: Vec<String> = (sorted.iter())
        .map(|l| {
            format!(
                "binaries/{}/{}{}",
                folder(l.platform),
                scene.name,
                l.platform.suffix()
            )
        })
        .collect();
    let resource = format!("resources/{SCENE_RESOURCE}");
    let mut entries: Vec<(&str, &[u8], bool)> =
        vec![("modelDescription.xml", xml.as_bytes(), false)];
    for (path, lib) in paths.iter().zip(&sorted) {
        entries.push((path, &lib.bytes, true));
    }
    entries.push((&resource, scene.source.as_bytes(), false));
    entries.push(("documentation/index.html", doc.as_bytes(), false));
    write_atomically(out, |tmp| write_archive(tmp, &entries))
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

/// A zip of `(path, bytes, executable)` entries, in this order, every one dated
/// 1980-01-01 00:00 (zip's epoch). Nothing of the machine or the moment enters the archive:
/// entries are marked Unix-made on every platform, deflated by the same pure-Rust code
/// (miniz_oxide), and dated explicitly (zip's `time` feature, if any crate turned it on,
/// would otherwise date them now). The same scene and libraries give the same bytes, on
/// Linux and Windows alike (python/tests/test_wheel_smoke.py, scripts/test_wheels).
pub(crate) fn write_archive(tmp: &Path, entries: &[(&str, &[u8], bool)]) -> Result<(), String> {
    let io = |e: std::io::Error| format!("{}: {e}", tmp.display());
    let zerr = |e: zip::result::ZipError| format!("{}: {e}", tmp.display());
    let mut zip = ZipWriter::new(fs::File::create(tmp).map_err(io)?);
    let text = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .last_modified_time(zip::DateTime::default())
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn archives_are_dated_at_the_zip_epoch_and_the_same_bytes_each_time() {
        let dir = std::env::temp_dir().join(format!("georod-archive-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let entries: [(&str, &[u8], bool); 2] = [("a.txt", b"a", false), ("bin/x.so", b"x", true)];
        let (one, two) = (dir.join("one.zip"), dir.join("two.zip"));
        write_archive(&one, &entries).unwrap();
        write_archive(&two, &entries).unwrap();
        assert_eq!(fs::read(&one).unwrap(), fs::read(&two).unwrap());
        let mut zip = zip::ZipArchive::new(fs::File::open(&one).unwrap()).unwrap();
        for i in 0..zip.len() {
            let entry = zip.by_index(i).unwrap();
            let date = entry.last_modified().unwrap();
            assert_eq!((date.year(), date.month(), date.day()), (1980, 1, 1));
            assert_eq!((date.hour(), date.minute(), date.second()), (0, 0, 0));
        }
        let _ = fs::remove_dir_all(&dir);
    }
}
