//! Where the nodes of each member go: every station an item names on a member (a support, a
//! mass, a spring, a link's end, a foundation's ends) is a node of it, and `elements` is spread
//! over the members without a count of their own in proportion to their lengths (at least
//! their segments each), then over each member's segments as a lone rod's is. A scene without
//! joints is member 0 alone, meshed as it always was.
use super::frame::MemberKind;
use super::{Scene, Station};

impl Scene {
    /// Every station of member `m` that must be a node (with its ends 0 and 1), sorted.
    pub fn member_stations(&self, m: usize) -> Vec<f64> {
        let on = |s: &Station| match *s {
            Station::On { member, at } if member == m => Some(at),
            _ => None,
        };
        let supports = self.supports.iter().filter_map(|s| on(&s.at));
        let masses = self.masses.iter().filter_map(|x| on(&x.at));
        let springs = self.springs.iter().filter_map(|s| on(&s.at));
        let stops = self.stops.iter().filter_map(|s| on(&s.at));
        let foundations = (self.foundations.iter())
            .filter(|f| f.member == m)
            .flat_map(|f| [f.from, f.to]);
        let links = (self.frame.iter())
            .flat_map(|f| f.links.iter().flat_map(|l| l.ends))
            .filter_map(|s| on(&s));
        crate::model::mesh::segment_boundaries(
            supports
                .chain(masses)
                .chain(springs)
                .chain(stops)
                .chain(foundations)
                .chain(links),
        )
    }

    /// The rod members that share the scene's `elements` (those without a count of their own),
    /// with their lengths; a scene without joints: its rod.
    fn sharing(&self) -> Vec<(usize, f64)> {
        let Some(frame) = &self.frame else {
            return vec![(0, 1.0)];
        };
        (frame.members.iter().enumerate())
            .filter(|(_, m)| m.kind == MemberKind::Rod && m.elements.is_none())
            .map(|(i, m)| (i, m.length(&frame.joints)))
            .collect()
    }

    /// The fewest elements `elements` must give: one per segment of every sharing member.
    pub(super) fn shared_segments(&self) -> usize {
        (self.sharing().iter())
            .map(|&(m, _)| self.member_stations(m).len() - 1)
            .sum::<usize>()
            .max(1)
    }

    /// The length of the model's dof vectors with `elements` elements: a rod's nodes, or a
    /// frame's joints and its rod members' own nodes (ends included).
    pub fn dofs(&self, elements: usize) -> usize {
        match &self.frame {
            None => 3 * (elements + 1),
            Some(f) => {
                let counts = self.member_elements(elements);
                let members: usize = (f.members.iter().zip(&counts))
                    .filter(|(m, _)| m.kind == MemberKind::Rod)
                    .map(|(_, &n)| 3 * (n + 1))
                    .sum();
                3 * f.joints.len() + members
            }
        }
    }

    /// How many reaction-like outputs a simulation books (a state carries them): one per
    /// support, then per spring, then per link, then per stop.
    pub fn reaction_slots(&self) -> usize {
        let links = self.frame.as_ref().map_or(0, |f| f.links.len());
        self.supports.len() + self.springs.len() + links + self.stops.len()
    }

    /// The element count of each member for `elements` (a truss member: 0, it is one bar):
    /// its own, or its share of `elements` (proportional to its length, largest remainders,
    /// at least its segments). `elements` must pass [`Scene::check_mesh`].
    pub fn member_elements(&self, elements: usize) -> Vec<usize> {
        let Some(frame) = &self.frame else {
            return vec![elements];
        };
        let sharing = self.sharing();
        let mut out: Vec<usize> = (frame.members.iter())
            .map(|m| match m.kind {
                MemberKind::Truss => 0,
                MemberKind::Rod => m.elements.unwrap_or(0),
            })
            .collect();
        if sharing.is_empty() {
            return out; // every rod member has its own count: `elements` is not used
        }
        let total: f64 = sharing.iter().map(|&(_, l)| l).sum();
        let fewest: Vec<usize> = (sharing.iter())
            .map(|&(m, _)| self.member_stations(m).len() - 1)
            .collect();
        let ideal: Vec<f64> = (sharing.iter())
            .map(|&(_, l)| l / total * elements as f64)
            .collect();
        let mut counts: Vec<usize> = (ideal.iter().zip(&fewest))
            .map(|(x, &f)| (x.floor() as usize).max(f))
            .collect();
        let mut sum: usize = counts.iter().sum();
        let shortfall = |counts: &[usize], j: usize| ideal[j] - counts[j] as f64;
        while sum < elements {
            let j = (0..counts.len())
                .max_by(|&a, &b| shortfall(&counts, a).total_cmp(&shortfall(&counts, b)))
                .expect("a sharing member");
            counts[j] += 1;
            sum += 1;
        }
        while sum > elements {
            let Some(j) = (0..counts.len())
                .filter(|&j| counts[j] > fewest[j])
                .min_by(|&a, &b| shortfall(&counts, a).total_cmp(&shortfall(&counts, b)))
            else {
                break;
            };
            counts[j] -= 1;
            sum -= 1;
        }
        for (&(m, _), c) in sharing.iter().zip(counts) {
            out[m] = c;
        }
        out
    }
}
