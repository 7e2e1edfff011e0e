//! Frames in statics against closed forms and an independent linear frame:
//! - a fixed-base portal frame's lateral stiffness against the slope-deflection formula
//!   `24 EI_c / h^3 (1 + 6 r) / (4 + 6 r)`, `r = (EI_b / L) / (EI_c / h)` (members made
//!   inextensible and shear-rigid by a large `A`, `As`), and with real sections against an
//!   independent Timoshenko frame (tests/common/linear_frame.rs);
//! - an inclined roller and an internal hinge: the reactions equal statics;
//! - a link between two cantilevers: its force is the stiffness split.
//!
//! The loads are small (sway / height ~1e-7): the geometrically exact model then differs from
//! the linear one by as little. The hybrid element's mesh error in the sway is `0.83 / n^2`
//! (`n` elements per member: -5.2e-4 at 40, -1.3e-4 at 80, -3.0e-5 at 160, second order): the
//! sways are extrapolated from 40 and 80 elements (Richardson, `(4 w_80 - w_40) / 3`), which
//! leaves 3e-6.
//!
//! Run: `cargo test --profile quick --test suite frames_statics:: -- --nocapture`
use crate::common;

use common::linear_frame::LinearFrame;
use common::{output, simulation_of};

const E: f64 = 210e9;
const NU: f64 = 0.3;
const I_C: f64 = 8.356e-5;

/// A portal frame of height `h`, span `l`; columns `(A, As, I)`, the beam's `I` = `ratio` times
/// the columns'; a lateral load `P` at the left corner; `elements` per member.
fn portal(a: f64, shear_area: f64, ratio: f64, p: f64, elements: usize) -> String {
    format!(
        r#"
name = "Portal"
[defaults]
E = {E}
nu = {NU}
rho = 7850.0
elements = {total}
[section]
shape = "general"
A = {a}
I = {I_C}
As = {shear_area}
[[joint]]
name = "A"
x = 0.0
y = 0.0
[[joint]]
name = "B"
x = 0.0
y = 4.0
[[joint]]
name = "C"
x = 6.0
y = 4.0
[[joint]]
name = "D"
x = 6.0
y = 0.0
[[member]]
name = "left"
from = "A"
to = "B"
elements = {elements}
[[member]]
name = "beam"
from = "B"
to = "C"
elements = {elements}
section = {{ shape = "general", A = {a}, I = {i_b}, As = {shear_area} }}
[[member]]
name = "right"
from = "D"
to = "C"
elements = {elements}
[[support]]
name = "a"
joint = "A"
fix = ["u1", "u2", "w"]
[[support]]
name = "d"
joint = "D"
fix = ["u1", "u2", "w"]
[[load]]
name = "P"
kind = "point"
joint = "B"
direction = "e1"
value = {p}
[[sensor]]
name = "sway"
joint = "B"
quantity = "u1"
"#,
        total = 3 * elements,
        i_b = ratio * I_C,
    )
}

/// The sway at 40 and 80 elements per member, extrapolated (Richardson, second order).
fn extrapolated_sway(scene: impl Fn(usize) -> String) -> f64 {
    let sway = |n| output(&simulation_of(&scene(n), &[]), "sway");
    let (coarse, fine) = (sway(40), sway(80));
    (4.0 * fine - coarse) / 3.0
}

/// Slope deflection (inextensible, shear-rigid members): the lateral stiffness of a
/// fixed-base portal frame with rigid corners.
#[test]
fn portal_sway_follows_the_slope_deflection_stiffness() {
    let (h, l, p) = (4.0, 6.0, 1.0);
    for ratio in [0.5, 2.0, 8.0] {
        let r = (ratio * E * I_C / l) / (E * I_C / h);
        let k = 24.0 * E * I_C / h.powi(3) * (1.0 + 6.0 * r) / (4.0 + 6.0 * r);
        // EA, GAs 1e4 times the real ones: their parts of the sway ~1e-6.
        let sway = extrapolated_sway(|n| portal(50.0, 50.0, ratio, p, n));
        let error = sway * k / p - 1.0;
        println!(
            "r = {r:.3}: sway {sway:.9e} m, slope deflection {:.9e} m, error {error:.2e}",
            p / k
        );
        // The extrapolation's residual (3e-6) and the members' residual axial and shear
        // flexibility (1e-6).
        assert!(error.abs() < 2e-5, "r = {r}: {error:e}");
    }
}

/// A member's own section is a set of FMU parameters (`beam_A`, `beam_I`, `beam_As`): a file
/// that writes the beam's `I` equal to the columns' and sets `beam_I` to another ratio gives the
/// same sway, bit for bit, as the file that writes that ratio, and so follows the slope-deflection
/// stiffness of the new ratio (within the tolerance of the test above).
#[test]
fn a_members_section_is_a_parameter() {
    let (h, l, p) = (4.0, 6.0, 1.0);
    for ratio in [0.5, 8.0] {
        let set = [("beam_I", ratio * I_C)];
        let sway = |n| output(&simulation_of(&portal(50.0, 50.0, 1.0, p, n), &set), "sway");
        let written = |n| {
            output(
                &simulation_of(&portal(50.0, 50.0, ratio, p, n), &[]),
                "sway",
            )
        };
        let (coarse, fine) = (sway(40), sway(80));
        assert_eq!((coarse, fine), (written(40), written(80)), "ratio {ratio}");
        let r = (ratio * E * I_C / l) / (E * I_C / h);
        let k = 24.0 * E * I_C / h.powi(3) * (1.0 + 6.0 * r) / (4.0 + 6.0 * r);
        let error = (4.0 * fine - coarse) / 3.0 * k / p - 1.0;
        println!(
            "beam_I = {:.4e}: sway error against slope deflection {error:.2e}",
            ratio * I_C
        );
        assert!(error.abs() < 2e-5, "r = {r}: {error:e}");
    }
}

/// With the real section's axial and shear flexibility: the sway and the base moment against
/// an independent linear Timoshenko frame (exact for end loads: one beam per member).
#[test]
fn portal_with_real_sections_matches_an_independent_linear_frame() {
    let (a, shear_area, ratio, p) = (5.38e-3, 2.5e-3, 2.0, 1.0);
    let g = E / (2.0 * (1.0 + NU));
    let mut frame = LinearFrame::default();
    let (na, nb, nc, nd) = (
        frame.node(0.0, 0.0),
        frame.node(0.0, 4.0),
        frame.node(6.0, 4.0),
        frame.node(6.0, 0.0),
    );
    let column =
        |f: &mut LinearFrame, x, y| f.member(x, y, 1, E * a, g * shear_area, E * I_C, 0.0, 0.0);
    column(&mut frame, na, nb);
    frame.member(nb, nc, 1, E * a, g * shear_area, ratio * E * I_C, 0.0, 0.0);
    column(&mut frame, nd, nc);
    frame.held = vec![0, 1, 2, 3 * nd, 3 * nd + 1, 3 * nd + 2];
    let mut f = vec![0.0; frame.dofs()];
    f[3 * nb] = p;
    let u = frame.solve(&f);
    let sway = extrapolated_sway(|n| portal(a, shear_area, ratio, p, n));
    // The base moment balances the load exactly at every mesh (the nodes' moments are exact).
    let base = output(
        &simulation_of(&portal(a, shear_area, ratio, p, 40), &[]),
        "a_M",
    );
    // The independent frame's reaction moment at A: its row of K u (no load there).
    let k = frame.stiffness();
    let moment_a: f64 = (0..frame.dofs()).map(|j| k[(2, j)] * u[j]).sum();
    println!(
        "sway {sway:.9e} vs {:.9e}; base moment {base:.6e} vs {moment_a:.6e}",
        u[3 * nb]
    );
    assert!((sway / u[3 * nb] - 1.0).abs() < 2e-5, "sway");
    // The frame is statically indeterminate: the moment's share depends on the stiffnesses,
    // which carry the mesh error (5e-5 at 40 elements).
    assert!(
        (base - moment_a).abs() < 2e-4 * moment_a.abs(),
        "base moment"
    );
}

/// The portal's lowest natural frequencies against the independent frame on a fine mesh
/// (lumped mass, 200 beams per member: its own error ~1e-5 in the lowest modes).
#[test]
fn portal_frequencies_match_an_independent_fine_mesh() {
    let (a, shear_area, ratio) = (5.38e-3, 2.5e-3, 2.0);
    let rho = 7850.0;
    let g = E / (2.0 * (1.0 + NU));
    let mut frame = LinearFrame::default();
    let (na, nb, nc, nd) = (
        frame.node(0.0, 0.0),
        frame.node(0.0, 4.0),
        frame.node(6.0, 4.0),
        frame.node(6.0, 0.0),
    );
    let n = 200;
    frame.member(
        na,
        nb,
        n,
        E * a,
        g * shear_area,
        E * I_C,
        rho * a,
        rho * I_C,
    );
    frame.member(
        nb,
        nc,
        n,
        E * a,
        g * shear_area,
        ratio * E * I_C,
        rho * a,
        ratio * rho * I_C,
    );
    frame.member(
        nd,
        nc,
        n,
        E * a,
        g * shear_area,
        E * I_C,
        rho * a,
        rho * I_C,
    );
    frame.held = vec![0, 1, 2, 3 * nd, 3 * nd + 1, 3 * nd + 2];
    let reference = frame.frequencies();
    let text = portal(a, shear_area, ratio, 0.0, 100).replacen(
        "[[support]]",
        "[modes]\ncount = 4\n[[support]]",
        1,
    );
    let sim = simulation_of(&text, &[]);
    for (k, want) in reference.iter().take(4).enumerate() {
        let f = sim.frequency(k);
        println!(
            "mode {}: {f:.8e} Hz vs {want:.8e} Hz ({:.2e})",
            k + 1,
            f / want - 1.0
        );
        // Both meshes' errors (second order): ~1e-5 here, up to 1e-4 in the fourth mode.
        assert!((f / want - 1.0).abs() < 3e-4, "mode {}", k + 1);
    }
}

/// A beam on a pin and a roller on a 30 degree incline under a midspan load: the roller pushes
/// along its normal `n = (-sin a, cos a)` with `R = P / (2 cos a)`; the pin takes `P tan(a) / 2`
/// horizontally and `P / 2` vertically.
#[test]
fn an_inclined_roller_carries_what_statics_says() {
    let (p, angle) = (1.0, 30.0f64);
    let text = format!(
        r#"
name = "Incline"
[defaults]
E = {E}
rho = 7850.0
elements = 20
[section]
b = 0.1
h = 0.2
[[joint]]
name = "A"
x = 0.0
y = 0.0
[[joint]]
name = "M"
x = 3.0
y = 0.0
[[joint]]
name = "B"
x = 6.0
y = 0.0
[[member]]
name = "left"
from = "A"
to = "M"
[[member]]
name = "right"
from = "M"
to = "B"
[[support]]
name = "pin"
joint = "A"
fix = ["u1", "u2"]
[[support]]
name = "roller"
joint = "B"
fix = ["u2"]
angle = {angle}
[[load]]
name = "P"
kind = "point"
joint = "M"
direction = "-e2"
value = {p}
"#
    );
    let sim = simulation_of(&text, &[]);
    let a = angle.to_radians();
    let r = p / (2.0 * a.cos());
    let checks = [
        ("roller_R2", r),
        ("roller_R1", 0.0),
        ("roller_Rx", -r * a.sin()),
        ("roller_Ry", r * a.cos()),
        ("pin_Rx", r * a.sin()),
        ("pin_Ry", 0.5 * p),
    ];
    for (name, want) in checks {
        let got = output(&sim, name);
        println!("{name}: {got:.12e} (statics {want:.12e})");
        // The deflection (1e-7 of the span) turns the lever arms by as much.
        assert!((got - want).abs() < 1e-6 * p, "{name}: {got} vs {want}");
    }
}

/// A cantilever with an internal hinge, its outer part on a roller (a Gerber beam): the outer
/// part is simply supported between the hinge and the roller, so under a load `P` at its
/// middle the roller and the hinge each carry `P / 2`, and the clamp `P / 2` with the moment
/// `P a / 2` (`a` the hinge's distance from the clamp).
#[test]
fn an_internal_hinge_carries_what_statics_says() {
    let (p, a, l) = (1.0, 2.0, 6.0);
    let text = format!(
        r#"
name = "Gerber"
[defaults]
E = {E}
rho = 7850.0
elements = 30
[section]
b = 0.1
h = 0.2
[[joint]]
name = "A"
x = 0.0
y = 0.0
[[joint]]
name = "H"
x = {a}
y = 0.0
[[joint]]
name = "C"
x = {l}
y = 0.0
[[member]]
name = "inner"
from = "A"
to = "H"
[[member]]
name = "outer"
from = "H"
to = "C"
hinges = ["start"]
[[support]]
name = "clamp"
joint = "A"
fix = ["u1", "u2", "w"]
[[support]]
name = "roller"
joint = "C"
fix = ["u2"]
[[load]]
name = "P"
kind = "point"
member = "outer"
at = 0.5
direction = "-e2"
value = {p}
[[sensor]]
name = "M_hinge"
joint = "H"
member = "outer"
quantity = "M"
"#
    );
    let sim = simulation_of(&text, &[]);
    for (name, want) in [
        ("roller_Ry", 0.5 * p),
        ("clamp_Ry", 0.5 * p),
        ("clamp_M", 0.5 * p * a),
        ("clamp_Rx", 0.0),
        ("M_hinge", 0.0),
    ] {
        let got = output(&sim, name);
        println!("{name}: {got:.12e} (statics {want:.12e})");
        assert!((got - want).abs() < 1e-6 * p * l, "{name}: {got} vs {want}");
    }
}

/// Two cantilevers, one above the other, their tips joined by a vertical link of stiffness
/// `k`; a load `P` down on the upper tip. With `k1`, `k2` the tips' own stiffnesses (from the
/// same model without the link), the link carries `P / (1 + k1 / k + k1 / k2)` in compression.
#[test]
fn a_link_carries_the_stiffness_split() {
    let (p, k_link) = (1.0, 2.0e4);
    let text = |link: bool, lower_load: bool| {
        let link = if link {
            format!("[[link]]\nname = \"tie\"\nfrom = \"T1\"\nto = \"T2\"\nk = {k_link}\n")
        } else {
            String::new()
        };
        let (upper, lower) = if lower_load { (0.0, p) } else { (p, 0.0) };
        format!(
            r#"
name = "Pair"
[defaults]
E = {E}
rho = 7850.0
elements = 40
[section]
b = 0.05
h = 0.05
[[joint]]
name = "R1"
x = 0.0
y = 1.0
[[joint]]
name = "T1"
x = 2.0
y = 1.0
[[joint]]
name = "R2"
x = 0.0
y = 0.0
[[joint]]
name = "T2"
x = 2.0
y = 0.0
[[member]]
name = "upper"
from = "R1"
to = "T1"
[[member]]
name = "lower"
from = "R2"
to = "T2"
section = {{ b = 0.06, h = 0.05 }}
[[support]]
name = "c1"
joint = "R1"
fix = ["u1", "u2", "w"]
[[support]]
name = "c2"
joint = "R2"
fix = ["u1", "u2", "w"]
[[load]]
name = "P1"
kind = "point"
joint = "T1"
direction = "-e2"
value = {upper}
[[load]]
name = "P2"
kind = "point"
joint = "T2"
direction = "-e2"
value = {lower}
[[sensor]]
name = "w1"
joint = "T1"
quantity = "u2"
[[sensor]]
name = "w2"
joint = "T2"
quantity = "u2"
{link}"#
        )
    };
    let k1 = p / -output(&simulation_of(&text(false, false), &[]), "w1");
    let k2 = p / -output(&simulation_of(&text(false, true), &[]), "w2");
    let sim = simulation_of(&text(true, false), &[]);
    let force = output(&sim, "tie_force");
    let want = -p / (1.0 + k1 / k_link + k1 / k2);
    println!("link force {force:.9e} N, split {want:.9e} N (k1 {k1:.4e}, k2 {k2:.4e} N/m)");
    // The tips move by ~1e-4 of the link's length: its direction turns by as much.
    assert!((force / want - 1.0).abs() < 1e-6, "{force} vs {want}");
}
