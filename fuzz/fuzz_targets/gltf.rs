//! glTF 2.0, JSON or GLB: parsed into meshes, materials, placements, cameras and lights (or
//! refused with a message naming what is wrong), then, where it parses, placed by a scene
//! that takes its camera and lights, and a few rays traced through it with both integrators
//! (materials and their maps, normal maps and MikkTSpace, cut-outs). Files it names resolve
//! into a folder that holds only it.
#![no_main]

use libfuzzer_sys::fuzz_target;
use snell::integrator::{Integrator, Path as PathTracer, RayStats, Whitted};
use snell::mesh_file::gltf;
use snell::sampler::{Sampler, SamplerKind};
use snell::scene::{Format, load_str};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// A folder of this process's own, holding only the file under test.
fn dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("snell-fuzz-gltf-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the fuzzer's folder");
        dir
    })
}

fuzz_target!(|data: &[u8]| {
    // Paths a file names could reach the machine's own files (see docs/fuzzing.md).
    if data.windows(4).any(|w| &w[..3] == b"dev" || &w[..3] == b"sys" || w == b"proc") {
        return;
    }
    match gltf::parse(data, Path::new("/nonexistent-snell-fuzz/fuzz.glb")) {
        Ok(scene) => {
            // The loader's promises: indices in range, per-vertex arrays in step, slots,
            // placements and textures that name what exists.
            for m in &scene.meshes {
                let d = &m.data;
                let n = d.positions.len();
                assert!(d.triangles.iter().flatten().all(|&i| (i as usize) < n));
                assert!(d.normals.is_empty() || d.normals.len() == n);
                assert!(d.uvs.is_empty() || d.uvs.len() == n);
                assert!(d.tangents.is_empty() || d.tangents.len() == n);
                assert_eq!(d.triangle_materials.len(), d.triangles.len());
                assert!(d.triangle_materials.iter().all(|&s| (s as usize) < m.slots.len()));
                assert!(m.slots.iter().flatten().all(|&k| k < scene.materials.len()));
            }
            assert!(scene.instances.iter().all(|i| i.mesh < scene.meshes.len()));
            for m in &scene.materials {
                assert!(m.textures().all(|t| t.image < scene.images.len()));
            }
            place(data);
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
});

/// The file placed by a scene that takes its camera (where it has one) and lights, and
/// rays traced through it.
fn place(data: &[u8]) {
    let file = dir().join("f.glb");
    if std::fs::write(&file, data).is_err() {
        return;
    }
    let object = "[[objects]]\ntype = \"mesh\"\nfile = \"f.glb\"\nlights = true\n";
    let [with_camera, without] = [
        format!("[image]\nwidth = 8\nheight = 6\nmax_depth = 4\n[camera]\ngltf = \"f.glb\"\n{object}"),
        format!("[image]\nwidth = 8\nheight = 6\nmax_depth = 4\n[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n{object}"),
    ];
    for text in [with_camera, without] {
        let Ok(scene) = load_str(&text, &dir().join("t.toml"), dir(), Format::Toml) else {
            continue;
        };
        let (w, h) = (scene.settings.width, scene.settings.height);
        let mut rays = RayStats::default();
        let mut sampler = Sampler::new(SamplerKind::Independent, 1);
        for (x, y) in [(0.5, 0.5), (4.0, 3.0), (7.5, 5.5)] {
            let ray = scene.camera.ray(x, y, w, h);
            let _ = Whitted.radiance(&scene, &ray, &mut rays);
            sampler.start(x as u32, y as u32, 0);
            let _ = PathTracer.radiance_sampled(&scene, &ray, &mut sampler, &mut rays);
        }
    }
}
