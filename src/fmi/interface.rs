//! What an instance knows of its scene: the scene file read from the FMU's `resources/` and
//! re-checked, its variables with a value-reference index, and the GUID of the
//! modelDescription.xml built from it (which must be the GUID the host passes: a scene file
//! changed after packaging is refused).
use crate::packaging::variables3::Layout3;
use crate::packaging::{model_description, SCENE_RESOURCE};
use crate::scene::variables::{self, Variable};
use crate::scene::Scene;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

pub struct Interface {
    pub scene: Arc<Scene>,
    pub variables: Vec<Variable>,
    by_vr: HashMap<u32, usize>,
    /// The variables as FMI 3.0 declares them (shape families as arrays).
    pub layout3: Layout3,
    pub guid: String,
}

impl Interface {
    pub fn new(scene: Scene) -> Interface {
        let guid = model_description::model_description(&scene).guid;
        let variables = variables::variables(&scene);
        let by_vr = variables
            .iter()
            .enumerate()
            .map(|(i, v)| (v.vr, i))
            .collect();
        Interface {
            scene: Arc::new(scene),
            layout3: Layout3::new(&variables),
            variables,
            by_vr,
            guid,
        }
    }

    /// Reads `resources/scene.toml` from the unzipped FMU and checks it against `guid`.
    pub fn load(resources: Option<&Path>, guid: &str) -> Result<Interface, String> {
        let dir = resources.ok_or(
            "no usable fmuResourceLocation: this FMU reads its scene from resources/scene.toml",
        )?;
        let path = dir.join(SCENE_RESOURCE);
        let scene = Scene::load(&path).map_err(|e| {
            format!("the scene file of this FMU cannot be used (resources altered?): {e}")
        })?;
        let interface = Interface::new(scene);
        if interface.guid != guid {
            return Err(format!(
                "{} does not match the GUID {guid} of modelDescription.xml (it gives {}): the \
                 scene file was changed after packaging, or the FMU mixes files of two builds; \
                 package it again with `georod fmu`",
                path.display(),
                interface.guid
            ));
        }
        Ok(interface)
    }

    pub fn by_vr(&self, vr: u32) -> Option<&Variable> {
        self.by_vr.get(&vr).map(|&i| &self.variables[i])
    }
}
