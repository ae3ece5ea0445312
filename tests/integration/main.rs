//! Integration tests, built as one test binary: the command line, whole renders (golden
//! images, determinism), optics through a built scene, and the scene's JSON Schema.

mod adaptive;
mod animation;
mod aov;
mod bad;
mod camera;
mod cli;
mod csg;
mod denoise;
mod detail;
mod dispersion;
mod docs;
mod environment;
mod explain;
mod filtering;
mod gltf;
mod gltf_unread;
mod groups;
mod inputs_kept;
mod khronos;
mod library;
mod lpe;
mod meshes;
mod optics;
mod path;
mod properties;
mod region;
mod renders;
mod robustness;
mod schema;
mod serve;
mod shading;
mod sky;
mod textured;

use std::path::{Path, PathBuf};

/// The repository root.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A path under the repository root.
pub fn repo(p: &str) -> PathBuf {
    root().join(p)
}

/// A fresh, empty scratch folder for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("snell-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
