//! Reading and checking `modelDescription/*.toml`, and emitting the Rust variable table.
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    pub name: String,
    pub description: String,
    pub start_time: f64,
    pub stop_time: f64,
    pub step_size: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Variable {
    pub name: String,
    pub vr: u32,
    #[serde(rename = "type")]
    pub var_type: String,
    pub causality: String,
    pub variability: String,
    pub description: String,
    pub unit: Option<String>,
    #[serde(default)]
    pub unit_by_scene: BTreeMap<String, String>,
    pub start: Option<toml::Value>,
    #[serde(default)]
    pub start_by_scene: BTreeMap<String, toml::Value>,
    pub min: Option<toml::Value>,
    pub max: Option<toml::Value>,
    #[serde(default)]
    pub min_exclusive: bool,
    #[serde(default)]
    pub max_exclusive: bool,
    pub scenes: Option<Vec<String>>,
    /// For `type = "Enumeration"`: the `[[type]]` that lists its items.
    pub declared_type: Option<String>,
}

/// An enumeration type (`[[type]]` in variables.toml).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnumType {
    pub name: String,
    pub description: String,
    pub items: Vec<EnumItem>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnumItem {
    pub name: String,
    pub value: i64,
    pub description: String,
}

#[derive(Deserialize)]
struct ScenesFile {
    scene: Vec<Scene>,
}

#[derive(Deserialize)]
struct VariablesFile {
    variable: Vec<Variable>,
    #[serde(default, rename = "type")]
    types: Vec<EnumType>,
}

pub struct Spec {
    pub scenes: Vec<Scene>,
    pub variables: Vec<Variable>,
    pub types: Vec<EnumType>,
}

fn number(v: &toml::Value, what: &str) -> Result<f64, String> {
    match v {
        toml::Value::Float(x) => Ok(*x),
        toml::Value::Integer(i) => Ok(*i as f64),
        other => Err(format!("{what}: expected a number, found {other}")),
    }
}

impl Variable {
    pub fn in_scene(&self, scene: &str) -> bool {
        match &self.scenes {
            None => true,
            Some(s) => s.iter().any(|n| n == scene),
        }
    }
    pub fn start_for(&self, scene: &str) -> Option<f64> {
        let v = self.start_by_scene.get(scene).or(self.start.as_ref())?;
        Some(number(v, &self.name).expect("checked on load"))
    }
    pub fn unit_for(&self, scene: &str) -> Option<&str> {
        self.unit_by_scene
            .get(scene)
            .or(self.unit.as_ref())
            .map(String::as_str)
    }
    pub fn min_value(&self) -> Option<f64> {
        self.min
            .as_ref()
            .map(|v| number(v, &self.name).expect("checked on load"))
    }
    pub fn max_value(&self) -> Option<f64> {
        self.max
            .as_ref()
            .map(|v| number(v, &self.name).expect("checked on load"))
    }
}

impl Spec {
    pub fn load(dir: &str) -> Result<Spec, String> {
        let read = |f: &str| {
            std::fs::read_to_string(format!("{dir}/{f}")).map_err(|e| format!("{dir}/{f}: {e}"))
        };
        let scenes: ScenesFile =
            toml::from_str(&read("scenes.toml")?).map_err(|e| format!("scenes.toml: {e}"))?;
        let vars: VariablesFile =
            toml::from_str(&read("variables.toml")?).map_err(|e| format!("variables.toml: {e}"))?;
        let spec = Spec {
            scenes: scenes.scene,
            variables: vars.variable,
            types: vars.types,
        };
        spec.check()?;
        Ok(spec)
    }

    fn check(&self) -> Result<(), String> {
        let scene_names: BTreeSet<&str> = self.scenes.iter().map(|s| s.name.as_str()).collect();
        if scene_names.len() != self.scenes.len() {
            return Err("scenes.toml: scene name used twice".into());
        }
        for sc in &self.scenes {
            let ok_name = sc
                .name
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphabetic())
                && sc
                    .name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_');
            if !ok_name {
                return Err(format!(
                    "scene `{}`: the name must be a C identifier",
                    sc.name
                ));
            }
            let times = [sc.start_time, sc.stop_time, sc.step_size];
            if !(times.iter().all(|t| t.is_finite())
                && sc.stop_time > sc.start_time
                && sc.step_size > 0.0)
            {
                return Err(format!(
                    "scene `{}`: need start_time < stop_time, step_size > 0",
                    sc.name
                ));
            }
        }
        let mut vrs = BTreeSet::new();
        let mut names = BTreeSet::new();
        for v in &self.variables {
            let ctx = format!("variable `{}`", v.name);
            if !vrs.insert(v.vr) {
                return Err(format!("{ctx}: value reference {} used twice", v.vr));
            }
            if !names.insert(v.name.as_str()) {
                return Err(format!("{ctx}: name used twice"));
            }
            if !["Real", "Integer", "Enumeration"].contains(&v.var_type.as_str()) {
                return Err(format!("{ctx}: type must be Real, Integer or Enumeration"));
            }
            let enumeration = v.var_type == "Enumeration";
            match &v.declared_type {
                Some(t) if enumeration => {
                    let ty = self.types.iter().find(|ty| &ty.name == t);
                    let Some(ty) = ty else {
                        return Err(format!("{ctx}: no [[type]] named {t}"));
                    };
                    let values: Vec<f64> = ty.items.iter().map(|i| i.value as f64).collect();
                    let start = v.start.as_ref().map(|x| number(x, &ctx)).transpose()?;
                    if start.is_some_and(|x| !values.contains(&x)) {
                        return Err(format!("{ctx}: start is not an item of {t}"));
                    }
                }
                None if !enumeration => {}
                _ => return Err(format!("{ctx}: declared_type goes with type = Enumeration")),
            }
            let pairs = [
                ("parameter", "fixed"),
                ("parameter", "tunable"),
                ("input", "continuous"),
                ("output", "continuous"),
                ("output", "discrete"),
            ];
            if !pairs.contains(&(v.causality.as_str(), v.variability.as_str())) {
                return Err(format!("{ctx}: unsupported causality/variability"));
            }
            let needs_start = v.causality != "output";
            if needs_start != v.start.is_some() {
                return Err(format!(
                    "{ctx}: parameters and inputs need a start, outputs none"
                ));
            }
            for (what, val) in [("start", &v.start), ("min", &v.min), ("max", &v.max)] {
                if let Some(val) = val {
                    number(val, &format!("{ctx} {what}"))?;
                }
            }
            for (scene, val) in &v.start_by_scene {
                number(val, &format!("{ctx} start_by_scene"))?;
                if !scene_names.contains(scene.as_str()) {
                    return Err(format!("{ctx}: unknown scene {scene}"));
                }
            }
            for s in v.scenes.iter().flatten().chain(v.unit_by_scene.keys()) {
                if !scene_names.contains(s.as_str()) {
                    return Err(format!("{ctx}: unknown scene {s}"));
                }
            }
        }
        Ok(())
    }

    /// Rust source of the variable table (types live in `src/variables.rs`). `guids[i]` is the
    /// GUID of scene `i`, whose modelDescription.xml is `$OUT_DIR/<Scene>.xml`.
    pub fn rust_table(&self, guids: &[String], log_categories: &[(&str, &str)]) -> String {
        let mut s = String::from("// Generated by build.rs from modelDescription/. Do not edit.\n");
        let opt = |x: Option<f64>| x.map_or("None".to_string(), |v| format!("Some({v:?})"));
        let n = self.scenes.len();
        let _ = writeln!(s, "pub const SCENE_NAMES: [&str; {n}] = [");
        for sc in &self.scenes {
            let _ = writeln!(s, "    {:?},", sc.name);
        }
        s.push_str("];\n\n/// The GUID of each scene's modelDescription.xml, indexed like [`SCENE_NAMES`].\n");
        let _ = writeln!(s, "pub const GUIDS: [&str; {n}] = [");
        for g in guids {
            let _ = writeln!(s, "    {g:?},");
        }
        s.push_str(
            "];\n\n/// The modelDescription.xml of each scene, exactly as packaged, indexed like \
             [`SCENE_NAMES`].\n",
        );
        let _ = writeln!(s, "pub const MODEL_DESCRIPTIONS: [&str; {n}] = [");
        for sc in &self.scenes {
            let _ = writeln!(
                s,
                "    include_str!(concat!(env!(\"OUT_DIR\"), \"/{}.xml\")),",
                sc.name
            );
        }
        s.push_str(
            "];\n\n/// The `<LogCategories>` of every modelDescription.xml: (name, description).\n",
        );
        let _ = writeln!(
            s,
            "pub const XML_LOG_CATEGORIES: [(&str, &str); {}] = [",
            log_categories.len()
        );
        for (name, desc) in log_categories {
            let _ = writeln!(s, "    ({name:?}, {desc:?}),");
        }
        s.push_str("];\n\n/// The description of each scene, indexed like [`SCENE_NAMES`].\n");
        let _ = writeln!(s, "pub const SCENE_DESCRIPTIONS: [&str; {n}] = [");
        for sc in &self.scenes {
            let _ = writeln!(s, "    {:?},", sc.description);
        }
        s.push_str(
            "];\n\n/// The default experiment (start time, stop time, step size) of each scene.\n",
        );
        let _ = writeln!(
            s,
            "pub const SCENE_DEFAULT_EXPERIMENTS: [[f64; 3]; {n}] = ["
        );
        for sc in &self.scenes {
            let (a, b, c) = (sc.start_time, sc.stop_time, sc.step_size);
            let _ = writeln!(s, "    [{a:?}, {b:?}, {c:?}],");
        }
        s.push_str(
            "];\n\n/// The unit of each variable in each scene (indexed like [`VARIABLES`], then \
             [`SCENE_NAMES`]).\n",
        );
        let _ = writeln!(s, "pub static VARIABLE_UNITS: &[[Option<&str>; {n}]] = &[");
        for v in &self.variables {
            let units: Vec<String> = self
                .scenes
                .iter()
                .map(|sc| format!("{:?}", v.unit_for(&sc.name)))
                .collect();
            let _ = writeln!(s, "    [{}],", units.join(", "));
        }
        s.push_str("];\n\npub static VARIABLES: &[Variable] = &[\n");
        for v in &self.variables {
            let cap = |x: &str| {
                let mut c = x.chars();
                c.next()
                    .map_or(String::new(), |f| f.to_uppercase().chain(c).collect())
            };
            let scenes: Vec<String> = self
                .scenes
                .iter()
                .map(|sc| v.in_scene(&sc.name).to_string())
                .collect();
            let starts: Vec<String> = self
                .scenes
                .iter()
                .map(|sc| opt(v.start_for(&sc.name)))
                .collect();
            let _ = writeln!(
                s,
                "    Variable {{ name: {:?}, vr: {}, var_type: VarType::{}, causality: Causality::{}, \
                 variability: Variability::{}, description: {:?}, min: {}, max: {}, \
                 min_exclusive: {}, max_exclusive: {}, scenes: [{}], start: [{}] }},",
                v.name,
                v.vr,
                v.var_type,
                cap(&v.causality),
                cap(&v.variability),
                v.description,
                opt(v.min_value()),
                opt(v.max_value()),
                v.min_exclusive,
                v.max_exclusive,
                scenes.join(", "),
                starts.join(", "),
            );
        }
        s.push_str("];\n\n/// Value references, named exactly like the variables (`vr::h` and `vr::H` differ).\n#[allow(non_upper_case_globals)]\npub mod vr {\n");
        for v in &self.variables {
            let _ = writeln!(s, "    pub const {}: u32 = {};", v.name, v.vr);
        }
        s.push_str("}\n");
        s
    }
}
