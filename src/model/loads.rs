//! External loads of fixed direction: `f_ext(t) = F cos(Omega t) q + P p`, with `q` the nodal
//! vector of the unit excitation (uniform per length, or at the crown) and `p` that of a unit
//! point force along `-e2` at `s = S/2` (constant preload plus the controller's `f_ctrl`).
use super::rod::Rod;

#[derive(Clone, Debug, PartialEq)]
pub struct LoadCase {
    /// Nodal forces of the excitation with unit amplitude.
    pub excitation_shape: Vec<f64>,
    /// Nodal forces of a unit point force along `-e2` at `s = S/2`.
    pub point_shape: Vec<f64>,
    /// `F`
    pub amplitude: f64,
    /// `Omega`
    pub frequency: f64,
    /// Constant point force at `s = S/2` along `-e2` (`P0 + f_ctrl`).
    pub point_force: f64,
}

/// Where the harmonic excitation acts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExcitationKind {
    /// Uniform load per unit length (the buckled beam).
    Distributed,
    /// Point load at `s = S/2` (the arches).
    Crown,
}

impl LoadCase {
    pub fn new(rod: &Rod, kind: ExcitationKind) -> LoadCase {
        let mut excitation_shape = vec![0.0; rod.dofs()];
        let mut point_shape = vec![0.0; rod.dofs()];
        rod.add_point_transverse_load(&mut point_shape, rod.midspan(), 1.0);
        match kind {
            ExcitationKind::Distributed => {
                rod.add_uniform_transverse_load(&mut excitation_shape, 1.0)
            }
            ExcitationKind::Crown => excitation_shape.copy_from_slice(&point_shape),
        }
        LoadCase {
            excitation_shape,
            point_shape,
            amplitude: 0.0,
            frequency: 0.0,
            point_force: 0.0,
        }
    }

    /// Excitation amplitude factor `F cos(Omega t)`.
    pub fn excitation(&self, t: f64) -> f64 {
        self.amplitude * (self.frequency * t).cos()
    }

    /// `out += scale * f_ext(t)`.
    pub fn add_to(&self, t: f64, out: &mut [f64], scale: f64) {
        let a = scale * self.excitation(t);
        let p = scale * self.point_force;
        for ((o, q), pp) in out
            .iter_mut()
            .zip(&self.excitation_shape)
            .zip(&self.point_shape)
        {
            *o += a * q + p * pp;
        }
    }
}
