//! `[[joint]]`, `[[member]]` and `[[link]]`: a frame's topology (members between joints, rigid
//! unless an end is hinged, rods or truss bars), the springs between its points, and where an
//! item sits on it ([`Station`]: a joint, or a fraction of a member's arc length). A file with
//! `[[member]]` tables is a frame; one with `[geometry]` a single rod (member 0, placed by `at`).
use super::checker::{entry, Checker};
use super::file::{JointFile, LinkFile, MemberFile};
use super::sections::{self, MemberSection};
use super::{SceneError, Station};
use crate::model::{Placement, ReferenceCurve};
use nalgebra::Vector2;

#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    pub name: String,
    pub position: Vector2<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MemberKind {
    /// The geometrically exact rod.
    Rod,
    /// A bar with axial force only, pinned at both ends.
    Truss,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MemberShape {
    Straight,
    /// A circular arc with its rise to the left of the chord from `from` to `to`.
    Arc {
        rise: f64,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    pub name: String,
    pub from: usize,
    pub to: usize,
    pub shape: MemberShape,
    /// Its own element count (`None`: a share of the scene's `elements`).
    pub elements: Option<usize>,
    /// Its own section (`None`: the scene's `[section]`).
    pub section: Option<MemberSection>,
    /// Hinged at its `from` end, at its `to` end.
    pub hinges: [bool; 2],
    pub kind: MemberKind,
    /// A truss member that carries tension only (`kind = "cable"`: `kind` is then `Truss`).
    pub cable: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    pub name: String,
    pub ends: [Station; 2],
    pub k: f64,
    pub c: f64,
    /// Rest length (`None`: the reference distance of its ends).
    pub length: Option<f64>,
}

/// A frame's joints, members and links.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    pub joints: Vec<Joint>,
    pub members: Vec<Member>,
    pub links: Vec<Link>,
}

impl Member {
    /// Its reference curve and where it lies: from its `from` joint towards its `to` joint
    /// (an arc with a negative rise mirrored, so it bulges to the right of that chord).
    pub fn curve(&self, joints: &[Joint]) -> (ReferenceCurve, Placement) {
        let chord = self.chord(joints);
        let length = chord.norm();
        let placement = Placement::new(joints[self.from].position, libm::atan2(chord[1], chord[0]));
        match self.shape {
            MemberShape::Straight => (ReferenceCurve::Straight { length }, placement),
            MemberShape::Arc { rise } if rise > 0.0 => {
                (ReferenceCurve::arc(length, rise), placement)
            }
            MemberShape::Arc { rise } => (ReferenceCurve::arc(length, -rise), placement.mirrored()),
        }
    }

    /// The reference position at the fraction `at` of its arc length.
    pub fn position(&self, joints: &[Joint], at: f64) -> Vector2<f64> {
        let (curve, placement) = self.curve(joints);
        placement.place(curve.position(at * curve.length()))
    }

    /// The chord from the `from` joint to the `to` joint.
    pub fn chord(&self, joints: &[Joint]) -> Vector2<f64> {
        joints[self.to].position - joints[self.from].position
    }

    /// Reference arc length.
    pub fn length(&self, joints: &[Joint]) -> f64 {
        self.curve(joints).0.length()
    }
}

impl Frame {
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }

    pub fn member(&self, name: &str) -> Option<usize> {
        self.members.iter().position(|m| m.name == name)
    }

    /// The member ends at joint `j`: `(member, end)` with end 0 (`from`) or 1 (`to`).
    pub fn ends_at(&self, j: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        (self.members.iter().enumerate()).flat_map(move |(m, member)| {
            [(member.from, 0), (member.to, 1)]
                .into_iter()
                .filter(move |&(joint, _)| joint == j)
                .map(move |(_, end)| (m, end))
        })
    }

    /// Whether joint `j` has a rotation: some rod member's end there is rigid.
    pub fn has_rotation(&self, j: usize) -> bool {
        self.ends_at(j)
            .any(|(m, end)| self.members[m].kind == MemberKind::Rod && !self.members[m].hinges[end])
    }

    /// The station of `at` on member `m`: its joint at an end (a member's end is its joint).
    pub fn station(&self, m: usize, at: f64) -> Station {
        let member = &self.members[m];
        if at == 0.0 {
            Station::Joint(member.from)
        } else if at == 1.0 {
            Station::Joint(member.to)
        } else {
            Station::On { member: m, at }
        }
    }

    /// The largest distance between two joints (the frame's size).
    pub fn extent(&self) -> f64 {
        let mut size = 0.0f64;
        for a in &self.joints {
            for b in &self.joints {
                size = size.max((a.position - b.position).norm());
            }
        }
        size
    }
}

impl super::Scene {
    /// The number of shape samples: `[shape] points` along the rod, or per member of a frame
    /// (in the order of the file).
    pub fn shape_samples(&self) -> usize {
        match &self.frame {
            None => self.shape_points,
            Some(f) => self.shape_points * f.members.len(),
        }
    }

    /// Where shape sample `i` is, in words: "at {at} of the arc length" as it always read, or
    /// "of member {name} at {at} of its arc length".
    pub fn shape_sample_text(&self, i: usize) -> String {
        let points = self.shape_points;
        let at = (i % points) as f64 / (points - 1) as f64;
        match &self.frame {
            None => format!("at {at} of the arc length"),
            Some(f) => format!(
                "of member {} at {at} of its arc length",
                f.members[i / points].name
            ),
        }
    }

    /// A station in words: its fraction in a scene without joints (as it always read), a
    /// joint or a fraction of a member in a frame.
    pub fn station_text(&self, s: &Station) -> String {
        match (*s, &self.frame) {
            (Station::On { at, .. }, None) => format!("{at}"),
            (Station::On { member, at }, Some(f)) => {
                format!("{at} of member {}", f.members[member].name)
            }
            (Station::Joint(j), Some(f)) => format!("joint {}", f.joints[j].name),
            (Station::Joint(_), None) => unreachable!("a joint is a frame's"),
        }
    }
}

/// The frame of a file with `[[member]]` tables (`None` without any).
pub(super) fn frame(
    c: &Checker,
    joints: &[JointFile],
    members: &[MemberFile],
) -> Result<Option<Frame>, SceneError> {
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

/// What an item of a frame names to place itself.
pub(super) struct PlaceKeys<'a> {
    pub at: Option<f64>,
    pub joint: Option<&'a String>,
    pub member: Option<&'a String>,
}

/// Where an item sits: in a scene without members by `at` (member 0); in a frame by `joint`,
/// or `member` and `at` (a member's end is its joint, unless `keep_member`: a sensor reading a
/// member's own end section names both `joint` and `member`).
pub(super) fn place(
    c: &Checker,
    frame: Option<&Frame>,
    p: PlaceKeys,
    keep_member: bool,
    key: &dyn Fn(&str) -> String,
) -> Result<Station, SceneError> {
    let Some(frame) = frame else {
        if p.joint.is_some() || p.member.is_some() {
            let k = if p.joint.is_some() { "joint" } else { "member" };
            return c.err(
                key(k),
                "a scene without [[member]]s places its items by `at` (a fraction of the rod's \
                 arc length)",
            );
        }
        let at = c.station(p.at, &key("at"))?;
        return Ok(Station::On { member: 0, at });
    };
    let member = match p.member {
        None => None,
        Some(name) => Some(frame.member(name).ok_or_else(|| {
            let names: Vec<&str> = frame.members.iter().map(|m| m.name.as_str()).collect();
            c.error(
                key("member"),
                format!(
                    "`{name}` is not a [[member]] of this scene (members: {})",
                    names.join(", ")
                ),
            )
        })?),
    };
    match (p.joint, member, p.at) {
        (Some(_), _, Some(_)) => c.err(
            key("at"),
            "give `joint`, or `member` and `at`, not both (a joint is its own place)",
        ),
        (Some(name), m, None) => {
            let Some(j) = frame.joint(name) else {
                let names: Vec<&str> = frame.joints.iter().map(|j| j.name.as_str()).collect();
                return c.err(
                    key("joint"),
                    format!(
                        "`{name}` is not a [[joint]] of this scene (joints: {})",
                        names.join(", ")
                    ),
                );
            };
            match m {
                None => Ok(Station::Joint(j)),
                Some(m) if keep_member => {
                    let mm = &frame.members[m];
                    if mm.from == j {
                        Ok(Station::On { member: m, at: 0.0 })
                    } else if mm.to == j {
                        Ok(Station::On { member: m, at: 1.0 })
                    } else {
                        c.err(
                            key("member"),
                            format!("member `{}` does not end at joint `{name}`", mm.name),
                        )
                    }
                }
                Some(_) => c.err(
                    key("member"),
                    "give `joint`, or `member` and `at`, not both",
                ),
            }
        }
        (None, Some(m), at) => {
            let at = c.station(at, &key("at"))?;
            if keep_member {
                return Ok(Station::On { member: m, at });
            }
            let station = frame.station(m, at);
            if let (Station::On { .. }, MemberKind::Truss) = (station, frame.members[m].kind) {
                return c.err(
                    key("at"),
                    format!(
                        "member `{}` is a truss bar: it is loaded and held at its joints only \
                         (at = 0 or 1)",
                        frame.members[m].name
                    ),
                );
            }
            Ok(station)
        }
        (None, None, _) => c.err(
            key("joint"),
            "missing: in a frame an item sits at a `joint`, or on a `member` at `at` (a \
             fraction of its arc length)",
        ),
    }
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
