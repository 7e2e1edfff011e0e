//! Where and along what a `[[load]]` acts, by its `kind`: a point force (`at`), a distributed
//! load (over `[from, to]`, varying linearly from `value` to `value_end`), a point moment about
//! e3 (`at`), or gravity (an acceleration on the rod's mass). The time law and the magnitude
//! are checked in `items.rs`.
use super::checker::Checker;
use super::file::LoadFile;
use super::frame::{self, Frame, MemberKind, PlaceKeys};
use super::params::{Param, Variability};
use super::{Direction, LoadKind, SceneError, Slot, NORMAL};

pub(super) const KINDS: [&str; 5] = ["point", "distributed", "moment", "gravity", "moving"];

/// A load's place and direction, with the unit of its magnitude.
pub(super) struct Placed {
    pub kind: LoadKind,
    pub direction: Direction,
    pub unit: &'static str,
    /// A moving load's route (members).
    pub path: Vec<usize>,
}

/// The direction a moment acts in: about e3, counter-clockwise (the rotation dof).
pub const ABOUT_E3: Direction = Direction {
    component: 2,
    sign: 1.0,
};

pub(super) fn place(
    c: &Checker,
    l: &LoadFile,
    params: &[Param],
    frame: Option<&Frame>,
    key: &dyn Fn(&str) -> String,
) -> Result<Placed, SceneError> {
    let kind_name = c.required(
        l.kind.as_deref(),
        &key("kind"),
        "\"point\", \"distributed\", \"moment\", \"gravity\" or \"moving\"",
    )?;
    let kind = c.one_of(kind_name, &KINDS, &key("kind"))?;
    let refuse = |k: &str, present: bool, why: &str| -> Result<(), SceneError> {
        if present {
            return c.err(
                key(k),
                format!("a {} load has no `{k}`: {why}", KINDS[kind]),
            );
        }
        Ok(())
    };
    if kind != 1 {
        let why = "only a distributed load acts over [from, to]";
        refuse("from", l.from.is_some(), why)?;
        refuse("to", l.to.is_some(), why)?;
        refuse("value_end", l.value_end.is_some(), why)?;
    }
    if kind == 1 || kind == 3 || kind == 4 {
        refuse("at", l.at.is_some(), "it acts along the rod")?;
        refuse("joint", l.joint.is_some(), "it acts along the members")?;
    }
    if kind == 3 {
        refuse(
            "member",
            l.member.is_some(),
            "gravity acts on every member and mass",
        )?;
    }
    if kind != 4 {
        refuse(
            "path",
            l.path.is_some(),
            "only a moving load travels along a path",
        )?;
    }
    let keys = PlaceKeys {
        at: l.at,
        joint: l.joint.as_ref(),
        member: l.member.as_ref(),
    };
    if kind != 4 {
        let why = "only a moving load travels";
        refuse("speed", l.speed.is_some(), why)?;
        refuse("enter", l.enter.is_some(), why)?;
    }
    if kind == 2 {
        refuse(
            "direction",
            l.direction.is_some(),
            "it turns about e3, counter-clockwise for a positive value",
        )?;
        let at = frame::place(c, frame, keys, false, key)?;
        return Ok(Placed {
            kind: LoadKind::Moment { at },
            direction: ABOUT_E3,
            unit: "N.m",
            path: Vec::new(),
        });
    }
    let direction = match (kind, l.direction.as_deref()) {
        (3, None) => Direction {
            component: 1,
            sign: -1.0,
        },
        (_, dir) => {
            let dir = c.required(dir, &key("direction"), "\"e1\", \"e2\", \"-e1\" or \"-e2\"")?;
            let names = ["e1", "e2", "-e1", "-e2", "normal", "-normal"];
            let d = c.one_of(dir, &names, &key("direction"))?;
            if d >= 4 && (kind != 1 || frame.is_none()) {
                return c.err(
                    key("direction"),
                    "\"normal\" is the direction of a distributed load on a frame's member \
                     (its chord turned by 90 degrees); use e1, e2, -e1 or -e2",
                );
            }
            Direction {
                component: if d >= 4 { NORMAL } else { d % 2 },
                sign: if d < 2 || d == 4 { 1.0 } else { -1.0 },
            }
        }
    };
    let (kind, unit, path) = match kind {
        0 => (
            LoadKind::Point {
                at: frame::place(c, frame, keys, false, key)?,
            },
            "N",
            Vec::new(),
        ),
        1 => (distributed(c, l, params, frame, key)?, "N/m", Vec::new()),
        3 => (LoadKind::Gravity, "m/s2", Vec::new()),
        _ => (moving(c, l, params, key)?, "N", route(c, l, frame, key)?),
    };
    Ok(Placed {
        kind,
        direction,
        unit,
        path,
    })
}

/// The members a moving load travels (`member`, or `path`: each member's `to` joint the next
/// one's `from`); a scene without joints: the rod.
fn route(
    c: &Checker,
    l: &LoadFile,
    frame: Option<&Frame>,
    key: &dyn Fn(&str) -> String,
) -> Result<Vec<usize>, SceneError> {
    let Some(frame) = frame else {
        if l.member.is_some() || l.path.is_some() {
            let k = if l.member.is_some() { "member" } else { "path" };
            return c.err(key(k), "a scene without [[member]]s has one rod to travel");
        }
        return Ok(vec![0]);
    };
    let names: Vec<&String> =
        match (&l.member, &l.path) {
            (Some(m), None) => vec![m],
            (None, Some(p)) if !p.is_empty() => p.iter().collect(),
            (Some(_), Some(_)) => return c.err(key("path"), "give `member` or `path`, not both"),
            _ => return c.err(
                key("member"),
                "missing: the member a moving load runs along (`member`), or its route (`path`)",
            ),
        };
    let mut path = Vec::new();
    for name in names {
        let Some(m) = frame.member(name) else {
            return c.err(
                key("path"),
                format!("`{name}` is not a [[member]] of this scene"),
            );
        };
        if frame.members[m].kind == MemberKind::Truss {
            return c.err(
                key("path"),
                format!("`{name}` is a truss bar: a moving load runs along rod members"),
            );
        }
        if let Some(&before) = path.last() {
            let (a, b): (&super::frame::Member, &super::frame::Member) =
                (&frame.members[before], &frame.members[m]);
            if a.to != b.from {
                return c.err(
                    key("path"),
                    format!(
                        "`{}` ends at joint `{}` but `{}` starts at `{}`: a path runs member \
                         after member, each from its `from` joint to its `to` joint",
                        a.name, frame.joints[a.to].name, b.name, frame.joints[b.from].name
                    ),
                );
            }
        }
        path.push(m);
    }
    Ok(path)
}

/// Over the whole rod and uniform: the paper's load, as it always was; else over `[from, to]`
/// with its end value.
fn distributed(
    c: &Checker,
    l: &LoadFile,
    params: &[Param],
    frame: Option<&Frame>,
    key: &dyn Fn(&str) -> String,
) -> Result<LoadKind, SceneError> {
    let member = match (frame, &l.member) {
        (None, Some(_)) => return c.err(key("member"), "a scene without [[member]]s has one rod"),
        (None, None) => 0,
        (Some(_), None) => {
            return c.err(
                key("member"),
                "missing: the member a distributed load acts on (a frame's gravity is kind = \
                 \"gravity\")",
            )
        }
        (Some(f), Some(name)) => match f.member(name) {
            Some(m) if f.members[m].kind == MemberKind::Truss => {
                return c.err(
                    key("member"),
                    format!("`{name}` is a truss bar: it is loaded at its joints only"),
                )
            }
            Some(m) => m,
            None => {
                return c.err(
                    key("member"),
                    format!("`{name}` is not a [[member]] of this scene"),
                )
            }
        },
    };
    let from = l
        .from
        .map_or(Ok(0.0), |x| c.station(Some(x), &key("from")))?;
    let to = l.to.map_or(Ok(1.0), |x| c.station(Some(x), &key("to")))?;
    if from >= to {
        return c.err(
            key("to"),
            format!("[{from}, {to}] is empty: `from` must be below `to`"),
        );
    }
    let value_end = match &l.value_end {
        None => None,
        Some(v) => Some(c.slot(v, params, &key("value_end"))?),
    };
    if frame.is_none() && from == 0.0 && to == 1.0 && value_end.is_none() {
        return Ok(LoadKind::Distributed);
    }
    Ok(LoadKind::Patch {
        member,
        from,
        to,
        value_end,
    })
}

/// Speed (> 0) and entry time of a moving load: numbers or fixed parameters (the path of the
/// load is laid out when the run starts).
fn moving(
    c: &Checker,
    l: &LoadFile,
    params: &[Param],
    key: &dyn Fn(&str) -> String,
) -> Result<LoadKind, SceneError> {
    let fixed_slot = |v: &toml::Value, k: &str| {
        let slot = c.slot(v, params, &key(k))?;
        if let Slot::Param { index, .. } = slot {
            if params[index].variability != Variability::Fixed {
                return c.err(
                    key(k),
                    format!(
                        "parameter `{}` is tunable: a moving load's path is fixed for the run \
                         (make it fixed)",
                        params[index].name
                    ),
                );
            }
        }
        Ok(slot)
    };
    let speed = c.required(l.speed.as_ref(), &key("speed"), "the speed in m/s (> 0)")?;
    let speed = fixed_slot(speed, "speed")?;
    if let Slot::Number(v) = speed {
        if v <= 0.0 {
            return c.err(key("speed"), format!("{v} is out of range: must be > 0"));
        }
    }
    let enter = match &l.enter {
        None => Slot::Number(0.0),
        Some(v) => fixed_slot(v, "enter")?,
    };
    Ok(LoadKind::Moving { speed, enter })
}
