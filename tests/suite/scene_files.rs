//! Scene files: the repository's scenes and examples parse and package; bad files are refused by
//! `Scene::parse` and by `georod fmu` with a message that names the file, the key and what is
//! allowed, and the packager then writes nothing.
use georod::scene::Scene;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A small valid scene: a pinned-pinned beam with a harmonic load, an input and a sensor.
const GOOD: &str = r#"
name = "Good"
[geometry]
shape = "straight"
L = 10.0
[defaults]
E = 1.2e4
rho = 1.0e-6
elements = 10
[[support]]
name = "left"
at = 0.0
fix = ["u1", "u2"]
[[support]]
name = "right"
at = 1.0
fix = ["u1", "u2"]
[[load]]
name = "q"
kind = "distributed"
direction = "-e2"
time = "harmonic"
[[load]]
name = "f_ctrl"
kind = "point"
at = 0.5
direction = "-e2"
time = "input"
[[sensor]]
name = "w_mid"
at = 0.5
quantity = "u2"
"#;

/// Bad files: (what, text, parts the message must contain).
fn bad_files() -> Vec<(&'static str, String, Vec<&'static str>)> {
    let edit = |from: &str, to: &str| {
        assert!(GOOD.contains(from), "{from}");
        GOOD.replacen(from, to, 1)
    };
    vec![
        ("an empty file", String::new(), vec!["empty"]),
        (
            "an unknown key",
            edit("L = 10.0", "L = 10.0\nwidth = 1.0"),
            vec!["geometry.width", "unknown field `width`", "line 6"],
        ),
        (
            "a wrong type in a table",
            edit("L = 10.0", "L = \"ten\""),
            vec![
                "geometry.L",
                "a string (\"ten\")",
                "a number is allowed",
                "line 5",
            ],
        ),
        (
            "a wrong type in an array of tables",
            edit("at = 0.5", "at = \"half\""),
            vec!["[[load]] #2 \"f_ctrl\", key `at`", "a number is allowed"],
        ),
        (
            "a wrong type in an array",
            edit("fix = [\"u1\", \"u2\"]", "fix = [\"u1\", 2]"),
            vec!["[[support]] #1 \"left\", key `fix`", "a string is allowed"],
        ),
        (
            "a number where an integer is allowed",
            format!("{GOOD}[shape]\npoints = 2.5\n"),
            vec!["shape.points", "an integer is allowed"],
        ),
        (
            "a table where an array of tables is allowed",
            edit("[[sensor]]", "[sensor]"),
            vec!["sensor: ", "write [[sensor]], not [sensor]"],
        ),
        (
            "a wrong type in an inline table",
            format!("experiment = {{ stop = \"1 s\" }}\n{GOOD}"),
            vec!["experiment.stop", "a number is allowed"],
        ),
        (
            "no material",
            edit("E = 1.2e4\nrho = 1.0e-6\n", ""),
            vec!["defaults.E, defaults.rho", "add E and rho", "steel"],
        ),
        (
            "no density",
            edit("rho = 1.0e-6\n", ""),
            vec!["defaults.rho", "add rho"],
        ),
        (
            "a station outside [0, 1]",
            edit("at = 1.0", "at = 1.5"),
            vec!["[[support]] #2 \"right\", key `at`", "[0, 1]"],
        ),
        (
            "fewer elements than segments between the supports",
            edit(
                "elements = 10\n",
                "elements = 2\n[[support]]\nname = \"mid1\"\nat = 0.3\nfix = [\"u2\"]\n\
                 [[support]]\nname = \"mid2\"\nat = 0.7\nfix = [\"u2\"]\n",
            ),
            vec!["defaults.elements", "[3, 100000]", "segments"],
        ),
        (
            "an undeclared parameter in a value slot",
            edit("time = \"harmonic\"", "time = \"constant\"\nvalue = \"-Q\""),
            vec![
                "[[load]] #1 \"q\", key `value`",
                "`Q` is not a declared parameter",
            ],
        ),
        (
            "a name used twice",
            edit("name = \"w_mid\"", "name = \"f_ctrl\""),
            vec!["`f_ctrl` is used twice"],
        ),
        (
            "a rod free to rotate",
            edit(
                "fix = [\"u1\", \"u2\"]\n[[load]]",
                "fix = [\"u1\"]\n[[load]]",
            ),
            vec!["free to", "no static equilibrium", "reference"],
        ),
        (
            "a dof name that does not exist",
            edit("fix = [\"u1\", \"u2\"]", "fix = [\"u1\", \"v\"]"),
            vec!["key `fix`", "\"u1\", \"u2\", \"w\""],
        ),
        (
            "a direction that does not exist",
            edit("direction = \"-e2\"", "direction = \"down\""),
            vec!["key `direction`", "\"e1\", \"e2\", \"-e1\", \"-e2\""],
        ),
        (
            "a tunable parameter as a prescribed displacement",
            edit(
                "name = \"right\"\nat = 1.0\nfix = [\"u1\", \"u2\"]",
                "name = \"right\"\nat = 1.0\nfix = [\"u1\", \"u2\"]\ndisplace = { u1 = \"-s\" }",
            )
            .replacen(
                "[[support]]",
                "[[parameter]]\nname = \"s\"\nstart = 0.1\nvariability = \"tunable\"\n[[support]]",
                1,
            ),
            vec!["displace.u1", "tunable"],
        ),
        (
            "a standard parameter declared again",
            GOOD.replacen(
                "[[support]]",
                "[[parameter]]\nname = \"E\"\nstart = 1.0\n[[support]]",
                1,
            ),
            vec!["[[parameter]] #1 \"E\", key `name`", "already a parameter"],
        ),
        (
            "a rise on a straight rod",
            edit("L = 10.0", "L = 10.0\nH = 1.0"),
            vec!["geometry.H", "straight"],
        ),
        (
            "a name that is not an identifier",
            edit("name = \"Good\"", "name = \"my rod\""),
            vec!["name: ", "C identifier"],
        ),
        (
            "a sensor quantity that does not exist",
            edit("quantity = \"u2\"", "quantity = \"moment\""),
            vec![
                "[[sensor]] #1 \"w_mid\", key `quantity`",
                "\"a2\"",
                "\"sigma_bottom\"",
            ],
        ),
        (
            "a shape field that does not exist",
            format!("{GOOD}[shape]\nfields = [\"M\", \"stress\"]\n"),
            vec!["shape.fields", "`stress` is not allowed", "\"kappa\""],
        ),
        (
            "a shape field twice",
            format!("{GOOD}[shape]\nfields = [\"M\", \"M\"]\n"),
            vec!["shape.fields", "\"M\" is listed twice"],
        ),
        (
            "shape fields without shape points",
            format!("{GOOD}[shape]\npoints = 0\nfields = [\"N\"]\n"),
            vec!["shape.fields", "set shape.points >= 2"],
        ),
        (
            "no natural frequencies",
            format!("{GOOD}[modes]\ncount = 0\n"),
            vec!["modes.count", "0 is out of range: must be in [1, 12]"],
        ),
        (
            "too many natural frequencies",
            format!("{GOOD}[modes]\ncount = 13\n"),
            vec!["modes.count", "13 is out of range: must be in [1, 12]"],
        ),
        (
            "modes without a count",
            format!("{GOOD}[modes]\n"),
            vec!["modes.count", "missing"],
        ),
    ]
}

#[test]
fn good_scene_and_repository_scenes_parse() {
    Scene::parse(GOOD, "good.toml").expect("the base of the bad files is good");
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    for dir in ["scenes", "examples"] {
        for entry in std::fs::read_dir(repo.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
                let stem = path.file_stem().unwrap().to_str().unwrap();
                assert_eq!(
                    scene.name,
                    stem,
                    "{}: name and file name differ",
                    path.display()
                );
                georod::packaging::check_initial_state(&scene).unwrap();
            }
        }
    }
}

/// `F` is a force per unit length where it scales distributed loads, a force where it scales
/// point loads (docs/model.md, units).
#[test]
fn the_amplitude_takes_the_unit_of_the_loads_it_scales() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    for (file, unit) in [
        ("scenes/BuckledBeam.toml", "N/m"),
        ("scenes/PinnedArch.toml", "N"),
        ("examples/ThreeSpan.toml", "N/m"),
    ] {
        let scene = Scene::load(repo.join(file)).unwrap();
        let (_, f) = scene.param("F").unwrap();
        assert_eq!(f.unit.as_deref(), Some(unit), "{file}");
    }
}

/// `elements` declares the fewest elements that put every support on a node (one per segment
/// between them, at least 2) and 100000, and both are accepted; the counts just outside are
/// refused when set.
#[test]
fn elements_declares_the_counts_the_supports_allow() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let three = Scene::load(repo.join("examples/ThreeSpan.toml")).unwrap();
    let off =
        GOOD.replacen("at = 1.0", "at = 0.35", 1)
            .replacen("elements = 10", "elements = 20", 1);
    let cases = [
        (Scene::parse(GOOD, "good.toml").unwrap(), (2, 100_000)),
        (three, (3, 100_000)), // supports at 1/3 and 2/3: three segments
        (Scene::parse(&off, "off.toml").unwrap(), (2, 100_000)), // at 0.35: two segments
    ];
    for (scene, (lo, hi)) in cases {
        assert_eq!(scene.element_range(), (lo, hi), "{}", scene.name);
        let (_, p) = scene.param("elements").unwrap();
        assert_eq!(
            (p.range.min, p.range.max),
            (Some(lo as f64), Some(hi as f64))
        );
        let xml = georod::packaging::model_description::model_description(&scene).xml;
        assert!(xml.contains(&format!(r#"<Integer min="{lo}" max="{hi}" start="#)));
        for n in [lo, hi] {
            scene.values_with([("elements", n as f64)]).unwrap();
        }
        for n in [lo - 1, hi + 1] {
            let e = scene.values_with([("elements", n as f64)]).unwrap_err();
            assert!(e.to_string().contains(&format!("[{lo}, {hi}]")), "{e}");
        }
    }
}

#[test]
fn bad_scene_files_are_refused_with_the_file_and_the_key() {
    for (what, text, parts) in bad_files() {
        let e = Scene::parse(&text, "bad.toml")
            .err()
            .unwrap_or_else(|| panic!("{what}: accepted"));
        let message = e.to_string();
        println!("{what}:\n    {message}");
        assert!(message.starts_with("bad.toml: "), "{what}: {message}");
        for part in parts {
            assert!(message.contains(part), "{what}: `{message}` lacks `{part}`");
        }
    }
}

fn georod() -> Command {
    Command::new(env!("CARGO_BIN_EXE_georod"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("georod-scene-files-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The library `georod fmu` ships: the cdylib of this build. `cargo test` leaves it in
/// `deps/` beside the binary (only `cargo build` copies it up), so that copy is the fresh one.
fn library() -> PathBuf {
    let exe = PathBuf::from(env!("CARGO_BIN_EXE_georod"));
    let name = format!("libgeorod{}", std::env::consts::DLL_SUFFIX);
    let in_deps = exe.with_file_name("deps").join(&name);
    if in_deps.is_file() {
        in_deps
    } else {
        exe.with_file_name(name)
    }
}

#[test]
fn the_packager_refuses_bad_files_and_writes_nothing() {
    let lib = library();
    if !lib.is_file() {
        // `cargo test` builds the bin and the cdylib of the same profile together.
        panic!(
            "{} is missing: build with `cargo build --profile quick --lib`",
            lib.display()
        );
    }
    let dir = scratch("bad");
    let mut cases = bad_files();
    // A file whose static equilibrium cannot be found: the pinned arch preloaded far beyond its
    // limit load (about 200 at the crown).
    let arch = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/PinnedArch.toml"),
    )
    .unwrap()
    .replace(
        "name = \"P0\"\nstart = 0.0",
        "name = \"P0\"\nstart = 2000.0",
    );
    cases.push((
        "no static equilibrium",
        arch,
        vec!["initial static state not found"],
    ));
    for (what, text, parts) in cases {
        let file = dir.join("bad.toml");
        std::fs::write(&file, &text).unwrap();
        let out = dir.join("Bad.fmu");
        let run = georod()
            .args([
                "fmu",
                file.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--lib",
            ])
            .arg(&lib)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{what}: packaged");
        // 101 is the exit code of a Rust panic: a bad file must be refused, never crash.
        assert_ne!(run.status.code(), Some(101), "{what}: panicked: {stderr}");
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        assert!(stderr.contains(file.to_str().unwrap()), "{what}: {stderr}");
        for part in parts {
            assert!(stderr.contains(part), "{what}: `{stderr}` lacks `{part}`");
        }
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(
            left,
            vec![std::ffi::OsString::from("bad.toml")],
            "{what}: files left"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_packager_writes_an_fmu_with_the_scene_inside() {
    let dir = scratch("good");
    let file = dir.join("good.toml");
    std::fs::write(&file, GOOD).unwrap();
    let out = dir.join("sub").join("Good.fmu");
    let run = georod()
        .args([
            "fmu",
            file.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--lib",
        ])
        .arg(library())
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let archive = zip::ZipArchive::new(std::fs::File::open(&out).unwrap()).unwrap();
    let names: Vec<&str> = archive.file_names().collect();
    for entry in [
        "modelDescription.xml",
        "resources/scene.toml",
        "documentation/index.html",
        "binaries/linux64/Good.so",
    ] {
        assert!(names.contains(&entry), "{entry} missing from {names:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
