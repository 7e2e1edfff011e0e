//! The scene's loads as the model sees them: each load's shape along the rod at unit magnitude,
//! its time law, moving loads, and the magnitudes of every load at a time (parameters and
//! inputs).
use crate::model::loads::{LoadShape, LoadTime};
use crate::model::moving_loads::MovingLoad;
use crate::scene::{Load, LoadKind, ParamValues, Scene, Slot, Std, TimeLaw};

/// The load shapes of a rod's scene (`station` the arc length of a station), and its moving
/// loads.
pub(super) fn load_shapes(
    scene: &Scene,
    values: &ParamValues,
    station: impl Fn(crate::scene::Station) -> f64,
    length: f64,
) -> (Vec<(LoadShape, LoadTime)>, Vec<MovingLoad>) {
    // Harmonic loads with the same amplitude slot share one nodal vector.
    let mut groups: Vec<Slot> = Vec::new();
    let mut time_of = |time: TimeLaw, value: Slot| time_law(&mut groups, time, value);
    let mut moving = Vec::new();
    let mut shapes: Vec<(LoadShape, LoadTime)> = (scene.loads.iter())
        .map(|l| match l.kind {
            LoadKind::Moving { speed, enter } => {
                moving.push(moving_load(l, speed, enter, values));
                let index = moving.len() - 1;
                (
                    load_shape(l, &station, length, false),
                    LoadTime::Moving { index },
                )
            }
            _ => (
                load_shape(l, &station, length, false),
                time_of(l.time, l.value),
            ),
        })
        .collect();
    // The weight of each point mass under each gravity load, after the scene's loads (its
    // magnitude: the acceleration times the mass, see `load_magnitudes`).
    for l in scene.loads.iter().filter(|l| l.kind == LoadKind::Gravity) {
        for m in &scene.masses {
            let (component, sign) = (l.direction.component, l.direction.sign);
            let at = LoadShape::Point {
                s: station(m.at),
                component,
                sign,
            };
            shapes.push((at, LoadTime::Constant));
        }
    }
    // The rising part of each linearly varying load, after those (its magnitude is the load's
    // `value_end`).
    for l in &scene.loads {
        if let LoadKind::Patch {
            value_end: Some(end),
            ..
        } = l.kind
        {
            shapes.push((load_shape(l, &station, length, true), time_of(l.time, end)));
        }
    }
    (shapes, moving)
}

/// The time law of a load; harmonic loads with the same amplitude slot share a group.
pub(super) fn time_law(groups: &mut Vec<Slot>, time: TimeLaw, value: Slot) -> LoadTime {
    match time {
        TimeLaw::Constant => LoadTime::Constant,
        TimeLaw::Input(_) => LoadTime::Input,
        TimeLaw::Harmonic => {
            let group = groups.iter().position(|g| *g == value).unwrap_or_else(|| {
                groups.push(value);
                groups.len() - 1
            });
            LoadTime::Harmonic { group }
        }
    }
}

/// A moving load's direction, speed and entry time.
pub(super) fn moving_load(l: &Load, speed: Slot, enter: Slot, values: &ParamValues) -> MovingLoad {
    MovingLoad {
        component: l.direction.component,
        sign: l.direction.sign,
        speed: speed.eval(values),
        enter: enter.eval(values),
        magnitude: 0.0,
    }
}

/// The nodal pattern of a load at unit magnitude on a rod (`station`: the arc length of a
/// station). A linearly varying load is two: the part falling from 1 at `from` to 0 at `to`
/// (`rising = false`, scaled by `value`) and the part rising from 0 to 1 (scaled by
/// `value_end`).
pub fn load_shape(
    load: &Load,
    station: &dyn Fn(crate::scene::Station) -> f64,
    length: f64,
    rising: bool,
) -> LoadShape {
    let (component, sign) = (load.direction.component, load.direction.sign);
    match load.kind {
        LoadKind::Point { at } | LoadKind::Moment { at } => LoadShape::Point {
            s: station(at),
            component,
            sign,
        },
        // Where it enters (its nodal forces follow it: `MovingLoads`).
        LoadKind::Moving { .. } => LoadShape::Point {
            s: 0.0,
            component,
            sign,
        },
        LoadKind::Distributed | LoadKind::Gravity => LoadShape::Distributed { component, sign },
        LoadKind::Patch {
            from,
            to,
            value_end,
            ..
        } => {
            let (start, end) = match (value_end, rising) {
                (None, _) => (1.0, 1.0),
                (Some(_), false) => (1.0, 0.0),
                (Some(_), true) => (0.0, 1.0),
            };
            LoadShape::Patch {
                from: from * length,
                to: to * length,
                start,
                end,
                component,
                sign,
            }
        }
    }
}

/// The magnitude of every load: its value slot (gravity: times the mass per length `rho A`),
/// or for input loads the input's value; then the point masses' weights and the end values of
/// the linearly varying loads.
pub fn load_magnitudes(scene: &Scene, values: &ParamValues, inputs: &[f64], out: &mut [f64]) {
    let (scene_loads, ends) = out.split_at_mut(scene.loads.len());
    for (m, l) in scene_loads.iter_mut().zip(&scene.loads) {
        *m = match (l.time, l.kind) {
            (TimeLaw::Input(i), _) => inputs[i],
            (_, LoadKind::Gravity) => {
                let area = scene.section.properties(values).area;
                l.value.eval(values) * values.std(Std::Rho) * area
            }
            _ => l.value.eval(values),
        };
    }
    let gravity = scene.loads.iter().filter(|l| l.kind == LoadKind::Gravity);
    let weights = gravity.flat_map(|l| scene.masses.iter().map(|m| l.value.eval(values) * m.m));
    let end_values = scene.loads.iter().filter_map(|l| match l.kind {
        LoadKind::Patch { value_end, .. } => value_end.map(|v| v.eval(values)),
        _ => None,
    });
    for (m, value) in ends.iter_mut().zip(weights.chain(end_values)) {
        *m = value;
    }
}
