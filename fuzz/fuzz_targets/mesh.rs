//! A mesh file (PLY when it starts with `ply`, OBJ otherwise) taken the way a scene takes it:
//! checked, arranged for ray queries (BVH build) and hit by rays from every side.
//!
//! Run it built with `-O` and `RUSTFLAGS=-Coverflow-checks=on` (docs/fuzzing.md): obvhs's
//! debug assertions validate each BVH against limits of a traversal snell does not use, and
//! snell's own builds switch them off.
#![no_main]

use glam::Vec3A;
use libfuzzer_sys::fuzz_target;
use snell::geometry::mesh::Mesh;
use snell::math::Ray;
use snell::mesh_file::{obj, ply};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn empty_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("snell-fuzz-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the fuzzer's empty folder");
        dir
    })
}

fuzz_target!(|data: &[u8]| {
    // `mtllib` reads the files it names; absolute or parent paths could reach devices.
    if data.windows(3).any(|w| w == b"dev" || w == b"sys") || data.windows(4).any(|w| w == b"proc")
    {
        return;
    }
    let parsed = if data.starts_with(b"ply") {
        ply::parse(data, Path::new("fuzz.ply"))
    } else {
        obj::parse(data, &empty_dir().join("fuzz.obj"))
    };
    let Ok(data) = parsed else {
        return;
    };
    // Checked and converted as a scene does, with `smooth = true` on a file without normals.
    let Ok((input, _materials)) = data.into_mesh_input(Some(true)) else {
        return;
    };
    let Ok((mesh, _dropped)) = Mesh::new(input) else {
        return;
    };
    let b = mesh.bounds();
    let centre = (b.min + b.max) * 0.5;
    let reach = (b.max - b.min).length() + 1.0;
    let dirs = [
        Vec3A::X,
        -Vec3A::X,
        Vec3A::Y,
        -Vec3A::Y,
        Vec3A::Z,
        -Vec3A::Z,
        Vec3A::new(1.0, 2.0, 3.0).normalize(),
        Vec3A::new(-3.0, 1.0, -2.0).normalize(),
    ];
    for dir in dirs {
        // From outside towards the centre, and from the centre outwards.
        for ray in [Ray::new(centre - dir * reach, dir), Ray::new(centre, dir)] {
            if let Some(hit) = mesh.intersect(&ray, f32::INFINITY) {
                let _ = mesh.surface(&hit);
                let _ = mesh.interpolated_normal(&hit);
                let _ = mesh.slot(hit.prim);
                assert!(mesh.occluded(&ray, f32::INFINITY));
            }
        }
    }
});
