//! Generates, from the single source of truth in `modelDescription/`:
//! - `$OUT_DIR/variables.rs`: the variable table and value-reference constants (included by
//!   `src/variables.rs`), used by the scene validation and the FMI layer;
//! - `$OUT_DIR/<Scene>.xml`: the modelDescription.xml of each scene (see `build/xml.rs`).
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
    fs::write(out.join("variables.rs"), spec.rust_table()).expect("write variables.rs");
    for scene in &spec.scenes {
        let xml = xml::model_description(&spec, scene);
        fs::write(out.join(format!("{}.xml", scene.name)), xml).expect("write modelDescription");
    }
}
