//! Cross-section stiffness and inertia: of a rectangular `b x h` section (model.md: no shear
//! correction factor), or of any section from its area, second moment and shear area.

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Section {
    /// Axial stiffness `EA`.
    pub ea: f64,
    /// Shear stiffness `GA`, `G = E / (2 (1 + nu))`.
    pub ga: f64,
    /// Bending stiffness `EI`, `I = b h^3 / 12`.
    pub ei: f64,
    /// Mass per length `rho A`.
    pub rho_a: f64,
    /// Rotary inertia per length `rho I`.
    pub rho_i: f64,
}

impl Section {
    pub fn rectangular(e: f64, nu: f64, rho: f64, b: f64, h: f64) -> Section {
        let area = b * h;
        let inertia = b * h * h * h / 12.0;
        let shear_modulus = e / (2.0 * (1.0 + nu));
        Section {
            ea: e * area,
            ga: shear_modulus * area,
            ei: e * inertia,
            rho_a: rho * area,
            rho_i: rho * inertia,
        }
    }

    /// A section of area `area`, second moment of area `inertia` and shear area `shear_area`
    /// (`GA_s` is the shear stiffness).
    pub fn from_properties(
        e: f64,
        nu: f64,
        rho: f64,
        area: f64,
        inertia: f64,
        shear_area: f64,
    ) -> Section {
        let shear_modulus = e / (2.0 * (1.0 + nu));
        Section {
            ea: e * area,
            ga: shear_modulus * shear_area,
            ei: e * inertia,
            rho_a: rho * area,
            rho_i: rho * inertia,
        }
    }
}
