//! From a scene and its parameter values to the model: the meshed rod with its held degrees of
//! freedom, the loads (`setup_loads.rs`), and the points where sensors and shape samples read the state.
use crate::model::attachments::{Attachments, FoundationPart, OnDof};
use crate::model::mesh;
use crate::model::moving_loads::MovingLoads;
use crate::model::rod::{ROTATION, U1, U2};
use crate::model::{LoadSet, Place, ReferenceCurve, Rod, Section, Structure};
use crate::scene::{Geometry, ParamValues, Scene, Slot, Station, Std};

use super::setup_loads::load_shapes;
pub use super::setup_loads::{load_magnitudes, load_shape};
pub(super) use super::setup_loads::{moving_load, time_law};

/// A held (constrained) degree of freedom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Held {
    /// Global dof index (a direction hold: the node's `u1`).
    pub dof: usize,
    pub support: usize,
    /// 0 `u1`, 1 `u2`, 2 `w` (in the support's frame).
    pub component: usize,
    /// Its prescribed value in the initial state.
    pub value: Slot,
    /// The FMI input that moves it, if any.
    pub input: Option<usize>,
    /// A support at an angle that holds one translation: the unit vector it holds along.
    pub direction: Option<[f64; 2]>,
}

impl Held {
    /// The rows of the equations of motion that give its reaction: its dof, or both
    /// translations of its node for a direction.
    pub fn rows(&self) -> &'static [usize] {
        match self.direction {
            None => &[0],
            Some(_) => &[0, 1],
        }
    }

    /// Sets the held value in a displacement vector: the dof, or the component along the
    /// direction (the other left as it is).
    pub fn set(&self, u: &mut [f64], value: f64) {
        match self.direction {
            None => u[self.dof] = value,
            Some([n1, n2]) => {
                let (i, j) = (self.dof, self.dof + 1);
                let along = n1 * u[i] + n2 * u[j];
                u[i] += (value - along) * n1;
                u[j] += (value - along) * n2;
            }
        }
    }
}

/// A point of the structure where something is read.
pub type Probe = Place;

/// What each member of the scene is in the structure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MemberRole {
    /// A rod: the structure's member with this index.
    Rod(usize),
    /// A truss bar: the structure's axial element with this index.
    Bar(usize),
}

pub struct Setup {
    pub structure: Structure,
    pub loads: LoadSet,
    /// The node of each support, and its angle (radians).
    pub support_nodes: Vec<usize>,
    pub support_angles: Vec<f64>,
    pub held: Vec<Held>,
    pub sensors: Vec<Probe>,
    pub shape: Vec<Probe>,
    /// Every spring, for its force output (and its base's motion).
    pub springs: Vec<SpringOnRod>,
    /// Per member of the scene (a scene without joints: the rod).
    pub members: Vec<MemberRole>,
    /// The axial element of each link.
    pub links: Vec<usize>,
}

/// A spring and dashpot from a dof of the structure to its base.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpringOnRod {
    pub dof: usize,
    pub k: f64,
    pub c: f64,
    /// The cubic part of its force, `k3 (u - b)^3` (0: linear).
    pub k3: f64,
    /// The FMI input its base follows; `None`: the base stays at 0.
    pub base: Option<usize>,
}

/// The reference curve of a scene without joints with these values.
pub fn curve(scene: &Scene, values: &ParamValues) -> ReferenceCurve {
    let span = values.std(Std::Span);
    match scene.geometry {
        Geometry::Straight => ReferenceCurve::Straight { length: span },
        Geometry::Arc => {
            let rise = values.get(scene.param_index("H").expect("an arc has H"));
            ReferenceCurve::arc(span, rise)
        }
        Geometry::Frame => unreachable!("a frame's members have their own curves"),
    }
}

/// The scene's `[section]` with the material: its stiffnesses and inertias.
pub fn scene_section(scene: &Scene, values: &ParamValues) -> Section {
    let (e, nu, rho) = (
        values.std(Std::E),
        values.std(Std::Nu),
        values.std(Std::Rho),
    );
    let mut section = match scene.section.rectangle(values) {
        Some((b, h)) => Section::rectangular(e, nu, rho, b, h),
        None => {
            let p = scene.section.properties(values);
            Section::from_properties(e, nu, rho, p.area, p.inertia, p.shear_area)
        }
    };
    section.ga *= scene.model.shear_factor;
    section
}

/// Meshes the scene. The values must have passed [`Scene::check`] (enough elements).
pub fn setup(scene: &Scene, values: &ParamValues) -> Setup {
    let mut setup = match scene.frame {
        None => rod_setup(scene, values),
        Some(_) => super::setup_frame::frame_setup(scene, values),
    };
    super::contact::attach(scene, &mut setup);
    setup
}

/// A scene without joints: its rod.
fn rod_setup(scene: &Scene, values: &ParamValues) -> Setup {
    let section = scene_section(scene, values);
    let model = scene.model;
    let n = values.elements();
    let (curve, damping) = (curve(scene, values), values.std(Std::Damping));
    // Every station a node: the uniform mesh where the stations are its nodes, else the
    // elements spread over the segments between them.
    let mut rod = match mesh::node_fractions(&scene.mesh_stations(), n) {
        None => Rod::new(curve, section, damping, n),
        Some(fractions) => Rod::with_nodes(curve, section, damping, &fractions),
    };
    if model.lumped_mass {
        rod = rod.with_lumped_mass();
    }
    if model.rotational_damping > 0.0 {
        rod = rod.with_rotational_damping(model.rotational_damping);
    }
    let length = rod.curve.length();
    let attachments = attachments(scene, &rod, 0);
    if !attachments.is_empty() {
        rod = rod.with_attachments(attachments);
    }
    let mut support_nodes = Vec::new();
    let mut held = Vec::new();
    for (k, s) in scene.supports.iter().enumerate() {
        let node = rod.node_at(s.at.fraction() * length);
        support_nodes.push(node);
        held.extend(held_dofs(scene, k, 3 * node));
    }
    for h in held.iter().filter(|h| h.direction.is_none()) {
        rod.fix(h.dof / 3, h.component);
    }
    let shapes = load_shapes(scene, values, |at| at.fraction() * length, length);
    let springs: Vec<SpringOnRod> = (scene.springs.iter())
        .map(|s| SpringOnRod {
            dof: 3 * rod.node_at(s.at.fraction() * length) + s.dof,
            k: s.k,
            c: s.c,
            k3: s.k3,
            base: s.base,
        })
        .collect();
    let moving_bases: Vec<usize> = (springs.iter())
        .filter(|s| s.base.is_some())
        .map(|s| s.dof)
        .collect();
    let (shapes, moving) = shapes;
    let loads = LoadSet::new(&rod, &shapes)
        .with_moving(MovingLoads::new(&rod.node_s, moving))
        .with_base_forces(&moving_bases);
    let mut structure = Structure::single(rod);
    for h in held.iter().filter(|h| h.direction.is_none()) {
        structure.hold(h.dof);
    }
    for h in held
        .iter()
        .filter_map(|h| h.direction.map(|n| (h.dof / 3, n)))
    {
        structure.hold_direction(h.0, h.1);
    }
    let probe = |at: f64| structure.member_place(0, at * length);
    let sensors = scene
        .sensors
        .iter()
        .map(|s| probe(s.at.fraction()))
        .collect();
    let points = scene.shape_points;
    let shape = (0..points)
        .map(|j| probe(j as f64 / (points - 1).max(1) as f64))
        .collect();
    Setup {
        support_angles: scene
            .supports
            .iter()
            .map(|s| s.angle.to_radians())
            .collect(),
        structure,
        loads,
        support_nodes,
        held,
        sensors,
        shape,
        springs,
        members: vec![MemberRole::Rod(0)],
        links: Vec::new(),
    }
}

/// The held dofs of support `k` at the node whose first dof is `first`: its own dofs, or, at an
/// angle, a direction (one translation held) or both translations.
pub(super) fn held_dofs(scene: &Scene, k: usize, first: usize) -> Vec<Held> {
    let s = &scene.supports[k];
    let input = |c: usize| {
        (scene.inputs.iter())
            .position(|i| i.kind == crate::scene::InputKind::Motion { support: k, dof: c })
    };
    let angle = s.angle.to_radians();
    let (c, sn) = (libm::cos(angle), libm::sin(angle));
    let mut out = Vec::new();
    let one_translation = s.angle != 0.0 && (s.fixed[0] != s.fixed[1]);
    for comp in (0..3).filter(|&comp| s.fixed[comp]) {
        let direction =
            (one_translation && comp < 2).then(|| exact_direction(s.angle, comp, c, sn));
        out.push(Held {
            dof: if direction.is_some() {
                first
            } else {
                first + comp
            },
            support: k,
            component: comp,
            value: s.displace[comp],
            input: input(comp),
            direction,
        });
    }
    out
}

/// The unit vector of a support frame's axis `comp` (0: along the angle, 1: at 90 degrees
/// more), exact where the angle is a multiple of 90 degrees.
fn exact_direction(degrees: f64, comp: usize, c: f64, s: f64) -> [f64; 2] {
    let quarter = degrees / 90.0;
    let (c, s) = if quarter == quarter.round() {
        match (quarter.round() as i64).rem_euclid(4) {
            0 => (1.0, 0.0),
            1 => (0.0, 1.0),
            2 => (-1.0, 0.0),
            _ => (0.0, -1.0),
        }
    } else {
        (c, s)
    };
    if comp == 0 {
        [c, s]
    } else {
        [-s, c]
    }
}

/// The scene's point masses, springs, dashpots and foundations on member `member`'s own
/// nodes (at stations inside it; a scene without joints: all of them).
pub(super) fn attachments(scene: &Scene, rod: &Rod, member: usize) -> Attachments {
    let length = rod.curve.length();
    let node = |at: f64| rod.node_at(at * length);
    let on = |s: &Station| match *s {
        Station::On { member: m, at } if m == member => Some(at),
        _ => None,
    };
    let mut a = Attachments::default();
    for (m, at) in scene.masses.iter().filter_map(|m| Some((m, on(&m.at)?))) {
        let n = node(at);
        for (k, value) in [(U1, m.m), (U2, m.m), (ROTATION, m.j)] {
            if value > 0.0 {
                a.masses.push(OnDof {
                    dof: 3 * n + k,
                    value,
                });
            }
        }
    }
    for (s, at) in scene.springs.iter().filter_map(|s| Some((s, on(&s.at)?))) {
        let dof = 3 * node(at) + s.dof;
        a.springs.push(OnDof { dof, value: s.k });
        if s.c > 0.0 {
            a.dashpots.push(OnDof { dof, value: s.c });
        }
    }
    for f in scene.foundations.iter().filter(|f| f.member == member) {
        // Its ends are nodes: the elements between them are wholly on it.
        let (first, last) = (node(f.from), node(f.to));
        for (e, el) in rod.elements.iter().enumerate().take(last).skip(first) {
            a.foundation.push(FoundationPart {
                element: e,
                k: f.k * el.length / 6.0,
                c: f.c * el.length / 6.0,
            });
        }
    }
    a
}
