//! Places of a structure where things act and are read: a joint, or a point of a member (its
//! element and shape-function weights), and what a vector of the structure is there.
use super::Structure;
use crate::model::rod::PointOnRod;
use nalgebra::Vector2;

/// A place of a structure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Place {
    /// At arc length `s` of member `member`.
    Member {
        member: usize,
        point: PointOnRod,
        s: f64,
    },
    /// A joint (its node).
    Joint(usize),
    /// The fraction `t` of axial element `bar` (a truss bar) from its first node to its second.
    Bar { bar: usize, t: f64 },
}

impl Structure {
    /// The place at arc length `s` of member `m`.
    pub fn member_place(&self, m: usize, s: f64) -> Place {
        Place::Member {
            member: m,
            point: self.members[m].rod.point_at(s),
            s,
        }
    }

    /// Dof `k` of the vector `x` at `place` (interpolated inside a member).
    pub fn interpolate(&self, x: &[f64], place: Place, k: usize) -> f64 {
        match place {
            Place::Member { member, point, .. } => {
                let m = &self.members[member];
                m.rod.interpolate(&x[m.range()], point, k)
            }
            Place::Joint(j) => x[3 * j + k],
            Place::Bar { bar, t } if k < 2 => {
                let [a, b] = self.axial[bar].nodes;
                (1.0 - t) * x[3 * a + k] + t * x[3 * b + k]
            }
            Place::Bar { .. } => 0.0,
        }
    }

    /// The reference position of `place`.
    pub fn reference_position(&self, place: Place) -> Vector2<f64> {
        match place {
            Place::Member { member, s, .. } => self.members[member].rod.reference_position(s),
            Place::Joint(j) => self.joints[j],
            Place::Bar { bar, t } => {
                let [a, b] = self.axial[bar].reference;
                (1.0 - t) * a + t * b
            }
        }
    }

    /// The current position of `place` with the displacements `u`.
    pub fn position(&self, u: &[f64], place: Place) -> Vector2<f64> {
        self.reference_position(place)
            + Vector2::new(self.interpolate(u, place, 0), self.interpolate(u, place, 1))
    }

    /// Adds `value` times the shape functions at `place` to dof `k` of `out` (a point force or
    /// moment), unfolded: call on a vector that is folded afterwards, or use
    /// [`Structure::add_point_force`].
    fn add_at(&self, out: &mut [f64], place: Place, k: usize, value: f64) {
        match place {
            Place::Member { member, point, .. } => {
                let offset = self.members[member].offset;
                let (na, nb) = point.weights;
                out[offset + 3 * point.element + k] += na * value;
                out[offset + 3 * (point.element + 1) + k] += nb * value;
            }
            Place::Joint(j) => out[3 * j + k] += value,
            Place::Bar { bar, t } => {
                let [a, b] = self.axial[bar].nodes;
                out[3 * a + k] += (1.0 - t) * value;
                out[3 * b + k] += t * value;
            }
        }
    }

    /// Adds a point force (or moment, `k = 2`) of `value` at `place` to the folded force
    /// vector `out`.
    pub fn add_point_force(&self, out: &mut [f64], place: Place, k: usize, value: f64) {
        self.add_at(out, place, k, value);
        self.fold(out);
    }

    /// The global dof of dof `k` at a place that is a node (a joint, or a member's node), its
    /// master.
    pub fn node_dof(&self, place: Place, k: usize) -> usize {
        match place {
            Place::Joint(j) => 3 * j + k,
            Place::Bar { bar, t } => 3 * self.axial[bar].nodes[usize::from(t > 0.5)] + k,
            Place::Member { member, point, .. } => {
                let m = &self.members[member];
                let node = if point.weights.1 > 0.5 {
                    point.element + 1
                } else {
                    point.element
                };
                self.master(m.offset + 3 * node + k)
            }
        }
    }
}
