//! What a sensor (or a shape field) reads: a nodal dof interpolated with the shape functions
//! (displacement, velocity, acceleration), or a quantity of the cross-section (strain, stress
//! resultant, fiber stress) from the elements' own strains and resultants.

/// A quantity of the cross-section (docs/scenes.md, "Section quantities").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SectionQuantity {
    /// Axial strain `eps = N / EA`.
    Eps,
    /// Shear strain `gamma = Q / GAs`.
    Gamma,
    /// Curvature change `kappa = M / EI`.
    Kappa,
    /// Normal force along the director `d1`.
    N,
    /// Shear force along the director `d2`.
    Q,
    /// Bending moment (counter-clockwise).
    M,
    /// Fiber stress on the `+d2` face, `N/A - M depth / (2 I)`.
    SigmaTop,
    /// Fiber stress on the `-d2` face, `N/A + M depth / (2 I)`.
    SigmaBottom,
}

/// How a quantity is read from the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reading {
    /// Dof `dof` (0 `u1`, 1 `u2`, 2 `w`) of the nodal displacements (`order` 0), velocities (1)
    /// or accelerations (2), interpolated with the shape functions.
    Nodal {
        dof: usize,
        order: usize,
    },
    Section(SectionQuantity),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    U1,
    U2,
    W,
    V1,
    V2,
    Vw,
    A1,
    A2,
    Aw,
    Eps,
    Gamma,
    Kappa,
    N,
    Q,
    M,
    SigmaTop,
    SigmaBottom,
}

impl Quantity {
    /// Every quantity, in the order of [`Quantity::NAMES`].
    pub const ALL: [Quantity; 17] = [
        Quantity::U1,
        Quantity::U2,
        Quantity::W,
        Quantity::V1,
        Quantity::V2,
        Quantity::Vw,
        Quantity::A1,
        Quantity::A2,
        Quantity::Aw,
        Quantity::Eps,
        Quantity::Gamma,
        Quantity::Kappa,
        Quantity::N,
        Quantity::Q,
        Quantity::M,
        Quantity::SigmaTop,
        Quantity::SigmaBottom,
    ];

    /// The names a scene file uses (`quantity = "..."`, `[shape] fields`).
    pub const NAMES: [&'static str; 17] = [
        "u1",
        "u2",
        "w",
        "v1",
        "v2",
        "vw",
        "a1",
        "a2",
        "aw",
        "eps",
        "gamma",
        "kappa",
        "N",
        "Q",
        "M",
        "sigma_top",
        "sigma_bottom",
    ];

    pub fn name(self) -> &'static str {
        Quantity::NAMES[self as usize]
    }

    pub fn from_name(name: &str) -> Option<Quantity> {
        Quantity::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| Quantity::ALL[i])
    }

    pub fn reading(self) -> Reading {
        use SectionQuantity as S;
        let nodal = |order: usize, dof: usize| Reading::Nodal { dof, order };
        match self {
            Quantity::U1 => nodal(0, 0),
            Quantity::U2 => nodal(0, 1),
            Quantity::W => nodal(0, 2),
            Quantity::V1 => nodal(1, 0),
            Quantity::V2 => nodal(1, 1),
            Quantity::Vw => nodal(1, 2),
            Quantity::A1 => nodal(2, 0),
            Quantity::A2 => nodal(2, 1),
            Quantity::Aw => nodal(2, 2),
            Quantity::Eps => Reading::Section(S::Eps),
            Quantity::Gamma => Reading::Section(S::Gamma),
            Quantity::Kappa => Reading::Section(S::Kappa),
            Quantity::N => Reading::Section(S::N),
            Quantity::Q => Reading::Section(S::Q),
            Quantity::M => Reading::Section(S::M),
            Quantity::SigmaTop => Reading::Section(S::SigmaTop),
            Quantity::SigmaBottom => Reading::Section(S::SigmaBottom),
        }
    }

    /// The dof of a displacement or rotation (`u1`, `u2`, `w`); `None` for anything else.
    pub fn displacement_dof(self) -> Option<usize> {
        match self.reading() {
            Reading::Nodal { dof, order: 0 } => Some(dof),
            _ => None,
        }
    }

    /// Whether reading it needs the acceleration of the last sub-step.
    pub fn is_acceleration(self) -> bool {
        matches!(self.reading(), Reading::Nodal { order: 2, .. })
    }

    /// The SI unit the FMU declares.
    pub fn unit(self) -> &'static str {
        use SectionQuantity as S;
        match self.reading() {
            Reading::Nodal { dof, order } => {
                let rotation = dof == 2;
                match (rotation, order) {
                    (false, 0) => "m",
                    (true, 0) => "rad",
                    (false, 1) => "m/s",
                    (true, 1) => "rad/s",
                    (false, _) => "m/s2",
                    (true, _) => "rad/s2",
                }
            }
            Reading::Section(S::Eps | S::Gamma) => "1",
            Reading::Section(S::Kappa) => "1/m",
            Reading::Section(S::N | S::Q) => "N",
            Reading::Section(S::M) => "N.m",
            Reading::Section(S::SigmaTop | S::SigmaBottom) => "Pa",
        }
    }

    /// What it is, for variable descriptions.
    pub fn what(self) -> &'static str {
        [
            "Displacement u1",
            "Displacement u2",
            "Rotation w",
            "Velocity v1",
            "Velocity v2",
            "Angular velocity vw",
            "Acceleration a1 (over the last sub-step)",
            "Acceleration a2 (over the last sub-step)",
            "Angular acceleration aw (over the last sub-step)",
            "Axial strain eps",
            "Shear strain gamma",
            "Curvature change kappa",
            "Normal force N",
            "Shear force Q",
            "Bending moment M",
            "Fiber stress on the top (+d2) face",
            "Fiber stress on the bottom (-d2) face",
        ][self as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_readings_are_distinct() {
        for (i, q) in Quantity::ALL.iter().enumerate() {
            assert_eq!(*q as usize, i);
            assert_eq!(Quantity::from_name(q.name()), Some(*q));
            for other in &Quantity::ALL[..i] {
                assert_ne!(q.reading(), other.reading());
            }
        }
        assert_eq!(Quantity::from_name("moment"), None);
        assert_eq!(Quantity::U2.displacement_dof(), Some(1));
        assert_eq!(Quantity::V2.displacement_dof(), None);
        assert!(Quantity::Aw.is_acceleration() && !Quantity::Vw.is_acceleration());
    }
}
