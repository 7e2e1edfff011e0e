//! Checks of what a scene reads out besides its sensors: `[shape]` (points and fields along
//! the rod) and `[modes]` (natural frequencies of the initial state).
use super::checker::Checker;
use super::file::{ModesFile, ShapeFile};
use super::variable_kinds as variables;
use super::{Quantity, SceneError};

/// Default shape samples when `[shape]` or its `points` is absent.
const DEFAULT_SHAPE_POINTS: usize = 21;
const MAX_SHAPE_POINTS: usize = 10_000;
const _: () = assert!(MAX_SHAPE_POINTS <= variables::MAX_SHAPE_POINTS);

/// The most natural frequencies `[modes] count` may ask for.
pub const MAX_MODES: usize = 12;

/// `[shape]`: the number of samples and the fields read at them.
pub(super) fn shape(
    c: &Checker,
    raw: Option<&ShapeFile>,
) -> Result<(usize, Vec<Quantity>), SceneError> {
    let Some(raw) = raw else {
        return Ok((DEFAULT_SHAPE_POINTS, Vec::new()));
    };
    let points = match raw.points {
        None => DEFAULT_SHAPE_POINTS,
        Some(n) if n == 0 || (2..=MAX_SHAPE_POINTS as i64).contains(&n) => n as usize,
        Some(n) => {
            return c.err(
                "shape.points",
                format!(
                "{n} is out of range: must be 0 (no shape outputs) or in [2, {MAX_SHAPE_POINTS}]"
            ),
            )
        }
    };
    let mut fields = Vec::new();
    for name in &raw.fields {
        let q = Quantity::ALL[c.one_of(name, &Quantity::NAMES, "shape.fields")?];
        if fields.contains(&q) {
            return c.err("shape.fields", format!("\"{name}\" is listed twice"));
        }
        fields.push(q);
    }
    if points == 0 && !fields.is_empty() {
        return c.err(
            "shape.fields",
            "fields are read at the shape points: set shape.points >= 2",
        );
    }
    Ok((points, fields))
}

/// `[modes]`: how many natural frequencies of the initial state to report (0: none).
pub(super) fn modes(c: &Checker, raw: Option<&ModesFile>) -> Result<usize, SceneError> {
    let Some(raw) = raw else { return Ok(0) };
    let count = c.required(
        raw.count,
        "modes.count",
        "the number of frequencies, in [1, 12]",
    )?;
    if !(1..=MAX_MODES as i64).contains(&count) {
        return c.err(
            "modes.count",
            format!("{count} is out of range: must be in [1, {MAX_MODES}]"),
        );
    }
    Ok(count as usize)
}
