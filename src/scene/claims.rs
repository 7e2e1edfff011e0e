//! What the variables of a scene claim: a unique name each, and a value reference inside its
//! block (scene parameters from 100, inputs from 1000, sensors from 2000, reactions from 3000,
//! shape samples from 10000 and 20000). A scene that breaks either is refused with the key
//! that makes it.
use super::checker::{entry, item};
use super::params::SCENE_PARAM_VR;
use super::stops::{STOP_CONTACT_VR, STOP_FORCE_VR};
use super::variables::{
    INPUT_VR, MAX_INPUTS, MAX_SCENE_PARAMS, MAX_SENSORS, MAX_SUPPORTS, REACTION_SUFFIXES,
    REACTION_VR, SENSOR_VR, SHAPE_X_VR, STANDARD_OUTPUTS,
};
use super::{InputKind, Scene};
use std::collections::BTreeMap;

/// Every name an FMU variable of this scene would get must be unique; a clash is reported with
/// the scene key that makes it.
pub fn check_names(scene: &Scene) -> Result<(), (String, String)> {
    let mut seen: BTreeMap<String, String> = BTreeMap::new();
    let mut claim = |name: String, by: String| -> Result<(), (String, String)> {
        match seen.get(&name) {
            Some(first) => Err((
                by.clone(),
                format!("the name `{name}` is used twice: by {first} and by {by}"),
            )),
            None => {
                seen.insert(name, by);
                Ok(())
            }
        }
    };
    for p in &scene.params {
        claim(p.name.clone(), format!("parameter {}", p.name))?;
    }
    for (_, name, ..) in STANDARD_OUTPUTS {
        claim(name.to_string(), format!("the standard output {name}"))?;
    }
    for i in &scene.inputs {
        claim(i.name.clone(), format!("the input {}", i.name))?;
    }
    for s in &scene.sensors {
        claim(s.name.clone(), format!("[[sensor]] {}", s.name))?;
    }
    for s in &scene.supports {
        for suffix in REACTION_SUFFIXES {
            claim(
                format!("{}_{suffix}", s.name),
                format!("the reactions of [[support]] {}", s.name),
            )?;
        }
    }
    for l in &scene.loads {
        if !matches!(l.time, super::TimeLaw::Input(_)) {
            // Only input loads become variables, but a load name is still one name.
            claim(l.name.clone(), format!("[[load]] {}", l.name))?;
        }
    }
    for s in &scene.stops {
        for suffix in ["force", "contact"] {
            claim(
                format!("{}_{suffix}", s.name),
                format!("the outputs of [[stop]] {}", s.name),
            )?;
        }
    }
    for n in ["shape_x", "shape_y"] {
        claim(n.to_string(), "the shape outputs".to_string())?;
    }
    for n in ["lyapunov", "lyapunov_per_period", "lyapunov_time"] {
        claim(n.to_string(), "the Lyapunov outputs".to_string())?;
    }
    Ok(())
}

/// Every value reference of the scene must stay in its block: too many scene parameters,
/// inputs, sensors or supports are refused with the key of the first one too many.
pub fn check_blocks(scene: &Scene) -> Result<(), (String, String)> {
    let own: Vec<&str> = (scene.params.iter())
        .filter(|p| p.vr >= SCENE_PARAM_VR)
        .map(|p| p.name.as_str())
        .collect();
    let over = |count: usize, max: usize, what: &str, block: String| {
        format!("{count} {what}: a scene has at most {max} ({block})")
    };
    if own.len() > MAX_SCENE_PARAMS {
        return Err((
            item(
                "parameter",
                MAX_SCENE_PARAMS,
                Some(&own[MAX_SCENE_PARAMS].to_string()),
            ),
            over(
                own.len(),
                MAX_SCENE_PARAMS,
                "[[parameter]] entries",
                format!(
                    "value references {SCENE_PARAM_VR}-{}; the inputs start at {INPUT_VR}",
                    INPUT_VR - 1
                ),
            ),
        ));
    }
    if let Some(input) = scene.inputs.get(MAX_INPUTS) {
        let key = match input.kind {
            InputKind::Load(l) => entry("load", l, Some(&scene.loads[l].name), "time"),
            InputKind::Motion { support, .. } => entry(
                "support",
                support,
                Some(&scene.supports[support].name),
                "motion",
            ),
            InputKind::SpringBase(k) => entry("spring", k, Some(&scene.springs[k].name), "motion"),
        };
        return Err((
            key,
            over(
                scene.inputs.len(),
                MAX_INPUTS,
                "FMI inputs (input loads, support motions one per held dof, spring bases)",
                format!(
                    "value references {INPUT_VR}-{}; the sensors start at {SENSOR_VR}",
                    SENSOR_VR - 1
                ),
            ),
        ));
    }
    if let Some(sensor) = scene.sensors.get(MAX_SENSORS) {
        return Err((
            item("sensor", MAX_SENSORS, Some(&sensor.name)),
            over(
                scene.sensors.len(),
                MAX_SENSORS,
                "[[sensor]] entries",
                format!(
                    "value references {SENSOR_VR}-{}; the support reactions start at {REACTION_VR}",
                    REACTION_VR - 1
                ),
            ),
        ));
    }
    let max_stops = (STOP_CONTACT_VR - STOP_FORCE_VR) as usize;
    if let Some(stop) = scene.stops.get(max_stops) {
        return Err((
            item("stop", max_stops, Some(&stop.name)),
            over(
                scene.stops.len(),
                max_stops,
                "[[stop]] entries",
                format!("value references {STOP_FORCE_VR}-{}", STOP_CONTACT_VR - 1),
            ),
        ));
    }
    if let Some(support) = scene.supports.get(MAX_SUPPORTS) {
        return Err((
            item("support", MAX_SUPPORTS, Some(&support.name)),
            over(
                scene.supports.len(),
                MAX_SUPPORTS,
                "[[support]] entries",
                format!(
                    "3 reactions each, value references {REACTION_VR}-{}; the shape outputs start at {SHAPE_X_VR}",
                    REACTION_VR + 3 * MAX_SUPPORTS as u32 - 1
                ),
            ),
        ));
    }
    Ok(())
}
