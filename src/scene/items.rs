//! Checks of the scene's items: `[[support]]`, `[[load]]` (which also declare the scene's
//! inputs) and `[[sensor]]`.
use super::checker::{entry, Checker};
use super::file::{LoadFile, SensorFile, SupportFile};
use super::frame::{place, Frame, PlaceKeys};
use super::load_kinds;
use super::params::{Param, Variability};
use super::{
    Direction, Input, InputKind, Load, LoadKind, Quantity, SceneError, Sensor, Slot, Station,
    Support, TimeLaw, DOF_NAMES,
};
use std::collections::BTreeSet;

pub(super) fn supports(
    c: &Checker,
    raw: &[SupportFile],
    params: &[Param],
    frame: Option<&Frame>,
    inputs: &mut Vec<Input>,
) -> Result<Vec<Support>, SceneError> {
    let mut out: Vec<Support> = Vec::new();
    for (i, s) in raw.iter().enumerate() {
        let key = |k: &str| entry("support", i, s.name.as_ref(), k);
        let name = c.identifier(s.name.as_ref(), &key("name"))?;
        let keys = PlaceKeys {
            at: s.at,
            joint: s.joint.as_ref(),
            member: s.member.as_ref(),
        };
        let at = place(c, frame, keys, false, &key)?;
        if let Some(other) = out.iter().find(|o| o.at.same(&at)) {
            return c.err(
                key(if s.joint.is_some() { "joint" } else { "at" }),
                format!(
                    "support `{}` is already there: hold both sets of dofs in one support",
                    other.name
                ),
            );
        }
        let angle = match s.angle {
            None => 0.0,
            Some(a) if a.is_finite() && a > -360.0 && a < 360.0 => a,
            Some(a) => {
                return c.err(
                    key("angle"),
                    format!("{a} is out of range: degrees in (-360, 360)"),
                )
            }
        };
        let fix = c.required(
            s.fix.as_ref(),
            &key("fix"),
            "the held dofs, a subset of [\"u1\", \"u2\", \"w\"]",
        )?;
        let mut fixed = [false; 3];
        for dof in fix {
            let k = c.one_of(dof, &DOF_NAMES, &key("fix"))?;
            if fixed[k] {
                return c.err(key("fix"), format!("\"{dof}\" is listed twice"));
            }
            fixed[k] = true;
        }
        if !fixed.iter().any(|&f| f) {
            return c.err(
                key("fix"),
                "a support must hold at least one dof of u1, u2, w",
            );
        }
        let mut displace = [Slot::Number(0.0); 3];
        for (dof, value) in &s.displace {
            let k = c.one_of(dof, &DOF_NAMES, &key("displace"))?;
            if !fixed[k] {
                return c.err(
                    key("displace"),
                    format!("\"{dof}\" is not held by this support (add it to `fix`)"),
                );
            }
            let slot = c.slot(value, params, &key(&format!("displace.{dof}")))?;
            if let Slot::Param { index, .. } = slot {
                if params[index].variability != Variability::Fixed {
                    return c.err(
                        key(&format!("displace.{dof}")),
                        format!(
                            "parameter `{}` is tunable: a prescribed displacement must not jump \
                             during a run (make it fixed, or use motion = \"input\")",
                            params[index].name
                        ),
                    );
                }
            }
            displace[k] = slot;
        }
        let motion = match s.motion.as_deref() {
            None | Some("none") => false,
            Some(m) => c.one_of(m, &["none", "input"], &key("motion"))? == 1,
        };
        if motion && angle != 0.0 {
            return c.err(
                key("motion"),
                "a support at an angle does not follow inputs (give its motion in the global \
                 frame: angle = 0, or move it through a spring base)",
            );
        }
        let index = out.len();
        if motion {
            for dof in (0..3).filter(|&k| fixed[k]) {
                inputs.push(Input {
                    name: format!("{name}_{}", DOF_NAMES[dof]),
                    kind: InputKind::Motion {
                        support: index,
                        dof,
                    },
                    start: displace[dof],
                    unit: Some(if dof == 2 { "rad" } else { "m" }.to_string()),
                    description: format!(
                        "Prescribed {} of support {name}: reached at the end of each communication \
                         step, linearly from its value at the start",
                        ["displacement u1", "displacement u2", "rotation w"][dof]
                    ),
                });
            }
        }
        out.push(Support {
            name,
            at,
            angle,
            fixed,
            displace,
            motion,
        });
    }
    Ok(out)
}

pub(super) fn loads(
    c: &Checker,
    raw: &[LoadFile],
    params: &mut [Param],
    frame: Option<&Frame>,
    inputs: &mut Vec<Input>,
) -> Result<Vec<Load>, SceneError> {
    let mut out = Vec::new();
    let mut f_units = BTreeSet::new();
    for (i, l) in raw.iter().enumerate() {
        let key = |k: &str| entry("load", i, l.name.as_ref(), k);
        let name = c.identifier(l.name.as_ref(), &key("name"))?;
        let placed = load_kinds::place(c, l, params, frame, &key)?;
        let (kind, direction, unit, path) =
            (placed.kind, placed.direction, placed.unit, placed.path);
        let time_name = l.time.as_deref().unwrap_or("constant");
        let time_kind = c.one_of(time_name, &["constant", "harmonic", "input"], &key("time"))?;
        if kind == LoadKind::Gravity && time_kind != 0 {
            return c.err(
                key("time"),
                "gravity is constant (it is part of the static initial state)",
            );
        }
        if matches!(kind, LoadKind::Moving { .. }) && time_kind != 0 {
            return c.err(
                key("time"),
                "a moving load has a constant value (it moves instead)",
            );
        }
        if time_kind == 2
            && matches!(
                kind,
                LoadKind::Patch {
                    value_end: Some(_),
                    ..
                }
            )
        {
            return c.err(
                key("value_end"),
                "an input load's magnitude is the input: it has no end value",
            );
        }
        if time_kind != 2 && l.start.is_some() {
            return c.err(
                key("start"),
                "only an input load (time = \"input\") has a start value",
            );
        }
        let (value, time) = match time_kind {
            0 => {
                let standard = toml::Value::Float(STANDARD_GRAVITY);
                let v = match (&l.value, kind) {
                    (None, LoadKind::Gravity) => &standard,
                    (v, _) => c.required(
                        v.as_ref(),
                        &key("value"),
                        "a number, a parameter name, or -name",
                    )?,
                };
                (c.slot(v, params, &key("value"))?, TimeLaw::Constant)
            }
            1 => {
                let default = toml::Value::String("F".into());
                let slot = c.slot(l.value.as_ref().unwrap_or(&default), params, &key("value"))?;
                if let Slot::Param { index, .. } = slot {
                    if params[index].name == "F" {
                        f_units.insert(unit);
                    }
                }
                (slot, TimeLaw::Harmonic)
            }
            _ => {
                if l.value.is_some() {
                    return c.err(
                        key("value"),
                        "the magnitude of an input load is the FMI input itself (give its start value with `start`)",
                    );
                }
                let start = l.start.unwrap_or(0.0);
                if !start.is_finite() {
                    return c.err(key("start"), "must be finite");
                }
                inputs.push(Input {
                    name: name.clone(),
                    kind: InputKind::Load(out.len()),
                    start: Slot::Number(start),
                    unit: Some(unit.to_string()),
                    description: if l.description.trim().is_empty() {
                        format!(
                            "{}, held over each communication step",
                            describe(kind, direction)
                        )
                    } else {
                        l.description.trim().to_string()
                    },
                });
                (Slot::Number(1.0), TimeLaw::Input(inputs.len() - 1))
            }
        };
        out.push(Load {
            name,
            kind,
            direction,
            value,
            time,
            path,
        });
    }
    if f_units.len() == 1 {
        if let Some(f) = params.iter_mut().find(|p| p.name == "F") {
            f.unit = f_units.first().map(|u| u.to_string());
        }
    }
    Ok(out)
}

/// Standard gravity (m/s2), the default value of a gravity load.
pub const STANDARD_GRAVITY: f64 = 9.81;

/// A load's kind, place and direction in words.
pub fn describe(kind: LoadKind, direction: Direction) -> String {
    let sign = if direction.sign < 0.0 { "-" } else { "" };
    let along = if direction.component == super::NORMAL {
        format!("along the member's {sign}normal")
    } else {
        format!("along {sign}e{}", direction.component + 1)
    };
    match kind {
        LoadKind::Point { at } => format!("Point load {along} at {}", where_(at)),
        LoadKind::Distributed => format!("Distributed load {along}"),
        LoadKind::Patch { from, to, .. } => {
            format!("Distributed load {along} over [{from}, {to}] of the length")
        }
        LoadKind::Moment { at } => {
            format!(
                "Point moment about e3 (counter-clockwise) at {}",
                where_(at)
            )
        }
        LoadKind::Gravity => format!("Gravity {along}"),
        LoadKind::Moving { .. } => format!("Moving load {along}"),
    }
}

/// A station in words (in variable descriptions).
pub fn where_(at: Station) -> String {
    match at {
        Station::On { at, .. } => format!("{at} of the length"),
        Station::Joint(_) => "a joint".to_string(),
    }
}

pub(super) fn sensor(
    c: &Checker,
    i: usize,
    s: &SensorFile,
    frame: Option<&Frame>,
) -> Result<Sensor, SceneError> {
    let key = |k: &str| entry("sensor", i, s.name.as_ref(), k);
    let name = c.identifier(s.name.as_ref(), &key("name"))?;
    let q = c.required(
        s.quantity.as_deref(),
        &key("quantity"),
        &format!("one of {}", Quantity::NAMES.join(", ")),
    )?;
    let quantity = Quantity::ALL[c.one_of(q, &Quantity::NAMES, &key("quantity"))?];
    let keys = PlaceKeys {
        at: s.at,
        joint: s.joint.as_ref(),
        member: s.member.as_ref(),
    };
    // A section quantity is read in a member's section: at a joint, name the member.
    let section = matches!(quantity.reading(), super::Reading::Section(_));
    let at = place(c, frame, keys, section || s.member.is_some(), &key)?;
    if let (Station::Joint(j), true) = (at, section) {
        let joint = &frame.expect("a joint is a frame's").joints[j].name;
        return c.err(
            key("member"),
            format!(
                "{q} is read in a member's section and joint `{joint}` joins several: name the \
                 member too (joint = \"{joint}\", member = \"...\")"
            ),
        );
    }
    Ok(Sensor {
        name,
        at,
        quantity,
        description: s.description.trim().to_string(),
    })
}

/// The unit of `F` from the harmonic loads it scales: N/m when they are all distributed
/// (per unit length), N when they are all point loads, none when they are mixed.
pub(super) fn label_amplitude(loads: &[Load], params: &mut [Param]) {
    let Some(f) = params.iter().position(|p| p.name == "F") else {
        return;
    };
    let amplitude = Slot::Param {
        index: f,
        sign: 1.0,
    };
    let units: Vec<&str> = loads
        .iter()
        .filter(|l| l.time == TimeLaw::Harmonic && l.value == amplitude)
        .map(|l| match l.kind {
            LoadKind::Distributed | LoadKind::Patch { .. } => "N/m",
            LoadKind::Point { .. } | LoadKind::Moving { .. } => "N",
            LoadKind::Moment { .. } => "N.m",
            LoadKind::Gravity => "m/s2",
        })
        .collect();
    if let Some(&first) = units.first() {
        if units.iter().all(|&u| u == first) {
            params[f].unit = Some(first.to_string());
        }
    }
}
