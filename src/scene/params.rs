//! Parameters of a scene: the standard ones every FMU has (material, section, mesh, step), the
//! ones that a scene's contents bring (`L`, `H` for arcs, `F`, `Omega` for harmonic loads,
//! `well` for a branch choice), and those the scene file declares. One table per scene holds
//! name, value reference, type, range, unit and start; [`ParamValues`] holds the current values,
//! indexed like the table. Ranges are checked here, once, for the packager, the core and the FMU.
use std::fmt;

/// FMI type of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarType {
    Real,
    Integer,
    /// Read and written with the Integer functions (FMI 2.0, section 2.2.7).
    Enumeration,
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

/// A standard parameter: everything but the start value, which the scene may set.
struct Standard {
    name: &'static str,
    vr: u32,
    var_type: VarType,
    variability: Variability,
    unit: Option<&'static str>,
    description: &'static str,
    start: f64,
    range: Range,
}

const fn real(
    name: &'static str,
    vr: u32,
    unit: &'static str,
    description: &'static str,
    start: f64,
    range: Range,
) -> Standard {
    Standard {
        name,
        vr,
        var_type: VarType::Real,
        variability: Variability::Fixed,
        unit: Some(unit),
        description,
        start,
        range,
    }
}

pub const ELEMENTS: &str = "elements";
pub const INTEGRATOR: &str = "integrator";
pub const WELL: &str = "well";

/// The parameters of every scene, in this order (indices of [`Std`]).
const ALWAYS: [Standard; 10] = [
    real("E", 0, "Pa", "Young's modulus", 1.2e4, Range::positive()),
    real(
        "nu",
        1,
        "1",
        "Poisson's ratio (shear modulus G = E / (2 (1 + nu)))",
        0.2,
        // The open interval of an isotropic material (docs/scenes.md): nu = -1 makes G infinite.
        Range::open(-1.0, 0.5),
    ),
    real("rho", 2, "kg/m3", "Mass density", 1.0e-6, Range::positive()),
    real(
        "d",
        3,
        "N.s/m2",
        "Viscous damping per unit length, acting on the translations only",
        5.0e-4,
        Range::at_least(0.0),
    ),
    real(
        "b",
        4,
        "m",
        "Width of the rectangular cross section",
        1.0,
        Range::positive(),
    ),
    real(
        "h",
        5,
        "m",
        "Height of the rectangular cross section (in the plane of motion)",
        1.0,
        Range::positive(),
    ),
    real(
        "L",
        6,
        "m",
        "Span: length of a straight rod, chord of an arc",
        10.0,
        Range::positive(),
    ),
    Standard {
        name: ELEMENTS,
        vr: 7,
        var_type: VarType::Integer,
        variability: Variability::Fixed,
        unit: None,
        description: "Number of finite elements (supports must fall on nodes)",
        start: 10.0,
        // Narrowed per scene to the counts its supports allow (`Scene::element_range`).
        range: Range::between(super::MIN_ELEMENTS as f64, super::MAX_ELEMENTS as f64),
    },
    real(
        "dt_max",
        8,
        "s",
        "Largest internal time step: each communication step is cut into the fewest equal \
         midpoint sub-steps no longer than this",
        1.0e-5,
        Range::positive(),
    ),
    Standard {
        name: INTEGRATOR,
        vr: 15,
        var_type: VarType::Enumeration,
        variability: Variability::Fixed,
        unit: None,
        description: "Time integration scheme: 1 = midpoint rule (the paper's), 2 = \
                      energy-momentum (discrete gradient)",
        start: 1.0,
        range: Range::between(1.0, 2.0),
    },
];

/// Present when the scene has a harmonic load.
const HARMONIC: [Standard; 2] = [
    Standard {
        name: "F",
        vr: 9,
        var_type: VarType::Real,
        variability: Variability::Tunable,
        unit: None,
        description: "Excitation amplitude of the harmonic loads: F cos(Omega t)",
        start: 0.0,
        range: Range::ANY,
    },
    Standard {
        name: "Omega",
        vr: 10,
        var_type: VarType::Real,
        variability: Variability::Tunable,
        unit: Some("rad/s"),
        description: "Excitation circular frequency",
        start: 0.0,
        range: Range::at_least(0.0),
    },
];

/// Present for an arc.
const RISE: Standard = real(
    "H",
    13,
    "m",
    "Rise of the circular arch (at most L/2)",
    1.0,
    Range::positive(),
);

/// Present when the initial state picks a branch: an Integer in [-1, 1], 0 refused.
const BRANCH: Standard = Standard {
    name: WELL,
    vr: 12,
    var_type: VarType::Integer,
    variability: Variability::Fixed,
    unit: None,
    description: "Initial equilibrium: +1 or -1, the sign of the branch sensor in it",
    start: 1.0,
    range: Range::between(-1.0, 1.0),
};

pub const LYAPUNOV: &str = "lyapunov_count";
pub const LYAPUNOV_START: &str = "lyapunov_start";
pub const LYAPUNOV_ALIGN: &str = "lyapunov_align";
pub const PERTURBATION: &str = "perturbation";

/// Analysis parameters of every scene (after the scene's other standard parameters): Lyapunov
/// exponents from the tangent map of the midpoint rule, and a kick for twin-trajectory checks.
const ANALYSIS: [Standard; 4] = [
    Standard {
        name: LYAPUNOV,
        vr: 16,
        var_type: VarType::Integer,
        variability: Variability::Fixed,
        unit: None,
        description: "Number of leading Lyapunov exponents to estimate from the exact tangent \
                      map of the midpoint rule (0: none; needs integrator = 1)",
        start: 0.0,
        range: Range::between(0.0, crate::integrator::tangent::MAX_EXPONENTS as f64),
    },
    real(
        LYAPUNOV_START,
        17,
        "s",
        "Time from which the tangent vectors of the Lyapunov exponents are advanced (before \
         it they cost nothing)",
        0.0,
        Range::at_least(0.0),
    ),
    real(
        LYAPUNOV_ALIGN,
        19,
        "s",
        "Time after lyapunov_start during which the tangent vectors only align with the \
         leading directions; the exponents average their growth after it",
        0.0,
        Range::at_least(0.0),
    ),
    Standard {
        name: PERTURBATION,
        vr: 18,
        var_type: VarType::Real,
        variability: Variability::Tunable,
        unit: Some("m"),
        description: "Kick for twin-trajectory checks: a change of this value by D displaces the \
                      state (u, v/Omega) by D along a fixed seeded unit direction over the free \
                      dofs, at the start of the next step (the start value displaces the \
                      initial state)",
        start: 0.0,
        range: Range::ANY,
    },
];

/// Indices of the parameters every scene has, in [`ParamValues`] and the scene's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Std {
    E = 0,
    Nu,
    Rho,
    Damping,
    Width,
    Height,
    Span,
    Elements,
    DtMax,
    Integrator,
}

/// Value references of scene-declared parameters start here (the standard ones use 0..100).
pub const SCENE_PARAM_VR: u32 = 100;

/// Names that a scene may not declare (standard parameters and outputs, reserved names).
pub fn is_standard_name(name: &str) -> bool {
    ALWAYS
        .iter()
        .chain(&HARMONIC)
        .chain([&RISE, &BRANCH])
        .chain(&ANALYSIS)
        .any(|s| s.name == name)
}

/// Which optional standard parameters a scene has.
pub struct Needs {
    pub harmonic: bool,
    pub arc: bool,
    pub branch: bool,
}

fn param_of(s: &Standard) -> Param {
    Param {
        name: s.name.to_string(),
        vr: s.vr,
        var_type: s.var_type,
        variability: s.variability,
        unit: s.unit.map(str::to_string),
        description: s.description.to_string(),
        start: s.start,
        range: s.range,
    }
}

/// The standard parameters of a scene with these needs, in table order.
pub fn standard_params(needs: &Needs) -> Vec<Param> {
    let mut params: Vec<Param> = ALWAYS.iter().map(param_of).collect();
    if needs.arc {
        params.push(param_of(&RISE));
    }
    if needs.harmonic {
        params.extend(HARMONIC.iter().map(param_of));
    }
    if needs.branch {
        params.push(param_of(&BRANCH));
    }
    params.extend(ANALYSIS.iter().map(param_of));
    params
}

/// The names of the standard parameters a `[defaults]` table may set.
pub fn default_settable(name: &str) -> bool {
    (ALWAYS.iter().chain(&HARMONIC).any(|s| s.name == name) && name != "L")
        || name == LYAPUNOV
        || name == LYAPUNOV_START
        || name == LYAPUNOV_ALIGN
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

    #[test]
    fn the_always_table_matches_std() {
        let names: Vec<&str> = ALWAYS.iter().map(|s| s.name).collect();
        assert_eq!(names[Std::E as usize], "E");
        assert_eq!(names[Std::Damping as usize], "d");
        assert_eq!(names[Std::Span as usize], "L");
        assert_eq!(names[Std::Elements as usize], ELEMENTS);
        assert_eq!(names[Std::DtMax as usize], "dt_max");
        assert_eq!(names[Std::Integrator as usize], INTEGRATOR);
    }
}
