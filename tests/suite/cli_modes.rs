//! `georod modes FILE.toml`: the natural frequencies of any scene's initial state, here a
//! simply supported beam under a constant distributed load (which the path-following form
//! refuses): the printed frequencies are the scene's `frequency[k]` outputs, the mode-shape CSV
//! has a row per node and three columns per mode, each shape scaled to a largest translation of
//! +1 (the first mode of a simply supported beam is a half sine), and an SVG beside it draws them.
use crate::common;

use georod::scene::Scene;
use georod::simulation::Simulation;
use std::process::Command;
use std::sync::Arc;

const BEAM: &str = r#"
name = "LoadedBeam"
[geometry]
shape = "straight"
L = 10.0
[defaults]
E = 2.0e5
nu = 0.3
rho = 1.0
b = 1.0
h = 0.5
elements = 20
[[support]]
name = "pin"
at = 0.0
fix = ["u1", "u2"]
[[support]]
name = "roller"
at = 1.0
fix = ["u2"]
[[load]]
name = "q"
kind = "distributed"
direction = "-e2"
value = 2.0
"#;

#[test]
fn modes_of_a_scene_file_prints_frequencies_and_writes_shapes() {
    let dir = std::env::temp_dir().join(format!("georod_cli_modes_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("LoadedBeam.toml");
    std::fs::write(&file, BEAM).unwrap();
    let shapes = dir.join("shapes.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_georod"))
        .args(["modes", file.to_str().unwrap(), "--count", "3", "-o"])
        .arg(&shapes)
        .output()
        .expect("georod runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let printed: Vec<f64> = stdout
        .lines()
        .filter_map(|l| {
            let cols: Vec<&str> = l.split_whitespace().collect();
            (cols.len() == 3 && cols[0].parse::<usize>().is_ok()).then(|| cols[1].parse().unwrap())
        })
        .collect();
    assert_eq!(printed.len(), 3, "{stdout}");
    // The same frequencies as the scene's outputs with [modes] count = 3.
    let text = format!("{BEAM}\n[modes]\ncount = 3\n");
    let scene = Arc::new(Scene::parse(&text, "LoadedBeam+modes").unwrap());
    let sim = Simulation::new(scene.clone(), scene.defaults()).unwrap();
    for (k, f) in printed.iter().enumerate() {
        let output = common::output(&sim, &format!("frequency[{}]", k + 1));
        assert!(
            (f - output).abs() < 1e-8 * output,
            "mode {}: {f} vs {output}",
            k + 1
        );
    }
    let csv = std::fs::read_to_string(&shapes).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert!(csv.starts_with("node,s,x,y,u1_1,u2_1,w_1,u1_2,"), "{csv}");
    assert_eq!(rows.len(), 21);
    // Mode 1: u2 = sin(pi s / L) (half sine, largest +1 at midspan), to the mesh's interpolation
    // of a slightly shear- and load-affected shape (1e-2).
    for r in &rows {
        let expected = (std::f64::consts::PI * r[1] / 10.0).sin();
        assert!((r[5] - expected).abs() < 1e-2, "{r:?}");
    }
    // The drawing beside it: per mode a panel with the rod at rest and displaced.
    let svg = std::fs::read_to_string(shapes.with_extension("svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<polyline").count(), 2 * 3);
    for k in 1..=3 {
        assert!(svg.contains(&format!("LoadedBeam: mode {k} at")), "{svg}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Without `--output` the shapes go to `<name>_modes.csv` in the working folder, and a second
/// run never replaces the first one's files: it writes `<name>_modes-2.csv` (and `.svg`).
#[test]
fn default_shape_files_never_replace_an_earlier_run() {
    let dir = std::env::temp_dir().join(format!("georod_cli_modes_default_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("LoadedBeam.toml"), BEAM).unwrap();
    let run = || {
        let out = Command::new(env!("CARGO_BIN_EXE_georod"))
            .args(["modes", "LoadedBeam.toml", "--count", "1"])
            .current_dir(&dir)
            .output()
            .expect("georod runs");
        assert!(out.status.success(), "{out:?}");
    };
    run();
    let first = dir.join("LoadedBeam_modes.csv");
    std::fs::write(&first, "an earlier run's result\n").unwrap();
    run();
    assert_eq!(
        std::fs::read_to_string(&first).unwrap(),
        "an earlier run's result\n"
    );
    for name in [
        "LoadedBeam_modes-2.csv",
        "LoadedBeam_modes-2.svg",
        "LoadedBeam_modes.svg",
    ] {
        assert!(dir.join(name).is_file(), "{name} written");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
