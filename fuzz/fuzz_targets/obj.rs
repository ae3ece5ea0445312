//! Wavefront OBJ text, and the same bytes as an MTL library: parsed into mesh data (or
//! refused with a message naming a line).
#![no_main]

use libfuzzer_sys::fuzz_target;
use snell::mesh_file::obj;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// An empty folder for the mesh file's path: `mtllib` and `map_Kd` names resolve into it and
/// are not found, as for a user whose MTL file is missing.
fn empty_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("snell-fuzz-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the fuzzer's empty folder");
        dir
    })
}

fuzz_target!(|data: &[u8]| {
    // `mtllib` reads the files it names; absolute or parent paths could reach devices
    // (/dev/zero never ends), which is not what is tested here.
    if data.windows(3).any(|w| w == b"dev" || w == b"sys") || data.windows(4).any(|w| w == b"proc")
    {
        return;
    }
    let path = empty_dir().join("fuzz.obj");
    match obj::parse(data, &path) {
        Ok(mesh) => {
            // The loader's promises: every index in range, per-vertex arrays in step.
            let n = mesh.positions.len();
            assert!(mesh.triangles.iter().flatten().all(|&i| (i as usize) < n));
            assert!(mesh.normals.is_empty() || mesh.normals.len() == n);
            assert!(mesh.uvs.is_empty() || mesh.uvs.len() == n);
            assert!(
                mesh.triangle_materials.is_empty()
                    || mesh.triangle_materials.len() == mesh.triangles.len()
            );
            assert!(
                mesh.triangle_materials
                    .iter()
                    .all(|&m| (m as usize) < mesh.materials.len())
            );
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
    let mut warnings = vec![];
    match obj::parse_mtl(data, &empty_dir().join("fuzz.mtl"), &mut warnings) {
        Ok(_) => {}
        Err(e) => {
            let _ = e.to_string();
        }
    }
});
