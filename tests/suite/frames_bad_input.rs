//! Frame scenes that must be refused, each with the file, the key or name, and what is
//! allowed (the packager and fmi2Instantiate read scenes through the same checker).
use crate::common;

use common::assert_refused;

/// A valid two-member frame; each case edits it.
const BASE: &str = r#"
name = "Frame"
[defaults]
E = 210e9
rho = 7850.0
[[joint]]
name = "A"
x = 0.0
y = 0.0
[[joint]]
name = "B"
x = 0.0
y = 3.0
[[joint]]
name = "C"
x = 4.0
y = 3.0
[[member]]
name = "column"
from = "A"
to = "B"
[[member]]
name = "beam"
from = "B"
to = "C"
[[support]]
name = "base"
joint = "A"
fix = ["u1", "u2", "w"]
"#;

fn with(replace: &str, by: &str) -> String {
    assert!(BASE.contains(replace), "{replace}");
    BASE.replacen(replace, by, 1)
}

#[test]
fn the_base_frame_is_accepted() {
    georod::scene::Scene::parse(BASE, "frame.toml").unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn bad_topology_is_refused_with_its_key() {
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        (
            "unknown joint",
            with("to = \"C\"", "to = \"Z\""),
            vec!["bad.toml", "[[member]] #2 \"beam\", key `to`", "`Z` is not a [[joint]]", "A, B, C"],
        ),
        (
            "zero length",
            with("to = \"C\"", "to = \"B\""),
            vec!["[[member]] #2 \"beam\", key `to`", "zero length"],
        ),
        (
            "geometry and members",
            format!("{BASE}\n[geometry]\nshape = \"straight\"\nL = 2.0\n"),
            vec!["[geometry]", "not both"],
        ),
        (
            "unknown member kind",
            with("to = \"C\"", "to = \"C\"\nkind = \"cable-stayed\""),
            vec!["key `kind`", "\"rod\", \"truss\""],
        ),
        (
            "a joint no member reaches",
            with("[[member]]", "[[joint]]\nname = \"D\"\nx = 9.0\ny = 9.0\n[[member]]"),
            vec!["[[joint]] #4 \"D\"", "no [[member]] reaches joint `D`"],
        ),
        (
            "a mechanism",
            with("fix = [\"u1\", \"u2\", \"w\"]", "fix = [\"u1\", \"u2\"]"),
            vec!["[[support]]", "mechanism"],
        ),
        (
            "a moment at an all-hinged joint",
            format!(
                "{}\n[[load]]\nname = \"m\"\nkind = \"moment\"\njoint = \"B\"\nvalue = 1.0\n",
                with("to = \"C\"", "to = \"C\"\nhinges = [\"start\"]").replacen(
                    "to = \"B\"",
                    "to = \"B\"\nhinges = [\"end\"]",
                    1
                )
            ),
            vec!["[[load]] #1 \"m\", key `joint`", "joint `B` has no rotation"],
        ),
        (
            "angle out of range",
            with("fix = [\"u1\", \"u2\", \"w\"]", "fix = [\"u1\", \"u2\", \"w\"]\nangle = 400.0"),
            vec!["[[support]] #1 \"base\", key `angle`", "(-360, 360)"],
        ),
        (
            "a station on a truss bar",
            format!(
                "{}\n[[mass]]\nname = \"m\"\nmember = \"beam\"\nat = 0.5\nm = 1.0\n",
                with("to = \"C\"", "to = \"C\"\nkind = \"truss\"")
            ),
            vec!["[[mass]] #1 \"m\"", "truss"],
        ),
        (
            "at on a frame item without member",
            format!("{BASE}\n[[sensor]]\nname = \"s\"\nat = 0.5\nquantity = \"u1\"\n"),
            vec!["[[sensor]] #1 \"s\"", "`joint`, or on a `member` at `at`"],
        ),
        (
            "a section quantity at a joint without its member",
            format!("{BASE}\n[[sensor]]\nname = \"s\"\njoint = \"B\"\nquantity = \"M\"\n"),
            vec!["[[sensor]] #1 \"s\", key `member`", "name the member"],
        ),
        (
            "a member name used twice",
            with("name = \"beam\"", "name = \"column\""),
            vec!["[[member]] #2 \"column\", key `name`", "already declared"],
        ),
        (
            "a link to an unknown member",
            format!("{BASE}\n[[link]]\nname = \"l\"\nfrom = \"A\"\nto = {{ member = \"roof\", at = 0.5 }}\nk = 1.0\n"),
            vec!["[[link]] #1 \"l\", key `to`", "`roof` is not a [[member]]"],
        ),
        (
            "a path that does not join",
            format!("{BASE}\n[[load]]\nname = \"truck\"\nkind = \"moving\"\npath = [\"beam\", \"column\"]\ndirection = \"-e2\"\nvalue = 1.0\nspeed = 1.0\n"),
            vec!["[[load]] #1 \"truck\", key `path`", "runs member after member"],
        ),
    ];
    for (what, text, parts) in cases {
        assert_refused(what, &text, &parts);
    }
}

/// A member's own section dimensions are parameters `<member>_<dimension>`: a value out of
/// range (a tube's wall not thinner than its radius, a negative height) is refused naming the
/// parameter, and an accepted one changes nothing else.
#[test]
fn a_members_section_parameters_are_checked() {
    let text = with(
        "to = \"C\"\n",
        "to = \"C\"\nsection = { shape = \"tube\", D = 0.2, t = 0.01 }\n",
    );
    let scene = georod::scene::Scene::parse(&text, "tube.toml").unwrap_or_else(|e| panic!("{e}"));
    let refused = |name: &str, value: f64| {
        scene
            .values_with([(name, value)])
            .err()
            .unwrap_or_else(|| panic!("{name} = {value} accepted"))
            .to_string()
    };
    let e = refused("beam_t", 0.1);
    assert!(
        e.contains("beam_t") && e.contains("thinner than its radius"),
        "{e}"
    );
    let e = refused("beam_D", -1.0);
    assert!(e.contains("beam_D"), "{e}");
    scene
        .values_with([("beam_t", 0.05)])
        .expect("a thicker wall below D/2");
}

/// Every member's section parameters need value references of their own: a frame has at most
/// 25000 members, and one more is refused with the count.
#[test]
fn too_many_members_are_refused() {
    let n = 25_001;
    let mut text = String::from("name = \"Long\"\n[defaults]\nE = 210e9\nrho = 7850.0\n");
    for j in 0..=n {
        text += &format!("[[joint]]\nname = \"J{j}\"\nx = {j}.0\ny = 0.0\n");
    }
    for m in 0..n {
        text += &format!(
            "[[member]]\nname = \"M{m}\"\nfrom = \"J{m}\"\nto = \"J{}\"\n",
            m + 1
        );
    }
    text += "[[support]]\nname = \"base\"\njoint = \"J0\"\nfix = [\"u1\", \"u2\", \"w\"]\n";
    assert_refused(
        "25001 members",
        &text,
        &["[[member]]", "25001 members", "at most 25000"],
    );
}
