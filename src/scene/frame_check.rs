//! What a frame's items may do where they are, and whether the frame can stand: nothing sits
//! inside a truss bar, no rotation is held, sprung, loaded or read at a joint that has none
//! (every member end there hinged), a member's own element count puts its stations on nodes,
//! and (for a static initial state) no part of the frame is a mechanism (`frame_mechanism.rs`).
use super::checker::entry;
use super::frame::{Frame, MemberKind};
use super::frame_mechanism::mechanism;
use super::{InitialState, LoadKind, Reading, Scene, Station};

type Refusal = (String, String);

/// Every check of a frame scene, with the key and message of the first that fails.
pub(super) fn check(scene: &Scene, frame: &Frame) -> Result<(), Refusal> {
    places(scene, frame)?;
    let samples = scene.shape_samples();
    if samples > crate::scene::variables::MAX_SHAPE_POINTS {
        return Err((
            "shape.points".to_string(),
            format!(
                "{} points on each of {} members are {samples} shape samples: a frame has at \
                 most {} (lower points)",
                scene.shape_points,
                frame.members.len(),
                crate::scene::variables::MAX_SHAPE_POINTS
            ),
        ));
    }
    rotations(scene, frame)?;
    for (i, m) in frame.members.iter().enumerate() {
        if let Some(n) = m.elements {
            let segments = scene.member_stations(i).len() - 1;
            if n < segments {
                return Err((
                    entry("member", i, Some(&m.name), "elements"),
                    format!(
                        "{n} elements cannot put the {segments} segments between its stations on \
                         nodes: give at least {segments}"
                    ),
                ));
            }
        }
    }
    if scene.initial.state == InitialState::Static {
        if let Some(free) = mechanism(scene, frame) {
            return Err((
                "[[support]]".to_string(),
                format!(
                    "the frame is a mechanism: {free} can move without resistance (a part held \
                     by nothing, or joined by hinges only). Hold it with supports, springs or \
                     links, make a joint rigid, or start from [initial] state = \"reference\""
                ),
            ));
        }
    }
    Ok(())
}

/// Every item that names a station inside a truss bar.
fn places(scene: &Scene, frame: &Frame) -> Result<(), Refusal> {
    let truss = |s: &Station| match *s {
        Station::On { member, .. } => frame.members[member].kind == MemberKind::Truss,
        Station::Joint(_) => false,
    };
    let refusal = |key: String| {
        Err((
            key,
            "a truss bar carries its axial force only: items sit at its joints".to_string(),
        ))
    };
    for (i, s) in scene.sensors.iter().enumerate() {
        if truss(&s.at) {
            return Err((
                entry("sensor", i, Some(&s.name), "member"),
                "a truss bar's force is its output <member>_N_start / _N_end; sensors read rod \
                 members and joints"
                    .to_string(),
            ));
        }
    }
    for (i, s) in scene.supports.iter().enumerate() {
        if truss(&s.at) {
            return refusal(entry("support", i, Some(&s.name), "member"));
        }
    }
    for (i, m) in scene.masses.iter().enumerate() {
        if truss(&m.at) {
            return refusal(entry("mass", i, Some(&m.name), "member"));
        }
    }
    for (i, s) in scene.springs.iter().enumerate() {
        if truss(&s.at) {
            return refusal(entry("spring", i, Some(&s.name), "member"));
        }
    }
    for (i, l) in frame.links.iter().enumerate() {
        if l.ends.iter().any(truss) {
            return refusal(entry("link", i, Some(&l.name), "from"));
        }
    }
    Ok(())
}

/// Rotations held, sprung, loaded or read at joints that have none.
fn rotations(scene: &Scene, frame: &Frame) -> Result<(), Refusal> {
    let dead = |s: &Station| match *s {
        Station::Joint(j) if !frame.has_rotation(j) => Some(&frame.joints[j].name),
        _ => None,
    };
    let why = |joint: &String, what: &str| {
        format!(
            "joint `{joint}` has no rotation (every member end there is hinged, or a truss bar's): \
             {what}"
        )
    };
    for (i, s) in scene.supports.iter().enumerate() {
        if let (Some(j), true) = (dead(&s.at), s.fixed[2]) {
            return Err((
                entry("support", i, Some(&s.name), "fix"),
                why(j, "nothing to hold in w (hold u1, u2)"),
            ));
        }
    }
    for (i, s) in scene.springs.iter().enumerate() {
        if let (Some(j), 2) = (dead(&s.at), s.dof) {
            return Err((
                entry("spring", i, Some(&s.name), "dof"),
                why(
                    j,
                    "a rotational spring there turns nothing (make a member end rigid)",
                ),
            ));
        }
    }
    for (i, m) in scene.masses.iter().enumerate() {
        if let (Some(j), true) = (dead(&m.at), m.j > 0.0) {
            return Err((
                entry("mass", i, Some(&m.name), "J"),
                why(j, "its rotary inertia J has nothing to turn (J = 0 there)"),
            ));
        }
    }
    for (i, l) in scene.loads.iter().enumerate() {
        if let LoadKind::Moment { at } = l.kind {
            if let Some(j) = dead(&at) {
                return Err((
                    entry("load", i, Some(&l.name), "joint"),
                    why(
                        j,
                        "a moment there acts on nothing (apply it on a member: member = ..., at = \
                         0 or 1)",
                    ),
                ));
            }
        }
    }
    for (i, s) in scene.sensors.iter().enumerate() {
        if let (Some(j), Reading::Nodal { dof: 2, .. }) = (dead(&s.at), s.quantity.reading()) {
            return Err((
                entry("sensor", i, Some(&s.name), "quantity"),
                why(j, "read a member's end rotation instead (joint and member)"),
            ));
        }
    }
    Ok(())
}
