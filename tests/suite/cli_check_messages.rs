//! `georod check FILE` names the file in every message, as `georod fmu` does (`georod fmu: FILE:
//! ...`): a refusal found while reading the scene (a key out of range) and one found only when
//! the initial state is set up with the default parameters (a parameter's start value that a
//! load cannot take).
//!
//! Run: `cargo test --profile quick --test suite cli_check_messages::`
use std::process::Command;

const SCENE: &str = r#"
name = "Refused"
[geometry]
shape = "straight"
L = 2.0
[defaults]
E = 210e9
rho = 7850.0
elements = ELEMENTS
[[parameter]]
name = "v"
start = SPEED
[[support]]
name = "a"
at = 0.0
fix = ["u1", "u2"]
[[support]]
name = "b"
at = 1.0
fix = ["u2"]
[[load]]
name = "truck"
kind = "moving"
direction = "-e2"
value = 1.0
speed = "v"
"#;

/// `georod check FILE` on the scene with `elements` and the speed's start value: the file's
/// path and the standard error.
fn refusal(elements: &str, speed: &str) -> (String, String) {
    let dir = std::env::temp_dir().join(format!(
        "georod_check_messages_{}_{elements}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("refused.toml");
    let text = SCENE.replace("ELEMENTS", elements).replace("SPEED", speed);
    std::fs::write(&file, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_georod"))
        .arg("check")
        .arg(&file)
        .output()
        .expect("georod runs");
    let _ = std::fs::remove_dir_all(&dir);
    assert!(!out.status.success(), "check accepted the scene");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    (file.display().to_string(), stderr)
}

#[test]
fn check_names_the_file_in_every_refusal() {
    for (elements, speed, says) in [
        ("1", "2.0", "defaults.elements: 1 is out of range"),
        (
            "8",
            "-1.0",
            "the speed of moving load `truck` is -1: must be > 0",
        ),
    ] {
        let (file, stderr) = refusal(elements, speed);
        assert!(stderr.contains(says), "{stderr}");
        assert!(
            stderr.starts_with(&format!("georod: {file}: ")),
            "georod check does not name {file} first: {stderr}"
        );
    }
}
