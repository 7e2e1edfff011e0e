//! From a scene file's text to a checked [`Scene`]: types and key names (serde), then every
//! value, every name and every reference, then the mechanics that can be judged without
//! solving anything (`mechanics.rs`: a rigid-body motion left free, read-outs the section cannot
//! give). The sections are checked here, `[defaults]` and `[[parameter]]` in `param_tables.rs`,
//! the items (supports, loads, sensors) in `items.rs`,
//! with the tools of `checker.rs`.
use super::checker::Checker;
use super::file::SceneFile;
use super::param_tables::{apply_defaults, scene_parameter};
use super::params::{self, Needs, Param, Range};
use super::{attached, claims, damping, items, mechanics, sections};
use super::{
    Branch, DefaultExperiment, Geometry, Initial, InitialState, Scene, SceneError, Sensor,
};

/// The scene in `text`, checked completely; `file` names it in every message.
pub fn check(text: &str, file: &str) -> Result<Scene, SceneError> {
    let c = Checker { file };
    if text.trim().is_empty() {
        return c.err(
            "",
            "the file is empty: a scene needs at least `name`, [geometry] and one [[support]] \
             (see docs/scenes.md)",
        );
    }
    let raw: SceneFile = super::syntax::read(text, file)?;
    let name = c.identifier(raw.name.as_ref(), "name")?;
    let experiment = experiment(&c, &raw)?;
    let mut frame = super::frame_read::frame(&c, &raw.joint, &raw.member)?;
    let (geometry, span, rise) =
        match &frame {
            None => geometry(&c, &raw)?,
            Some(_) if raw.geometry.is_some() => return c.err(
                "[geometry]",
                "a file is one rod ([geometry]) or a frame ([[joint]]s and [[member]]s), not both",
            ),
            Some(f) => (Geometry::Frame, f.extent(), None),
        };
    super::frame_read::links(&c, &raw.link, frame.as_mut())?;

    let harmonic = raw
        .load
        .iter()
        .any(|l| l.time.as_deref() == Some("harmonic"));
    let initial_raw = raw.initial.as_ref();
    let branch = initial_raw.and_then(|i| i.branch.as_deref());
    let needs = Needs {
        harmonic,
        arc: geometry == Geometry::Arc,
        branch: branch.is_some(),
    };
    let mut params = params::standard_params(&needs);
    params[super::Std::Span as usize].start = span;
    if geometry == Geometry::Frame {
        // A frame's joints fix its geometry: L reports its size.
        let l = &mut params[super::Std::Span as usize];
        l.description = "Size of the frame: the largest distance between two of its joints \
                         (its joints fix the geometry: informative)"
            .to_string();
        l.range = Range::between(span, span);
    }
    if let Some(h) = rise {
        let i = params.iter().position(|p| p.name == "H").expect("arc");
        params[i].start = h;
    }
    require_material(&c, &raw)?;
    let number_in_defaults = |name: &str| match raw.defaults.get(name) {
        None => Ok(None),
        Some(toml::Value::Float(x)) => Ok(Some(*x)),
        Some(toml::Value::Integer(i)) => Ok(Some(*i as f64)),
        Some(other) => c.err(
            format!("defaults.{name}"),
            format!("{other} is not a number"),
        ),
    };
    let (section, dimensions, section_shear) = sections::section(
        &c,
        raw.section.as_ref(),
        &number_in_defaults,
        params::SECTION_AT,
    )?;
    params.splice(params::SECTION_AT..params::SECTION_AT, dimensions);
    apply_defaults(&c, &raw, &mut params, harmonic)?;
    for (i, p) in raw.parameter.iter().enumerate() {
        let param = scene_parameter(&c, i, p, &params)?;
        params.push(param);
    }
    if let Some(f) = frame.as_mut() {
        sections::member_parameters(&mut f.members, &mut params);
    }
    let frame_ref = frame.as_ref();

    let mut inputs = Vec::new();
    let supports = items::supports(&c, &raw.support, &params, frame_ref, &mut inputs)?;
    let loads = items::loads(&c, &raw.load, &mut params, frame_ref, &mut inputs)?;
    // Spring bases' inputs after the loads': earlier scenes keep their value references.
    let springs = attached::springs(&c, &raw.spring, &supports, frame_ref, &mut inputs)?;
    let stops = super::stops::stops(&c, &raw.stop, &supports, frame_ref)?;
    items::label_amplitude(&loads, &mut params);
    let sensors = raw
        .sensor
        .iter()
        .enumerate()
        .map(|(i, s)| items::sensor(&c, i, s, frame_ref))
        .collect::<Result<Vec<_>, _>>()?;
    let (shape_points, shape_fields) = super::readouts::shape(&c, raw.shape.as_ref())?;
    let initial = initial(&c, &raw, &sensors, &params)?;
    let modes = super::readouts::modes(&c, raw.modes.as_ref())?;
    let mut model = model(&c, &raw)?;
    if let Some(factor) = section_shear {
        if raw.model.as_ref().is_some_and(|m| m.shear_factor.is_some()) {
            return c.err(
                "section.shear_factor",
                "also given in [model]: give the shear factor once",
            );
        }
        model.shear_factor = factor;
    }
    if section.shape == sections::SectionShape::General && model.shear_factor != 1.0 {
        return c.err(
            "model.shear_factor",
            "a general section gives its shear area As directly: no shear_factor",
        );
    }

    let mut scene = Scene {
        name,
        description: raw.description.trim().to_string(),
        experiment,
        geometry,
        params,
        supports,
        loads,
        sensors,
        inputs,
        shape_points,
        shape_fields,
        modes,
        initial,
        model,
        section,
        rayleigh: damping::rayleigh(&c, raw.damping.as_ref())?,
        masses: attached::masses(&c, &raw.mass, frame_ref)?,
        springs,
        foundations: attached::foundations(&c, &raw.foundation, frame_ref)?,
        stops,
        frame,
        source: text.to_string(),
    };
    if let Err(e) = scene.section.check(&scene.defaults()) {
        return c.err(format!("section.{}", e.name), e.message);
    }
    if scene.section.depth(&scene.defaults()).is_none() {
        if let Some(key) = mechanics::fiber_stress_reader(&scene) {
            return c.err(
                key,
                "reads a fiber stress, which needs the section's depth: add `depth` to the \
                 general [section]",
            );
        }
    }
    if let Err((key, message)) = claims::check_blocks(&scene) {
        return c.err(key, message);
    }
    if let Err((key, message)) = claims::check_names(&scene) {
        return c.err(key, message);
    }
    if let Some(frame) = &scene.frame {
        if let Err((key, message)) = super::frame_check::check(&scene, frame) {
            return c.err(key, message);
        }
    } else if scene.initial.state == InitialState::Static {
        if let Some(free) = mechanics::free_rigid_motion(&scene, span, rise) {
            return c.err(
                "[[support]]",
                format!(
                    "the supports (with the springs, foundations and stops) leave the rod free to \
                     {free}: it has no static equilibrium. Hold more degrees of freedom, or start \
                     from [initial] state = \"reference\""
                ),
            );
        }
    }
    // The declared range of `elements`: from the fewest that put every station on a node.
    let (lo, hi) = scene.element_range();
    scene.params[super::Std::Elements as usize].range = Range::between(lo as f64, hi as f64);
    if let Err(e) = scene.check_mesh(scene.defaults().elements()) {
        return c.err("defaults.elements", e.message);
    }
    Ok(scene)
}

fn experiment(c: &Checker, raw: &SceneFile) -> Result<DefaultExperiment, SceneError> {
    let e = raw.experiment.as_ref();
    let x = DefaultExperiment {
        start: e.and_then(|e| e.start).unwrap_or(0.0),
        stop: e.and_then(|e| e.stop).unwrap_or(0.1),
        step: e.and_then(|e| e.step).unwrap_or(1e-4),
    };
    if !(x.start.is_finite() && x.stop.is_finite() && x.stop > x.start) {
        return c.err(
            "experiment.stop",
            format!(
                "{} must be finite and greater than start = {}",
                x.stop, x.start
            ),
        );
    }
    if !(x.step.is_finite() && x.step > 0.0) {
        return c.err(
            "experiment.step",
            format!("{} must be finite and > 0", x.step),
        );
    }
    Ok(x)
}

fn geometry(c: &Checker, raw: &SceneFile) -> Result<(Geometry, f64, Option<f64>), SceneError> {
    let g = c.required(raw.geometry.as_ref(), "[geometry]", "shape and L")?;
    let shape = c.required(
        g.shape.as_deref(),
        "geometry.shape",
        "\"straight\" or \"arc\"",
    )?;
    let geometry = [Geometry::Straight, Geometry::Arc]
        [c.one_of(shape, &["straight", "arc"], "geometry.shape")?];
    let span = c.required(g.span, "geometry.L", "the span (length of a straight rod)")?;
    if !(span.is_finite() && span > 0.0) {
        return c.err("geometry.L", format!("{span} is out of range: must be > 0"));
    }
    let rise = match (geometry, g.rise) {
        (Geometry::Straight, None) => None,
        (Geometry::Straight, Some(_)) => {
            return c.err(
                "geometry.H",
                "a straight rod has no rise (H is for shape = \"arc\")",
            )
        }
        (Geometry::Arc, None) => return c.err("geometry.H", "missing: the rise of the arc"),
        (Geometry::Arc, Some(h)) if h.is_finite() && h > 0.0 && h <= 0.5 * span => Some(h),
        (Geometry::Frame, _) => unreachable!("[geometry] names a straight rod or an arc"),
        (Geometry::Arc, Some(h)) => {
            return c.err(
                "geometry.H",
                format!(
                    "{h} is out of range: must be in (0, L/2] = (0, {}]",
                    0.5 * span
                ),
            )
        }
    };
    Ok((geometry, span, rise))
}

/// A scene names its material: no silent default for `E` and `rho` (a forgotten one would run
/// with numbers no engineer chose).
fn require_material(c: &Checker, raw: &SceneFile) -> Result<(), SceneError> {
    let missing: Vec<&str> = ["E", "rho"]
        .into_iter()
        .filter(|k| !raw.defaults.contains_key(*k))
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    let keys: Vec<String> = missing.iter().map(|k| format!("defaults.{k}")).collect();
    c.err(
        keys.join(", "),
        format!(
            "missing: a scene gives its material in [defaults]: add {} (for example steel: \
             E = 210e9 Pa, rho = 7850 kg/m3; aluminium: E = 70e9 Pa, rho = 2700 kg/m3)",
            missing.join(" and ")
        ),
    )
}

fn initial(
    c: &Checker,
    raw: &SceneFile,
    sensors: &[Sensor],
    params: &[Param],
) -> Result<Initial, SceneError> {
    let Some(i) = raw.initial.as_ref() else {
        return Ok(Initial {
            state: InitialState::Static,
            branch: None,
        });
    };
    let state = match i.state.as_deref() {
        None => InitialState::Static,
        Some(s) => [InitialState::Static, InitialState::Reference]
            [c.one_of(s, &["static", "reference"], "initial.state")?],
    };
    let branch = match i.branch.as_deref() {
        None if i.branch_sensor.is_some() => {
            return c.err("initial.branch_sensor", "goes with branch = \"well\"")
        }
        None => None,
        Some(b) => {
            c.one_of(b, &["well"], "initial.branch")?;
            if state != InitialState::Static {
                return c.err(
                    "initial.branch",
                    "a branch is chosen only for state = \"static\"",
                );
            }
            let name = c.required(
                i.branch_sensor.as_ref(),
                "initial.branch_sensor",
                "the sensor whose sign `well` picks",
            )?;
            let Some(sensor) = sensors.iter().position(|s| &s.name == name) else {
                return c.err(
                    "initial.branch_sensor",
                    format!("`{name}` is not a [[sensor]] of this scene"),
                );
            };
            if sensors[sensor].quantity.displacement_dof().is_none() {
                return c.err(
                    "initial.branch_sensor",
                    format!(
                        "`{name}` measures {}: pick a displacement sensor (u1, u2, w)",
                        sensors[sensor].quantity.name()
                    ),
                );
            }
            let well_param = params
                .iter()
                .position(|p| p.name == params::WELL)
                .expect("declared with a branch");
            Some(Branch { sensor, well_param })
        }
    };
    Ok(Initial { state, branch })
}

fn model(c: &Checker, raw: &SceneFile) -> Result<super::ModelOptions, SceneError> {
    let mut m = super::ModelOptions::default();
    let Some(f) = raw.model.as_ref() else {
        return Ok(m);
    };
    if let Some(mass) = f.mass.as_deref() {
        m.lumped_mass = c.one_of(mass, &["consistent", "lumped"], "model.mass")? == 1;
    }
    if let Some(k) = f.shear_factor {
        if !(k.is_finite() && k > 0.0) {
            return c.err(
                "model.shear_factor",
                format!("{k} is out of range: must be > 0"),
            );
        }
        m.shear_factor = k;
    }
    if let Some(d) = f.rotational_damping {
        if !(d.is_finite() && d >= 0.0) {
            return c.err(
                "model.rotational_damping",
                format!("{d} is out of range: must be >= 0"),
            );
        }
        m.rotational_damping = d;
    }
    Ok(m)
}
