//! Whether a frame can stand (for a static initial state): judged on a linear model of the frame
//! made here (one straight beam element between consecutive stations of each member, unit
//! stiffnesses), whose stiffness with the supports, springs, links and bars must have no zero
//! eigenvalue.
use super::frame::{Frame, MemberKind};
use super::{Scene, Station, DOF_NAMES};
use nalgebra::{DMatrix, Vector2};

/// A node of the linear model: its dofs `(u1, u2, w)`, its station and position.
type Node = ([Option<usize>; 3], f64, Vector2<f64>);

/// A linear model of the frame for the mechanism check: dofs of the joints (a rotation only
/// where some rod end is rigid), of the stations inside members, and a rotation for each hinged
/// rod end.
struct Linear {
    dofs: usize,
    /// Each joint's dofs.
    joints: Vec<[Option<usize>; 3]>,
    /// Per member: its nodes' dofs, stations and positions.
    nodes: Vec<Vec<Node>>,
    k: DMatrix<f64>,
    /// What each dof moves (for the message).
    names: Vec<String>,
}

/// What the frame leaves free with its supports, springs, links and bars (a message naming a
/// free motion), or `None` when its linear stiffness has no zero eigenvalue.
pub(super) fn mechanism(scene: &Scene, frame: &Frame) -> Option<String> {
    let mut lin = Linear::new(scene, frame);
    lin.assemble(scene, frame);
    let held = lin.held(scene, frame);
    let free: Vec<usize> = (0..lin.dofs).filter(|d| !held.contains(d)).collect();
    if free.is_empty() {
        return None;
    }
    let k = DMatrix::from_fn(free.len(), free.len(), |r, c| lin.k[(free[r], free[c])]);
    let eig = k.symmetric_eigen();
    let largest = eig.eigenvalues.amax();
    let (index, smallest) = (eig.eigenvalues.iter().enumerate())
        .min_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map(|(i, v)| (i, v.abs()))?;
    if smallest > 1e-9 * largest {
        return None;
    }
    let v = eig.eigenvectors.column(index);
    let (r, _) = (v.iter().enumerate()).max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
    Some(lin.names[free[r]].clone())
}

impl Linear {
    fn new(scene: &Scene, frame: &Frame) -> Linear {
        let mut names = Vec::new();
        let mut next = |what: String| {
            names.push(what);
            names.len() - 1
        };
        let joints: Vec<[Option<usize>; 3]> = (frame.joints.iter().enumerate())
            .map(|(j, joint)| {
                let mut dof = |k: usize| next(format!("joint `{}` ({})", joint.name, DOF_NAMES[k]));
                [
                    Some(dof(0)),
                    Some(dof(1)),
                    frame.has_rotation(j).then(|| dof(2)),
                ]
            })
            .collect();
        let mut nodes = Vec::new();
        for member in &frame.members {
            let mut list = Vec::new();
            if member.kind == MemberKind::Rod {
                let stations = scene.member_stations(nodes.len());
                for &at in &stations {
                    let x = member.position(&frame.joints, at);
                    let dofs = if at == 0.0 || at == 1.0 {
                        let (end, joint) = if at == 0.0 {
                            (0, member.from)
                        } else {
                            (1, member.to)
                        };
                        let mut d = joints[joint];
                        if member.hinges[end] {
                            d[2] = Some(next(format!(
                                "the hinged end of member `{}` (w)",
                                member.name
                            )));
                        }
                        d
                    } else {
                        let mut dof = |k: usize| {
                            next(format!(
                                "member `{}` at {at} ({})",
                                member.name, DOF_NAMES[k]
                            ))
                        };
                        [Some(dof(0)), Some(dof(1)), Some(dof(2))]
                    };
                    list.push((dofs, at, x));
                }
            }
            nodes.push(list);
        }
        let dofs = names.len();
        Linear {
            dofs,
            joints,
            nodes,
            k: DMatrix::zeros(dofs, dofs),
            names,
        }
    }

    /// The dofs of a station.
    fn station_dofs(&self, s: &Station) -> [Option<usize>; 3] {
        match *s {
            Station::Joint(j) => self.joints[j],
            Station::On { member, at } => {
                (self.nodes[member].iter())
                    .find(|n| (n.1 - at).abs() < 1e-12)
                    .expect("every station of a member is a node")
                    .0
            }
        }
    }

    fn add(&mut self, dofs: &[Option<usize>], k: &DMatrix<f64>) {
        for (r, a) in dofs.iter().enumerate() {
            for (c, b) in dofs.iter().enumerate() {
                if let (Some(a), Some(b)) = (a, b) {
                    self.k[(*a, *b)] += k[(r, c)];
                }
            }
        }
    }

    /// A bar between two points: `e e^T / l` on their translations.
    fn bar(
        &mut self,
        a: [Option<usize>; 3],
        b: [Option<usize>; 3],
        xa: Vector2<f64>,
        xb: Vector2<f64>,
    ) {
        let d = xb - xa;
        let l = d.norm();
        let e = d / l;
        let mut k = DMatrix::zeros(4, 4);
        for r in 0..2 {
            for c in 0..2 {
                let v = e[r] * e[c] / l;
                k[(r, c)] = v;
                k[(r + 2, c + 2)] = v;
                k[(r, c + 2)] = -v;
                k[(r + 2, c)] = -v;
            }
        }
        self.add(&[a[0], a[1], b[0], b[1]], &k);
    }

    fn assemble(&mut self, scene: &Scene, frame: &Frame) {
        let size = frame.extent().max(1e-300);
        for (m, member) in frame.members.iter().enumerate() {
            if member.kind == MemberKind::Truss {
                let (a, b) = (Station::Joint(member.from), Station::Joint(member.to));
                let (da, db) = (self.station_dofs(&a), self.station_dofs(&b));
                let (xa, xb) = (
                    frame.joints[member.from].position,
                    frame.joints[member.to].position,
                );
                self.bar(da, db, xa, xb);
                continue;
            }
            for i in 0..self.nodes[m].len() - 1 {
                let ((da, _, xa), (db, _, xb)) = (self.nodes[m][i], self.nodes[m][i + 1]);
                self.beam(da, db, xa, xb, size);
            }
        }
        for l in &frame.links {
            let position = |s: &Station| match *s {
                Station::Joint(j) => frame.joints[j].position,
                Station::On { member, at } => frame.members[member].position(&frame.joints, at),
            };
            let (a, b) = (self.station_dofs(&l.ends[0]), self.station_dofs(&l.ends[1]));
            self.bar(a, b, position(&l.ends[0]), position(&l.ends[1]));
        }
        for s in scene.springs.iter().filter(|s| s.k > 0.0) {
            if let Some(d) = self.station_dofs(&s.at)[s.dof] {
                self.k[(d, d)] += 1.0 / size;
            }
        }
        // A stop restrains where the static state presses on it (else the static solve says so).
        for s in &scene.stops {
            if let Some(d) = self.station_dofs(&s.at)[s.dof] {
                self.k[(d, d)] += 1.0 / size;
            }
        }
        for f in scene.foundations.iter().filter(|f| f.k > 0.0) {
            for (dofs, at, _) in self.nodes[f.member].clone() {
                if at >= f.from - 1e-12 && at <= f.to + 1e-12 {
                    if let Some(d) = dofs[1] {
                        self.k[(d, d)] += 1.0 / size;
                    }
                }
            }
        }
    }

    /// An Euler-Bernoulli beam between two points with `EA = 1`, `EI = size^2 / 12`.
    fn beam(
        &mut self,
        a: [Option<usize>; 3],
        b: [Option<usize>; 3],
        xa: Vector2<f64>,
        xb: Vector2<f64>,
        size: f64,
    ) {
        let d = xb - xa;
        let l = d.norm();
        let (c, s) = (d[0] / l, d[1] / l);
        let (ea, ei) = (1.0, size * size / 12.0);
        let local = DMatrix::from_row_slice(
            6,
            6,
            &[
                ea / l,
                0.0,
                0.0,
                -ea / l,
                0.0,
                0.0,
                0.0,
                12.0 * ei / l.powi(3),
                6.0 * ei / l.powi(2),
                0.0,
                -12.0 * ei / l.powi(3),
                6.0 * ei / l.powi(2),
                0.0,
                6.0 * ei / l.powi(2),
                4.0 * ei / l,
                0.0,
                -6.0 * ei / l.powi(2),
                2.0 * ei / l,
                -ea / l,
                0.0,
                0.0,
                ea / l,
                0.0,
                0.0,
                0.0,
                -12.0 * ei / l.powi(3),
                -6.0 * ei / l.powi(2),
                0.0,
                12.0 * ei / l.powi(3),
                -6.0 * ei / l.powi(2),
                0.0,
                6.0 * ei / l.powi(2),
                2.0 * ei / l,
                0.0,
                -6.0 * ei / l.powi(2),
                4.0 * ei / l,
            ],
        );
        let mut t = DMatrix::zeros(6, 6);
        for n in 0..2 {
            let o = 3 * n;
            t[(o, o)] = c;
            t[(o, o + 1)] = s;
            t[(o + 1, o)] = -s;
            t[(o + 1, o + 1)] = c;
            t[(o + 2, o + 2)] = 1.0;
        }
        let k = t.transpose() * local * t;
        self.add(&[a[0], a[1], a[2], b[0], b[1], b[2]], &k);
    }

    /// The dofs the supports hold (a support at an angle that holds one direction: its
    /// direction's component is held by a stiff bar along it instead).
    fn held(&mut self, scene: &Scene, frame: &Frame) -> Vec<usize> {
        let mut held = Vec::new();
        let size = frame.extent().max(1e-300);
        for s in &scene.supports {
            let dofs = self.station_dofs(&s.at);
            let both = s.fixed[0] && s.fixed[1];
            for k in 0..3 {
                if !s.fixed[k] {
                    continue;
                }
                match dofs[k] {
                    Some(d) if k == 2 || s.angle == 0.0 || both => held.push(d),
                    Some(_) => {
                        let a = s.angle.to_radians()
                            + if k == 1 {
                                std::f64::consts::FRAC_PI_2
                            } else {
                                0.0
                            };
                        let n = Vector2::new(libm::cos(a), libm::sin(a));
                        let (d0, d1) = (dofs[0].expect("u1"), dofs[1].expect("u2"));
                        for r in 0..2 {
                            for c in 0..2 {
                                self.k[([d0, d1][r], [d0, d1][c])] += n[r] * n[c] / size;
                            }
                        }
                    }
                    None => {}
                }
            }
        }
        held
    }
}
