//! The `georod` command line: `--help` for the program and every command prints usage and
//! succeeds; a zero, negative or non-finite step, time or count, a missing option or a stray
//! argument is refused before anything runs, with a message naming the option and what is
//! allowed and exit status 2 (a usage error: not 1, a failed run, nor 101, a panic).
//! `simulate` writes the support reactions by default and any output by name (`--outputs`),
//! refusing an unknown name with the scene's outputs; `check` lists each shape array on one line
//! and prints the static reactions and the initial sensor values.
use std::process::{Command, Output};

const COMMANDS: [&str; 7] = [
    "fmu",
    "check",
    "simulate",
    "bench-steps",
    "path",
    "modes",
    "demo",
];

fn georod(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_georod"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("georod runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn help_prints_usage_for_the_program_and_every_command() {
    for args in [vec!["--help"], vec!["-h"], vec!["help"]] {
        let out = georod(&args);
        let stdout = text(&out.stdout);
        assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
        assert!(stdout.starts_with("usage: georod COMMAND"), "{stdout}");
        for command in COMMANDS {
            assert!(
                stdout.contains(&format!("\n  {command} ")),
                "{command}: {stdout}"
            );
        }
    }
    for command in COMMANDS {
        for flag in ["--help", "-h"] {
            let out = georod(&[command, flag]);
            let stdout = text(&out.stdout);
            assert!(
                out.status.success(),
                "{command} {flag}: {}",
                text(&out.stderr)
            );
            assert!(
                stdout.starts_with(&format!("usage: georod {command}")),
                "{command}: {stdout}"
            );
        }
    }
}

/// (arguments, the parts the message must contain)
#[rustfmt::skip]
const BAD: &[(&[&str], &[&str])] = &[
    (&["simulate", "--scene", "BuckledBeam", "--step", "0", "--stop", "1e-3"], &["--step 0", "finite number > 0"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "-1e-4", "--stop", "1e-3"], &["--step -1e-4", "> 0"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "nan", "--stop", "1e-3"], &["--step nan", "> 0"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "inf", "--stop", "1e-3"], &["--step inf", "> 0"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "1e-4", "--stop", "0"], &["--stop 0", "> 0"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "1e-4", "--stop", "-1"], &["--stop -1", "> 0"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "1e-4", "--stop", "-inf"], &["--stop -inf", "> 0"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "1e-4", "--stop", "NaN"], &["--stop NaN", "> 0"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "1", "--stop", "1e-3"], &["no step to take"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "1e-300", "--stop", "1"], &["steps: at most"]),
    (&["simulate", "--scene", "BuckledBeam", "--stop", "1e-3"], &["needs --step"]),
    (&["simulate", "--scene", "BuckledBeam", "--step", "1e-4"], &["needs --stop"]),
    (&["simulate", "--step"], &["--step needs a value"]),
    (&["bench-steps", "--scene", "BuckledBeam", "--steps", "0", "--dt", "1e-4"], &["--steps 0", "whole number > 0"]),
    (&["bench-steps", "--scene", "BuckledBeam", "--steps", "-5", "--dt", "1e-4"], &["--steps -5", "whole number > 0"]),
    (&["bench-steps", "--scene", "BuckledBeam", "--steps", "2.5", "--dt", "1e-4"], &["--steps 2.5", "whole number > 0"]),
    (&["bench-steps", "--scene", "BuckledBeam", "--steps", "10", "--dt", "0"], &["--dt 0", "> 0"]),
    (&["bench-steps", "--scene", "BuckledBeam", "--steps", "10"], &["needs --dt"]),
    (&["modes", "--scene", "PinnedArch", "--count", "0"], &["--count 0", "whole number > 0"]),
    (&["modes", "--scene", "PinnedArch", "--count", "-1"], &["--count -1", "whole number > 0"]),
    (&["modes", "--scene", "PinnedArch", "--load", "inf"], &["--load inf", "finite number"]),
    (&["path", "--scene", "PinnedArch", "--stop", "0"], &["--stop 0", "> 0"]),
    (&["path", "--scene", "PinnedArch", "--max-arc", "-0.1"], &["--max-arc -0.1", "> 0"]),
    (&["path", "--scene", "PinnedArch", "--imperfection", "nan"], &["--imperfection nan", "finite"]),
    (&["simulate", "--scene", "BuckledBeam", "--set", "E=inf", "--step", "1e-4", "--stop", "1e-3"], &["--set inf", "finite"]),
    (&["simulate", "--scene", "BuckledBeam", "--set", "E", "--step", "1e-4", "--stop", "1e-3"], &["NAME=VALUE"]),
    (&["simulate", "--bogus"], &["unknown option `--bogus`"]),
    (&["simulate", "stray", "--step", "1e-4", "--stop", "1e-3"], &["unexpected argument `stray`"]),
    (&["fmu"], &["fmu takes one scene file"]),
    (&["fmu", "scenes/BuckledBeam.toml", "--fmi", "4"], &["--fmi 4", "2 or 3"]),
    (&["check", "a.toml", "b.toml"], &["check takes one scene file"]),
    (&["nonsense"], &["unknown command `nonsense`"]),
    (&[], &["usage: georod COMMAND"]),
];

#[test]
fn bad_command_lines_are_refused_with_status_2_and_a_message() {
    for (args, parts) in BAD {
        let out = georod(args);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            out.stdout.is_empty(),
            "{args:?}: printed {}",
            text(&out.stdout)
        );
        assert!(stderr.starts_with("georod: "), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        for part in *parts {
            assert!(stderr.contains(part), "{args:?}: `{stderr}` lacks `{part}`");
        }
    }
}

/// A good command line still runs; a failure while running (here a scene that does not exist)
/// is status 1, not a usage error.
#[test]
fn good_command_lines_run_and_run_failures_are_status_1() {
    let out = georod(&[
        "simulate",
        "--scene",
        "BuckledBeam",
        "--step",
        "1e-4",
        "--stop",
        "3e-4",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let csv = text(&out.stdout);
    assert_eq!(
        csv.lines().count(),
        1 + 4,
        "header, t = 0 and 3 steps: {csv}"
    );
    // Every sensor, every support's reaction, then the energies and Newton iterations.
    assert!(csv.starts_with(
        "time,w_mid,v_mid,left_Rx,left_Ry,left_M,right_Rx,right_Ry,right_M,E_kin,E_strain,\
         newton_iterations\n"
    ));
    let out = georod(&[
        "simulate",
        "--scene",
        "NoSuchScene",
        "--step",
        "1e-4",
        "--stop",
        "1e-3",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("no scene `NoSuchScene`"));
}

/// A reader that closes the pipe early ends `georod` quietly, not with a panic.
#[test]
fn a_closed_pipe_ends_the_command_quietly() {
    use std::io::Read;
    use std::process::{Command, Stdio};
    // 5000 rows of CSV, far more than a pipe buffers (64 KiB).
    let mut child = Command::new(env!("CARGO_BIN_EXE_georod"))
        .args([
            "simulate",
            "--scene",
            "BuckledBeam",
            "--step",
            "1e-5",
            "--stop",
            "0.05",
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap();
    // The read end is closed here: the rest of the listing meets a broken pipe.
    let out = child.wait_with_output().unwrap();
    let stderr = text(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_ne!(out.status.code(), Some(101), "{stderr}");
}

fn stdout(out: &Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The cantilever's tip load is `P` along -e2 (1 N here): the static root reaction is +1 along
/// e2 at every row of a run that stays at rest.
#[test]
fn simulate_writes_reactions_and_outputs_by_name() {
    let scene = "examples/Cantilever.toml";
    let run = |extra: &[&str]| {
        let mut args = vec![
            "simulate", "--scene", scene, "--set", "P=1", "--step", "1e-3",
        ];
        args.extend_from_slice(&["--stop", "2e-3"]);
        args.extend_from_slice(extra);
        stdout(&georod(&args))
    };
    let csv = run(&[]);
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for column in ["time", "w_tip", "root_Rx", "root_Ry", "root_M", "E_kin"] {
        assert!(header.contains(&column), "{header:?}");
    }
    let ry = header.iter().position(|c| *c == "root_Ry").unwrap();
    for row in csv.lines().skip(1) {
        let value: f64 = row.split(',').nth(ry).unwrap().parse().unwrap();
        assert!((value - 1.0).abs() < 1e-9, "{row}");
    }
    let chosen = run(&["--outputs", "shape_y[41],root_M"]);
    assert_eq!(chosen.lines().next(), Some("time,shape_y[41],root_M"));
    assert_eq!(chosen.lines().count(), 4);
    let bad = georod(&[
        "simulate",
        "--scene",
        scene,
        "--step",
        "1e-3",
        "--stop",
        "1e-3",
        "--outputs",
        "M_tip",
    ]);
    let message = String::from_utf8_lossy(&bad.stderr);
    assert_eq!(bad.status.code(), Some(1), "{message}");
    assert!(
        message.contains("`M_tip` is not an output of Cantilever")
            && message.contains("shape_x[..]"),
        "{message}"
    );
}

#[test]
fn check_groups_shape_arrays_and_prints_the_static_reactions() {
    let text = stdout(&georod(&["check", "examples/Cantilever.toml"]));
    let shape_lines: Vec<&str> = text.lines().filter(|l| l.contains("shape_x")).collect();
    assert_eq!(shape_lines.len(), 1, "{text}");
    assert!(shape_lines[0].contains("shape_x[1..41]"), "{text}");
    assert!(text.contains("lyapunov[1..4]"), "{text}");
    let reaction = text
        .lines()
        .find(|l| l.trim_start().starts_with("support root"))
        .expect("the root's static reaction");
    // The root carries the example's tip load P (along -e2), whatever its value.
    let scene = georod::scene::Scene::load("examples/Cantilever.toml").unwrap();
    let p = scene.defaults().get(scene.param("P").unwrap().0);
    assert!(reaction.contains(&format!("Ry = {p:+.6e}")), "{reaction}");
    assert!(text.contains("sensor  w_tip"), "{text}");
}

#[test]
fn version_prints_the_crate_version() {
    for flag in ["--version", "-V"] {
        let out = georod(&[flag]);
        assert!(out.status.success(), "{flag}: {}", text(&out.stderr));
        assert_eq!(
            text(&out.stdout),
            format!("georod {}\n", env!("CARGO_PKG_VERSION"))
        );
    }
}
