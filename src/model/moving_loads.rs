//! Point forces that travel along the rod at a constant speed: a force enters at `s = 0` at
//! the time `enter`, is at `s = speed (t - enter)` at time `t` (taken at each sub-step's
//! midpoint, like the harmonic excitation) and acts no more once it has left at `s = S`. Its
//! nodal forces are shared by the linear shape functions of the element it is on.

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

#[derive(Clone, Debug, Default, PartialEq)]
pub struct MovingLoads {
    /// Arc length of each node (the loads find their element by bisection).
    node_s: Vec<f64>,
    pub loads: Vec<MovingLoad>,
}

impl MovingLoads {
    pub fn new(node_s: &[f64], loads: Vec<MovingLoad>) -> MovingLoads {
        MovingLoads {
            node_s: node_s.to_vec(),
            loads,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.loads.is_empty()
    }

    /// Element and shape-function weights of load `l` at time `t`; `None` while it is off the
    /// rod.
    fn place(&self, l: &MovingLoad, t: f64) -> Option<(usize, f64, f64)> {
        let s = l.speed * (t - l.enter);
        let total = *self.node_s.last()?;
        if !(0.0..=total).contains(&s) {
            return None;
        }
        let n = self.node_s.len() - 1;
        let e = self.node_s.partition_point(|&x| x <= s).clamp(1, n) - 1;
        let (a, b) = (self.node_s[e], self.node_s[e + 1]);
        let nb = ((s - a) / (b - a)).clamp(0.0, 1.0);
        Some((e, 1.0 - nb, nb))
    }

    /// `out += scale * f(t)`.
    pub fn add_to(&self, t: f64, out: &mut [f64], scale: f64) {
        for l in &self.loads {
            if let Some((e, na, nb)) = self.place(l, t) {
                let f = scale * l.sign * l.magnitude;
                out[3 * e + l.component] += f * na;
                out[3 * e + 3 + l.component] += f * nb;
            }
        }
    }

    /// `f(t) . du`: their work over an increment with the loads where they are at `t`.
    pub fn work(&self, du: &[f64], t: f64) -> f64 {
        let mut work = 0.0;
        for l in &self.loads {
            if let Some((e, na, nb)) = self.place(l, t) {
                let f = l.sign * l.magnitude;
                work += f * (na * du[3 * e + l.component] + nb * du[3 * e + 3 + l.component]);
            }
        }
        work
    }
}
