//! The command on frames: `georod path` through Lee's frame (both limit points and the
//! equilibria at zero load), `georod modes` writing every member's nodes, `georod check`
//! naming which shape samples sample which member.
use crate::common;
use std::process::{Command, Output};

fn georod(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_georod"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("georod runs")
}

fn stdout(out: &Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Lee's frame (`common::scenes::LEE_FRAME`) with a sensor at the load.
fn lee_with_sensor() -> String {
    format!(
        "{}{}",
        common::scenes::LEE_FRAME,
        r#"[[sensor]]
name = "v"
member = "beam"
at = 0.2
quantity = "u2"
"#
    )
}

#[test]
fn path_follows_lee_frame_through_both_limit_points() {
    let dir = std::env::temp_dir().join(format!("georod_cli_frames_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("Lee.toml");
    std::fs::write(&file, lee_with_sensor()).unwrap();
    let out = georod(&[
        "path",
        "--scene",
        file.to_str().unwrap(),
        "--load-name",
        "P",
        "--stop",
        "2.5",
    ]);
    let csv = stdout(&out);
    let limits: Vec<f64> = (csv.lines())
        .filter(|l| l.starts_with("# critical,LimitPoint,"))
        .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
        .collect();
    // The first limit load of this 40-element mesh (1.8634; 18.55 P L^2/EI converged, see
    // tests/suite/frames_stability.rs) and the second, on the way back (-0.956).
    assert_eq!(limits.len(), 2, "{csv}");
    assert!((limits[0] - 1.8634).abs() < 1e-3, "{limits:?}");
    assert!((limits[1] + 0.956).abs() < 1e-2, "{limits:?}");
    // Three equilibria at zero load: the undeformed frame, the snapped one and the one between.
    let zero: Vec<&str> = csv
        .lines()
        .filter(|l| l.starts_with("# equilibrium,"))
        .collect();
    assert_eq!(zero.len(), 3, "{csv}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn modes_and_check_name_the_members() {
    let dir = std::env::temp_dir().join(format!("georod_cli_frames_modes_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("portal.csv");
    let out = georod(&[
        "modes",
        "examples/PortalFrame.toml",
        "--count",
        "2",
        "--output",
        csv.to_str().unwrap(),
    ]);
    let text = stdout(&out);
    assert!(
        text.contains("5.6216"),
        "the sway frequency (check's frequency[1]): {text}"
    );
    let shapes = std::fs::read_to_string(&csv).unwrap();
    let header = shapes.lines().next().unwrap();
    assert_eq!(header, "member,node,s,x,y,u1_1,u2_1,w_1,u1_2,u2_2,w_2");
    for member in ["left", "beam", "right"] {
        assert!(
            shapes.lines().any(|l| l.starts_with(&format!("{member},"))),
            "{member}"
        );
    }
    let check = stdout(&georod(&["check", "examples/PortalFrame.toml"]));
    assert!(
        check.contains("[1..11] left, [12..22] beam, [23..33] right"),
        "{check}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
