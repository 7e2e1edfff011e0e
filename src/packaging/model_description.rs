//! modelDescription.xml of a scene (FMI 2.0 Co-Simulation).
//!
//! The document lists the scene's variables in [`variables`] order; the `ModelStructure`
//! indices are 1-based positions in `ModelVariables`. The GUID is a hash of the document (with
//! the `guid` attribute blank) and of the scene file, so it changes with either. The FMU
//! binary builds the same document from the scene file it finds in `resources/` and compares
//! GUIDs: an altered scene file is refused at instantiation.
use crate::scene::variables::{self, Causality, Variable};
use crate::scene::{Scene, VarType};
use std::fmt::Write;

/// The log categories declared in every modelDescription.xml: (name, description); the FMI
/// logger accepts exactly these.
pub const LOG_CATEGORIES: &[(&str, &str)] = &[
    (
        "logEvents",
        "Changes of the FMU state: instantiation, initialization, termination, reset, FMU state get/set/serialization",
    ),
    ("logStatusWarning", "Warnings and discarded communication steps (fmi2Warning, fmi2Discard)"),
    ("logStatusError", "Refused calls and arguments (fmi2Error); logged even when debug logging is off"),
    ("logAll", "Every message, including a trace of every FMI function call"),
];

/// SI base-unit exponents of a unit name: (kg, m, s, A, K, mol, cd, rad). `None` for a name
/// this table does not know (declared without a base unit).
fn base_unit(name: &str) -> Option<[i32; 8]> {
    Some(match name {
        "1" => [0, 0, 0, 0, 0, 0, 0, 0],
        "m" => [0, 1, 0, 0, 0, 0, 0, 0],
        "s" => [0, 0, 1, 0, 0, 0, 0, 0],
        "kg" => [1, 0, 0, 0, 0, 0, 0, 0],
        "rad" => [0, 0, 0, 0, 0, 0, 0, 1],
        "m/s" => [0, 1, -1, 0, 0, 0, 0, 0],
        "rad/s" => [0, 0, -1, 0, 0, 0, 0, 1],
        "1/s" => [0, 0, -1, 0, 0, 0, 0, 0],
        "N" => [1, 1, -2, 0, 0, 0, 0, 0],
        "N/m" => [1, 0, -2, 0, 0, 0, 0, 0],
        "N.m" => [1, 2, -2, 0, 0, 0, 0, 0],
        "rad/s2" => [0, 0, -2, 0, 0, 0, 0, 1],
        "m/s2" => [0, 1, -2, 0, 0, 0, 0, 0],
        "Pa" => [1, -1, -2, 0, 0, 0, 0, 0],
        "J" => [1, 2, -2, 0, 0, 0, 0, 0],
        "kg/m3" => [1, -3, 0, 0, 0, 0, 0, 0],
        "N.s/m2" => [1, -1, -1, 0, 0, 0, 0, 0],
        _ => return None,
    })
}

/// Escapes text for an XML attribute value in double quotes.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\n' => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            '\t' => out.push_str("&#9;"),
            c => out.push(c),
        }
    }
    out
}

/// FNV-1a, 128 bits.
pub fn fnv1a_128(bytes: &[u8]) -> u128 {
    const OFFSET: u128 = 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d;
    const PRIME: u128 = 0x0000_0000_0100_0000_0000_0000_0000_013b;
    bytes
        .iter()
        .fold(OFFSET, |h, &b| (h ^ u128::from(b)).wrapping_mul(PRIME))
}

/// `{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}` from a 128-bit hash.
pub fn guid_text(hash: u128) -> String {
    let hex = format!("{hash:032x}");
    format!(
        "{{{}-{}-{}-{}-{}}}",
        &hex[..8],
        &hex[8..12],
        &hex[12..16],
        &hex[16..20],
        &hex[20..]
    )
}

/// A Real value as an `xs:double` literal (shortest round-trip form, e.g. `12000.0`, `1e-6`).
pub(crate) fn real(x: f64) -> String {
    format!("{x:?}")
}

/// The generated document of one scene.
pub struct ModelDescription {
    pub xml: String,
    pub guid: String,
}

pub(crate) fn number(v: &Variable, x: f64) -> String {
    match v.var_type {
        VarType::Real => real(x),
        VarType::Integer => format!("{}", x as i64),
    }
}

/// The modelDescription.xml of `scene`.
pub fn model_description(scene: &Scene) -> ModelDescription {
    let vars = variables::variables(scene);
    let mut x = String::new();
    let w = &mut x;
    let _ = writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        w,
        r#"<fmiModelDescription fmiVersion="2.0" modelName="{name}" guid="" description="{desc}" version="{ver}" license="{lic}" generationTool="georod {ver}" variableNamingConvention="structured" numberOfEventIndicators="0">"#,
        name = escape(&scene.name),
        desc = escape(&scene.description),
        ver = escape(env!("CARGO_PKG_VERSION")),
        lic = escape(env!("CARGO_PKG_LICENSE")),
    );
    let _ = writeln!(
        w,
        r#"  <CoSimulation modelIdentifier="{}" canHandleVariableCommunicationStepSize="true" canGetAndSetFMUstate="true" canSerializeFMUstate="true" canNotUseMemoryManagementFunctions="true" canInterpolateInputs="true" maxOutputDerivativeOrder="0" canRunAsynchronuously="false" canBeInstantiatedOnlyOncePerProcess="false" providesDirectionalDerivative="false"/>"#,
        escape(&scene.name)
    );

    unit_definitions(w, &vars);

    log_categories_and_experiment(w, scene);

    let _ = writeln!(w, "  <ModelVariables>");
    let mut outputs = Vec::new();
    for (i, v) in vars.iter().enumerate() {
        let index = i + 1;
        let _ = writeln!(w, "    <!-- index=\"{index}\" -->");
        let (causality, initial) = match v.causality {
            Causality::Parameter => ("parameter", r#" initial="exact""#),
            Causality::Input => ("input", ""),
            Causality::Output => {
                outputs.push(index);
                ("output", r#" initial="calculated""#)
            }
        };
        let _ = writeln!(
            w,
            r#"    <ScalarVariable name="{}" valueReference="{}" description="{}" causality="{causality}" variability="{}"{initial}>"#,
            escape(&v.name),
            v.vr,
            escape(&v.description),
            v.timing.name(),
        );
        let mut attrs = String::new();
        if let Some(u) = &v.unit {
            let _ = write!(attrs, r#" unit="{}""#, escape(u));
        }
        // The extreme values accepted (FMI 2.0 bounds are inclusive; an open end is declared
        // as the double next to it inside).
        if let Some(m) = v.range.declared_min() {
            let _ = write!(attrs, r#" min="{}""#, number(v, m));
        }
        if let Some(m) = v.range.declared_max() {
            let _ = write!(attrs, r#" max="{}""#, number(v, m));
        }
        if let Some(s) = v.start {
            let _ = write!(attrs, r#" start="{}""#, number(v, s));
        }
        let element = match v.var_type {
            VarType::Real => "Real",
            VarType::Integer => "Integer",
        };
        let _ = writeln!(w, "      <{element}{attrs}/>");
        let _ = writeln!(w, "    </ScalarVariable>");
    }
    let _ = writeln!(w, "  </ModelVariables>");

    // Outputs with initial="calculated" are initial unknowns (FMI 2.0, section 2.2.8); without a
    // `dependencies` attribute each depends on all knowns.
    let _ = writeln!(w, "  <ModelStructure>");
    if !outputs.is_empty() {
        for list in ["Outputs", "InitialUnknowns"] {
            let _ = writeln!(w, "    <{list}>");
            for i in &outputs {
                let _ = writeln!(w, r#"      <Unknown index="{i}"/>"#);
            }
            let _ = writeln!(w, "    </{list}>");
        }
    }
    let _ = writeln!(w, "  </ModelStructure>");
    let _ = writeln!(w, "</fmiModelDescription>");

    // The GUID covers the document and the scene file (model options and comments included):
    // any change of either makes another FMU.
    let guid = guid_text(fnv1a_128(format!("{x}\n{}", scene.source).as_bytes()));
    let xml = x.replacen(r#"guid="""#, &format!(r#"guid="{guid}""#), 1);
    ModelDescription { xml, guid }
}

/// `<UnitDefinitions>` of the units `vars` use (the same element in FMI 2.0 and 3.0).
pub(crate) fn unit_definitions(w: &mut String, vars: &[Variable]) {
    let mut units: Vec<&str> = Vec::new();
    for v in vars {
        if let Some(u) = v.unit.as_deref() {
            if !units.contains(&u) {
                units.push(u);
            }
        }
    }
    if !units.is_empty() {
        let _ = writeln!(w, "  <UnitDefinitions>");
        for u in &units {
            match base_unit(u) {
                Some(exps) => {
                    let attrs: String = ["kg", "m", "s", "A", "K", "mol", "cd", "rad"]
                        .iter()
                        .zip(exps)
                        .filter(|(_, e)| *e != 0)
                        .map(|(n, e)| format!(r#" {n}="{e}""#))
                        .collect();
                    let _ = writeln!(w, r#"    <Unit name="{}">"#, escape(u));
                    let _ = writeln!(w, "      <BaseUnit{attrs}/>");
                    let _ = writeln!(w, "    </Unit>");
                }
                None => {
                    let _ = writeln!(w, r#"    <Unit name="{}"/>"#, escape(u));
                }
            }
        }
        let _ = writeln!(w, "  </UnitDefinitions>");
    }
}

/// `<LogCategories>` and `<DefaultExperiment>` (the same elements in FMI 2.0 and 3.0).
pub(crate) fn log_categories_and_experiment(w: &mut String, scene: &Scene) {
    let _ = writeln!(w, "  <LogCategories>");
    for (name, desc) in LOG_CATEGORIES {
        let _ = writeln!(
            w,
            r#"    <Category name="{}" description="{}"/>"#,
            name,
            escape(desc)
        );
    }
    let _ = writeln!(w, "  </LogCategories>");

    let e = scene.experiment;
    let _ = writeln!(
        w,
        r#"  <DefaultExperiment startTime="{}" stopTime="{}" stepSize="{}"/>"#,
        real(e.start),
        real(e.stop),
        real(e.step)
    );
}
