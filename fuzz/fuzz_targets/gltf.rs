//! glTF 2.0, JSON or GLB: parsed into meshes, materials and placements (or refused with a
//! message naming what is wrong). Files it names resolve into an empty folder.
#![no_main]

use libfuzzer_sys::fuzz_target;
use snell::mesh_file::gltf;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    // Paths a file names could reach the machine's own files (see docs/fuzzing.md).
    if data.windows(4).any(|w| &w[..3] == b"dev" || &w[..3] == b"sys" || w == b"proc") {
        return;
    }
    match gltf::parse(data, Path::new("/nonexistent-snell-fuzz/fuzz.glb")) {
        Ok(scene) => {
            // The loader's promises: indices in range, per-vertex arrays in step, slots and
            // placements that name what exists.
            for m in &scene.meshes {
                let d = &m.data;
                let n = d.positions.len();
                assert!(d.triangles.iter().flatten().all(|&i| (i as usize) < n));
                assert!(d.normals.is_empty() || d.normals.len() == n);
                assert!(d.uvs.is_empty() || d.uvs.len() == n);
                assert_eq!(d.triangle_materials.len(), d.triangles.len());
                assert!(d.triangle_materials.iter().all(|&s| (s as usize) < m.slots.len()));
                assert!(m.slots.iter().flatten().all(|&k| k < scene.materials.len()));
            }
            assert!(scene.instances.iter().all(|i| i.mesh < scene.meshes.len()));
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
});
