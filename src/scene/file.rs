//! The scene file as written (TOML), before any check beyond types and key names. Every table
//! refuses unknown keys; value slots (`value`, `displace`) stay raw TOML values here so that a
//! wrong type can be reported with the key it sits under.
use serde::Deserialize;
use std::collections::BTreeMap;

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub name: Option<String>,
    #[serde(default)]
    pub description: String,
    pub experiment: Option<ExperimentFile>,
    pub geometry: Option<GeometryFile>,
    #[serde(default)]
    pub defaults: BTreeMap<String, toml::Value>,
    #[serde(default)]
    pub parameter: Vec<ParameterFile>,
    #[serde(default)]
    pub support: Vec<SupportFile>,
    #[serde(default)]
    pub load: Vec<LoadFile>,
    #[serde(default)]
    pub sensor: Vec<SensorFile>,
    pub shape: Option<ShapeFile>,
    pub initial: Option<InitialFile>,
    pub model: Option<ModelFile>,
    pub modes: Option<ModesFile>,
    pub section: Option<SectionFile>,
    pub damping: Option<DampingFile>,
    #[serde(default)]
    pub mass: Vec<MassFile>,
    #[serde(default)]
    pub spring: Vec<SpringFile>,
    #[serde(default)]
    pub foundation: Vec<FoundationFile>,
    #[serde(default)]
    pub stop: Vec<StopFile>,
    #[serde(default)]
    pub joint: Vec<JointFile>,
    #[serde(default)]
    pub member: Vec<MemberFile>,
    #[serde(default)]
    pub link: Vec<LinkFile>,
}

/// A joint of a frame: where member ends meet.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct JointFile {
    pub name: Option<String>,
    pub x: Option<f64>,
    pub y: Option<f64>,
}

/// A member of a frame: a rod (or a truss bar) between two joints.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct MemberFile {
    pub name: Option<String>,
    pub from: Option<String>,
    pub to: Option<String>,
    pub shape: Option<String>,
    #[serde(rename = "H")]
    pub rise: Option<f64>,
    pub elements: Option<i64>,
    pub section: Option<SectionFile>,
    pub hinges: Option<Vec<String>>,
    pub kind: Option<String>,
}

/// A spring and dashpot between two points of a frame.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct LinkFile {
    pub name: Option<String>,
    pub from: Option<toml::Value>,
    pub to: Option<toml::Value>,
    pub k: Option<f64>,
    pub c: Option<f64>,
    pub length: Option<f64>,
}

/// Natural frequencies of the initial state.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct ModesFile {
    pub count: Option<i64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct MassFile {
    pub name: Option<String>,
    pub at: Option<f64>,
    pub joint: Option<String>,
    pub member: Option<String>,
    pub m: Option<f64>,
    #[serde(rename = "J")]
    pub rotary: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct SpringFile {
    pub name: Option<String>,
    pub at: Option<f64>,
    pub joint: Option<String>,
    pub member: Option<String>,
    pub dof: Option<String>,
    pub k: Option<f64>,
    pub c: Option<f64>,
    pub motion: Option<String>,
    pub k3: Option<f64>,
}

/// A one-sided support (`docs/scenes.md`, `[[stop]]`).
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct StopFile {
    pub name: Option<String>,
    pub at: Option<f64>,
    pub joint: Option<String>,
    pub member: Option<String>,
    pub dof: Option<String>,
    pub side: Option<String>,
    pub gap: Option<f64>,
    pub k: Option<f64>,
    pub c: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct FoundationFile {
    pub name: Option<String>,
    pub member: Option<String>,
    pub k: Option<f64>,
    pub c: Option<f64>,
    pub from: Option<f64>,
    pub to: Option<f64>,
}

/// Rayleigh damping: coefficients, or a ratio at two frequencies.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct DampingFile {
    pub alpha: Option<f64>,
    pub beta: Option<f64>,
    pub ratio: Option<f64>,
    pub frequencies: Option<Vec<f64>>,
}

/// The cross section: a shape and its dimensions.
#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
pub struct SectionFile {
    pub shape: Option<String>,
    pub b: Option<f64>,
    pub h: Option<f64>,
    #[serde(rename = "D")]
    pub diameter: Option<f64>,
    pub t: Option<f64>,
    #[serde(rename = "A")]
    pub area: Option<f64>,
    #[serde(rename = "I")]
    pub inertia: Option<f64>,
    #[serde(rename = "As")]
    pub shear_area: Option<f64>,
    pub depth: Option<f64>,
    pub shear_factor: Option<f64>,
}

impl SectionFile {
    /// Every dimension key with its value, if given.
    pub fn dimensions(&self) -> [(&'static str, Option<f64>); 8] {
        [
            ("b", self.b),
            ("h", self.h),
            ("D", self.diameter),
            ("t", self.t),
            ("A", self.area),
            ("I", self.inertia),
            ("As", self.shear_area),
            ("depth", self.depth),
        ]
    }
}

/// Departures from the specified model, for studies.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct ModelFile {
    pub mass: Option<String>,
    pub shear_factor: Option<f64>,
    pub rotational_damping: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct ExperimentFile {
    pub start: Option<f64>,
    pub stop: Option<f64>,
    pub step: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct GeometryFile {
    pub shape: Option<String>,
    #[serde(rename = "L")]
    pub span: Option<f64>,
    #[serde(rename = "H")]
    pub rise: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct ParameterFile {
    pub name: Option<String>,
    pub start: Option<f64>,
    pub unit: Option<String>,
    pub variability: Option<String>,
    #[serde(default)]
    pub description: String,
    pub min: Option<f64>,
    pub max: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct SupportFile {
    pub name: Option<String>,
    pub at: Option<f64>,
    pub joint: Option<String>,
    pub member: Option<String>,
    /// Degrees, counter-clockwise from e1: the frame of `fix` and `displace`.
    pub angle: Option<f64>,
    pub fix: Option<Vec<String>>,
    #[serde(default)]
    pub displace: BTreeMap<String, toml::Value>,
    pub motion: Option<String>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct LoadFile {
    pub name: Option<String>,
    pub kind: Option<String>,
    pub at: Option<f64>,
    pub joint: Option<String>,
    pub member: Option<String>,
    /// A moving load's route: members end to end.
    pub path: Option<Vec<String>>,
    pub from: Option<f64>,
    pub to: Option<f64>,
    pub value_end: Option<toml::Value>,
    /// A moving load's speed (m/s) and entry time (s): value slots.
    pub speed: Option<toml::Value>,
    pub enter: Option<toml::Value>,
    pub direction: Option<String>,
    pub value: Option<toml::Value>,
    pub time: Option<String>,
    /// Start value of an input load (`time = "input"`), default 0.
    pub start: Option<f64>,
    #[serde(default)]
    pub description: String,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct SensorFile {
    pub name: Option<String>,
    pub at: Option<f64>,
    pub joint: Option<String>,
    pub member: Option<String>,
    pub quantity: Option<String>,
    #[serde(default)]
    pub description: String,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct ShapeFile {
    pub points: Option<i64>,
    /// Quantities read at the shape points (`shape_<field>[i]`).
    #[serde(default)]
    pub fields: Vec<String>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct InitialFile {
    pub state: Option<String>,
    pub branch: Option<String>,
    pub branch_sensor: Option<String>,
}
