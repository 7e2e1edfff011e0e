//! A frame scene meshed: each rod member a [`Rod`] along its own curve with its own section and
//! mesh (nodes at its stations), truss members and links as axial elements, joint masses and
//! springs as terms on the joints' dofs, the supports' held dofs (or directions), and every load
//! as a folded nodal vector of the [`Structure`].
use super::setup::{
    attachments, held_dofs, moving_load, scene_section, time_law, Held, MemberRole, Setup,
    SpringOnRod,
};
use crate::model::loads::{LoadShape, LoadTime};
use crate::model::mesh;
use crate::model::moving_loads::{MovingLoads, Segment};
use crate::model::structure::{Axial, MemberEnd, NodalTerms};
use crate::model::{LoadSet, Place, Rod, Section, Structure};
use crate::scene::frame::{Frame, MemberKind};
use crate::scene::{LoadKind, ParamValues, Scene, Slot, Station, Std, NORMAL};
use nalgebra::Vector2;

/// The materials of a member: the scene's section, or its own.
fn member_section(scene: &Scene, values: &ParamValues, default: &Section, m: usize) -> Section {
    let frame = scene.frame.as_ref().expect("a frame");
    let Some(own) = &frame.members[m].section else {
        return *default;
    };
    let (e, nu, rho) = (
        values.std(Std::E),
        values.std(Std::Nu),
        values.std(Std::Rho),
    );
    let p = own.properties(values);
    let mut section = Section::from_properties(e, nu, rho, p.area, p.inertia, p.shear_area);
    section.ga *= own.shear_factor;
    section
}

/// Where each scene member is: the structure member (rod) or axial element (bar).
struct Layout<'a> {
    frame: &'a Frame,
    roles: Vec<MemberRole>,
    /// Each rod member's first dof.
    offsets: Vec<usize>,
    rods: Vec<Rod>,
}

impl Layout<'_> {
    /// The global node of a station (its joint, or its member's node there).
    fn node(&self, s: Station) -> usize {
        match s {
            Station::Joint(j) => j,
            Station::On { member, at } => match self.roles[member] {
                MemberRole::Rod(r) => {
                    let rod = &self.rods[r];
                    self.offsets[r] / 3 + rod.node_at(at * rod.curve.length())
                }
                MemberRole::Bar(_) => unreachable!("nothing sits inside a truss bar (checked)"),
            },
        }
    }

    /// The place of a station for reading and loading.
    fn place(&self, structure: &Structure, s: Station) -> Place {
        match s {
            Station::Joint(j) => Place::Joint(j),
            Station::On { member, at } => match self.roles[member] {
                MemberRole::Rod(r) => {
                    structure.member_place(r, at * structure.members[r].rod.curve.length())
                }
                MemberRole::Bar(b) => Place::Bar { bar: b, t: at },
            },
        }
    }

    /// A member's path segment for moving loads: its nodes' arc lengths and first dofs (its
    /// ends' joints).
    fn segment(&self, m: usize) -> Segment {
        let MemberRole::Rod(r) = self.roles[m] else {
            unreachable!("moving loads run along rods (checked)")
        };
        let rod = &self.rods[r];
        let last = rod.last_node();
        let member = &self.frame.members[m];
        let node_dofs = (0..=last)
            .map(|i| match i {
                0 => 3 * member.from,
                i if i == last => 3 * member.to,
                i => self.offsets[r] + 3 * i,
            })
            .collect();
        Segment {
            node_s: rod.node_s.clone(),
            node_dofs,
        }
    }
}

/// Meshes a frame scene.
pub fn frame_setup(scene: &Scene, values: &ParamValues) -> Setup {
    let frame = scene.frame.as_ref().expect("a frame");
    let default = scene_section(scene, values);
    let damping = values.std(Std::Damping);
    let counts = scene.member_elements(values.elements());
    let mut layout = Layout {
        frame,
        roles: Vec::new(),
        offsets: Vec::new(),
        rods: Vec::new(),
    };
    let mut ends = Vec::new();
    let mut bars = Vec::new();
    for (m, member) in frame.members.iter().enumerate() {
        let section = member_section(scene, values, &default, m);
        if member.kind == MemberKind::Truss {
            layout.roles.push(MemberRole::Bar(bars.len()));
            let reference = [
                frame.joints[member.from].position,
                frame.joints[member.to].position,
            ];
            let bar = Axial::bar(
                [member.from, member.to],
                reference,
                section.ea,
                section.rho_a,
                damping,
            );
            bars.push(if member.cable { bar.cable() } else { bar });
            continue;
        }
        let (curve, placement) = member.curve(&frame.joints);
        let n = counts[m];
        let mut rod = match mesh::node_fractions(&scene.member_stations(m), n) {
            None => Rod::new(curve, section, damping, n),
            Some(fractions) => Rod::with_nodes(curve, section, damping, &fractions),
        };
        if scene.model.lumped_mass {
            rod = rod.with_lumped_mass();
        }
        if scene.model.rotational_damping > 0.0 {
            rod = rod.with_rotational_damping(scene.model.rotational_damping);
        }
        let a = attachments(scene, &rod, m);
        if !a.is_empty() {
            rod = rod.with_attachments(a);
        }
        layout.roles.push(MemberRole::Rod(layout.rods.len()));
        layout.rods.push(rod.with_placement(placement));
        ends.push([
            MemberEnd {
                joint: member.from,
                hinged: member.hinges[0],
            },
            MemberEnd {
                joint: member.to,
                hinged: member.hinges[1],
            },
        ]);
    }
    layout.offsets =
        Structure::member_offsets(frame.joints.len(), layout.rods.iter().map(Rod::nodes));
    let position = |s: Station| match s {
        Station::Joint(j) => frame.joints[j].position,
        Station::On { member, at } => frame.members[member].position(&frame.joints, at),
    };
    let mut axial = bars;
    let mut links = Vec::new();
    for l in &frame.links {
        let nodes = [layout.node(l.ends[0]), layout.node(l.ends[1])];
        let reference = [position(l.ends[0]), position(l.ends[1])];
        let rest = l.length.unwrap_or((reference[1] - reference[0]).norm());
        links.push(axial.len());
        axial.push(Axial::link(nodes, reference, l.k, l.c, rest));
    }
    let mut nodal = NodalTerms::default();
    for m in &scene.masses {
        if let Station::Joint(j) = m.at {
            for (k, value) in [(0, m.m), (1, m.m), (2, m.j)] {
                if value > 0.0 {
                    nodal.masses.push((3 * j + k, value));
                }
            }
        }
    }
    for s in &scene.springs {
        if let Station::Joint(j) = s.at {
            nodal.springs.push((3 * j + s.dof, s.k));
            if s.c > 0.0 {
                nodal.dashpots.push((3 * j + s.dof, s.c));
            }
        }
    }
    let joints: Vec<Vector2<f64>> = frame.joints.iter().map(|j| j.position).collect();
    let members: Vec<(Rod, [MemberEnd; 2])> = layout.rods.clone().into_iter().zip(ends).collect();
    let mut structure = Structure::frame(joints, members, axial, nodal);

    let mut support_nodes = Vec::new();
    let mut held: Vec<Held> = Vec::new();
    for (k, s) in scene.supports.iter().enumerate() {
        let node = layout.node(s.at);
        support_nodes.push(node);
        held.extend(held_dofs(scene, k, 3 * node));
    }
    for h in &held {
        match h.direction {
            None => structure.hold(h.dof),
            Some(n) => structure.hold_direction(h.dof / 3, n),
        }
    }
    let springs: Vec<SpringOnRod> = (scene.springs.iter())
        .map(|s| SpringOnRod {
            dof: 3 * layout.node(s.at) + s.dof,
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
    let loads =
        frame_loads(scene, values, &structure, &layout, &default).with_base_forces(&moving_bases);
    let sensors = (scene.sensors.iter())
        .map(|s| layout.place(&structure, s.at))
        .collect();
    let points = scene.shape_points;
    let mut shape = Vec::new();
    for role in &layout.roles {
        for j in 0..points {
            let t = j as f64 / (points - 1).max(1) as f64;
            shape.push(match *role {
                MemberRole::Rod(r) => {
                    structure.member_place(r, t * structure.members[r].rod.curve.length())
                }
                MemberRole::Bar(b) => Place::Bar { bar: b, t },
            });
        }
    }
    Setup {
        support_angles: scene
            .supports
            .iter()
            .map(|s| s.angle.to_radians())
            .collect(),
        support_nodes,
        held,
        sensors,
        shape,
        springs,
        members: layout.roles.clone(),
        links,
        loads,
        structure,
    }
}

/// Every load's folded nodal vector at unit magnitude (in the order of `load_magnitudes`), the
/// moving loads along their paths.
fn frame_loads(
    scene: &Scene,
    values: &ParamValues,
    structure: &Structure,
    layout: &Layout,
    default: &Section,
) -> LoadSet {
    let n = structure.dofs();
    let frame = layout.frame;
    let mut groups: Vec<Slot> = Vec::new();
    let mut vectors: Vec<(Vec<f64>, LoadTime)> = Vec::new();
    let mut moving = Vec::new();
    let mut paths = Vec::new();
    let point = |at: Station, component: usize, sign: f64| {
        let mut v = vec![0.0; n];
        structure.add_point_force(&mut v, layout.place(structure, at), component, sign);
        v
    };
    // A member's distributed pattern (unit intensity from `start` to `end` over [from, to]).
    let patch = |m: usize,
                 (from, to): (f64, f64),
                 (start, end): (f64, f64),
                 component: usize,
                 sign: f64| {
        let mut v = vec![0.0; n];
        let MemberRole::Rod(r) = layout.roles[m] else {
            unreachable!("distributed loads act on rods (checked)")
        };
        let member = &structure.members[r];
        let length = member.rod.curve.length();
        let directions: Vec<(usize, f64)> = if component == NORMAL {
            let chord = frame.members[m].chord(&frame.joints);
            let normal = Vector2::new(-chord[1], chord[0]) / chord.norm();
            vec![(0, sign * normal[0]), (1, sign * normal[1])]
        } else {
            vec![(component, sign)]
        };
        for (component, sign) in directions {
            let shape = LoadShape::Patch {
                from: from * length,
                to: to * length,
                start,
                end,
                component,
                sign,
            };
            for (k, x) in shape.nodal_vector(&member.rod).into_iter().enumerate() {
                v[member.offset + k] += x;
            }
        }
        structure_fold(structure, &mut v);
        v
    };
    for l in &scene.loads {
        let (component, sign) = (l.direction.component, l.direction.sign);
        let time = time_law(&mut groups, l.time, l.value);
        let vector = match l.kind {
            LoadKind::Point { at } | LoadKind::Moment { at } => point(at, component, sign),
            LoadKind::Patch {
                member,
                from,
                to,
                value_end,
            } => {
                let ramp = if value_end.is_some() {
                    (1.0, 0.0)
                } else {
                    (1.0, 1.0)
                };
                patch(member, (from, to), ramp, component, sign)
            }
            LoadKind::Gravity => {
                gravity(scene, values, structure, layout, default, component, sign)
            }
            LoadKind::Distributed => unreachable!("a frame's distributed loads name their member"),
            LoadKind::Moving { speed, enter } => {
                moving.push(moving_load(l, speed, enter, values));
                paths.push(l.path.iter().map(|&m| layout.segment(m)).collect());
                let index = moving.len() - 1;
                vectors.push((Vec::new(), LoadTime::Moving { index }));
                continue;
            }
        };
        vectors.push((vector, time));
    }
    for l in scene.loads.iter().filter(|l| l.kind == LoadKind::Gravity) {
        for m in &scene.masses {
            vectors.push((
                point(m.at, l.direction.component, l.direction.sign),
                LoadTime::Constant,
            ));
        }
    }
    for l in &scene.loads {
        if let LoadKind::Patch {
            member,
            from,
            to,
            value_end: Some(end),
        } = l.kind
        {
            let v = patch(
                member,
                (from, to),
                (0.0, 1.0),
                l.direction.component,
                l.direction.sign,
            );
            vectors.push((v, time_law(&mut groups, l.time, end)));
        }
    }
    LoadSet::from_vectors(n, vectors).with_moving(MovingLoads::along(paths, moving))
}

/// Gravity's folded nodal vector per unit magnitude `g rho A` of the scene's section: every rod
/// member's distributed weight and every bar's, each scaled by its area over the scene's.
fn gravity(
    scene: &Scene,
    values: &ParamValues,
    structure: &Structure,
    layout: &Layout,
    default: &Section,
    component: usize,
    sign: f64,
) -> Vec<f64> {
    let mut v = vec![0.0; structure.dofs()];
    for (m, role) in layout.roles.iter().enumerate() {
        let ratio = member_section(scene, values, default, m).rho_a / default.rho_a;
        match *role {
            MemberRole::Rod(r) => {
                let member = &structure.members[r];
                let shape = LoadShape::Distributed { component, sign };
                for (k, x) in shape.nodal_vector(&member.rod).into_iter().enumerate() {
                    v[member.offset + k] += ratio * x;
                }
            }
            MemberRole::Bar(b) => {
                let bar = &structure.axial[b];
                let half = 0.5 * bar.rest * ratio * sign;
                for node in bar.nodes {
                    v[3 * node + component] += half;
                }
            }
        }
    }
    structure_fold(structure, &mut v);
    v
}

fn structure_fold(structure: &Structure, v: &mut [f64]) {
    // A member's end rows belong to its joints.
    structure.fold(v);
}
