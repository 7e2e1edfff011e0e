//! Reading a frame's tables: `[[joint]]` and `[[member]]` into a [`Frame`] (names, geometry,
//! sections, hinges, kinds, element counts), then `[[link]]` between its points, each value
//! checked with the key it came from.
use super::checker::{entry, Checker};
use super::file::{JointFile, LinkFile, MemberFile};
use super::frame::{place, Frame, Joint, Link, Member, MemberKind, MemberShape, PlaceKeys};
use super::sections;
use super::{SceneError, Station};
use nalgebra::Vector2;

/// The frame of a file with `[[member]]` tables (`None` without any).
pub(super) fn frame(
    c: &Checker,
    joints: &[JointFile],
    members: &[MemberFile],
) -> Result<Option<Frame>, SceneError> {
    if members.len() > sections::MAX_MEMBERS {
        return c.err(
            "[[member]]",
            format!(
                "{} members: a frame has at most {}",
                members.len(),
                sections::MAX_MEMBERS
            ),
        );
    }
    if members.is_empty() {
        if !joints.is_empty() {
            return c.err(
                "[[joint]]",
                "joints without [[member]]s: a frame needs members between its joints",
            );
        }
        return Ok(None);
    }
    let mut out = Frame {
        joints: Vec::new(),
        members: Vec::new(),
        links: Vec::new(),
    };
    for (i, j) in joints.iter().enumerate() {
        let key = |k: &str| entry("joint", i, j.name.as_ref(), k);
        let name = c.identifier(j.name.as_ref(), &key("name"))?;
        if out.joint(&name).is_some() {
            return c.err(key("name"), format!("a joint `{name}` is already declared"));
        }
        let coordinate = |v: Option<f64>, k: &str| {
            let x = c.required(v, &key(k), "a coordinate in m")?;
            if !x.is_finite() {
                return c.err(key(k), format!("{x} is not a finite number"));
            }
            Ok(x)
        };
        let position = Vector2::new(coordinate(j.x, "x")?, coordinate(j.y, "y")?);
        if let Some(other) = out.joints.iter().find(|o| o.position == position) {
            return c.err(
                key("x"),
                format!(
                    "joint `{}` is already at ({}, {}): one joint per point",
                    other.name, position[0], position[1]
                ),
            );
        }
        out.joints.push(Joint { name, position });
    }
    for (i, m) in members.iter().enumerate() {
        let member = member(c, i, m, &out)?;
        out.members.push(member);
    }
    for (j, joint) in out.joints.iter().enumerate() {
        if out.ends_at(j).next().is_none() {
            return c.err(
                entry("joint", j, Some(&joint.name), "name"),
                format!("no [[member]] reaches joint `{}`", joint.name),
            );
        }
    }
    Ok(Some(out))
}

fn member(c: &Checker, i: usize, m: &MemberFile, frame: &Frame) -> Result<Member, SceneError> {
    let key = |k: &str| entry("member", i, m.name.as_ref(), k);
    let name = c.identifier(m.name.as_ref(), &key("name"))?;
    if frame.member(&name).is_some() {
        return c.err(
            key("name"),
            format!("a member `{name}` is already declared"),
        );
    }
    let joint = |v: Option<&String>, k: &str| {
        let j = c.required(v, &key(k), "a joint name")?;
        frame.joint(j).ok_or_else(|| {
            let names: Vec<&str> = frame.joints.iter().map(|j| j.name.as_str()).collect();
            c.error(
                key(k),
                format!(
                    "`{j}` is not a [[joint]] of this scene (joints: {})",
                    names.join(", ")
                ),
            )
        })
    };
    let (from, to) = (joint(m.from.as_ref(), "from")?, joint(m.to.as_ref(), "to")?);
    if from == to {
        return c.err(
            key("to"),
            "a member joins two different joints (this one has zero length)",
        );
    }
    let (kind, cable) = match m.kind.as_deref() {
        None => (MemberKind::Rod, false),
        Some(k) => match c.one_of(k, &["rod", "truss", "cable"], &key("kind"))? {
            0 => (MemberKind::Rod, false),
            1 => (MemberKind::Truss, false),
            _ => (MemberKind::Truss, true),
        },
    };
    let shape = match m.shape.as_deref() {
        None | Some("straight") if m.rise.is_some() => {
            return c.err(
                key("H"),
                "a straight member has no rise (H is for shape = \"arc\")",
            )
        }
        None => MemberShape::Straight,
        Some(s) => {
            let arc = c.one_of(s, &["straight", "arc"], &key("shape"))? == 1;
            if !arc {
                MemberShape::Straight
            } else {
                if kind == MemberKind::Truss {
                    return c.err(key("shape"), "a truss bar is straight");
                }
                let chord = (frame.joints[to].position - frame.joints[from].position).norm();
                let rise = c.required(m.rise, &key("H"), "the rise of the arc (m)")?;
                if !(rise.is_finite() && rise != 0.0 && rise.abs() <= 0.5 * chord) {
                    return c.err(
                        key("H"),
                        format!(
                            "{rise} is out of range: must be in [-chord/2, chord/2] = [{}, {}] \
                             and not 0 (positive: to the left of the chord from `from` to `to`)",
                            -0.5 * chord,
                            0.5 * chord
                        ),
                    );
                }
                MemberShape::Arc { rise }
            }
        }
    };
    let elements = match (m.elements, kind) {
        (None, _) => None,
        (Some(_), MemberKind::Truss) => {
            return c.err(
                key("elements"),
                "a truss member is one bar (two pinned ends, no interior nodes)",
            )
        }
        (Some(n), _) if (1..=crate::scene::MAX_ELEMENTS as i64).contains(&n) => Some(n as usize),
        (Some(n), _) => {
            return c.err(
                key("elements"),
                format!(
                    "{n} is out of range: must be in [1, {}]",
                    crate::scene::MAX_ELEMENTS
                ),
            )
        }
    };
    let mut hinges = [false; 2];
    for h in m.hinges.iter().flatten() {
        let end = c.one_of(h, &["start", "end"], &key("hinges"))?;
        if hinges[end] {
            return c.err(key("hinges"), format!("\"{h}\" is listed twice"));
        }
        hinges[end] = true;
    }
    if kind == MemberKind::Truss && m.hinges.is_some() {
        return c.err(
            key("hinges"),
            "a truss member is pinned at both ends already",
        );
    }
    if kind == MemberKind::Truss {
        hinges = [true, true];
    }
    let section = match &m.section {
        None => None,
        Some(s) => Some(sections::member_section(c, s, &key("section"))?),
    };
    Ok(Member {
        name,
        from,
        to,
        shape,
        elements,
        section,
        hinges,
        kind,
        cable,
    })
}

/// `[[link]]`: springs and dashpots between two points of the frame.
pub(super) fn links(
    c: &Checker,
    raw: &[LinkFile],
    frame: Option<&mut Frame>,
) -> Result<(), SceneError> {
    let Some(frame) = frame else {
        if raw.is_empty() {
            return Ok(());
        }
        return c.err(
            "[[link]]",
            "links join points of a frame: declare [[joint]]s and [[member]]s (a spring to \
             ground is a [[spring]])",
        );
    };
    for (i, l) in raw.iter().enumerate() {
        let key = |k: &str| entry("link", i, l.name.as_ref(), k);
        let name = c.identifier(l.name.as_ref(), &key("name"))?;
        let mut ends = [Station::Joint(0); 2];
        for (end, (k, v)) in ends.iter_mut().zip([("from", &l.from), ("to", &l.to)]) {
            let v = c.required(
                v.as_ref(),
                &key(k),
                "a joint name or { member = ..., at = ... }",
            )?;
            *end = match v {
                toml::Value::String(joint) => {
                    let p = PlaceKeys {
                        at: None,
                        joint: Some(joint),
                        member: None,
                    };
                    place(c, Some(frame), p, false, &|_| key(k))?
                }
                toml::Value::Table(t) => {
                    let member = t.get("member").and_then(|m| m.as_str()).map(str::to_string);
                    let at = t
                        .get("at")
                        .and_then(|a| a.as_float().or(a.as_integer().map(|i| i as f64)));
                    if let Some(bad) = t.keys().find(|k| *k != "member" && *k != "at") {
                        return c.err(key(k), format!("unknown key `{bad}`: give member and at"));
                    }
                    let p = PlaceKeys {
                        at,
                        joint: None,
                        member: member.as_ref(),
                    };
                    place(c, Some(frame), p, false, &|_| key(k))?
                }
                other => {
                    return c.err(
                        key(k),
                        format!("{other}: write a joint name or {{ member = \"...\", at = ... }}"),
                    )
                }
            };
        }
        if ends[0] == ends[1] {
            return c.err(key("to"), "a link joins two different points");
        }
        let number = |x: Option<f64>, k: &str, default: Option<f64>, positive: bool| {
            let x = match (x, default) {
                (Some(x), _) => x,
                (None, Some(d)) => d,
                (None, None) => return c.err(key(k), "missing: the stiffness in N/m (> 0)"),
            };
            let ok = x.is_finite() && if positive { x > 0.0 } else { x >= 0.0 };
            if !ok {
                let what = if positive { "> 0" } else { ">= 0" };
                return c.err(key(k), format!("{x} is out of range: must be {what}"));
            }
            Ok(x)
        };
        frame.links.push(Link {
            name,
            ends,
            k: number(l.k, "k", None, true)?,
            c: number(l.c, "c", Some(0.0), false)?,
            length: match l.length {
                None => None,
                Some(x) => Some(number(Some(x), "length", None, true)?),
            },
        });
    }
    Ok(())
}
