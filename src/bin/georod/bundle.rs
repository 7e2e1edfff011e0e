//! The libraries that a `georod` installed from a wheel packs: its bundle, the folder of the
//! executable (`georod_tools/bin/` in site-packages). `bundle.toml` there lists each platform's
//! library with its size and CRC-32, written when the wheel was built (`hatch_build.py`). A
//! library that is missing, of another size or checksum, or that fails the platform checks is
//! refused with the platform, the file and how to get a good one: a broken installation never
//! writes an FMU short of a platform the wheel promised.
//!
//! A `georod` built in a source checkout has no `bundle.toml`: it packs what scripts/build_fmus
//! built in its target folder (see `fmu.rs`).
use georod::packaging::binaries::Platform;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The manifest's file name, beside the executable.
pub const MANIFEST: &str = "bundle.toml";

/// How to repair an installed wheel, for every message about its bundle.
pub const REPAIR: &str = "reinstall georod (pip install --force-reinstall georod, or the wheel \
    file), or rebuild the wheels from a source checkout with scripts/build_wheels (docs/python.md)";

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Manifest {
    version: String,
    #[serde(default)]
    library: Vec<Entry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Entry {
    platform: String,
    file: String,
    bytes: u64,
    crc32: u32,
}

/// A bundle: its folder and the library file it lists for each platform.
pub struct Bundle {
    pub dir: PathBuf,
    libraries: Vec<(Platform, PathBuf, u64, u32)>,
}

impl Bundle {
    /// The bundle beside the executable in `dir`; `None` when there is no manifest (a source
    /// checkout's build), an error when there is one that cannot be used.
    pub fn beside(dir: &Path) -> Result<Option<Bundle>, String> {
        let path = dir.join(MANIFEST);
        if !path.exists() {
            return Ok(None);
        }
        let damaged = |why: String| {
            format!(
                "this installation's bundle manifest {} is damaged: {why}; {REPAIR}",
                path.display()
            )
        };
        let text = std::fs::read_to_string(&path).map_err(|e| damaged(e.to_string()))?;
        let manifest: Manifest = toml::from_str(&text).map_err(|e| damaged(e.to_string()))?;
        let ours = env!("CARGO_PKG_VERSION");
        if manifest.version != ours {
            return Err(damaged(format!(
                "it lists the libraries of georod {}, this executable is georod {ours}",
                manifest.version
            )));
        }
        let mut libraries: Vec<(Platform, PathBuf, u64, u32)> = Vec::new();
        for entry in manifest.library {
            let platform = Platform::from_folder(&entry.platform).map_err(damaged)?;
            if libraries.iter().any(|(p, ..)| *p == platform) {
                return Err(damaged(format!("{platform} listed twice")));
            }
            let file = dir.join(&entry.file);
            libraries.push((platform, file, entry.bytes, entry.crc32));
        }
        Ok(Some(Bundle {
            dir: dir.to_path_buf(),
            libraries,
        }))
    }

    /// The library file of `platform`, checked against the manifest (present, same size and
    /// CRC-32); `None` when the bundle has none for it.
    pub fn library(&self, platform: Platform) -> Result<Option<PathBuf>, String> {
        let Some((_, file, bytes, crc)) = self.libraries.iter().find(|(p, ..)| *p == platform)
        else {
            return Ok(None);
        };
        let content = std::fs::read(file).map_err(|e| {
            format!(
                "the {platform} library of this installation is missing: {} ({e}; {} lists \
                 it); {REPAIR}",
                file.display(),
                MANIFEST
            )
        })?;
        let found = (content.len() as u64, crc32fast::hash(&content));
        if found != (*bytes, *crc) {
            return Err(format!(
                "the {platform} library of this installation is damaged: {} has {} bytes and \
                 CRC-32 {:08x}, {} lists {bytes} bytes and {crc:08x}; {REPAIR}",
                file.display(),
                found.0,
                found.1,
                MANIFEST
            ));
        }
        Ok(Some(file.clone()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("georod-bundle-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(dir.join("win64")).unwrap();
        dir
    }

    fn manifest(dir: &Path, version: &str, bytes: u64, crc: u32) {
        let text = format!(
            "version = \"{version}\"\n[[library]]\nplatform = \"win64\"\n\
             file = \"win64/georod.dll\"\nbytes = {bytes}\ncrc32 = {crc}\n"
        );
        fs::write(dir.join(MANIFEST), text).unwrap();
    }

    #[test]
    fn no_manifest_is_a_source_build() {
        let dir = folder("none");
        assert!(Bundle::beside(&dir).unwrap().is_none());
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_listed_library_is_checked_against_its_size_and_checksum() {
        let dir = folder("listed");
        let dll = b"MZ a library".to_vec();
        manifest(
            &dir,
            env!("CARGO_PKG_VERSION"),
            dll.len() as u64,
            crc32fast::hash(&dll),
        );
        let bundle = Bundle::beside(&dir).unwrap().unwrap();
        assert_eq!(bundle.library(Platform::Linux64).unwrap(), None);

        let e = bundle.library(Platform::Win64).unwrap_err();
        assert!(
            e.starts_with("the win64 library of this installation is missing: "),
            "{e}"
        );
        assert!(e.contains("scripts/build_wheels"), "{e}");

        fs::write(dir.join("win64/georod.dll"), &dll).unwrap();
        let file = bundle.library(Platform::Win64).unwrap().unwrap();
        assert_eq!(file, dir.join("win64/georod.dll"));

        fs::write(dir.join("win64/georod.dll"), b"MZ a librarY").unwrap();
        let e = bundle.library(Platform::Win64).unwrap_err();
        assert!(
            e.starts_with("the win64 library of this installation is damaged: "),
            "{e}"
        );
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_manifest_of_another_version_or_unreadable_is_refused() {
        let dir = folder("version");
        manifest(&dir, "0.0.0-other", 1, 2);
        let e = Bundle::beside(&dir).err().unwrap();
        assert!(
            e.contains("it lists the libraries of georod 0.0.0-other"),
            "{e}"
        );
        fs::write(dir.join(MANIFEST), "version = 1").unwrap();
        let e = Bundle::beside(&dir).err().unwrap();
        assert!(e.contains("bundle manifest"), "{e}");
        assert!(e.contains("pip install --force-reinstall"), "{e}");
        let _ = fs::remove_dir_all(&dir);
    }
}
