//! Reference curves `X(s)` parametrized by arc length, with the tangent angle `alpha(s)` measured
//! from `e1` (model.md: `G = cos(alpha) e1 + sin(alpha) e2`).
//! [`Placement`]: where a curve lies in the plane (a frame member's, from its `from` joint).
use nalgebra::Vector2;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReferenceCurve {
    /// Straight rod from the origin along `e1`.
    Straight { length: f64 },
    /// Circular arc from `(0, 0)` to `(span, 0)` through the crown `(span/2, rise)`.
    CircularArc {
        radius: f64,
        half_angle: f64,
        span: f64,
        rise: f64,
    },
    /// Two straight bars `(0, 0) -> (span/2, rise) -> (span, 0)` (a von Mises truss), kinked at
    /// `s = S/2`; mesh it with an even number of elements so the kink falls on a node.
    TwoBar { span: f64, rise: f64 },
}

impl ReferenceCurve {
    /// The circular arc of span `L` and rise `H`: `R = (L^2/4 + H^2) / (2H)`,
    /// `t0 = asin(L / (2R))`, `alpha(s) = t0 - s/R`.
    pub fn arc(span: f64, rise: f64) -> ReferenceCurve {
        let radius = (0.25 * span * span + rise * rise) / (2.0 * rise);
        let half_angle = libm::asin((0.5 * span / radius).clamp(-1.0, 1.0));
        ReferenceCurve::CircularArc {
            radius,
            half_angle,
            span,
            rise,
        }
    }

    /// Arc length `S`.
    pub fn length(&self) -> f64 {
        match *self {
            ReferenceCurve::Straight { length } => length,
            ReferenceCurve::CircularArc {
                radius, half_angle, ..
            } => 2.0 * radius * half_angle,
            ReferenceCurve::TwoBar { span, rise } => {
                2.0 * (0.25 * span * span + rise * rise).sqrt()
            }
        }
    }

    /// Tangent angle `alpha(s)` from `e1`.
    pub fn tangent_angle(&self, s: f64) -> f64 {
        match *self {
            ReferenceCurve::Straight { .. } => 0.0,
            ReferenceCurve::CircularArc {
                radius, half_angle, ..
            } => half_angle - s / radius,
            ReferenceCurve::TwoBar { span, rise } => {
                let angle = libm::atan2(rise, 0.5 * span);
                if s < 0.5 * self.length() {
                    angle
                } else {
                    -angle
                }
            }
        }
    }

    /// Position `X(s)`.
    pub fn position(&self, s: f64) -> Vector2<f64> {
        match *self {
            ReferenceCurve::Straight { .. } => Vector2::new(s, 0.0),
            ReferenceCurve::CircularArc {
                radius,
                half_angle,
                span,
                rise,
            } => {
                let a = half_angle - s / radius;
                Vector2::new(
                    0.5 * span - radius * libm::sin(a),
                    rise - radius + radius * libm::cos(a),
                )
            }
            ReferenceCurve::TwoBar { span, rise } => {
                let bar = 0.5 * self.length();
                let (x, y) = (0.5 * span / bar, rise / bar);
                if s <= bar {
                    Vector2::new(x * s, y * s)
                } else {
                    Vector2::new(x * s, y * (2.0 * bar - s))
                }
            }
        }
    }
}

/// Where a rod's reference curve lies in the plane: its curve (which starts at the origin
/// along `e1`), mirrored across `e1` if `mirrored`, turned by `angle` about the origin, then
/// moved to `origin`. A member of a frame is placed so that its curve runs from its `from`
/// joint to its `to` joint (an arc bulging to the right of that chord is mirrored).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub origin: Vector2<f64>,
    pub angle: f64,
    pub mirrored: bool,
    /// `(cos angle, sin angle)`.
    pub direction: Vector2<f64>,
}

impl Placement {
    pub fn new(origin: Vector2<f64>, angle: f64) -> Placement {
        Placement {
            origin,
            angle,
            mirrored: false,
            direction: Vector2::new(libm::cos(angle), libm::sin(angle)),
        }
    }

    /// The same placement, mirrored.
    pub fn mirrored(mut self) -> Placement {
        self.mirrored = true;
        self
    }

    /// `origin + R(angle) x` (with `x` mirrored first when the placement is).
    pub fn place(&self, x: Vector2<f64>) -> Vector2<f64> {
        let (c, s) = (self.direction[0], self.direction[1]);
        let y = if self.mirrored { -x[1] } else { x[1] };
        self.origin + Vector2::new(c * x[0] - s * y, s * x[0] + c * y)
    }

    /// A tangent angle of the curve, placed.
    pub fn turn(&self, alpha: f64) -> f64 {
        if self.mirrored {
            self.angle - alpha
        } else {
            self.angle + alpha
        }
    }
}
