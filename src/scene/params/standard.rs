//! The standard parameters: those every scene has (material, section, span, mesh, step,
//! integrator: the indices of [`Std`]), those a scene's contents bring (`F`, `Omega`, `H`,
//! `well`), and the analysis parameters (Lyapunov exponents, perturbation), with their value
//! references, units, descriptions, start values and ranges.
use super::{Param, Range, VarType, Variability};

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
const ALWAYS: [Standard; 8] = [
    real("E", 0, "Pa", "Young's modulus", 1.2e4, Range::positive()),
    real(
        "nu",
        1,
        "1",
        "Poisson's ratio (shear modulus G = E / (2 (1 + nu)))",
        // A metal's, not the paper's 0.2: a user's scene that says nothing gets no paper value
        // (the paper's scenes state theirs).
        0.3,
        // The open interval of an isotropic material (docs/scenes.md): nu = -1 makes G infinite.
        Range::open(-1.0, 0.5),
    ),
    real("rho", 2, "kg/m3", "Mass density", 1.0e-6, Range::positive()),
    real(
        "d",
        3,
        "N.s/m2",
        "Viscous damping per unit length, acting on the translations only",
        // Undamped unless the scene says so (the paper's 5e-4 is stated in its scenes).
        0.0,
        Range::at_least(0.0),
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
        description: "Number of finite elements (spread over the segments between the supports)",
        start: 10.0,
        // Narrowed per scene to one element per segment at least (`Scene::element_range`).
        range: Range::between(
            crate::scene::MIN_ELEMENTS as f64,
            crate::scene::MAX_ELEMENTS as f64,
        ),
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
        // An Integer, not an Enumeration: libcosim (and other FMI 2.0 hosts) cannot set an
        // Enumeration variable; the description names the values.
        var_type: VarType::Integer,
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

/// Indices of the parameters every scene has, in [`ParamValues`](super::ParamValues) and the
/// scene's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Std {
    E = 0,
    Nu,
    Rho,
    Damping,
    Span,
    Elements,
    DtMax,
    Integrator,
}

/// Where the section's dimensions go in a scene's parameter table: right after the parameters
/// every scene has.
pub const SECTION_AT: usize = Std::Integrator as usize + 1;

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

/// The names of the standard parameters a `[defaults]` table may set (and a rectangle's `b`,
/// `h`).
pub fn default_settable(name: &str) -> bool {
    (ALWAYS.iter().chain(&HARMONIC).any(|s| s.name == name) && name != "L")
        || name == "b"
        || name == "h"
        || name == LYAPUNOV
        || name == LYAPUNOV_START
        || name == LYAPUNOV_ALIGN
}

#[cfg(test)]
mod tests {
    use super::*;

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
