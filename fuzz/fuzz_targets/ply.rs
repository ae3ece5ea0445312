//! Stanford PLY, ASCII or binary: parsed into mesh data (or refused with a message naming a
//! line or byte offset).
#![no_main]

use libfuzzer_sys::fuzz_target;
use snell::mesh_file::ply;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match ply::parse(data, Path::new("fuzz.ply")) {
        Ok(mesh) => {
            // The loader's promises: every index in range, per-vertex arrays in step.
            let n = mesh.positions.len();
            assert!(mesh.triangles.iter().flatten().all(|&i| (i as usize) < n));
            assert!(mesh.normals.is_empty() || mesh.normals.len() == n);
            assert!(mesh.uvs.is_empty() || mesh.uvs.len() == n);
            assert!(mesh.triangle_materials.is_empty());
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
});
