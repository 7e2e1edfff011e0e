//! `[[mass]]`, `[[spring]]` and `[[foundation]]`: point masses with rotary inertia, springs
//! and dashpots from a dof to ground, and Winkler foundations on `u2` over a part of the rod.
//! Their stations are nodes of every mesh.
use super::checker::{entry, Checker};
use super::file::{FoundationFile, MassFile, SpringFile};
use super::frame::{place, Frame, MemberKind, PlaceKeys};
use super::{Input, InputKind, SceneError, Slot, Support, DOF_NAMES};

#[derive(Clone, Debug, PartialEq)]
pub struct PointMass {
    pub name: String,
    pub at: super::Station,
    /// Mass (on u1 and u2) and rotary inertia (on w).
    pub m: f64,
    pub j: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Spring {
    pub name: String,
    pub at: super::Station,
    /// 0 `u1`, 1 `u2`, 2 `w`.
    pub dof: usize,
    pub k: f64,
    pub c: f64,
    /// The cubic part of its force `k u + k3 u^3` (0: a linear spring; < 0: softening).
    pub k3: f64,
    /// The FMI input its base follows (`motion = "input"`); without one the base is fixed.
    pub base: Option<usize>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Foundation {
    pub name: String,
    /// The member it is under (0 in a scene without joints).
    pub member: usize,
    /// Stiffness and damping per unit length, on u2.
    pub k: f64,
    pub c: f64,
    /// Stations.
    pub from: f64,
    pub to: f64,
}

/// A number `>= 0` (`what` says what it is), or its default when absent.
pub(super) fn non_negative(
    c: &Checker,
    x: Option<f64>,
    default: Option<f64>,
    key: &str,
    what: &str,
) -> Result<f64, SceneError> {
    let x = match (x, default) {
        (Some(x), _) => x,
        (None, Some(d)) => d,
        (None, None) => return c.err(key, format!("missing: {what}")),
    };
    if !(x.is_finite() && x >= 0.0) {
        return c.err(key, format!("{x} is out of range: must be >= 0"));
    }
    Ok(x)
}

pub(super) fn masses(
    c: &Checker,
    raw: &[MassFile],
    frame: Option<&Frame>,
) -> Result<Vec<PointMass>, SceneError> {
    (raw.iter().enumerate())
        .map(|(i, m)| {
            let key = |k: &str| entry("mass", i, m.name.as_ref(), k);
            let keys = PlaceKeys {
                at: m.at,
                joint: m.joint.as_ref(),
                member: m.member.as_ref(),
            };
            Ok(PointMass {
                name: c.identifier(m.name.as_ref(), &key("name"))?,
                at: place(c, frame, keys, false, &key)?,
                m: non_negative(c, m.m, None, &key("m"), "the mass (kg)")?,
                j: non_negative(c, m.rotary, Some(0.0), &key("J"), "")?,
            })
        })
        .collect()
}

pub(super) fn springs(
    c: &Checker,
    raw: &[SpringFile],
    supports: &[Support],
    frame: Option<&Frame>,
    inputs: &mut Vec<Input>,
) -> Result<Vec<Spring>, SceneError> {
    (raw.iter().enumerate())
        .map(|(i, s)| {
            let key = |k: &str| entry("spring", i, s.name.as_ref(), k);
            let name = c.identifier(s.name.as_ref(), &key("name"))?;
            let keys = PlaceKeys {
                at: s.at,
                joint: s.joint.as_ref(),
                member: s.member.as_ref(),
            };
            let at = place(c, frame, keys, false, &key)?;
            let dof_name = c.required(s.dof.as_deref(), &key("dof"), "\"u1\", \"u2\" or \"w\"")?;
            let dof = c.one_of(dof_name, &DOF_NAMES, &key("dof"))?;
            if let Some(held) = supports
                .iter()
                .find(|p| p.at.same(&at) && p.fixed[dof] && p.angle == 0.0)
            {
                return c.err(
                    key("dof"),
                    format!(
                        "support `{}` already holds {dof_name} there: a spring there would \
                         carry nothing",
                        held.name
                    ),
                );
            }
            let moving = match s.motion.as_deref() {
                None => false,
                Some(m) => c.one_of(m, &["none", "input"], &key("motion"))? == 1,
            };
            let base = moving.then(|| {
                inputs.push(base_input(&name, i, dof));
                inputs.len() - 1
            });
            Ok(Spring {
                name,
                at,
                dof,
                k: non_negative(c, s.k, None, &key("k"), "the stiffness (N/m, N.m/rad on w)")?,
                c: non_negative(c, s.c, Some(0.0), &key("c"), "")?,
                k3: match s.k3 {
                    Some(x) if !x.is_finite() => {
                        return c.err(key("k3"), format!("{x} is not a finite number"))
                    }
                    x => x.unwrap_or(0.0),
                },
                base,
            })
        })
        .collect()
}

/// The input `<name>_base` that the base of spring `index` follows (starting at 0).
fn base_input(name: &str, index: usize, dof: usize) -> Input {
    Input {
        name: format!("{name}_base"),
        kind: InputKind::SpringBase(index),
        start: Slot::Number(0.0),
        unit: Some(if dof == 2 { "rad" } else { "m" }.to_string()),
        description: format!(
            "Position of the base (far end) of spring {name} along {}: reached at the end of \
             each communication step, linearly from its value at the start; set in \
             initialization mode, part of the static initial state",
            ["e1", "e2", "the rotation w"][dof]
        ),
    }
}

pub(super) fn foundations(
    c: &Checker,
    raw: &[FoundationFile],
    frame: Option<&Frame>,
) -> Result<Vec<Foundation>, SceneError> {
    (raw.iter().enumerate())
        .map(|(i, f)| {
            let key = |k: &str| entry("foundation", i, f.name.as_ref(), k);
            let name = c.identifier(f.name.as_ref(), &key("name"))?;
            let member = match (frame, &f.member) {
                (None, None) => 0,
                (None, Some(_)) => {
                    return c.err(key("member"), "a scene without [[member]]s has one rod")
                }
                (Some(_), None) => {
                    return c.err(key("member"), "missing: the member on the foundation")
                }
                (Some(frame), Some(m)) => match frame.member(m) {
                    Some(k) if frame.members[k].kind == MemberKind::Rod => k,
                    Some(_) => {
                        return c.err(
                            key("member"),
                            format!("`{m}` is a truss bar: no foundation"),
                        )
                    }
                    None => {
                        return c.err(
                            key("member"),
                            format!("`{m}` is not a [[member]] of this scene"),
                        )
                    }
                },
            };
            let from = f
                .from
                .map_or(Ok(0.0), |x| c.station(Some(x), &key("from")))?;
            let to = f.to.map_or(Ok(1.0), |x| c.station(Some(x), &key("to")))?;
            if from >= to {
                return c.err(
                    key("to"),
                    format!("[{from}, {to}] is empty: `from` must be below `to`"),
                );
            }
            Ok(Foundation {
                name,
                member,
                k: non_negative(c, f.k, None, &key("k"), "the stiffness per length (N/m2)")?,
                c: non_negative(c, f.c, Some(0.0), &key("c"), "")?,
                from,
                to,
            })
        })
        .collect()
}
