//! From a scene and its parameter values to the model: the meshed rod with its held degrees of
//! freedom, the loads, and the points where sensors and shape samples read the state.
use crate::model::attachments::{Attachments, FoundationPart, OnDof};
use crate::model::loads::{LoadShape, LoadTime};
use crate::model::mesh;
use crate::model::moving_loads::{MovingLoad, MovingLoads};
use crate::model::rod::{ROTATION, U1, U2};
use crate::model::{LoadSet, Place, ReferenceCurve, Rod, Section, Structure};
use crate::scene::{Geometry, Load, LoadKind, ParamValues, Scene, Slot, Std, TimeLaw};

/// A held (constrained) degree of freedom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Held {
    /// Global dof index.
    pub dof: usize,
    pub support: usize,
    /// 0 `u1`, 1 `u2`, 2 `w`.
    pub component: usize,
    /// Its prescribed value in the initial state.
    pub value: Slot,
    /// The FMI input that moves it, if any.
    pub input: Option<usize>,
}

/// A point of the structure where something is read.
pub type Probe = Place;

pub struct Setup {
    pub structure: Structure,
    pub loads: LoadSet,
    /// The node of each support.
    pub support_nodes: Vec<usize>,
    pub held: Vec<Held>,
    pub sensors: Vec<Probe>,
    pub shape: Vec<Probe>,
    /// Every spring, for its force output (and its base's motion).
    pub springs: Vec<SpringOnRod>,
}

/// A spring and dashpot from a dof of the rod to its base.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpringOnRod {
    pub dof: usize,
    pub k: f64,
    pub c: f64,
    /// The FMI input its base follows; `None`: the base stays at 0.
    pub base: Option<usize>,
}

/// The reference curve of a scene with these values.
pub fn curve(scene: &Scene, values: &ParamValues) -> ReferenceCurve {
    let span = values.std(Std::Span);
    match scene.geometry {
        Geometry::Straight => ReferenceCurve::Straight { length: span },
        Geometry::Arc => {
            let rise = values.get(scene.param_index("H").expect("an arc has H"));
            ReferenceCurve::arc(span, rise)
        }
    }
}

/// Meshes the scene. The values must have passed [`Scene::check`] (enough elements).
pub fn setup(scene: &Scene, values: &ParamValues) -> Setup {
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
    let model = scene.model;
    section.ga *= model.shear_factor;
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
    let attachments = attachments(scene, &rod);
    if !attachments.is_empty() {
        rod = rod.with_attachments(attachments);
    }
    let mut support_nodes = Vec::new();
    let mut held = Vec::new();
    for (k, s) in scene.supports.iter().enumerate() {
        let node = rod.node_at(s.at * length);
        support_nodes.push(node);
        for c in (0..3).filter(|&c| s.fixed[c]) {
            let input = scene
                .inputs
                .iter()
                .position(|i| i.kind == crate::scene::InputKind::Motion { support: k, dof: c });
            held.push(Held {
                dof: 3 * node + c,
                support: k,
                component: c,
                value: s.displace[c],
                input,
            });
        }
    }
    for h in &held {
        rod.fix(h.dof / 3, h.component);
    }

    // Harmonic loads with the same amplitude slot share one nodal vector.
    let mut groups: Vec<Slot> = Vec::new();
    let mut time_of = |time: TimeLaw, value: Slot| match time {
        TimeLaw::Constant => LoadTime::Constant,
        TimeLaw::Input(_) => LoadTime::Input,
        TimeLaw::Harmonic => {
            let group = groups.iter().position(|g| *g == value).unwrap_or_else(|| {
                groups.push(value);
                groups.len() - 1
            });
            LoadTime::Harmonic { group }
        }
    };
    let mut moving = Vec::new();
    let mut shapes: Vec<(LoadShape, LoadTime)> = scene
        .loads
        .iter()
        .map(|l| match l.kind {
            LoadKind::Moving { speed, enter } => {
                moving.push(MovingLoad {
                    component: l.direction.component,
                    sign: l.direction.sign,
                    speed: speed.eval(values),
                    enter: enter.eval(values),
                    magnitude: 0.0,
                });
                let index = moving.len() - 1;
                (load_shape(l, length, false), LoadTime::Moving { index })
            }
            _ => (load_shape(l, length, false), time_of(l.time, l.value)),
        })
        .collect();
    // The weight of each point mass under each gravity load, after the scene's loads (its
    // magnitude: the acceleration times the mass, see `load_magnitudes`).
    for l in scene.loads.iter().filter(|l| l.kind == LoadKind::Gravity) {
        for m in &scene.masses {
            let (component, sign) = (l.direction.component, l.direction.sign);
            let at = LoadShape::Point {
                s: m.at * length,
                component,
                sign,
            };
            shapes.push((at, LoadTime::Constant));
        }
    }
    // The rising part of each linearly varying load, after those (its magnitude is the load's
    // `value_end`).
    for l in &scene.loads {
        if let LoadKind::Patch {
            value_end: Some(end),
            ..
        } = l.kind
        {
            shapes.push((load_shape(l, length, true), time_of(l.time, end)));
        }
    }
    let springs: Vec<SpringOnRod> = (scene.springs.iter())
        .map(|s| SpringOnRod {
            dof: 3 * rod.node_at(s.at * length) + s.dof,
            k: s.k,
            c: s.c,
            base: s.base,
        })
        .collect();
    let moving_bases: Vec<usize> = (springs.iter())
        .filter(|s| s.base.is_some())
        .map(|s| s.dof)
        .collect();
    let loads = LoadSet::new(&rod, &shapes)
        .with_moving(MovingLoads::new(&rod.node_s, moving))
        .with_base_forces(&moving_bases);
    let structure = Structure::single(rod);
    let probe = |at: f64| structure.member_place(0, at * length);

    let sensors = scene.sensors.iter().map(|s| probe(s.at)).collect();
    let points = scene.shape_points;
    let shape = (0..points)
        .map(|j| probe(j as f64 / (points - 1).max(1) as f64))
        .collect();
    Setup {
        structure,
        loads,
        support_nodes,
        held,
        sensors,
        shape,
        springs,
    }
}

/// The nodal pattern of a load at unit magnitude. A linearly varying load is two: the part
/// falling from 1 at `from` to 0 at `to` (`rising = false`, scaled by `value`) and the part
/// rising from 0 to 1 (scaled by `value_end`).
pub fn load_shape(load: &Load, length: f64, rising: bool) -> LoadShape {
    let (component, sign) = (load.direction.component, load.direction.sign);
    match load.kind {
        LoadKind::Point { at } | LoadKind::Moment { at } => LoadShape::Point {
            s: at * length,
            component,
            sign,
        },
        // Where it enters (its nodal forces follow it: `MovingLoads`).
        LoadKind::Moving { .. } => LoadShape::Point {
            s: 0.0,
            component,
            sign,
        },
        LoadKind::Distributed | LoadKind::Gravity => LoadShape::Distributed { component, sign },
        LoadKind::Patch {
            from,
            to,
            value_end,
        } => {
            let (start, end) = match (value_end, rising) {
                (None, _) => (1.0, 1.0),
                (Some(_), false) => (1.0, 0.0),
                (Some(_), true) => (0.0, 1.0),
            };
            LoadShape::Patch {
                from: from * length,
                to: to * length,
                start,
                end,
                component,
                sign,
            }
        }
    }
}

/// The magnitude of every load: its value slot (gravity: times the mass per length `rho A`),
/// or for input loads the input's value; then the point masses' weights and the end values of
/// the linearly varying loads.
pub fn load_magnitudes(scene: &Scene, values: &ParamValues, inputs: &[f64], out: &mut [f64]) {
    let (scene_loads, ends) = out.split_at_mut(scene.loads.len());
    for (m, l) in scene_loads.iter_mut().zip(&scene.loads) {
        *m = match (l.time, l.kind) {
            (TimeLaw::Input(i), _) => inputs[i],
            (_, LoadKind::Gravity) => {
                let area = scene.section.properties(values).area;
                l.value.eval(values) * values.std(Std::Rho) * area
            }
            _ => l.value.eval(values),
        };
    }
    let gravity = scene.loads.iter().filter(|l| l.kind == LoadKind::Gravity);
    let weights = gravity.flat_map(|l| scene.masses.iter().map(|m| l.value.eval(values) * m.m));
    let end_values = scene.loads.iter().filter_map(|l| match l.kind {
        LoadKind::Patch { value_end, .. } => value_end.map(|v| v.eval(values)),
        _ => None,
    });
    for (m, value) in ends.iter_mut().zip(weights.chain(end_values)) {
        *m = value;
    }
}

/// The scene's point masses, springs, dashpots and foundations on the rod's dofs.
fn attachments(scene: &Scene, rod: &Rod) -> Attachments {
    let length = rod.curve.length();
    let node = |at: f64| rod.node_at(at * length);
    let mut a = Attachments::default();
    for m in &scene.masses {
        let n = node(m.at);
        for (k, value) in [(U1, m.m), (U2, m.m), (ROTATION, m.j)] {
            if value > 0.0 {
                a.masses.push(OnDof {
                    dof: 3 * n + k,
                    value,
                });
            }
        }
    }
    for s in &scene.springs {
        let dof = 3 * node(s.at) + s.dof;
        a.springs.push(OnDof { dof, value: s.k });
        if s.c > 0.0 {
            a.dashpots.push(OnDof { dof, value: s.c });
        }
    }
    for f in &scene.foundations {
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
