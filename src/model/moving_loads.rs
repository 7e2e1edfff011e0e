//! Point forces that travel along the rod at a constant speed: a force enters at `s = 0` at
//! the time `enter`, is at `s = speed (t - enter)` at time `t` (taken at each sub-step's
//! midpoint, like the harmonic excitation) and acts no more once it has left at `s = S`. Its
//! nodal forces are shared by the linear shape functions of the element it is on. On a frame
//! a load runs along a path of members end to end (`s` counted over the path), its forces on
//! each member's nodes (the end nodes' going to their joints).

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MovingLoad {
    /// 0 (`e1`) or 1 (`e2`), and the sign of the direction.
    pub component: usize,
    pub sign: f64,
    /// Arc length travelled per second, > 0.
    pub speed: f64,
    /// When it enters at `s = 0`.
    pub enter: f64,
    pub magnitude: f64,
}

/// A member a load travels: the arc length of each of its nodes, and the first dof of each
/// node (its joint's for an end node of a frame's member).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Segment {
    pub node_s: Vec<f64>,
    pub node_dofs: Vec<usize>,
}

impl Segment {
    /// A lone rod's nodes (dof `3 i`).
    pub fn rod(node_s: &[f64]) -> Segment {
        Segment {
            node_s: node_s.to_vec(),
            node_dofs: (0..node_s.len()).map(|i| 3 * i).collect(),
        }
    }
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct MovingLoads {
    /// The path of each load: its members in order.
    paths: Vec<Vec<Segment>>,
    pub loads: Vec<MovingLoad>,
}

impl MovingLoads {
    /// Loads on a lone rod with these node arc lengths.
    pub fn new(node_s: &[f64], loads: Vec<MovingLoad>) -> MovingLoads {
        let path = vec![Segment::rod(node_s)];
        MovingLoads {
            paths: vec![path; loads.len()],
            loads,
        }
    }

    /// Loads along paths of members (one path per load).
    pub fn along(paths: Vec<Vec<Segment>>, loads: Vec<MovingLoad>) -> MovingLoads {
        assert_eq!(paths.len(), loads.len());
        MovingLoads { paths, loads }
    }

    pub fn is_empty(&self) -> bool {
        self.loads.is_empty()
    }

    /// The first dofs of the two nodes of the element load `i` is on at time `t`, and its
    /// shape-function weights; `None` while it is off its path.
    fn place(&self, i: usize, t: f64) -> Option<(usize, usize, f64, f64)> {
        let l = &self.loads[i];
        let mut s = l.speed * (t - l.enter);
        let path = &self.paths[i];
        for (k, segment) in path.iter().enumerate() {
            let node_s = &segment.node_s;
            let total = *node_s.last()?;
            if s > total && k + 1 < path.len() {
                s -= total;
                continue;
            }
            if !(0.0..=total).contains(&s) {
                return None;
            }
            let n = node_s.len() - 1;
            let e = node_s.partition_point(|&x| x <= s).clamp(1, n) - 1;
            let (a, b) = (node_s[e], node_s[e + 1]);
            let nb = ((s - a) / (b - a)).clamp(0.0, 1.0);
            let dofs = &segment.node_dofs;
            return Some((dofs[e], dofs[e + 1], 1.0 - nb, nb));
        }
        None
    }

    /// `out += scale * f(t)`.
    pub fn add_to(&self, t: f64, out: &mut [f64], scale: f64) {
        for (i, l) in self.loads.iter().enumerate() {
            if let Some((a, b, na, nb)) = self.place(i, t) {
                let f = scale * l.sign * l.magnitude;
                out[a + l.component] += f * na;
                out[b + l.component] += f * nb;
            }
        }
    }

    /// `f(t) . du`: their work over an increment with the loads where they are at `t`.
    pub fn work(&self, du: &[f64], t: f64) -> f64 {
        let mut work = 0.0;
        for (i, l) in self.loads.iter().enumerate() {
            if let Some((a, b, na, nb)) = self.place(i, t) {
                let f = l.sign * l.magnitude;
                work += f * (na * du[a + l.component] + nb * du[b + l.component]);
            }
        }
        work
    }
}
