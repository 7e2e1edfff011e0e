//! `[[stop]]`: one-sided supports (docs/scenes.md): a point of the rod or frame that touches a
//! stop when its displacement along `u1` or `u2` reaches the gap on the stop's side, and is then
//! pushed back by a penalty spring and a dashpot that never pull (docs/model.md, section 14).
//! Their outputs `<name>_force` and `<name>_contact` follow every other block of value
//! references.
use super::attached::non_negative;
use super::checker::{entry, Checker};
use super::file::StopFile;
use super::frame::{place, Frame, PlaceKeys};
use super::variables::{output, OutputId, Variable};
use super::{Scene, SceneError, Station, Support};

/// The stops' forces `<stop>_force`, one per `[[stop]]` in file order.
pub const STOP_FORCE_VR: u32 = 1_400_000;
/// Their contact fractions `<stop>_contact`.
pub const STOP_CONTACT_VR: u32 = 1_500_000;

#[derive(Clone, Debug, PartialEq)]
pub struct Stop {
    pub name: String,
    pub at: Station,
    /// 0 `u1`, 1 `u2`.
    pub dof: usize,
    /// +1 (`side = "+"`: touched at `u = gap`) or -1 (`"-"`: at `u = -gap`).
    pub sign: f64,
    pub gap: f64,
    pub k: f64,
    pub c: f64,
}

pub(super) fn stops(
    c: &Checker,
    raw: &[StopFile],
    supports: &[Support],
    frame: Option<&Frame>,
) -> Result<Vec<Stop>, SceneError> {
    (raw.iter().enumerate())
        .map(|(i, s)| {
            let key = |k: &str| entry("stop", i, s.name.as_ref(), k);
            let name = c.identifier(s.name.as_ref(), &key("name"))?;
            let keys = PlaceKeys {
                at: s.at,
                joint: s.joint.as_ref(),
                member: s.member.as_ref(),
            };
            let at = place(c, frame, keys, false, &key)?;
            let dof_name = c.required(s.dof.as_deref(), &key("dof"), "\"u1\" or \"u2\"")?;
            let dof = c.one_of(dof_name, &["u1", "u2"], &key("dof"))?;
            if let Some(held) = supports.iter().find(|p| {
                p.at.same(&at) && ((p.fixed[dof] && p.angle == 0.0) || (p.fixed[0] && p.fixed[1]))
            }) {
                return c.err(
                    key("dof"),
                    format!(
                        "support `{}` already holds {dof_name} there: a stop there would never \
                         be touched",
                        held.name
                    ),
                );
            }
            let side = c.required(
                s.side.as_deref(),
                &key("side"),
                "\"+\" (the stop is on the positive side of the dof) or \"-\"",
            )?;
            let sign = [1.0, -1.0][c.one_of(side, &["+", "-"], &key("side"))?];
            let gap = non_negative(c, s.gap, Some(0.0), &key("gap"), "")?;
            let k = c.required(s.k, &key("k"), "the contact stiffness in N/m (> 0)")?;
            if !(k.is_finite() && k > 0.0) {
                return c.err(key("k"), format!("{k} is out of range: must be > 0"));
            }
            Ok(Stop {
                name,
                at,
                dof,
                sign,
                gap,
                k,
                c: non_negative(c, s.c, Some(0.0), &key("c"), "")?,
            })
        })
        .collect()
}

/// The outputs of the scene's stops: `<name>_force`, then `<name>_contact`.
pub(super) fn outputs(scene: &Scene) -> Vec<Variable> {
    let mut vars = Vec::new();
    for (k, s) in scene.stops.iter().enumerate() {
        let e = ["e1", "e2"][s.dof];
        vars.push(output(
            format!("{}_force", s.name),
            STOP_FORCE_VR + k as u32,
            Some("N"),
            format!(
                "Force of stop {} on the structure along {e} (spring and dashpot; it never \
                 pulls: {}); averaged over the last communication step like a reaction (before \
                 the first step: the static force)",
                s.name,
                if s.sign > 0.0 { "<= 0" } else { ">= 0" }
            ),
            OutputId::StopForce(k),
        ));
    }
    for (k, s) in scene.stops.iter().enumerate() {
        vars.push(output(
            format!("{}_contact", s.name),
            STOP_CONTACT_VR + k as u32,
            Some("1"),
            format!(
                "Fraction of the last communication step that stop {} spent in contact (0 to 1; \
                 before the first step: 1 if the initial state touches it, else 0)",
                s.name
            ),
            OutputId::StopContact(k),
        ));
    }
    vars
}

/// The key of an entry of an array of tables as the checker's messages spell it
/// (`[[spring]] #2 "soft", key `k3``), for refusals that come after the check (the static
/// state).
pub fn entry_key(table: &str, index: usize, name: &str, key: &str) -> String {
    entry(table, index, Some(&name.to_string()), key)
}
