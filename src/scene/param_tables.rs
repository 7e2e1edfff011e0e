//! The parameters a scene file sets: `[defaults]` (start values of the standard parameters) and
//! `[[parameter]]` (the scene's own, value references from `SCENE_PARAM_VR`).
use super::checker::{entry, Checker};
use super::file::{ParameterFile, SceneFile};
use super::params::{self, Param, Range, VarType, Variability, SCENE_PARAM_VR};
use super::{sections, SceneError};

/// `[defaults]`: each value is the start of the standard parameter of that name, checked
/// against its range.
pub(super) fn apply_defaults(
    c: &Checker,
    raw: &SceneFile,
    params: &mut [Param],
    harmonic: bool,
) -> Result<(), SceneError> {
    for (name, value) in &raw.defaults {
        let key = format!("defaults.{name}");
        if !params::default_settable(name) {
            return c.err(
                key,
                "not a standard parameter with a default here (allowed: E, nu, rho, d, b, h, \
                 elements, dt_max, integrator, and F, Omega with a harmonic load; L and H come \
                 from [geometry])",
            );
        }
        let Some(p) = params.iter_mut().find(|p| &p.name == name) else {
            if name == "b" || name == "h" {
                return c.err(
                    key,
                    "b and h are the dimensions of a rectangle: give this scene's section \
                     dimensions in [section]",
                );
            }
            debug_assert!(!harmonic);
            return c.err(
                key,
                "F and Omega exist only when a [[load]] has time = \"harmonic\"",
            );
        };
        let x = match value {
            toml::Value::Float(x) => *x,
            toml::Value::Integer(i) => *i as f64,
            other => return c.err(key, format!("{other} is not a number")),
        };
        if let Err(e) = p.check(x) {
            return c.err(key, e.message);
        }
        p.start = x;
    }
    Ok(())
}

/// `[[parameter]]` #`i`: a parameter of the scene's own, its name new to the scene.
pub(super) fn scene_parameter(
    c: &Checker,
    i: usize,
    p: &ParameterFile,
    existing: &[Param],
) -> Result<Param, SceneError> {
    let key = |k: &str| entry("parameter", i, p.name.as_ref(), k);
    let name = c.identifier(p.name.as_ref(), &key("name"))?;
    if params::is_standard_name(&name)
        || sections::is_dimension_name(&name)
        || existing.iter().any(|q| q.name == name)
    {
        return c.err(
            key("name"),
            format!("`{name}` is already a parameter of this scene"),
        );
    }
    let start = c.required(p.start, &key("start"), "a start value")?;
    let variability = match p.variability.as_deref() {
        None => Variability::Fixed,
        Some(v) => [Variability::Fixed, Variability::Tunable]
            [c.one_of(v, &["fixed", "tunable"], &key("variability"))?],
    };
    let range = Range {
        min: p.min,
        max: p.max,
        ..Range::ANY
    };
    if range.min.zip(range.max).is_some_and(|(a, b)| a > b) {
        return c.err(key("max"), "must not be below min");
    }
    let param = Param {
        name,
        vr: SCENE_PARAM_VR + i as u32,
        var_type: VarType::Real,
        variability,
        unit: p.unit.clone().filter(|u| !u.is_empty()),
        description: p.description.trim().to_string(),
        start,
        range,
    };
    if let Err(e) = param.check(start) {
        return c.err(key("start"), e.message);
    }
    Ok(param)
}
