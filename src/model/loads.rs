//! External loads of fixed direction: `f_ext(t) = sum_g A_g cos(Omega t) q_g + s`, where each
//! harmonic group `g` (loads sharing one amplitude) has the summed nodal vector `q_g` of its
//! loads at unit magnitude, and `s` is the steady part: the constant loads and the input loads
//! (held over a communication step) times their nodal vectors. Steady loads with the same nodal
//! vector are summed before they are spread, so a preload and a control force at one point act
//! as one force, as a single load would.
use super::moving_loads::MovingLoads;
use super::rod::Rod;
use std::cell::Cell;

/// When a load acts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadTime {
    Constant,
    /// `magnitude cos(Omega t)`; loads with the same `group` share their magnitude.
    Harmonic {
        group: usize,
    },
    /// An input, held over a communication step.
    Input,
    /// Moving load `index` of [`LoadSet::with_moving`] (its shape is not used).
    Moving {
        index: usize,
    },
}

/// Where a load acts, along a fixed direction: `component` 0 (`e1`) or 1 (`e2`), `sign` +-1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LoadShape {
    /// At arc length `s`, shared by the shape functions when `s` falls inside an element.
    Point { s: f64, component: usize, sign: f64 },
    /// Uniform per unit length over the whole rod.
    Distributed { component: usize, sign: f64 },
    /// Per unit length over the arc lengths `[from, to]`, with the intensity `start` at `from`
    /// and `end` at `to`, linear in between.
    Patch {
        from: f64,
        to: f64,
        start: f64,
        end: f64,
        component: usize,
        sign: f64,
    },
}

impl LoadShape {
    /// The nodal forces of this load at unit magnitude.
    pub fn nodal_vector(&self, rod: &Rod) -> Vec<f64> {
        let mut out = vec![0.0; rod.dofs()];
        match *self {
            LoadShape::Point { s, component, sign } => {
                let p = rod.point_at(s);
                let (na, nb) = p.weights;
                out[3 * p.element + component] += sign * na;
                out[3 * (p.element + 1) + component] += sign * nb;
            }
            LoadShape::Distributed { component, sign } => {
                for (e, el) in rod.elements.iter().enumerate() {
                    let half = 0.5 * el.length;
                    out[3 * e + component] += sign * half;
                    out[3 * (e + 1) + component] += sign * half;
                }
            }
            LoadShape::Patch {
                from,
                to,
                start,
                end,
                component,
                sign,
            } => {
                let intensity = |s: f64| start + (end - start) * (s - from) / (to - from);
                for e in 0..rod.elements.len() {
                    let (a, b) = (rod.node_s[e], rod.node_s[e + 1]);
                    let (lo, hi) = (a.max(from), b.min(to));
                    if hi <= lo {
                        continue;
                    }
                    // Simpson's rule: exact for the quadratic q(s) N(s) over the overlap.
                    let mut integrals = [0.0; 2];
                    for (s, w) in [(lo, 1.0), (0.5 * (lo + hi), 4.0), (hi, 1.0)] {
                        let nb = (s - a) / (b - a);
                        let q = w * (hi - lo) / 6.0 * intensity(s);
                        integrals[0] += q * (1.0 - nb);
                        integrals[1] += q * nb;
                    }
                    out[3 * e + component] += sign * integrals[0];
                    out[3 * (e + 1) + component] += sign * integrals[1];
                }
            }
        }
        out
    }
}

/// Steady loads that share one nodal vector.
#[derive(Clone, Debug, PartialEq)]
struct SteadyEntry {
    shape: Vec<f64>,
    loads: Vec<usize>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct LoadSet {
    times: Vec<LoadTime>,
    /// Per harmonic group: its summed unit nodal vector and current amplitude.
    harmonic: Vec<(Vec<f64>, f64)>,
    steady_entries: Vec<SteadyEntry>,
    /// `Omega`
    pub frequency: f64,
    steady: Vec<f64>,
    /// The constant and the input part of `steady` (for the energy ledger), and whether there
    /// are any such loads (the ledger skips the products with vectors that stay zero).
    constant_part: Vec<f64>,
    input_part: Vec<f64>,
    has_constant: bool,
    has_input: bool,
    /// The last `(Omega, t, cos(Omega t))`: a step asks for the excitation at its midpoint
    /// twice (its equation and its energy ledger), and the cosine of a large argument is not
    /// cheap.
    last_cos: Cell<(f64, f64, f64)>,
    /// Point forces travelling along the rod (none: no cost).
    moving: MovingLoads,
    /// `(dof, force)` that moving spring bases exert through their springs, set before each
    /// sub-step by the simulation, which also books their work (none: no cost).
    base_forces: Vec<(usize, f64)>,
}

impl LoadSet {
    /// Loads `(where, when)` on `rod`, all with magnitude 0 until [`LoadSet::set_magnitudes`].
    pub fn new(rod: &Rod, loads: &[(LoadShape, LoadTime)]) -> LoadSet {
        let vectors = (loads.iter())
            .map(|(shape, time)| match time {
                // Placed as they travel (`MovingLoads`).
                LoadTime::Moving { .. } => (Vec::new(), *time),
                _ => (shape.nodal_vector(rod), *time),
            })
            .collect();
        LoadSet::from_vectors(rod.dofs(), vectors)
    }

    /// Loads given by their nodal vectors at unit magnitude (folded, for a structure) over
    /// `n` dofs, and when they act (a moving load's vector is not used).
    pub fn from_vectors(n: usize, loads: Vec<(Vec<f64>, LoadTime)>) -> LoadSet {
        let groups = loads
            .iter()
            .filter_map(|(_, t)| match t {
                LoadTime::Harmonic { group } => Some(group + 1),
                _ => None,
            })
            .max()
            .unwrap_or(0);
        let mut harmonic = vec![(vec![0.0; n], 0.0); groups];
        let mut steady_entries: Vec<SteadyEntry> = Vec::new();
        for (i, (q, time)) in loads.iter().enumerate() {
            if let LoadTime::Moving { .. } = time {
                continue;
            }
            match *time {
                LoadTime::Harmonic { group } => {
                    let sum = &mut harmonic[group].0;
                    if sum.iter().all(|&x| x == 0.0) {
                        sum.copy_from_slice(q);
                    } else {
                        sum.iter_mut().zip(q).for_each(|(a, b)| *a += b);
                    }
                }
                LoadTime::Moving { .. } => {}
                LoadTime::Constant | LoadTime::Input => {
                    match steady_entries.iter_mut().find(|e| &e.shape == q) {
                        Some(entry) => entry.loads.push(i),
                        None => steady_entries.push(SteadyEntry {
                            shape: q.clone(),
                            loads: vec![i],
                        }),
                    }
                }
            }
        }
        LoadSet {
            has_constant: loads.iter().any(|(_, t)| *t == LoadTime::Constant),
            has_input: loads.iter().any(|(_, t)| *t == LoadTime::Input),
            times: loads.iter().map(|(_, t)| *t).collect(),
            harmonic,
            steady_entries,
            frequency: 0.0,
            steady: vec![0.0; n],
            constant_part: vec![0.0; n],
            input_part: vec![0.0; n],
            last_cos: Cell::new((f64::NAN, f64::NAN, f64::NAN)),
            moving: MovingLoads::default(),
            base_forces: Vec::new(),
        }
    }

    /// The same loads with room for a force on each of these dofs (the springs whose bases
    /// move), 0 until [`LoadSet::set_base_force`].
    pub fn with_base_forces(mut self, dofs: &[usize]) -> LoadSet {
        self.base_forces = dofs.iter().map(|&d| (d, 0.0)).collect();
        self
    }

    /// Sets the force of the `i`-th moving spring base (in the order of `with_base_forces`).
    pub fn set_base_force(&mut self, i: usize, force: f64) {
        self.base_forces[i].1 = force;
    }

    /// The same loads with the travelling ones (the targets of [`LoadTime::Moving`]).
    pub fn with_moving(mut self, moving: MovingLoads) -> LoadSet {
        self.moving = moving;
        self
    }

    /// Sets every load's magnitude (harmonic: its amplitude; loads of one group must agree)
    /// and rebuilds the steady vector. Allocates nothing.
    pub fn set_magnitudes(&mut self, magnitudes: &[f64]) {
        for (m, t) in magnitudes.iter().zip(&self.times) {
            match t {
                LoadTime::Harmonic { group } => self.harmonic[*group].1 = *m,
                LoadTime::Moving { index } => self.moving.loads[*index].magnitude = *m,
                _ => {}
            }
        }
        self.steady.fill(0.0);
        self.constant_part.fill(0.0);
        self.input_part.fill(0.0);
        for entry in &self.steady_entries {
            let mut total = 0.0;
            let (mut constant, mut input) = (0.0, 0.0);
            for &i in &entry.loads {
                total += magnitudes[i];
                match self.times[i] {
                    LoadTime::Input => input += magnitudes[i],
                    _ => constant += magnitudes[i],
                }
            }
            for (k, q) in entry.shape.iter().enumerate() {
                self.steady[k] += total * q;
                self.constant_part[k] += constant * q;
                self.input_part[k] += input * q;
            }
        }
    }

    /// `cos(Omega t)` times the amplitude of harmonic group `g`.
    pub fn excitation(&self, g: usize, t: f64) -> f64 {
        let (omega, at, value) = self.last_cos.get();
        let cos = if omega == self.frequency && at == t {
            value
        } else {
            let value = libm::cos(self.frequency * t);
            self.last_cos.set((self.frequency, t, value));
            value
        };
        self.harmonic[g].1 * cos
    }

    /// `out += scale * f_ext(t)`.
    pub fn add_to(&self, t: f64, out: &mut [f64], scale: f64) {
        if !self.moving.is_empty() {
            self.moving.add_to(t, out, scale);
        }
        for &(dof, force) in &self.base_forces {
            out[dof] += scale * force;
        }
        match self.harmonic.as_slice() {
            [] => {
                for (o, s) in out.iter_mut().zip(&self.steady) {
                    *o += scale * s;
                }
            }
            // The step's residual takes -f_ext: `-s` is exactly `-1 * s`, one product less.
            [(q, _)] if scale == -1.0 => {
                let a = scale * self.excitation(0, t);
                for ((o, q), s) in out.iter_mut().zip(q).zip(&self.steady) {
                    *o += a * q - s;
                }
            }
            [(q, _)] => {
                let a = scale * self.excitation(0, t);
                for ((o, q), s) in out.iter_mut().zip(q).zip(&self.steady) {
                    *o += a * q + scale * s;
                }
            }
            groups => {
                for (o, s) in out.iter_mut().zip(&self.steady) {
                    *o += scale * s;
                }
                for (g, (q, _)) in groups.iter().enumerate() {
                    let a = scale * self.excitation(g, t);
                    out.iter_mut().zip(q).for_each(|(o, q)| *o += a * q);
                }
            }
        }
    }

    /// The work of the loads over an increment `du` with the harmonic loads taken at `t`:
    /// `(constant and harmonic, input)`; not the spring bases' forces (booked apart).
    pub fn work(&self, du: &[f64], t: f64) -> (f64, f64) {
        let dot = |f: &[f64], any: bool| {
            if any {
                du.iter().zip(f).map(|(a, b)| a * b).sum::<f64>()
            } else {
                0.0
            }
        };
        let harmonic: f64 = (0..self.harmonic.len())
            .map(|g| self.excitation(g, t) * dot(&self.harmonic[g].0, true))
            .sum();
        let moving = if self.moving.is_empty() {
            0.0
        } else {
            self.moving.work(du, t)
        };
        (
            harmonic + moving + dot(&self.constant_part, self.has_constant),
            dot(&self.input_part, self.has_input),
        )
    }

    /// The constant loads' nodal force at dof `k`.
    pub fn constant_at(&self, k: usize) -> f64 {
        self.constant_part[k]
    }

    /// The constant loads alone (the loads of the initial static state).
    pub fn constant_vector(&self) -> &[f64] {
        &self.constant_part
    }

    /// The number of loads (magnitudes of [`LoadSet::set_magnitudes`]).
    pub fn len(&self) -> usize {
        self.times.len()
    }

    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    pub fn has_harmonic(&self) -> bool {
        self.harmonic.iter().any(|(_, a)| *a != 0.0)
    }
}
