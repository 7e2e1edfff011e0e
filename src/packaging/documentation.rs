//! `documentation/index.html` of a scene's FMU: what the rod is, how it is held and loaded, its
//! variables, and a short fmpy example.
use crate::scene::variables::{self, Causality, Timing};
use crate::scene::{InitialState, LoadKind, Scene, Slot, TimeLaw, VarType, DOF_NAMES};
use std::fmt::Write as _;

fn html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn slot_text(scene: &Scene, slot: &Slot) -> String {
    match *slot {
        Slot::Number(x) => format!("{x}"),
        Slot::Param { index, sign } => {
            let sign = if sign < 0.0 { "-" } else { "" };
            format!("{sign}<code>{}</code>", html(&scene.params[index].name))
        }
    }
}

/// The scene in sentences: geometry, supports, loads, initial state.
fn scene_summary(scene: &Scene) -> String {
    let mut h = String::from("<ul>\n");
    let shape = match scene.geometry {
        crate::scene::Geometry::Straight => "a straight rod from (0, 0) to (L, 0)",
        crate::scene::Geometry::Arc => "a circular arc of span L and rise H from (0, 0) to (L, 0)",
        crate::scene::Geometry::Frame => "a frame of members between joints",
    };
    let _ = writeln!(
        h,
        "<li>Geometry: {shape}; stations are fractions of the arc length.</li>"
    );
    for s in &scene.supports {
        let held: Vec<String> = (0..3)
            .filter(|&k| s.fixed[k])
            .map(|k| match s.displace[k] {
                Slot::Number(0.0) => DOF_NAMES[k].to_string(),
                slot => format!("{} = {}", DOF_NAMES[k], slot_text(scene, &slot)),
            })
            .collect();
        let motion = if s.motion {
            format!(
                "; moved by the inputs <code>{}_*</code> (linearly over each communication step)",
                html(&s.name)
            )
        } else {
            String::new()
        };
        let _ = writeln!(
            h,
            "<li>Support <code>{}</code> at {}: holds {}{motion}; reactions <code>{0}_Rx</code>, \
             <code>{0}_Ry</code>, <code>{0}_M</code>.</li>",
            html(&s.name),
            scene.station_text(&s.at),
            held.join(", ")
        );
    }
    for l in &scene.loads {
        let place = match l.kind {
            LoadKind::Point { at } => format!("point load at {}", scene.station_text(&at)),
            LoadKind::Distributed => "distributed load (per unit length)".to_string(),
            LoadKind::Patch { from, to, .. } => {
                format!("distributed load (per unit length) over [{from}, {to}]")
            }
            LoadKind::Moment { at } => format!("point moment at {}", scene.station_text(&at)),
            LoadKind::Gravity => "gravity (acceleration of the rod's mass)".to_string(),
            LoadKind::Moving { speed, enter } => format!(
                "point load moving at {} m/s from t = {} s",
                slot_text(scene, &speed),
                slot_text(scene, &enter)
            ),
        };
        let dir = format!(
            "{}e{}",
            if l.direction.sign < 0.0 { "-" } else { "" },
            l.direction.component + 1
        );
        let time = match l.time {
            TimeLaw::Constant => format!("constant {}", slot_text(scene, &l.value)),
            TimeLaw::Harmonic => {
                format!("{} cos(<code>Omega</code> t)", slot_text(scene, &l.value))
            }
            TimeLaw::Input(_) => format!(
                "the input <code>{}</code>, held over each communication step",
                html(&l.name)
            ),
        };
        let _ = writeln!(
            h,
            "<li>Load <code>{}</code>: {place} along {dir}, {time}.</li>",
            html(&l.name)
        );
    }
    for line in attachment_lines(scene) {
        let _ = writeln!(h, "<li>{line}</li>");
    }
    let initial = match (scene.initial.state, scene.initial.branch) {
        (InitialState::Reference, _) => "the undeformed rod at rest".to_string(),
        (InitialState::Static, None) => {
            "the static equilibrium under the constant loads and prescribed displacements, at rest"
                .to_string()
        }
        (InitialState::Static, Some(b)) => format!(
            "the static equilibrium under the constant loads and prescribed displacements in \
             which <code>{}</code> has the sign of <code>well</code>, at rest",
            html(&scene.sensors[b.sensor].name)
        ),
    };
    let _ = writeln!(h, "<li>Initial state (t = 0): {initial}.</li>\n</ul>");
    h
}

/// The page.
pub fn documentation(scene: &Scene, guid: &str) -> String {
    let name = html(&scene.name);
    let e = scene.experiment;
    let mut h = String::new();
    let _ = writeln!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{name} (georod FMU)</title>\n<style>\n\
         body {{ font-family: sans-serif; max-width: 60em; margin: 2em auto; line-height: 1.4; }}\n\
         table {{ border-collapse: collapse; }}\n\
         th, td {{ border: 1px solid #bbb; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }}\n\
         th {{ background: #eee; }}\n\
         code, pre {{ background: #f4f4f4; }}\n</style>\n</head>\n<body>"
    );
    let _ = writeln!(h, "<h1>{name}</h1>\n<p>{}</p>", html(&scene.description));
    let _ = writeln!(
        h,
        "<p>A geometrically exact planar rod (Cosserat line with shear) discretized by the hybrid \
         two-node element of Sansour, Sansour &amp; Wriggers and integrated by the implicit \
         midpoint rule, as an FMI 2.0 Co-Simulation FMU (<code>modelIdentifier=\"{name}\"</code>, \
         GUID <code>{}</code>), packaged by georod from the scene file in \
         <code>resources/scene.toml</code>. Each communication step is cut into the fewest equal \
         sub-steps no longer than <code>dt_max</code>; a step whose Newton iteration fails even \
         after cutting returns <code>fmi2Discard</code> and leaves the state unchanged. The FMU \
         can get, set and serialize its state, and several instances may run at once.</p>",
        html(guid)
    );
    let _ = writeln!(h, "<h2>The scene</h2>\n{}", scene_summary(scene));
    let _ = writeln!(
        h,
        "<p>Default experiment: from {} s to {} s, communication step {} s. Parameters outside \
         their range are refused when set, with a message that names the variable.</p>",
        e.start, e.stop, e.step
    );
    let _ = writeln!(h, "<h2>Variables</h2>\n<table>");
    let _ = writeln!(
        h,
        "<tr><th>name</th><th>causality / variability</th><th>type</th><th>unit</th>\
         <th>start</th><th>range</th><th>description</th></tr>"
    );
    let vars = variables::variables(scene);
    for v in &vars {
        let causality = match v.causality {
            Causality::Parameter => "parameter",
            Causality::Input => "input",
            Causality::Output => "output",
        };
        let start = v.start.map_or(String::new(), |x| match v.var_type {
            VarType::Real => format!("{x}"),
            _ => format!("{}", x as i64),
        });
        let _ = writeln!(
            h,
            "<tr><td><code>{}</code></td><td>{causality} / {}</td><td>{:?}</td><td>{}</td>\
             <td>{}</td><td>{}</td><td>{}</td></tr>",
            html(&v.name),
            v.timing.name(),
            v.var_type,
            html(v.unit.as_deref().unwrap_or("")),
            html(&start),
            html(&v.range.text().unwrap_or_default()),
            html(&v.description),
        );
    }
    let _ = writeln!(h, "</table>");
    let sensors: Vec<String> = scene
        .sensors
        .iter()
        .map(|s| format!("\"{}\"", s.name))
        .collect();
    let shown = if sensors.is_empty() {
        "\"E_kin\"".to_string()
    } else {
        sensors[0].clone()
    };
    let tunable: Vec<String> = vars
        .iter()
        .filter(|v| v.timing == Timing::Tunable)
        .filter_map(|v| v.start.map(|x| format!("\"{}\": {x:?}", v.name)))
        .collect();
    let outputs = if sensors.is_empty() {
        vec!["\"E_kin\"".to_string(), "\"E_strain\"".to_string()]
    } else {
        sensors
    };
    let snippet = format!(
        r#"from fmpy import dump, simulate_fmu

dump("{name}.fmu")  # variables, units, default experiment
result = simulate_fmu(
    "{name}.fmu",
    start_values={{{tunable}}},
    stop_time={stop},
    output_interval={step},
    output=[{outputs}],
)
print(result["time"][-1], result[{shown}][-1])"#,
        name = scene.name,
        tunable = tunable.join(", "),
        stop = e.stop,
        step = e.step,
        outputs = outputs.join(", "),
    );
    let _ = writeln!(
        h,
        "<h2>Use from Python (fmpy)</h2>\n<pre><code>{}</code></pre>",
        html(&snippet)
    );
    if !scene.inputs.is_empty() {
        let _ = writeln!(
            h,
            "<p>Inputs are set between <code>doStep</code> calls (e.g. with \
             <code>fmpy.fmi2.FMU2Slave</code>): a load input is held over the step; a support \
             motion input is the position the support reaches at the end of the step, moving \
             linearly from where it was.</p>"
        );
    }
    if let (Some(frame), true) = (&scene.frame, scene.shape_points > 0) {
        let ranges: Vec<String> = (frame.members.iter().enumerate())
            .map(|(m, member)| {
                let p = scene.shape_points;
                format!(
                    "{}..{} member <code>{}</code>",
                    m * p + 1,
                    (m + 1) * p,
                    html(&member.name)
                )
            })
            .collect();
        let _ = writeln!(
            h,
            "<p>This is a frame: the shape samples run member by member, {} points along each \
             from its <code>from</code> joint: {}.</p>",
            scene.shape_points,
            ranges.join(", ")
        );
    }
    if scene.shape_points > 0 {
        let _ = writeln!(
            h,
            "<p>The outputs <code>shape_x[i]</code>, <code>shape_y[i]</code> (i = 1..{}) sample \
             the deformed rod at equally spaced arc lengths; <code>python -m georod_tools animate \
             {}.fmu</code> draws them over time.</p>",
            scene.shape_samples(),
            name
        );
    }
    if !scene.shape_fields.is_empty() {
        let names: Vec<String> = (scene.shape_fields.iter())
            .map(|q| format!("<code>shape_{}[i]</code>", q.name()))
            .collect();
        let _ = writeln!(
            h,
            "<p>{} read the same points (<code>animate --field NAME</code> colours the rod by              one).</p>",
            names.join(", ")
        );
    }
    let _ = writeln!(h, "</body>\n</html>");
    h
}

/// The section, the point masses, springs, foundations and Rayleigh damping, one line each.
fn attachment_lines(scene: &Scene) -> Vec<String> {
    let mut lines = Vec::new();
    let dims: Vec<String> = (scene.section.dims.iter())
        .map(|&i| format!("<code>{}</code>", html(&scene.params[i].name)))
        .collect();
    lines.push(format!(
        "Section: {:?}, dimensions {}.",
        scene.section.shape,
        dims.join(", ")
    ));
    for m in &scene.masses {
        lines.push(format!(
            "Point mass <code>{}</code> at {}: m = {} kg, J = {} kg m2.",
            html(&m.name),
            scene.station_text(&m.at),
            m.m,
            m.j
        ));
    }
    for s in &scene.springs {
        let base = match s.base {
            Some(_) => format!(
                "its base follows the input <code>{}_base</code>",
                html(&s.name)
            ),
            None => "to ground".to_string(),
        };
        lines.push(format!(
            "Spring <code>{}</code> at {} on {}: k = {}, c = {} ({base}).",
            html(&s.name),
            scene.station_text(&s.at),
            DOF_NAMES[s.dof],
            s.k,
            s.c
        ));
    }
    for f in &scene.foundations {
        lines.push(format!(
            "Foundation <code>{}</code> over [{}, {}]: k = {} N/m2, c = {} N s/m2 on u2.",
            html(&f.name),
            f.from,
            f.to,
            f.k,
            f.c
        ));
    }
    if let Some(r) = scene.rayleigh {
        lines.push(format!(
            "Rayleigh damping: alpha = {:e} /s, beta = {:e} s (on the initial tangent).",
            r.alpha, r.beta
        ));
    }
    lines
}
