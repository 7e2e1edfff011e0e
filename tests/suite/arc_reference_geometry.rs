//! The reference geometry an arc scene gives its elements at their integration points, against
//! the closed-form circle through (0, 0), the crown (L/2, H) and (L, 0): radius
//! `R = (L^2/4 + H^2) / (2H)`, centre `(L/2, H - R)`, arc length `S = 2 R asin(L / 2R)`. At each
//! element's two Gauss points `s = s_a + l (1 + xi) / 2`, `xi = -+1/sqrt(3)` (in that order),
//! the position lies on the circle at the arc length `s` from the first end, the tangent angle
//! is the circle's (perpendicular to the radius, pointing along increasing `s`), and the
//! curvature between the two points is `-1/R` (the angle decreases: the arc turns clockwise).
//! The element's stiffness reads only these angles, so a wrong angle is a wrong arch.
//!
//! Run: `cargo test --profile quick --test suite arc_reference_geometry::`
use crate::common;

use common::simulation;

/// Angles and lengths here come from a handful of operations on numbers of order 1..100:
/// 1e-12 relative is a thousand round-offs.
const TOL: f64 = 1e-12;

#[test]
fn arc_elements_carry_the_circle_at_their_gauss_points() {
    // The paper's shallow arch, a deep one and a half circle; odd and even meshes.
    for (rise, elements) in [(2.0, 7), (2.0, 10), (9.0, 5), (16.0, 12)] {
        let sim = simulation("PinnedArch", &[("H", rise), ("elements", elements as f64)]);
        let rod = sim.rod();
        let span = 32.0;
        let radius = (0.25 * span * span + rise * rise) / (2.0 * rise);
        let centre = [0.5 * span, rise - radius];
        let half_angle = (0.5 * span / radius).asin();
        let length = 2.0 * radius * half_angle;
        let what = format!("H = {rise}, {elements} elements");
        assert!((rod.curve.length() - length).abs() < TOL * length, "{what}");
        assert_eq!(rod.elements.len(), elements, "{what}");
        let xi = 1.0 / 3f64.sqrt();
        // The radius to the first end, from which the arc length is the angle swept times R.
        let first = [-centre[0], -centre[1]];
        for (e, element) in rod.elements.iter().enumerate() {
            let l = length / elements as f64;
            assert!((element.length - l).abs() < TOL * l, "{what}: element {e}");
            let gauss = [-xi, xi].map(|x| e as f64 * l + 0.5 * l * (1.0 + x));
            let alpha = element.alpha();
            for (g, &s) in gauss.iter().enumerate() {
                let x = rod.curve.position(s);
                let r = [x[0] - centre[0], x[1] - centre[1]];
                let on_circle = (r[0].hypot(r[1]) - radius).abs();
                assert!(
                    on_circle < TOL * radius,
                    "{what}: element {e}, point {g} off the circle by {on_circle:e}"
                );
                // Clockwise angle from the first end's radius to this one, times R: the arc length.
                let swept =
                    (first[0] * r[1] - first[1] * r[0]).atan2(first[0] * r[0] + first[1] * r[1]);
                assert!(
                    (-swept * radius - s).abs() < TOL * length,
                    "{what}: element {e}, point {g}: at arc length {} instead of {s}",
                    -swept * radius
                );
                // The tangent: the radius turned clockwise by a right angle, (r2, -r1) / R.
                let expected = (-r[0]).atan2(r[1]);
                assert!(
                    (alpha[g] - expected).abs() < TOL,
                    "{what}: element {e}, Gauss point {g}: alpha {} instead of {expected}",
                    alpha[g]
                );
            }
            let curvature = (alpha[1] - alpha[0]) / (gauss[1] - gauss[0]);
            assert!(
                (curvature * radius + 1.0).abs() < 1e-10,
                "{what}: element {e}: curvature {curvature:e} instead of {:e}",
                -1.0 / radius
            );
        }
    }
}
