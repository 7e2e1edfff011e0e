//! Checks of what a scene reads out besides its sensors: `[shape]` (points and fields along
//! the rod) and `[modes]` (natural frequencies of the initial state).
use super::checker::Checker;
use super::file::{ModesFile, ShapeFile};
use super::variables::{self, OutputId};
use super::{Quantity, Scene, SceneError};

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

/// Value reference of `shape_<field>[1]` of the `k`-th field: a block of
/// [`variables::MAX_SHAPE_POINTS`] per field after `shape_y`.
pub const SHAPE_FIELD_VR: u32 = 30_000;
/// Value reference of `frequency[1]`.
pub const FREQUENCY_VR: u32 = 52;

/// The outputs `shape_<field>[i]` and `frequency[k]`.
pub(super) fn outputs(scene: &Scene) -> Vec<variables::Variable> {
    let mut vars = Vec::new();
    for (field, q) in scene.shape_fields.iter().enumerate() {
        let base = SHAPE_FIELD_VR + (field * variables::MAX_SHAPE_POINTS) as u32;
        for point in 0..scene.shape_samples() {
            vars.push(variables::output(
                format!("shape_{}[{}]", q.name(), point + 1),
                base + point as u32,
                Some(q.unit()),
                format!("{} {}", q.what(), scene.shape_sample_text(point)),
                OutputId::ShapeField { field, point },
            ));
        }
    }
    for k in 0..scene.modes {
        let mut v = variables::output(
            format!("frequency[{}]", k + 1),
            FREQUENCY_VR + k as u32,
            Some("Hz"),
            format!(
                "Natural frequency {} (ascending) of the initial state: undamped, about the \
                 static equilibrium under the constant loads and prescribed displacements, \
                 computed at fmi2ExitInitializationMode (negative, -sqrt(-omega^2) / (2 pi), for an \
                 unstable direction)",
                k + 1
            ),
            OutputId::Frequency(k),
        );
        v.timing = variables::Timing::Discrete;
        vars.push(v);
    }
    vars
}
