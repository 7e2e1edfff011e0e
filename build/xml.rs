//! modelDescription.xml generation (FMI 2.0 Co-Simulation), one document per scene.
//!
//! The document lists only the variables of its scene, in `variables.toml` order; the
//! `ModelStructure` indices are 1-based positions in that scene's `ModelVariables`. The GUID is a
//! hash of the document itself (with the `guid` attribute blank), so it changes exactly when the
//! interface changes.
use crate::spec::{Scene, Spec, Variable};
use std::fmt::Write;

/// The log categories declared in every modelDescription.xml: (name, description). The FMI code
/// exports the same names as `georod::fmi::logging::LOG_CATEGORIES`; the generated
/// `variables::XML_LOG_CATEGORIES` lets a test compare the two.
pub const LOG_CATEGORIES: [(&str, &str); 4] = [
    (
        "logEvents",
        "Changes of the FMU state: instantiation, initialization, termination, reset, FMU state get/set/serialization",
    ),
    ("logStatusWarning", "Warnings and discarded communication steps (fmi2Warning, fmi2Discard)"),
    ("logStatusError", "Refused calls and arguments (fmi2Error); logged even when debug logging is off"),
    ("logAll", "Every message, including a trace of every FMI function call"),
];

/// SI base-unit exponents of a unit name used in `variables.toml`:
/// (kg, m, s, A, K, mol, cd, rad). `None` for an unknown name (a build error).
fn base_unit(name: &str) -> Option<[i32; 8]> {
    Some(match name {
        "1" => [0, 0, 0, 0, 0, 0, 0, 0],
        "m" => [0, 1, 0, 0, 0, 0, 0, 0],
        "s" => [0, 0, 1, 0, 0, 0, 0, 0],
        "kg" => [1, 0, 0, 0, 0, 0, 0, 0],
        "rad" => [0, 0, 0, 0, 0, 0, 0, 1],
        "m/s" => [0, 1, -1, 0, 0, 0, 0, 0],
        "rad/s" => [0, 0, -1, 0, 0, 0, 0, 1],
        "N" => [1, 1, -2, 0, 0, 0, 0, 0],
        "N/m" => [1, 0, -2, 0, 0, 0, 0, 0],
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
fn real(x: f64) -> String {
    format!("{x:?}")
}

/// An Integer value as an `xs:int` literal.
fn integer(x: f64, what: &str) -> Result<String, String> {
    if x.fract() != 0.0 || x.abs() > f64::from(i32::MAX) {
        return Err(format!("{what}: {x} is not a 32-bit integer"));
    }
    Ok(format!("{}", x as i64))
}

/// The generated document of one scene.
pub struct ModelDescription {
    pub xml: String,
    pub guid: String,
}

/// The modelDescription.xml of `scene`.
pub fn model_description(spec: &Spec, scene: &Scene) -> Result<ModelDescription, String> {
    let vars: Vec<&Variable> = spec
        .variables
        .iter()
        .filter(|v| v.in_scene(&scene.name))
        .collect();
    let mut x = String::new();
    let w = &mut x;
    let _ = writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        w,
        r#"<fmiModelDescription fmiVersion="2.0" modelName="{name}" guid="" description="{desc}" version="{ver}" license="{lic}" generationTool="georod build.rs" variableNamingConvention="flat" numberOfEventIndicators="0">"#,
        name = escape(&scene.name),
        desc = escape(&scene.description),
        ver = escape(env!("CARGO_PKG_VERSION")),
        lic = escape(env!("CARGO_PKG_LICENSE")),
    );
    let _ = writeln!(
        w,
        r#"  <CoSimulation modelIdentifier="{}" canHandleVariableCommunicationStepSize="true" canGetAndSetFMUstate="true" canSerializeFMUstate="true" canNotUseMemoryManagementFunctions="true" canInterpolateInputs="false" maxOutputDerivativeOrder="0" canRunAsynchronuously="false" canBeInstantiatedOnlyOncePerProcess="false" providesDirectionalDerivative="false"/>"#,
        escape(&scene.name)
    );

    // Units, in order of first use.
    let mut units: Vec<&str> = Vec::new();
    for v in &vars {
        if let Some(u) = v.unit_for(&scene.name) {
            if v.var_type != "Real" {
                return Err(format!(
                    "variable `{}`: only Real variables have a unit",
                    v.name
                ));
            }
            if !units.contains(&u) {
                units.push(u);
            }
        }
    }
    if !units.is_empty() {
        let _ = writeln!(w, "  <UnitDefinitions>");
        for u in &units {
            let exps = base_unit(u).ok_or_else(|| {
                format!("unit `{u}`: unknown; add its SI base-unit exponents to build/xml.rs")
            })?;
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
        let _ = writeln!(w, "  </UnitDefinitions>");
    }

    // Enumeration types used by this scene.
    let used: Vec<&str> = vars
        .iter()
        .filter_map(|v| v.declared_type.as_deref())
        .collect();
    let types: Vec<_> = spec
        .types
        .iter()
        .filter(|t| used.contains(&t.name.as_str()))
        .collect();
    if !types.is_empty() {
        let _ = writeln!(w, "  <TypeDefinitions>");
        for t in types {
            let _ = writeln!(
                w,
                r#"    <SimpleType name="{}" description="{}">"#,
                escape(&t.name),
                escape(&t.description)
            );
            let _ = writeln!(w, "      <Enumeration>");
            for item in &t.items {
                let _ = writeln!(
                    w,
                    r#"        <Item name="{}" value="{}" description="{}"/>"#,
                    escape(&item.name),
                    item.value,
                    escape(&item.description)
                );
            }
            let _ = writeln!(w, "      </Enumeration>");
            let _ = writeln!(w, "    </SimpleType>");
        }
        let _ = writeln!(w, "  </TypeDefinitions>");
    }

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

    let _ = writeln!(
        w,
        r#"  <DefaultExperiment startTime="{}" stopTime="{}" stepSize="{}"/>"#,
        real(scene.start_time),
        real(scene.stop_time),
        real(scene.step_size)
    );

    let _ = writeln!(w, "  <ModelVariables>");
    let mut outputs = Vec::new();
    for (i, v) in vars.iter().enumerate() {
        let index = i + 1;
        let ctx = format!("variable `{}`", v.name);
        let _ = writeln!(w, "    <!-- index=\"{index}\" -->");
        let initial = match v.causality.as_str() {
            "parameter" => r#" initial="exact""#,
            "output" => {
                outputs.push(index);
                r#" initial="calculated""#
            }
            _ => "",
        };
        let _ = writeln!(
            w,
            r#"    <ScalarVariable name="{}" valueReference="{}" description="{}" causality="{}" variability="{}"{initial}>"#,
            escape(&v.name),
            v.vr,
            escape(&v.description),
            v.causality,
            v.variability,
        );
        let mut attrs = String::new();
        let is_real = v.var_type == "Real";
        let fmt = |x: f64| {
            if is_real {
                Ok(real(x))
            } else {
                integer(x, &ctx)
            }
        };
        if let Some(t) = &v.declared_type {
            let _ = write!(attrs, r#" declaredType="{}""#, escape(t));
        }
        if let Some(u) = v.unit_for(&scene.name) {
            let _ = write!(attrs, r#" unit="{}""#, escape(u));
        }
        if let Some(m) = v.min_value() {
            let _ = write!(attrs, r#" min="{}""#, fmt(m)?);
        }
        if let Some(m) = v.max_value() {
            let _ = write!(attrs, r#" max="{}""#, fmt(m)?);
        }
        if let Some(s) = v.start_for(&scene.name) {
            let _ = write!(attrs, r#" start="{}""#, fmt(s)?);
        }
        let _ = writeln!(w, "      <{}{attrs}/>", v.var_type);
        let _ = writeln!(w, "    </ScalarVariable>");
    }
    let _ = writeln!(w, "  </ModelVariables>");

    // Outputs with initial="calculated" are initial unknowns (FMI 2.0, section 2.2.8); without a
    // `dependencies` attribute each depends on all knowns.
    let _ = writeln!(w, "  <ModelStructure>");
    if !outputs.is_empty() {
        let _ = writeln!(w, "    <Outputs>");
        for i in &outputs {
            let _ = writeln!(w, r#"      <Unknown index="{i}"/>"#);
        }
        let _ = writeln!(w, "    </Outputs>");
        let _ = writeln!(w, "    <InitialUnknowns>");
        for i in &outputs {
            let _ = writeln!(w, r#"      <Unknown index="{i}"/>"#);
        }
        let _ = writeln!(w, "    </InitialUnknowns>");
    }
    let _ = writeln!(w, "  </ModelStructure>");
    let _ = writeln!(w, "</fmiModelDescription>");

    let guid = guid_text(fnv1a_128(x.as_bytes()));
    let xml = x.replacen(r#"guid="""#, &format!(r#"guid="{guid}""#), 1);
    Ok(ModelDescription { xml, guid })
}
