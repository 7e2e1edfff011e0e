//! A frame as data: its joints, members (between joints, rigid unless an end is hinged, rods or
//! truss bars) and links (springs between its points), and where an item sits on it
//! ([`Station`]: a joint, or a fraction of a member's arc length, found by [`place`]). A file
//! with `[[member]]` tables is a frame (read by `frame_read`); one with `[geometry]` a single rod
//! (member 0, placed by `at`).
use super::checker::Checker;
use super::sections::MemberSection;
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
