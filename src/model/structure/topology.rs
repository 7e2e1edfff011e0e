//! Building a structure: the joints, the members between them with their ties, bars and links,
//! and the lists of constrained dofs that follow from the supports.
use super::graph::Graph;
use super::{Axial, Member, MemberEnd, NodalTerms, Structure};
use crate::model::rod::{Rod, ROTATION, U1, U2};
use nalgebra::Vector2;

impl Structure {
    /// A frame: `joints` (reference positions; joint `j` is node `j`), `members` (each a rod
    /// placed from its first end's joint to its second's, with its ends), `axial` bars and
    /// links between nodes (joint nodes, or member nodes: see [`Structure::member_node`], which
    /// numbers them as this constructor will), `nodal` terms on dofs.
    pub fn frame(
        joints: Vec<Vector2<f64>>,
        members: Vec<(Rod, [MemberEnd; 2])>,
        axial: Vec<Axial>,
        nodal: NodalTerms,
    ) -> Structure {
        let mut offset = 3 * joints.len();
        let lumped = members.first().is_some_and(|(r, _)| r.lumped);
        let members: Vec<Member> = (members.into_iter())
            .map(|(rod, ends)| {
                let m = Member {
                    offset,
                    ends: Some(ends),
                    rod,
                };
                offset += m.rod.dofs();
                m
            })
            .collect();
        let dofs = offset;
        let mut ties = Vec::new();
        let mut rigid = vec![false; joints.len()];
        for m in &members {
            let ends = m.ends.expect("a frame's members have ends");
            for (end, node) in ends.iter().zip([0, m.rod.last_node()]) {
                let first = m.offset + 3 * node;
                ties.push((first + U1, 3 * end.joint + U1));
                ties.push((first + U2, 3 * end.joint + U2));
                if !end.hinged {
                    ties.push((first + ROTATION, 3 * end.joint + ROTATION));
                    rigid[end.joint] = true;
                }
            }
        }
        let dead = (0..joints.len())
            .filter(|&j| !rigid[j])
            .map(|j| 3 * j + ROTATION)
            .collect();
        let cables = (axial.iter().enumerate())
            .filter(|(_, a)| a.tension_only)
            .map(|(i, _)| i)
            .collect();
        let mut s = Structure {
            members,
            joints,
            axial,
            nodal,
            nonlinear: super::Nonlinear {
                cables,
                ..super::Nonlinear::default()
            },
            dofs,
            slaves: ties.iter().map(|&(s, _)| s).collect(),
            ties,
            held: vec![false; dofs],
            dead,
            directions: Vec::new(),
            zeroed: Vec::new(),
            eliminated: Vec::new(),
            projected: Vec::new(),
            graph: None,
            lumped,
            rayleigh: None,
        };
        s.graph = Some(Graph::new(&s));
        s.update_constraints();
        s
    }

    /// The first dof of each member of a frame with `joints` joints whose members have these
    /// node counts (as [`Structure::frame`] lays them out).
    pub fn member_offsets(joints: usize, nodes: impl IntoIterator<Item = usize>) -> Vec<usize> {
        let mut offset = 3 * joints;
        (nodes.into_iter())
            .map(|n| {
                let first = offset;
                offset += 3 * n;
                first
            })
            .collect()
    }

    /// The lists that follow from the ties, the supports and the dead rotations.
    pub(super) fn update_constraints(&mut self) {
        let mut zero = vec![false; self.dofs];
        for (d, &h) in self.held.iter().enumerate() {
            zero[d] |= h;
        }
        for &d in &self.dead {
            zero[d] = true;
        }
        let mut eliminated = zero.clone();
        for &(s, m) in &self.ties {
            eliminated[s] = true;
            if zero[m] {
                zero[s] = true;
            }
        }
        let list = |flags: &[bool]| (0..flags.len()).filter(|&d| flags[d]).collect::<Vec<_>>();
        self.zeroed = list(&zero);
        self.eliminated = list(&eliminated);
        self.projected.clear();
        for &(node, n) in &self.directions {
            self.projected.push((node, n));
            for &(s, m) in &self.ties {
                if m == 3 * node + U1 {
                    self.projected.push((s / 3, n));
                }
            }
        }
    }

    /// Sets the held entries of a vector to zero and removes the held directions' components.
    pub(super) fn zero_held(&self, x: &mut [f64]) {
        for &d in &self.zeroed {
            x[d] = 0.0;
        }
        for &(node, [n1, n2]) in &self.projected {
            let (i, j) = (3 * node + U1, 3 * node + U2);
            let along = n1 * x[i] + n2 * x[j];
            x[i] -= along * n1;
            x[j] -= along * n2;
        }
    }

    /// The nodal terms, for readers (joint masses, springs, dashpots).
    pub fn nodal_terms(&self) -> &NodalTerms {
        &self.nodal
    }

    /// The `(slave, master)` ties.
    pub fn ties(&self) -> &[(usize, usize)] {
        &self.ties
    }
}
