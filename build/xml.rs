//! modelDescription.xml generation (placeholder until the FMU issue fills it in).
use crate::spec::{Scene, Spec};

pub fn model_description(_spec: &Spec, scene: &Scene) -> String {
    format!("<!-- {} -->\n", scene.name)
}
