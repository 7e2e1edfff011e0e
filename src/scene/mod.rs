//! A scene is data: one TOML file (format in `docs/scenes.md`) says what the rod is (geometry,
//! material, mesh), how it is held (supports, fixed or prescribed or moved by an input), what
//! acts on it (point and distributed loads: constant, harmonic or an FMI input), what is
//! measured (sensors, shape samples, support reactions) and where it starts (static equilibrium
//! or the reference state). [`Scene::parse`] checks a file completely, with messages that name
//! the file, the key and what is allowed; the packager, the core and the FMU all read scenes
//! through it.
pub mod attached;
mod check;
mod checker;
mod claims;
pub mod damping;
mod file;
pub mod frame;
mod frame_check;
mod frame_mechanism;
mod frame_mesh;
mod frame_outputs;
mod frame_read;
mod items;
mod load_kinds;
mod mechanics;
mod param_tables;
pub mod params;
pub mod quantity;
pub mod readouts;
pub mod sections;
pub mod stops;
mod syntax;
pub mod variable_kinds;
pub mod variables;

pub use params::{Param, ParamError, ParamValues, Range, Std, VarType, Variability};
pub use quantity::{Quantity, Reading, SectionQuantity};

use std::fmt;
use std::path::Path;

/// Degrees of freedom of a node, in the order of the global vectors.
pub const DOF_NAMES: [&str; 3] = ["u1", "u2", "w"];

/// Why a scene file was refused: the file, the key and what is allowed.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    pub file: String,
    pub key: String,
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.key.is_empty() {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}: {}: {}", self.file, self.key, self.message)
        }
    }
}

impl std::error::Error for SceneError {}

/// The default experiment of the FMU.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DefaultExperiment {
    pub start: f64,
    pub stop: f64,
    pub step: f64,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Geometry {
    /// Along `e1` from `(0, 0)` to `(L, 0)`.
    Straight,
    /// Circular arc from `(0, 0)` to `(L, 0)` through the crown `(L/2, H)`.
    Arc,
    /// Members between joints (`[[joint]]`, `[[member]]`): [`Scene::frame`].
    Frame,
}

/// A number or a (possibly negated) parameter, as written in a value slot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Slot {
    Number(f64),
    Param { index: usize, sign: f64 },
}

impl Slot {
    pub fn eval(&self, values: &ParamValues) -> f64 {
        match *self {
            Slot::Number(x) => x,
            Slot::Param { index, sign } => sign * values.get(index),
        }
    }
}

/// Where an item sits: on a member at a fraction of its arc length (a scene without joints:
/// member 0, the rod), or at a joint of a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Station {
    On { member: usize, at: f64 },
    Joint(usize),
}

impl Station {
    /// The fraction of the arc length on member 0 (a scene without joints).
    pub fn fraction(&self) -> f64 {
        match *self {
            Station::On { at, .. } => at,
            Station::Joint(_) => f64::NAN,
        }
    }

    /// Whether two stations are one place (within 1e-12 of a member's length).
    pub fn same(&self, other: &Station) -> bool {
        match (self, other) {
            (Station::On { member: a, at: x }, Station::On { member: b, at: y }) => {
                a == b && (x - y).abs() < 1e-12
            }
            (Station::Joint(a), Station::Joint(b)) => a == b,
            _ => false,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Support {
    pub name: String,
    pub at: Station,
    /// The frame of `fixed` and `displace`: degrees counter-clockwise from e1 (0: e1, e2).
    pub angle: f64,
    /// Which of `u1, u2, w` are held.
    pub fixed: [bool; 3],
    /// The prescribed value of each held dof (0 unless `displace` says otherwise).
    pub displace: [Slot; 3],
    /// The held dofs follow FMI inputs `<name>_<dof>`.
    pub motion: bool,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LoadKind {
    Point {
        at: Station,
    },
    /// Per unit length over the whole rod, uniform (a scene without joints).
    Distributed,
    /// Per unit length over the stations `[from, to]` of `member`, varying linearly from the
    /// load's value to `value_end` (`None`: uniform).
    Patch {
        member: usize,
        from: f64,
        to: f64,
        value_end: Option<Slot>,
    },
    /// A point couple about e3 (counter-clockwise positive); its direction is the rotation dof.
    Moment {
        at: Station,
    },
    /// An acceleration (the load's value) on the rod's mass: `value rho A` per unit length.
    Gravity,
    /// A point force entering at station 0 at the time `enter` and travelling along the arc
    /// length at `speed` (both slots of fixed parameters or numbers).
    Moving {
        speed: Slot,
        enter: Slot,
    },
}

/// A fixed direction: `component` 0 (`e1`) or 1 (`e2`), or 2 (the rotation, for moments), or
/// [`NORMAL`] (a member's normal in its reference state: its chord turned by 90 degrees
/// counter-clockwise), `sign` +1 or -1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Direction {
    pub component: usize,
    pub sign: f64,
}

/// The direction component of a member's normal.
pub const NORMAL: usize = 3;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeLaw {
    Constant,
    /// `value cos(Omega t)`.
    Harmonic,
    /// The FMI input of the scene's input list with this index, held over a communication step.
    Input(usize),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Load {
    pub name: String,
    pub kind: LoadKind,
    pub direction: Direction,
    /// Magnitude (for inputs: 1, the input is the magnitude).
    pub value: Slot,
    pub time: TimeLaw,
    /// A moving load's route: members travelled end to end (a scene without joints: `[0]`).
    pub path: Vec<usize>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Sensor {
    pub name: String,
    pub at: Station,
    pub quantity: Quantity,
    pub description: String,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InitialState {
    /// The static equilibrium under the constant loads and prescribed displacements.
    Static,
    /// The undeformed reference state, at rest.
    Reference,
}

/// The branch choice of the initial static state: the equilibrium in which `sensor` has the
/// sign of the parameter `well`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Branch {
    pub sensor: usize,
    pub well_param: usize,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Initial {
    pub state: InitialState,
    pub branch: Option<Branch>,
}

/// What an FMI input drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputKind {
    /// The magnitude of load `i`.
    Load(usize),
    /// The prescribed value of dof `dof` of support `support`.
    Motion { support: usize, dof: usize },
    /// The base (far end) of spring `i`.
    SpringBase(usize),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Input {
    pub name: String,
    pub kind: InputKind,
    pub start: Slot,
    pub unit: Option<String>,
    pub description: String,
}

/// Departures from the specified model (`[model]`), for studies; the defaults are the model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelOptions {
    /// Lumped (diagonal) instead of consistent mass and damping matrices.
    pub lumped_mass: bool,
    /// `GA` is multiplied by this (1: no shear correction factor).
    pub shear_factor: f64,
    /// Viscous damping per unit length on the rotations (0: translations only).
    pub rotational_damping: f64,
}

impl Default for ModelOptions {
    fn default() -> Self {
        ModelOptions {
            lumped_mass: false,
            shear_factor: 1.0,
            rotational_damping: 0.0,
        }
    }
}

/// A checked scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub name: String,
    pub description: String,
    pub experiment: DefaultExperiment,
    pub geometry: Geometry,
    /// Standard parameters first (indices of [`Std`]), then the optional standard ones, then
    /// the scene's own.
    pub params: Vec<Param>,
    pub supports: Vec<Support>,
    pub loads: Vec<Load>,
    pub sensors: Vec<Sensor>,
    pub inputs: Vec<Input>,
    /// Number of shape samples (0: none).
    pub shape_points: usize,
    /// Quantities read at the shape samples besides the position (`[shape] fields`).
    pub shape_fields: Vec<Quantity>,
    /// Natural frequencies of the initial state reported as `frequency[k]` (`[modes] count`).
    pub modes: usize,
    pub initial: Initial,
    pub model: ModelOptions,
    /// The cross section: its shape and the parameters of its dimensions.
    pub section: sections::CrossSection,
    /// Rayleigh damping (`[damping]`), added to `d`.
    pub rayleigh: Option<damping::Rayleigh>,
    pub masses: Vec<attached::PointMass>,
    pub springs: Vec<attached::Spring>,
    pub foundations: Vec<attached::Foundation>,
    /// One-sided supports (`[[stop]]`).
    pub stops: Vec<stops::Stop>,
    /// The joints, members and links of a frame (`None`: one rod, `[geometry]`).
    pub frame: Option<frame::Frame>,
    /// The file's text, exactly as read (what an FMU carries in `resources/`).
    pub source: String,
}

impl Scene {
    /// Checks a scene file's text; `origin` names it in messages.
    pub fn parse(text: &str, origin: &str) -> Result<Scene, SceneError> {
        check::check(text, origin)
    }

    /// Reads and checks a scene file.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let origin = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| SceneError {
            file: origin.clone(),
            key: String::new(),
            message: format!("cannot read the scene file: {e}"),
        })?;
        Scene::parse(&text, &origin)
    }

    pub fn param_index(&self, name: &str) -> Option<usize> {
        self.params.iter().position(|p| p.name == name)
    }

    /// The parameter named `name`, or an error naming the parameters there are.
    pub fn param(&self, name: &str) -> Result<(usize, &Param), ParamError> {
        self.param_index(name)
            .map(|i| (i, &self.params[i]))
            .ok_or_else(|| {
                let names: Vec<&str> = self.params.iter().map(|p| p.name.as_str()).collect();
                params::refuse(
                    name,
                    format!(
                        "not a parameter of the {} scene (it has: {})",
                        self.name,
                        names.join(", ")
                    ),
                )
            })
    }

    /// The start values of every parameter.
    pub fn defaults(&self) -> ParamValues {
        ParamValues(self.params.iter().map(|p| p.start).collect())
    }

    /// The start values with some parameters overridden by name, checked.
    pub fn values_with<'a>(
        &self,
        overrides: impl IntoIterator<Item = (&'a str, f64)>,
    ) -> Result<ParamValues, ParamError> {
        let mut values = self.defaults();
        for (name, value) in overrides {
            self.set(&mut values, name, value)?;
        }
        self.check(&values)?;
        Ok(values)
    }

    /// Sets one parameter by name after checking its own range (conditions between parameters
    /// are checked by [`Scene::check`]). On error nothing changes.
    pub fn set(&self, values: &mut ParamValues, name: &str, value: f64) -> Result<(), ParamError> {
        let (index, param) = self.param(name)?;
        param.check(value)?;
        values.0[index] = value;
        Ok(())
    }

    /// Every range, the conditions between parameters (an arc's rise, a tube's wall, a moving
    /// load's speed), and that `elements` puts every station on a node.
    pub fn check(&self, values: &ParamValues) -> Result<(), ParamError> {
        for (param, &value) in self.params.iter().zip(&values.0) {
            param.check(value)?;
        }
        if let Some(rise) = self.param_index("H") {
            let (h, span) = (values.get(rise), values.std(Std::Span));
            if h > 0.5 * span {
                return Err(params::refuse(
                    "H",
                    format!(
                        "{h} is out of range: must be in (0, L/2] = (0, {}]",
                        0.5 * span
                    ),
                ));
            }
        }
        self.section.check(values)?;
        for m in self.frame.iter().flat_map(|f| &f.members) {
            if let Some(own) = &m.section {
                own.check(&m.name, values)?;
            }
        }
        for l in &self.loads {
            if let LoadKind::Moving {
                speed: Slot::Param { index, sign },
                ..
            } = l.kind
            {
                let v = sign * values.get(index);
                if v <= 0.0 {
                    return Err(params::refuse(
                        &self.params[index].name,
                        format!("the speed of moving load `{}` is {v}: must be > 0", l.name),
                    ));
                }
            }
        }
        self.check_mesh(values.elements())
    }

    /// The stations of the rod (member 0 of a scene without joints) that are nodes of every
    /// mesh: see [`Scene::member_stations`].
    pub fn mesh_stations(&self) -> Vec<f64> {
        self.member_stations(0)
    }

    /// Whether `elements` can put every station on a node (one element per segment at least);
    /// if not, the error says which counts work.
    pub fn check_mesh(&self, elements: usize) -> Result<(), ParamError> {
        let (lo, hi) = self.element_range();
        if (lo..=hi).contains(&elements) {
            return Ok(());
        }
        let segments = self.shared_segments();
        Err(params::refuse(
            params::ELEMENTS,
            format!(
                "{elements} is out of range: must be in [{lo}, {hi}] (the {segments} segments \
                 between the ends and the stations of the supports, masses and springs need one \
                 element each at least)"
            ),
        ))
    }

    /// The fewest and the most elements: one per segment between the stations (at least
    /// [`MIN_ELEMENTS`]) up to [`MAX_ELEMENTS`]; every count between works.
    pub fn element_range(&self) -> (usize, usize) {
        (self.shared_segments().max(MIN_ELEMENTS), MAX_ELEMENTS)
    }
}

/// The widest range of `elements` (a scene declares the part of it its supports allow).
pub const MIN_ELEMENTS: usize = 2;
pub const MAX_ELEMENTS: usize = 100_000;
