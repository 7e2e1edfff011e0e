//! Generates, from the single source of truth in `modelDescription/`:
//! - `$OUT_DIR/<Scene>.xml`: the modelDescription.xml of each scene (see `build/xml.rs`);
//! - `$OUT_DIR/variables.rs`: the variable table, value-reference constants, scene GUIDs and the
//!   embedded modelDescription.xml documents (included by `src/variables.rs`), used by the scene
//!   validation, the FMI layer and the FMU packager.
use std::{env, fs, path::PathBuf};

#[path = "build/spec.rs"]
mod spec;
#[path = "build/xml.rs"]
mod xml;

fn main() {
    println!("cargo:rerun-if-changed=modelDescription");
    println!("cargo:rerun-if-changed=build");
    let spec = spec::Spec::load("modelDescription").unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env::var("OUT_DIR").expect("OUT_DIR"));
    let mut guids = Vec::new();
    for scene in &spec.scenes {
        let md = xml::model_description(&spec, scene)
            .unwrap_or_else(|e| panic!("modelDescription/ ({}): {e}", scene.name));
        let path = out.join(format!("{}.xml", scene.name));
        fs::write(&path, md.xml).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        guids.push(md.guid);
    }
    let table = spec.rust_table(&guids, &xml::LOG_CATEGORIES);
    fs::write(out.join("variables.rs"), table).expect("write variables.rs");
}
