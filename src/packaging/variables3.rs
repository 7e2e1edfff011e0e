//! The variables of a scene as FMI 3.0 declares them: the FMI 2.0 list ([`variables`](crate::scene::variables::variables)) with each
//! family `shape_<field>[1]` ... `shape_<field>[N]` made one array `shape_<field>` of N elements.
//! The grouping reads only the names, so every shape field the scene defines becomes an array.
//! An array takes the value reference of its first element; every other variable keeps its
//! own, so an FMI 3.0 value reference is always one of FMI 2.0's.
use crate::scene::variables::Variable;
use std::collections::HashMap;

/// The value reference of `time`, the independent variable FMI 3.0 requires: the last one, far
/// from every range the scene's variables use.
pub const TIME_VR: u32 = u32::MAX;

/// The prefix of the families that become arrays.
const ARRAY_PREFIX: &str = "shape_";

/// One FMI 3.0 variable: elements `first .. first + len` of the FMI 2.0 list.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable3 {
    pub name: String,
    pub vr: u32,
    pub first: usize,
    pub len: usize,
    /// Declared with a `<Dimension>` (an array of one element stays an array).
    pub array: bool,
}

/// `("shape_x", 3)` for `shape_x[3]`.
fn indexed(name: &str) -> Option<(&str, usize)> {
    let (base, rest) = name.split_once('[')?;
    let index = rest.strip_suffix(']')?.parse().ok()?;
    Some((base, index))
}

/// The FMI 3.0 variables of an FMI 2.0 variable list, in its order.
pub fn variables3(vars: &[Variable]) -> Vec<Variable3> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < vars.len() {
        let family = indexed(&vars[i].name)
            .filter(|&(base, index)| base.starts_with(ARRAY_PREFIX) && index == 1);
        let mut len = 1;
        if let Some((base, _)) = family {
            while let Some(next) = vars.get(i + len) {
                let same = indexed(&next.name) == Some((base, len + 1))
                    && (next.var_type, next.causality, &next.unit)
                        == (vars[i].var_type, vars[i].causality, &vars[i].unit);
                if !same {
                    break;
                }
                len += 1;
            }
        }
        out.push(Variable3 {
            name: family.map_or_else(|| vars[i].name.clone(), |(base, _)| base.to_string()),
            vr: vars[i].vr,
            first: i,
            len,
            array: family.is_some(),
        });
        i += len;
    }
    out
}

/// The FMI 3.0 variables with a value-reference index and the FMI 2.0 value references of
/// their elements (what the FMI 3.0 API hands to the version-free instance).
#[derive(Clone, Debug, Default)]
pub struct Layout3 {
    pub variables: Vec<Variable3>,
    element_vrs: Vec<u32>,
    by_vr: HashMap<u32, usize>,
}

impl Layout3 {
    pub fn new(vars: &[Variable]) -> Layout3 {
        let variables = variables3(vars);
        let by_vr = variables
            .iter()
            .enumerate()
            .map(|(k, v)| (v.vr, k))
            .collect();
        Layout3 {
            variables,
            element_vrs: vars.iter().map(|v| v.vr).collect(),
            by_vr,
        }
    }

    pub fn by_vr(&self, vr: u32) -> Option<&Variable3> {
        self.by_vr.get(&vr).map(|&k| &self.variables[k])
    }

    /// The FMI 2.0 value references of the elements of `var`.
    pub fn element_vrs(&self, var: &Variable3) -> &[u32] {
        &self.element_vrs[var.first..var.first + var.len]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::variables::variables;
    use crate::scene::Scene;

    fn scene() -> Scene {
        Scene::load("scenes/BuckledBeam.toml").unwrap()
    }

    #[test]
    fn every_shape_family_is_one_array_and_the_rest_stay_scalars() {
        let scene = scene();
        let vars = variables(&scene);
        let layout = Layout3::new(&vars);
        let families: Vec<&str> = vars
            .iter()
            .filter_map(|v| indexed(&v.name).map(|(base, _)| base))
            .filter(|b| b.starts_with(ARRAY_PREFIX))
            .fold(Vec::new(), |mut seen, b| {
                if !seen.contains(&b) {
                    seen.push(b);
                }
                seen
            });
        assert!(families.len() >= 2, "shape_x and shape_y at least");
        for base in &families {
            let array = layout.variables.iter().find(|v| v.name == *base).unwrap();
            assert!(array.array);
            assert_eq!(array.len, scene.shape_samples());
            let names: Vec<String> = layout
                .element_vrs(array)
                .iter()
                .map(|vr| vars.iter().find(|v| v.vr == *vr).unwrap().name.clone())
                .collect();
            let expected: Vec<String> = (1..=array.len).map(|i| format!("{base}[{i}]")).collect();
            assert_eq!(names, expected);
        }
        let elements: usize = layout.variables.iter().map(|v| v.len).sum();
        assert_eq!(
            elements,
            vars.len(),
            "every FMI 2.0 variable is in exactly one"
        );
        let scalars = layout.variables.iter().filter(|v| !v.array).count();
        assert_eq!(scalars, layout.variables.len() - families.len());
        for v in layout.variables.iter().filter(|v| !v.array) {
            assert_eq!((v.len, &v.name), (1, &vars[v.first].name));
        }
    }

    #[test]
    fn an_array_takes_the_value_reference_of_its_first_element() {
        let vars = variables(&scene());
        let layout = Layout3::new(&vars);
        let x = layout
            .variables
            .iter()
            .find(|v| v.name == "shape_x")
            .unwrap();
        assert_eq!(
            x.vr,
            vars.iter().find(|v| v.name == "shape_x[1]").unwrap().vr
        );
        assert_eq!(layout.by_vr(x.vr), Some(x));
        assert!(
            layout.by_vr(x.vr + 1).is_none(),
            "element 2 has no FMI 3.0 reference"
        );
        assert!(
            vars.iter().all(|v| v.vr != TIME_VR),
            "time's reference is free"
        );
    }

    #[test]
    fn only_consecutive_indices_from_one_form_an_array() {
        assert_eq!(indexed("shape_x[12]"), Some(("shape_x", 12)));
        assert_eq!(indexed("shape_x"), None);
        assert_eq!(indexed("shape_x[a]"), None);
    }
}
