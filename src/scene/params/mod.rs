//! Parameters of a scene: the standard ones every FMU has (material, section, mesh, step), the
//! ones that a scene's contents bring (`L`, `H` for arcs, `F`, `Omega` for harmonic loads,
//! `well` for a branch choice), and those the scene file declares. One table per scene holds
//! name, value reference, type, range, unit and start; [`ParamValues`] holds the current values,
//! indexed like the table. Ranges are checked here, once, for the packager, the core and the FMU.
//!
//! This file holds what a parameter is (type, range, the check of a value) and its values; the
//! tables of the standard parameters are in `standard.rs`.
mod standard;

pub use standard::{
    default_settable, is_standard_name, standard_params, Needs, Std, ELEMENTS, INTEGRATOR,
    LYAPUNOV, LYAPUNOV_ALIGN, LYAPUNOV_START, PERTURBATION, SCENE_PARAM_VR, SECTION_AT, WELL,
};

use std::fmt;

/// FMI type of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarType {
    Real,
    Integer,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variability {
    Fixed,
    Tunable,
}

/// An allowed range; bounds are inclusive unless marked exclusive.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Range {
    pub min: Option<f64>,
    pub max: Option<f64>,
    pub min_exclusive: bool,
    pub max_exclusive: bool,
}

impl Range {
    pub const ANY: Range = Range {
        min: None,
        max: None,
        min_exclusive: false,
        max_exclusive: false,
    };

    pub const fn at_least(min: f64) -> Range {
        Range {
            min: Some(min),
            ..Range::ANY
        }
    }

    /// Every positive normal number: declared as an inclusive bound (FMI 2.0 `min` is
    /// inclusive), so that a host may set exactly the declared minimum.
    pub const fn positive() -> Range {
        Range::at_least(f64::MIN_POSITIVE)
    }

    pub const fn between(min: f64, max: f64) -> Range {
        Range {
            min: Some(min),
            max: Some(max),
            ..Range::ANY
        }
    }

    /// The open interval `(min, max)`: both ends refused. Declared (FMI 2.0 bounds are
    /// inclusive) as the doubles next to them inside, [`Range::declared_min`] and
    /// [`Range::declared_max`], so the declared bounds are exactly the extreme values accepted.
    pub const fn open(min: f64, max: f64) -> Range {
        Range {
            min: Some(min),
            max: Some(max),
            min_exclusive: true,
            max_exclusive: true,
        }
    }

    /// The smallest value accepted, as declared in `min` (for Real variables).
    pub fn declared_min(&self) -> Option<f64> {
        let m = self.min?;
        Some(if self.min_exclusive { next_up(m) } else { m })
    }

    /// The largest value accepted, as declared in `max` (for Real variables).
    pub fn declared_max(&self) -> Option<f64> {
        let m = self.max?;
        Some(if self.max_exclusive { -next_up(-m) } else { m })
    }

    /// The range in words, e.g. `(-1, 0.5)`, `[2, 5]` or `>= 0`; `None` if any finite value goes.
    pub fn text(&self) -> Option<String> {
        if *self == Range::positive() {
            return Some(format!(
                "> 0 (>= {:e}, the smallest normal number)",
                f64::MIN_POSITIVE
            ));
        }
        let lo = self
            .min
            .map(|m| (if self.min_exclusive { "(" } else { "[" }, m));
        let hi = self
            .max
            .map(|m| (if self.max_exclusive { ")" } else { "]" }, m));
        match (lo, hi) {
            (Some((l, a)), Some((r, b))) => Some(format!("{l}{a}, {b}{r}")),
            (Some((l, a)), None) => Some(format!("{} {a}", if l == "(" { ">" } else { ">=" })),
            (None, Some((r, b))) => Some(format!("{} {b}", if r == ")" { "<" } else { "<=" })),
            (None, None) => None,
        }
    }

    /// Whether `value` is finite and in the range.
    pub fn admits(&self, value: f64) -> bool {
        let above = self.min.is_none_or(|m| {
            if self.min_exclusive {
                value > m
            } else {
                value >= m
            }
        });
        let below = self.max.is_none_or(|m| {
            if self.max_exclusive {
                value < m
            } else {
                value <= m
            }
        });
        value.is_finite() && above && below
    }
}

/// The next double above the finite `x` (`f64::next_up`, stable only from Rust 1.86).
fn next_up(x: f64) -> f64 {
    if x == 0.0 {
        return f64::from_bits(1); // the smallest subnormal
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

/// One parameter of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    pub name: String,
    pub vr: u32,
    pub var_type: VarType,
    pub variability: Variability,
    pub unit: Option<String>,
    pub description: String,
    pub start: f64,
    pub range: Range,
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

pub(crate) fn refuse(name: &str, message: impl Into<String>) -> ParamError {
    ParamError {
        name: name.to_string(),
        message: message.into(),
    }
}

impl Param {
    /// Checks a value against the type and range of this parameter.
    pub fn check(&self, value: f64) -> Result<(), ParamError> {
        if !value.is_finite() {
            return Err(refuse(
                &self.name,
                format!("{value} is not a finite number"),
            ));
        }
        if self.var_type != VarType::Real && value.fract() != 0.0 {
            return Err(refuse(&self.name, format!("{value} is not an integer")));
        }
        if !self.range.admits(value) {
            let range = self.range.text().unwrap_or_default();
            return Err(refuse(
                &self.name,
                format!("{value} is out of range: must be {range}"),
            ));
        }
        if self.name == WELL && value == 0.0 {
            return Err(refuse(WELL, "0 is not allowed: must be +1 or -1"));
        }
        Ok(())
    }
}

/// The current values of a scene's parameters, indexed like its parameter table.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamValues(pub Vec<f64>);

impl ParamValues {
    pub fn get(&self, index: usize) -> f64 {
        self.0[index]
    }

    pub fn std(&self, p: Std) -> f64 {
        self.0[p as usize]
    }

    pub fn elements(&self) -> usize {
        self.std(Std::Elements) as usize
    }

    pub fn dt_max(&self) -> f64 {
        self.std(Std::DtMax)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_in_words() {
        assert!(Range::positive()
            .text()
            .unwrap()
            .starts_with("> 0 (>= 2.2250738585072014e-308"));
        assert_eq!(Range::between(2.0, 5.0).text().unwrap(), "[2, 5]");
        let open = Range::open(-1.0, 0.5);
        assert_eq!(open.text().unwrap(), "(-1, 0.5)");
        let (lo, hi) = (open.declared_min().unwrap(), open.declared_max().unwrap());
        assert_eq!((lo, hi), (-0.9999999999999999, 0.49999999999999994));
        assert!(lo > -1.0 && hi < 0.5 && open.admits(lo) && open.admits(hi));
        assert!(!open.admits(-1.0) && !open.admits(0.5));
        // Nothing lies between a declared bound and the excluded end.
        assert_eq!((next_up(-1.0), next_up(hi)), (lo, 0.5));
        assert_eq!(next_up(0.0), 5e-324);
        assert!(Range::positive().admits(1e-300));
        assert!(!Range::positive().admits(0.0));
        assert!(!Range::ANY.admits(f64::NAN));
    }
}
