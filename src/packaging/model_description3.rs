//! modelDescription.xml of a scene for FMI 3.0 Co-Simulation: the variables of the FMI 2.0
//! document with the same names, value references, units, ranges and start values, except that
//! every `shape_*` family is one array output ([`variables3`](super::variables3)). The instantiation token is the
//! FMI 2.0 document's GUID: both versions of a scene identify its scene file the same way, and
//! the library checks it against the scene file in `resources/` whichever API instantiates it.
use super::model_description::{
    escape, log_categories_and_experiment, model_description, number, unit_definitions,
};
use super::variables3::{variables3, TIME_VR};
use crate::scene::variables::{self, Causality, Variable};
use crate::scene::{Scene, VarType};
use std::fmt::Write;

/// The generated document of one scene, and its instantiation token.
pub struct ModelDescription3 {
    pub xml: String,
    pub token: String,
}

/// The FMI 3.0 element of a variable type.
fn element(t: VarType) -> &'static str {
    match t {
        VarType::Real => "Float64",
        VarType::Integer => "Int32",
    }
}

/// The attributes after `valueReference`: description, causality, variability, initial, type,
/// unit, range and start (`v` is the first element of an array).
fn attributes(v: &Variable, array: bool) -> String {
    let mut a = format!(r#" description="{}""#, escape(&v.description));
    let initial = match v.causality {
        Causality::Parameter => r#" initial="exact""#,
        Causality::Input => "",
        Causality::Output => r#" initial="calculated""#,
    };
    let causality = match v.causality {
        Causality::Parameter => "parameter",
        Causality::Input => "input",
        Causality::Output => "output",
    };
    let _ = write!(
        a,
        r#" causality="{causality}" variability="{}"{initial}"#,
        v.timing.name()
    );
    // Only the float types carry a unit in FMI 3.0.
    if let (Some(u), VarType::Real) = (&v.unit, v.var_type) {
        let _ = write!(a, r#" unit="{}""#, escape(u));
    }
    if let Some(m) = v.range.declared_min() {
        let _ = write!(a, r#" min="{}""#, number(v, m));
    }
    if let Some(m) = v.range.declared_max() {
        let _ = write!(a, r#" max="{}""#, number(v, m));
    }
    if let (Some(s), false) = (v.start, array) {
        let _ = write!(a, r#" start="{}""#, number(v, s));
    }
    a
}

/// The FMI 3.0 modelDescription.xml of `scene`.
pub fn model_description3(scene: &Scene) -> ModelDescription3 {
    let token = model_description(scene).guid;
    let vars = variables::variables(scene);
    let mut x = String::new();
    let w = &mut x;
    let _ = writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        w,
        r#"<fmiModelDescription fmiVersion="3.0" modelName="{name}" instantiationToken="{token}" description="{desc}" version="{ver}" license="{lic}" generationTool="georod {ver}" variableNamingConvention="structured">"#,
        name = escape(&scene.name),
        desc = escape(&scene.description),
        ver = escape(env!("CARGO_PKG_VERSION")),
        lic = escape(env!("CARGO_PKG_LICENSE")),
    );
    // What the FMU honours; every other flag keeps its default, false.
    let _ = writeln!(
        w,
        r#"  <CoSimulation modelIdentifier="{}" canHandleVariableCommunicationStepSize="true" canGetAndSetFMUState="true" canSerializeFMUState="true"/>"#,
        escape(&scene.name)
    );
    unit_definitions(w, &vars);
    log_categories_and_experiment(w, scene);

    let _ = writeln!(w, "  <ModelVariables>");
    let _ = writeln!(
        w,
        r#"    <Float64 name="time" valueReference="{TIME_VR}" description="Simulation time" causality="independent" variability="continuous" unit="s"/>"#
    );
    let mut outputs = Vec::new();
    for v3 in variables3(&vars) {
        let v = &vars[v3.first];
        if v.causality == Causality::Output {
            outputs.push(v3.vr);
        }
        let head = format!(
            r#"<{} name="{}" valueReference="{}"{}"#,
            element(v.var_type),
            escape(&v3.name),
            v3.vr,
            attributes(v, v3.array)
        );
        if v3.array {
            let _ = writeln!(w, "    {head}>");
            let _ = writeln!(w, r#"      <Dimension start="{}"/>"#, v3.len);
            let _ = writeln!(w, "    </{}>", element(v.var_type));
        } else {
            let _ = writeln!(w, "    {head}/>");
        }
    }
    let _ = writeln!(w, "  </ModelVariables>");

    // Outputs are calculated at initialization: each is also an initial unknown; without a
    // `dependencies` attribute each depends on every known.
    let _ = writeln!(w, "  <ModelStructure>");
    for element in ["Output", "InitialUnknown"] {
        for vr in &outputs {
            let _ = writeln!(w, r#"    <{element} valueReference="{vr}"/>"#);
        }
    }
    let _ = writeln!(w, "  </ModelStructure>");
    let _ = writeln!(w, "</fmiModelDescription>");
    ModelDescription3 { xml: x, token }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_have_a_dimension_and_the_token_is_the_fmi2_guid() {
        let scene = Scene::load("scenes/BuckledBeam.toml").unwrap();
        let md = model_description3(&scene);
        assert_eq!(md.token, model_description(&scene).guid);
        assert!(md
            .xml
            .contains(&format!(r#"instantiationToken="{}""#, md.token)));
        let dimension = format!(r#"<Dimension start="{}"/>"#, scene.shape_samples());
        for name in ["shape_x", "shape_y"] {
            let at = md.xml.find(&format!(r#"name="{name}""#)).unwrap();
            let rest = &md.xml[at..];
            let end = rest.find("</Float64>").unwrap();
            assert!(rest[..end].contains(&dimension), "{name}");
        }
        assert!(!md.xml.contains("shape_x[1]"));
        assert!(
            !md.xml.contains("canGetAndSetFMUstate"),
            "FMI 3.0 spells it FMUState"
        );
    }
}
