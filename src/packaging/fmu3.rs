//! Packaging a scene into an FMI 3.0 Co-Simulation FMU: the same library files as the FMI 2.0
//! FMU (one library exports both APIs), under FMI 3.0's platform folders
//! (`binaries/x86_64-linux/<name>.so`, ...), `modelDescription.xml` 3.0, the scene file in
//! `resources/` and `documentation/index.html`. Reproducible like the FMI 2.0 archive.
use super::binaries::{Api, Platform};
use super::documentation::documentation;
use super::model_description3::model_description3;
use super::{check_initial_state, check_libraries, write_fmu, Library, Packaged};
use crate::scene::Scene;
use std::path::Path;

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

/// Writes the FMI 3.0 FMU of `scene` to `out` with `libraries` (the files the FMI 2.0 FMU of
/// the same build holds, each under its platform's FMI 3.0 folder, and each checked to export
/// every FMI 3.0 function). Through a temporary file: on error nothing is left.
pub fn package3(scene: &Scene, libraries: &[Library], out: &Path) -> Result<Packaged, String> {
    check_libraries(libraries, Api::Fmi3)?;
    check_initial_state(scene)?;
    let md = model_description3(scene);
    let doc = documentation3(scene, &md.token);
    let bytes = write_fmu(out, scene, libraries, Platform::fmi3_folder, &md.xml, &doc)?;
    Ok(Packaged {
        path: out.to_path_buf(),
        bytes,
        guid: md.token,
        // `time` and the scene's variables, each array counted once.
        variables: 1 + super::variables3::variables3(&crate::scene::variables::variables(scene))
            .len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    #[test]
    fn every_platform_has_its_fmi3_tuple() {
        assert_eq!(Platform::Linux64.fmi3_folder(), "x86_64-linux");
        assert_eq!(Platform::Win64.fmi3_folder(), "x86_64-windows");
        assert_eq!(Platform::Darwin64.fmi3_folder(), "x86_64-darwin");
    }

    #[test]
    fn a_library_without_the_fmi3_functions_is_refused() {
        let fake = Library {
            platform: Platform::Linux64,
            bytes: b"\x7fELF fmi3InstantiateCoSimulation\0".to_vec(),
        };
        let scene = Scene::load("scenes/BuckledBeam.toml").unwrap();
        let out = std::env::temp_dir().join(format!("georod-fmu3-bad-{}.fmu", std::process::id()));
        assert!(package3(&scene, &[fake], &out).is_err());
        assert!(package3(&scene, &[], &out).is_err());
        assert!(!out.exists(), "nothing written");
    }

    #[test]
    fn the_archive_holds_each_library_under_its_fmi3_platform_folder() {
        let scene = Scene::load("scenes/BuckledBeam.toml").unwrap();
        let libraries = [
            Library {
                platform: Platform::Win64,
                bytes: b"MZ a dll".to_vec(),
            },
            Library {
                platform: Platform::Linux64,
                bytes: b"\x7fELF a library".to_vec(),
            },
        ];
        let dir = std::env::temp_dir().join(format!("georod-fmu3-{}", std::process::id()));
        let out = dir.join("BuckledBeam.fmu");
        // The archive as package3 writes it once the libraries passed their checks.
        let md = model_description3(&scene);
        let doc = documentation3(&scene, &md.token);
        write_fmu(
            &out,
            &scene,
            &libraries,
            Platform::fmi3_folder,
            &md.xml,
            &doc,
        )
        .unwrap();
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
        assert!(xml.contains(&md.token));
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
