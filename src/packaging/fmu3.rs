//! Packaging a scene into an FMI 3.0 Co-Simulation FMU: the same library files as the FMI 2.0
//! FMU (one library exports both APIs), under FMI 3.0's platform folders
//! (`binaries/x86_64-linux/<name>.so`, ...), `modelDescription.xml` 3.0, the scene file in
//! `resources/` and `documentation/index.html`. Reproducible like the FMI 2.0 archive.
use super::documentation::documentation;
use super::model_description3::model_description3;
use super::{
    check_exports, check_initial_state, write_archive, write_atomically, Packaged, SCENE_RESOURCE,
};
use crate::scene::Scene;
use std::path::Path;

/// FMI 2.0 platform folder -> FMI 3.0 platform tuple, and the library file suffix there.
pub const PLATFORMS3: [(&str, &str, &str); 5] = [
    ("linux64", "x86_64-linux", ".so"),
    ("linux32", "x86-linux", ".so"),
    ("win64", "x86_64-windows", ".dll"),
    ("win32", "x86-windows", ".dll"),
    ("darwin64", "x86_64-darwin", ".dylib"),
];

/// The FMI 3.0 platform tuple and library suffix of an FMI 2.0 platform folder.
pub fn platform3(fmi2_platform: &str) -> Result<(&'static str, &'static str), String> {
    PLATFORMS3
        .iter()
        .find(|(two, ..)| *two == fmi2_platform)
        .map(|&(_, three, suffix)| (three, suffix))
        .ok_or_else(|| format!("no FMI 3.0 platform for the FMI 2.0 platform `{fmi2_platform}`"))
}

/// The FMU's documentation page, for FMI 3.0: the FMI 2.0 page with the version's names, and
/// what a host sees differently.
pub fn documentation3(scene: &Scene, token: &str) -> String {
    let page = documentation(scene, token)
        .replace(
            "an FMI 2.0 Co-Simulation FMU",
            "an FMI 3.0 Co-Simulation FMU",
        )
        .replace("GUID <code>", "instantiation token <code>")
        .replace("fmi2Discard", "fmi3Discard")
        .replace("fmpy.fmi2.FMU2Slave", "fmpy.fmi3.FMU3Slave")
        .replace(
            "shape_x[i]</code>, <code>shape_y[i]</code> (i = 1..",
            "shape_x</code>, <code>shape_y</code> (arrays of ",
        );
    let note = "<h2>FMI 3.0</h2>\n<p>Every <code>shape_*</code> output is one Float64 array \
        (<code>&lt;Dimension&gt;</code>: the shape's point count), read whole with one \
        <code>fmi3GetFloat64</code> call whose <code>nValues</code> counts elements; the other \
        variables are the scalars of the FMI 2.0 FMU of this scene, with the same names and \
        value references. Inputs are held over a communication step (FMI 3.0 Co-Simulation has \
        no input derivatives). <code>fmi3DoStep</code> never returns early, never needs event \
        handling and never ends the simulation on its own; <code>lastSuccessfulTime</code> is \
        the time the FMU reached. The FMU has no event mode, clocks or structural parameters; \
        the functions of those answer <code>fmi3Error</code> with a logged reason.</p>\n";
    page.replacen("</body>", &format!("{note}</body>"), 1)
}

/// Writes the FMI 3.0 FMU of `scene` to `out` with `libraries`, (FMI 2.0 platform folder,
/// library bytes) pairs: the files the FMI 2.0 FMU of the same build holds. Through a
/// temporary file: on error nothing is left.
pub fn package3(
    scene: &Scene,
    libraries: &[(&str, &[u8])],
    out: &Path,
) -> Result<Packaged, String> {
    if libraries.is_empty() {
        return Err("no library to package".to_string());
    }
    let mut binaries = Vec::new();
    for &(platform, lib) in libraries {
        check_library3(lib)?;
        let (folder, suffix) = platform3(platform)?;
        binaries.push((format!("binaries/{folder}/{}{suffix}", scene.name), lib));
    }
    check_initial_state(scene)?;
    let md = model_description3(scene);
    let doc = documentation3(scene, &md.token);
    let resource = format!("resources/{SCENE_RESOURCE}");
    let mut entries: Vec<(&str, &[u8], bool)> =
        vec![("modelDescription.xml", md.xml.as_bytes(), false)];
    entries.extend(
        binaries
            .iter()
            .map(|(path, lib)| (path.as_str(), *lib, true)),
    );
    entries.push((&resource, scene.source.as_bytes(), false));
    entries.push(("documentation/index.html", doc.as_bytes(), false));
    let bytes = write_atomically(out, |tmp| write_archive(tmp, &entries))?;
    Ok(Packaged {
        path: out.to_path_buf(),
        bytes,
        guid: md.token,
        // `time` and the scene's variables, each array counted once.
        variables: 1 + super::variables3::variables3(&crate::scene::variables::variables(scene))
            .len(),
    })
}

/// The library must be a shared library exporting the FMI 3.0 Co-Simulation entry point.
fn check_library3(lib: &[u8]) -> Result<(), String> {
    check_exports(lib, "fmi3InstantiateCoSimulation")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    #[test]
    fn every_fmi2_platform_maps_to_an_fmi3_tuple() {
        assert_eq!(platform3("linux64").unwrap(), ("x86_64-linux", ".so"));
        assert_eq!(platform3("win64").unwrap(), ("x86_64-windows", ".dll"));
        assert!(platform3("amiga").is_err());
    }

    #[test]
    fn a_library_without_the_fmi3_entry_point_is_refused() {
        assert!(check_library3(b"\x7fELF fmi2Instantiate\0").is_err());
        assert!(check_library3(b"\x7fELF fmi3InstantiateCoSimulation\0").is_ok());
        assert!(check_library3(b"text fmi3InstantiateCoSimulation\0").is_err());
    }

    #[test]
    fn the_archive_holds_each_library_under_its_fmi3_platform_folder() {
        let scene = Scene::load("scenes/BuckledBeam.toml").unwrap();
        let lib: &[u8] = b"\x7fELF fmi3InstantiateCoSimulation\0";
        let dll: &[u8] = b"MZ fmi3InstantiateCoSimulation\0";
        let dir = std::env::temp_dir().join(format!("georod-fmu3-{}", std::process::id()));
        let out = dir.join("BuckledBeam.fmu");
        let packaged = package3(&scene, &[("linux64", lib), ("win64", dll)], &out).unwrap();
        let mut zip = zip::ZipArchive::new(fs::File::open(&out).unwrap()).unwrap();
        let names: Vec<String> = zip.file_names().map(str::to_string).collect();
        for name in [
            "modelDescription.xml",
            "binaries/x86_64-linux/BuckledBeam.so",
            "binaries/x86_64-windows/BuckledBeam.dll",
            "resources/scene.toml",
            "documentation/index.html",
        ] {
            assert!(names.contains(&name.to_string()), "{name} in {names:?}");
        }
        let mut xml = String::new();
        std::io::Read::read_to_string(&mut zip.by_name("modelDescription.xml").unwrap(), &mut xml)
            .unwrap();
        assert!(xml.contains(r#"fmiVersion="3.0""#));
        assert!(xml.contains(&packaged.guid));
        assert!(package3(&scene, &[("amiga", lib)], &out).is_err());
        assert!(package3(&scene, &[], &out).is_err());
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_documentation_names_fmi3_and_its_arrays() {
        let scene = Scene::load("scenes/BuckledBeam.toml").unwrap();
        let page = documentation3(&scene, "{token}");
        assert!(page.contains("an FMI 3.0 Co-Simulation FMU"));
        assert!(!page.contains("FMI 2.0 Co-Simulation FMU"));
        assert!(!page.contains("fmi2"), "no FMI 2.0 function named");
        assert!(page.contains("<h2>FMI 3.0</h2>"));
    }
}
