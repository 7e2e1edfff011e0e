//! `[section]`: the cross section's shape and dimensions. A rectangle (`b`, `h`, the default,
//! whose dimensions may also stay in `[defaults]`), a circle (`D`), a tube (`D`, `t`) or a
//! general section (`A`, `I`, `As`, and `depth` for stresses). Each dimension becomes a fixed
//! parameter of the FMU with that name; only the shape's own are declared.
use super::checker::Checker;
use super::file::SectionFile;
use super::params::{self, Param, ParamError, ParamValues, Range, VarType, Variability};
use super::SceneError;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SectionShape {
    Rectangle,
    Circle,
    Tube,
    General,
}

impl SectionShape {
    const NAMES: [&'static str; 4] = ["rectangle", "circle", "tube", "general"];

    /// The dimensions' names, in the order of [`CrossSection::dims`]; the optional ones last.
    fn dimensions(self) -> &'static [&'static str] {
        match self {
            SectionShape::Rectangle => &["b", "h"],
            SectionShape::Circle => &["D"],
            SectionShape::Tube => &["D", "t"],
            SectionShape::General => &["A", "I", "As", "depth"],
        }
    }
}

/// The scene's section: its shape, the parameter indices of its dimensions, and the shear
/// factor of the shapes with dimensions (`As = shear_factor A`).
#[derive(Clone, Debug, PartialEq)]
pub struct CrossSection {
    pub shape: SectionShape,
    /// Indices in the scene's parameter table, in the order of the shape's dimensions (a
    /// general section without `depth` has three).
    pub dims: Vec<usize>,
}

/// Area, second moment of area and shear area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Properties {
    pub area: f64,
    pub inertia: f64,
    pub shear_area: f64,
}

impl CrossSection {
    fn dim(&self, values: &ParamValues, k: usize) -> f64 {
        values.get(self.dims[k])
    }

    /// The rectangle's `(b, h)`, or `None` for another shape.
    pub fn rectangle(&self, values: &ParamValues) -> Option<(f64, f64)> {
        (self.shape == SectionShape::Rectangle).then(|| (self.dim(values, 0), self.dim(values, 1)))
    }

    /// Area, second moment of area and shear area (before the shear factor of `[model]` or
    /// `[section]`, which the caller applies to the shapes with dimensions).
    pub fn properties(&self, values: &ParamValues) -> Properties {
        shape_properties(self.shape, &|k| self.dim(values, k))
    }

    /// The distance between the extreme fibers, where a shape has one (a general section only
    /// with `depth`).
    pub fn depth(&self, values: &ParamValues) -> Option<f64> {
        shape_depth(self.shape, self.dims.len(), &|k| self.dim(values, k))
    }
}

/// A frame member's own section: its shape, its dimensions as fixed FMU parameters named
/// `<member>_<dimension>` (`column_h`, `brace_D`, ...: a host or a sweep varies one member's
/// section), and its shear factor.
#[derive(Clone, Debug, PartialEq)]
pub struct MemberSection {
    pub shape: SectionShape,
    /// The dimensions the file gives, in the order of the shape's dimensions (the parameters'
    /// start values).
    pub given: Vec<f64>,
    /// Their indices in the scene's parameter table ([`member_parameters`]).
    pub dims: Vec<usize>,
    /// `As = shear_factor A` (1 when not given; a general section gives `As`).
    pub shear_factor: f64,
}

impl MemberSection {
    fn dim(&self, values: &ParamValues, k: usize) -> f64 {
        values.get(self.dims[k])
    }

    pub fn properties(&self, values: &ParamValues) -> Properties {
        shape_properties(self.shape, &|k| self.dim(values, k))
    }

    pub fn depth(&self, values: &ParamValues) -> Option<f64> {
        shape_depth(self.shape, self.dims.len(), &|k| self.dim(values, k))
    }

    /// A tube's wall thinner than its radius, for member `member`.
    pub fn check(&self, member: &str, values: &ParamValues) -> Result<(), ParamError> {
        if self.shape == SectionShape::Tube {
            let (outer, wall) = (self.dim(values, 0), self.dim(values, 1));
            if wall >= 0.5 * outer {
                return Err(params::refuse(
                    &format!("{member}_t"),
                    format!(
                        "{wall} is out of range: a tube's wall must be thinner than its radius, \
                         t in (0, D/2) = (0, {})",
                        0.5 * outer
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Value references of the members' section dimensions: `MEMBER_SECTION_VR + 4 m + k` for
/// dimension `k` of member `m`.
pub const MEMBER_SECTION_VR: u32 = 1_600_000;
/// The most members a frame may have (their section parameters' value references).
pub const MAX_MEMBERS: usize = 25_000;

/// Appends the dimensions of every member's own section to the parameter table as
/// `<member>_<dimension>` and points each section at them.
pub(super) fn member_parameters(members: &mut [super::frame::Member], params: &mut Vec<Param>) {
    for (m, member) in members.iter_mut().enumerate() {
        let Some(section) = &mut member.section else {
            continue;
        };
        section.dims.clear();
        let names = section.shape.dimensions();
        for (k, (name, &start)) in names.iter().zip(&section.given).enumerate() {
            let mut p = dimension_param(name, start);
            p.name = format!("{}_{name}", member.name);
            p.vr = MEMBER_SECTION_VR + 4 * m as u32 + k as u32;
            p.description = format!("{} (member {})", p.description, member.name);
            section.dims.push(params.len());
            params.push(p);
        }
    }
}

fn shape_depth(shape: SectionShape, count: usize, d: &dyn Fn(usize) -> f64) -> Option<f64> {
    match shape {
        SectionShape::Rectangle => Some(d(1)),
        SectionShape::Circle | SectionShape::Tube => Some(d(0)),
        SectionShape::General => (count == 4).then(|| d(3)),
    }
}

fn shape_properties(shape: SectionShape, d: &dyn Fn(usize) -> f64) -> Properties {
    {
        use std::f64::consts::PI;
        let (area, inertia) = match shape {
            SectionShape::Rectangle => (d(0) * d(1), d(0) * d(1).powi(3) / 12.0),
            SectionShape::Circle => (PI * d(0).powi(2) / 4.0, PI * d(0).powi(4) / 64.0),
            SectionShape::Tube => {
                let inner = d(0) - 2.0 * d(1);
                (
                    PI * (d(0).powi(2) - inner.powi(2)) / 4.0,
                    PI * (d(0).powi(4) - inner.powi(4)) / 64.0,
                )
            }
            SectionShape::General => {
                return Properties {
                    area: d(0),
                    inertia: d(1),
                    shear_area: d(2),
                }
            }
        };
        Properties {
            area,
            inertia,
            shear_area: area,
        }
    }
}

impl CrossSection {
    /// The conditions between dimensions: a tube's wall thinner than its radius.
    pub fn check(&self, values: &ParamValues) -> Result<(), ParamError> {
        if self.shape == SectionShape::Tube {
            let (outer, wall) = (self.dim(values, 0), self.dim(values, 1));
            if wall >= 0.5 * outer {
                return Err(params::refuse(
                    "t",
                    format!(
                        "{wall} is out of range: a tube's wall must be thinner than its radius, \
                         t in (0, D/2) = (0, {}) (a solid bar is shape = \"circle\")",
                        0.5 * outer
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Value references of the dimensions (`b`, `h` keep those of the former standard parameters).
fn vr(name: &str) -> u32 {
    match name {
        "b" => 4,
        "h" => 5,
        "D" => 20,
        "t" => 21,
        "A" => 22,
        "I" => 23,
        "As" => 24,
        _ => 25, // depth
    }
}

fn dimension_param(name: &str, start: f64) -> Param {
    let (unit, description) = match name {
        "b" => ("m", "Width of the rectangular cross section"),
        "h" => (
            "m",
            "Height of the rectangular cross section (in the plane of motion)",
        ),
        "D" => ("m", "Outer diameter of the circular section"),
        "t" => ("m", "Wall thickness of the tube, in (0, D/2)"),
        "A" => ("m2", "Cross-section area"),
        "I" => ("m4", "Second moment of area about the bending axis"),
        "As" => ("m2", "Shear area (GA_s is the shear stiffness)"),
        _ => (
            "m",
            "Depth of the section: distance between its extreme fibers",
        ),
    };
    Param {
        name: name.to_string(),
        vr: vr(name),
        var_type: VarType::Real,
        variability: Variability::Fixed,
        unit: Some(unit.to_string()),
        description: description.to_string(),
        start,
        range: Range::positive(),
    }
}

/// The names a scene may not declare as its own parameters.
pub fn is_dimension_name(name: &str) -> bool {
    ["b", "h", "D", "t", "A", "I", "As", "depth"].contains(&name)
}

/// The checked `[section]`: its shape, the dimensions' parameters (to be placed at `first` in
/// the parameter table), and the shear factor it gives, if any. A rectangle's `b`, `h` may come
/// from `[defaults]` instead (`from_defaults`), and default to 1.
/// A member's `section = { ... }`: the keys of `[section]`, dimensions as numbers.
pub(super) fn member_section(
    c: &Checker,
    raw: &SectionFile,
    key: &str,
) -> Result<MemberSection, SceneError> {
    let none = |_: &str| Ok(None);
    let nested = Checker { file: c.file };
    let (section, params, factor) = section(&nested, Some(raw), &none, 0).map_err(|mut e| {
        e.key = e.key.replacen("section", key, 1);
        e
    })?;
    if section.shape == SectionShape::Rectangle && (raw.b.is_none() || raw.h.is_none()) {
        return c.err(key, "a member's rectangle gives both b and h");
    }
    let dims: Vec<f64> = params.iter().map(|p| p.start).collect();
    if section.shape == SectionShape::Tube && dims[1] >= 0.5 * dims[0] {
        return c.err(
            format!("{key}.t"),
            format!(
                "{} is out of range: a tube's wall must be thinner than its radius, t in (0, D/2)",
                dims[1]
            ),
        );
    }
    Ok(MemberSection {
        shape: section.shape,
        given: dims,
        dims: Vec::new(),
        shear_factor: factor.unwrap_or(1.0),
    })
}

pub(super) fn section(
    c: &Checker,
    raw: Option<&SectionFile>,
    from_defaults: &dyn Fn(&str) -> Result<Option<f64>, SceneError>,
    first: usize,
) -> Result<(CrossSection, Vec<Param>, Option<f64>), SceneError> {
    let empty = SectionFile::default();
    let raw = raw.unwrap_or(&empty);
    let shape = match raw.shape.as_deref() {
        None => SectionShape::Rectangle,
        Some(s) => {
            let all = [
                SectionShape::Rectangle,
                SectionShape::Circle,
                SectionShape::Tube,
                SectionShape::General,
            ];
            all[c.one_of(s, &SectionShape::NAMES, "section.shape")?]
        }
    };
    let names = shape.dimensions();
    let given = raw.dimensions();
    if let Some((name, _)) = given
        .iter()
        .find(|(n, v)| v.is_some() && !names.contains(n))
    {
        return c.err(
            format!("section.{name}"),
            format!(
                "not a dimension of shape = \"{}\" (its dimensions: {})",
                SectionShape::NAMES[shape as usize],
                names.join(", ")
            ),
        );
    }
    let mut params = Vec::new();
    for &name in names {
        let key = format!("section.{name}");
        let in_section = given.iter().find(|(n, _)| *n == name).and_then(|g| g.1);
        let start = match (in_section, shape) {
            (Some(x), SectionShape::Rectangle) => {
                if from_defaults(name)?.is_some() {
                    return c.err(
                        key,
                        "given twice: in [section] and in [defaults] (keep one)",
                    );
                }
                x
            }
            (Some(x), _) => x,
            (None, SectionShape::Rectangle) => from_defaults(name)?.unwrap_or(1.0),
            (None, SectionShape::General) if name == "depth" => continue,
            (None, _) => {
                return c.err(
                    key,
                    format!(
                        "missing: shape = \"{}\" needs {}",
                        SectionShape::NAMES[shape as usize],
                        names.join(", ")
                    ),
                )
            }
        };
        let param = dimension_param(name, start);
        if let Err(e) = param.check(start) {
            return c.err(key, e.message);
        }
        params.push(param);
    }
    let section = CrossSection {
        shape,
        dims: (first..first + params.len()).collect(),
    };
    let factor = match raw.shear_factor {
        None => None,
        Some(_) if shape == SectionShape::General => {
            return c.err(
                "section.shear_factor",
                "a general section gives its shear area As directly: no shear_factor",
            )
        }
        Some(k) if k.is_finite() && k > 0.0 => Some(k),
        Some(k) => {
            return c.err(
                "section.shear_factor",
                format!("{k} is out of range: must be > 0"),
            )
        }
    };
    Ok((section, params, factor))
}
