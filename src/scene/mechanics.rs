//! What a scene's mechanics allow, judged without solving anything: the rigid-body motion its
//! supports, springs and foundations leave free, and read-outs its section cannot give.
use super::checker::entry;
use super::{Quantity, Scene};

/// The rigid-body motion the supports leave free, if any: the held dofs must see all three
/// planar rigid motions (two translations, a rotation about the origin) independently.
pub(super) fn free_rigid_motion(
    scene: &Scene,
    span: f64,
    rise: Option<f64>,
) -> Option<&'static str> {
    let curve = match rise {
        Some(h) => crate::model::ReferenceCurve::arc(span, h),
        None => crate::model::ReferenceCurve::Straight { length: span },
    };
    // Rows: what each held dof sees of (translation e1, translation e2, rotation).
    let mut rows: Vec<[f64; 3]> = Vec::new();
    // Supports, springs, stops and foundations (on u2 at both ends) restrain.
    let mut held: Vec<(f64, usize)> = Vec::new();
    for s in &scene.supports {
        held.extend((0..3).filter(|&k| s.fixed[k]).map(|k| (s.at.fraction(), k)));
    }
    let springs = scene.springs.iter().filter(|s| s.k > 0.0);
    held.extend(springs.map(|s| (s.at.fraction(), s.dof)));
    // A stop restrains where the static state presses on it (else the static solve says so).
    held.extend(scene.stops.iter().map(|s| (s.at.fraction(), s.dof)));
    let foundations = scene.foundations.iter().filter(|f| f.k > 0.0);
    held.extend(foundations.flat_map(|f| [(f.from, 1), (f.to, 1)]));
    for (at, k) in held {
        let x = curve.position(at * curve.length()) / span;
        rows.push(match k {
            0 => [1.0, 0.0, -x[1]],
            1 => [0.0, 1.0, x[0]],
            _ => [0.0, 0.0, 1.0],
        });
    }
    let m = nalgebra::DMatrix::from_fn(rows.len(), 3, |i, j| rows[i][j]);
    let rank = if rows.is_empty() { 0 } else { m.rank(1e-9) };
    if rank == 3 {
        return None;
    }
    // Name one free motion: a null vector of the rows.
    let free = |v: [f64; 3]| {
        rows.iter()
            .all(|r| (r[0] * v[0] + r[1] * v[1] + r[2] * v[2]).abs() < 1e-9)
    };
    Some(if free([1.0, 0.0, 0.0]) {
        "translate along e1"
    } else if free([0.0, 1.0, 0.0]) {
        "translate along e2"
    } else {
        "rotate"
    })
}

/// The key of the first sensor or shape field that reads a fiber stress, if any.
pub(super) fn fiber_stress_reader(scene: &Scene) -> Option<String> {
    let fiber = |q: Quantity| matches!(q, Quantity::SigmaTop | Quantity::SigmaBottom);
    if let Some(i) = scene.sensors.iter().position(|s| fiber(s.quantity)) {
        return Some(entry("sensor", i, Some(&scene.sensors[i].name), "quantity"));
    }
    scene
        .shape_fields
        .iter()
        .any(|&q| fiber(q))
        .then(|| "shape.fields".to_string())
}
