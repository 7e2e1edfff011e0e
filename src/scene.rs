//! The three scenes of `shared/spec/model.md` as plain, validated data.
//!
//! Names, defaults and ranges come from the variable table generated from `modelDescription/`
//! (see [`crate::variables`]), so a scene file, the FMU and the docs all use the same names:
//! `E`, `nu`, `rho`, `d`, `b`, `h`, `L`, `elements`, `dt_max`, `F`, `Omega`, and per scene
//! `pre_shortening`, `well` (BuckledBeam) or `H`, `P0` (arches).
use crate::integrator::Scheme;
use crate::variables::{self, Causality, VarType, Variable};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SceneKind {
    BuckledBeam,
    PinnedArch,
    ClampedArch,
}

impl SceneKind {
    pub const ALL: [SceneKind; 3] = [
        SceneKind::BuckledBeam,
        SceneKind::PinnedArch,
        SceneKind::ClampedArch,
    ];

    /// Position in [`variables::SCENE_NAMES`] and in `Variable::start` / `Variable::scenes`.
    pub fn index(self) -> usize {
        self as usize
    }

    pub fn name(self) -> &'static str {
        variables::SCENE_NAMES[self.index()]
    }

    pub fn from_name(name: &str) -> Option<SceneKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

impl fmt::Display for SceneKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A parameter value that was refused: names the variable and the allowed range.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    pub name: String,
    pub message: String,
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "parameter `{}`: {}", self.name, self.message)
    }
}

impl std::error::Error for ParamError {}

fn refuse(name: &str, message: impl Into<String>) -> ParamError {
    ParamError {
        name: name.to_string(),
        message: message.into(),
    }
}

/// Every parameter of a scene. Fields that a scene does not use keep their defaults and are
/// ignored (`pre_shortening`, `well` only for the BuckledBeam; `rise`, `preload` for the arches).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SceneParams {
    pub kind: SceneKind,
    /// `E`
    pub youngs_modulus: f64,
    /// `nu`
    pub poisson_ratio: f64,
    /// `rho`
    pub density: f64,
    /// `d`: viscous damping per unit length on the translations.
    pub damping: f64,
    /// `b`
    pub width: f64,
    /// `h`
    pub height: f64,
    /// `L`: span between the supports.
    pub span: f64,
    pub elements: usize,
    pub dt_max: f64,
    /// `F`
    pub forcing_amplitude: f64,
    /// `Omega`, rad/s.
    pub forcing_frequency: f64,
    pub pre_shortening: f64,
    /// `+1`: buckled upwards, `-1`: downwards.
    pub well: i32,
    /// `H`
    pub rise: f64,
    /// `P0`
    pub preload: f64,
    /// `integrator`: 1 = midpoint rule, 2 = energy-momentum.
    pub integrator: Scheme,
}

impl SceneParams {
    /// The defaults of `model.md` for this scene.
    pub fn defaults(kind: SceneKind) -> SceneParams {
        let start = |name: &str| {
            variables::by_name(name)
                .and_then(|v| v.start[kind.index()].or(v.start[0]))
                .unwrap_or_else(|| panic!("variables.toml has no start for `{name}`"))
        };
        SceneParams {
            kind,
            youngs_modulus: start("E"),
            poisson_ratio: start("nu"),
            density: start("rho"),
            damping: start("d"),
            width: start("b"),
            height: start("h"),
            span: start("L"),
            elements: start("elements") as usize,
            dt_max: start("dt_max"),
            forcing_amplitude: start("F"),
            forcing_frequency: start("Omega"),
            pre_shortening: start("pre_shortening"),
            well: start("well") as i32,
            rise: start("H"),
            preload: start("P0"),
            integrator: scheme_from_code(start("integrator")),
        }
    }

    /// The defaults with some parameters overridden by name, validated.
    pub fn with<'a>(
        kind: SceneKind,
        overrides: impl IntoIterator<Item = (&'a str, f64)>,
    ) -> Result<SceneParams, ParamError> {
        let mut p = SceneParams::defaults(kind);
        for (name, value) in overrides {
            p.set(name, value)?;
        }
        p.validate()?;
        Ok(p)
    }

    /// The parameter `name` of this scene, checked against its declared range.
    pub fn variable(&self, name: &str) -> Result<&'static Variable, ParamError> {
        let v = variables::by_name(name)
            .filter(|v| v.causality == Causality::Parameter)
            .ok_or_else(|| refuse(name, "no such parameter"))?;
        if !v.scenes[self.kind.index()] {
            return Err(refuse(
                name,
                format!("not a parameter of the {} scene", self.kind),
            ));
        }
        Ok(v)
    }

    /// Sets one parameter by its FMU name, checking its own range (cross-parameter conditions
    /// are checked by [`SceneParams::validate`]). On error nothing changes.
    pub fn set(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
        let var = self.variable(name)?;
        check_range(var, value)?;
        match name {
            "E" => self.youngs_modulus = value,
            "nu" => self.poisson_ratio = value,
            "rho" => self.density = value,
            "d" => self.damping = value,
            "b" => self.width = value,
            "h" => self.height = value,
            "L" => self.span = value,
            "elements" => self.elements = value as usize,
            "dt_max" => self.dt_max = value,
            "F" => self.forcing_amplitude = value,
            "Omega" => self.forcing_frequency = value,
            "pre_shortening" => self.pre_shortening = value,
            "well" => self.well = value as i32,
            "H" => self.rise = value,
            "P0" => self.preload = value,
            "integrator" => self.integrator = scheme_from_code(value),
            _ => return Err(refuse(name, "no such parameter")),
        }
        Ok(())
    }

    /// The value of a parameter by its FMU name.
    pub fn get(&self, name: &str) -> Option<f64> {
        Some(match name {
            "E" => self.youngs_modulus,
            "nu" => self.poisson_ratio,
            "rho" => self.density,
            "d" => self.damping,
            "b" => self.width,
            "h" => self.height,
            "L" => self.span,
            "elements" => self.elements as f64,
            "dt_max" => self.dt_max,
            "F" => self.forcing_amplitude,
            "Omega" => self.forcing_frequency,
            "pre_shortening" => self.pre_shortening,
            "well" => self.well as f64,
            "H" => self.rise,
            "P0" => self.preload,
            "integrator" => match self.integrator {
                Scheme::Midpoint => 1.0,
                Scheme::EnergyMomentum => 2.0,
            },
            _ => return None,
        })
    }

    /// Every range and every condition between parameters.
    pub fn validate(&self) -> Result<(), ParamError> {
        for var in variables::VARIABLES.iter() {
            if var.causality == Causality::Parameter && var.scenes[self.kind.index()] {
                let value = self.get(var.name).expect("every parameter has a field");
                check_range(var, value)?;
            }
        }
        match self.kind {
            SceneKind::BuckledBeam => {
                if self.well == 0 {
                    return Err(refuse(
                        "well",
                        "must be +1 (midspan up) or -1 (down), not 0",
                    ));
                }
                if self.pre_shortening >= 0.5 * self.span {
                    return Err(refuse(
                        "pre_shortening",
                        format!(
                            "{} is out of range: must be in [0, L/2) = [0, {})",
                            self.pre_shortening,
                            0.5 * self.span
                        ),
                    ));
                }
            }
            SceneKind::PinnedArch | SceneKind::ClampedArch => {
                if self.rise > 0.5 * self.span {
                    return Err(refuse(
                        "H",
                        format!(
                            "{} is out of range: must be in (0, L/2] = (0, {}]",
                            self.rise,
                            0.5 * self.span
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The scheme of the `integrator` enumeration (1 midpoint, 2 energy-momentum; range-checked).
fn scheme_from_code(code: f64) -> Scheme {
    if code == 2.0 {
        Scheme::EnergyMomentum
    } else {
        Scheme::Midpoint
    }
}

fn check_range(var: &Variable, value: f64) -> Result<(), ParamError> {
    if !value.is_finite() {
        return Err(refuse(var.name, format!("{value} is not a finite number")));
    }
    if var.var_type != VarType::Real && value.fract() != 0.0 {
        return Err(refuse(var.name, format!("{value} is not an integer")));
    }
    if !var.admits(value) {
        let range = var.range_text().unwrap_or_default();
        return Err(refuse(
            var.name,
            format!("{value} is out of range: must be {range}"),
        ));
    }
    Ok(())
}

/// A scene as written in a file: `{ "scene": "BuckledBeam", "F": 0.9, "elements": 20 }`.
/// Parameters not given keep the defaults of `model.md`.
#[derive(Deserialize)]
struct SceneFile {
    scene: SceneKind,
    #[serde(flatten)]
    overrides: BTreeMap<String, f64>,
}

impl<'de> Deserialize<'de> for SceneParams {
    fn deserialize<D: serde::Deserializer<'de>>(de: D) -> Result<Self, D::Error> {
        let file = SceneFile::deserialize(de)?;
        SceneParams::with(
            file.scene,
            file.overrides.iter().map(|(k, v)| (k.as_str(), *v)),
        )
        .map_err(serde::de::Error::custom)
    }
}
