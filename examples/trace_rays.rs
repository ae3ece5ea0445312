//! Ray throughput of snell's acceleration structure on a mesh, for rays read from a file, so
//! it can be compared with another tracer on the very same rays (bench/vs-embree.sh).
//!
//! ```text
//! cargo run --release --example trace_rays -- MESH RAYS... [--threads N] [--repeats N] [--any]
//! ```
//!
//! MESH is an OBJ or PLY file, placed as the only object of a scene (so rays go through the
//! object BVH and the mesh's BVH, as when rendering). Each RAYS file is raw little-endian
//! `f32`, six per ray: origin x y z, direction x y z. Each ray finds its closest hit in
//! `(0, inf)`; the best of the repeats is reported with the hit count and the sum of the hit
//! distances (to check that both tracers saw the same thing). With `--any` each ray only asks
//! whether it meets the mesh at all, as a shadow ray does (the walk stops at the first hit
//! found; the t-sum is then 0).

use rayon::prelude::*;
use snell::math::{Ray, Vec3A};
use snell::scene::{Format, Scene, load_str};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("trace_rays: {e}");
            ExitCode::from(2)
        }
    }
}

fn run() -> Result<(), String> {
    let mut files: Vec<PathBuf> = vec![];
    let mut threads = None;
    let mut repeats = 3;
    let mut any = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut number = |name: &str| -> Result<usize, String> {
            args.next()
                .and_then(|v| v.parse().ok())
                .ok_or(format!("{name} needs a number"))
        };
        match a.as_str() {
            "--threads" => threads = Some(number("--threads")?),
            "--repeats" => repeats = number("--repeats")?.max(1),
            "--any" => any = true,
            _ => files.push(a.into()),
        }
    }
    if files.len() < 2 {
        return Err("usage: trace_rays MESH RAYS... [--threads N] [--repeats N] [--any]".into());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| e.to_string())?;
    let scene = mesh_scene(&files[0])?;
    let s = &scene.stats;
    if !say(format_args!(
        "mesh {}: {} triangles; load {:.1} ms, BVH build {:.1} ms, BVH {:.1} bytes/triangle; {} threads",
        files[0].display(),
        s.unique_triangles,
        s.mesh_load_time.as_secs_f64() * 1e3,
        s.mesh_bvh_time.as_secs_f64() * 1e3,
        s.bvh_bytes as f64 / s.unique_triangles.max(1) as f64,
        pool.current_num_threads()
    ))? {
        return Ok(());
    }
    if !say(format_args!(
        "{:<12} {:>10} {:>10} {:>16} {:>10}",
        "rays", "count", "hits", "t-sum", "Mrays/s"
    ))? {
        return Ok(());
    }
    for f in &files[1..] {
        let rays = read_rays(f)?;
        let mut best = f64::INFINITY;
        let mut summary = (0usize, 0f64);
        for _ in 0..repeats {
            let start = Instant::now();
            summary = pool.install(|| trace(&scene, &rays, any));
            best = best.min(start.elapsed().as_secs_f64());
        }
        let name = f.file_stem().map_or("?".into(), |s| s.to_string_lossy());
        if !say(format_args!(
            "{:<12} {:>10} {:>10} {:>16.6} {:>10.2}",
            name,
            rays.len(),
            summary.0,
            summary.1,
            rays.len() as f64 / best / 1e6
        ))? {
            return Ok(());
        }
    }
    Ok(())
}

/// Prints a line; `Ok(false)` when the reader has gone (`trace_rays ... | head -1`), so the
/// run stops quietly where `println!` would panic.
fn say(line: std::fmt::Arguments) -> Result<bool, String> {
    use std::io::Write;
    match writeln!(std::io::stdout(), "{line}") {
        Ok(()) => Ok(true),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(false),
        Err(e) => Err(format!("standard output: {e}")),
    }
}

/// A scene whose only object is the mesh, untransformed.
fn mesh_scene(mesh: &Path) -> Result<Scene, String> {
    let file = mesh
        .canonicalize()
        .map_err(|e| format!("{}: {e}", mesh.display()))?;
    let text = format!(
        "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\n\
         [materials.m]\ncolor = 1\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0, -1, 0]\n\
         [[objects]]\ntype = \"mesh\"\nmaterial = \"m\"\nfile = {:?}\n",
        file.to_string_lossy()
    );
    load_str(
        &text,
        Path::new("trace_rays.toml"),
        Path::new("."),
        Format::Toml,
    )
    .map_err(|e| e.to_string())
}

fn read_rays(path: &Path) -> Result<Vec<Ray>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes.len() % 24 != 0 {
        return Err(format!(
            "{}: {} bytes is not a whole number of rays (24 bytes each)",
            path.display(),
            bytes.len()
        ));
    }
    // Six floats a ray, in an array: no allocation per ray (a `Vec` each cost 144
    // instructions a ray, which inflated instruction counts taken over the whole program).
    let f = |b: &[u8]| f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
    Ok(bytes
        .chunks_exact(24)
        .map(|r| {
            let v: [f32; 6] = std::array::from_fn(|k| f(&r[4 * k..]));
            Ray::new(Vec3A::new(v[0], v[1], v[2]), Vec3A::new(v[3], v[4], v[5]))
        })
        .collect())
}

/// Closest hits of all rays, in parallel: (hits, sum of hit distances).
fn trace(scene: &Scene, rays: &[Ray], any: bool) -> (usize, f64) {
    rays.par_chunks(4096)
        .map(|chunk| {
            let mut hits = 0;
            let mut sum = 0.0;
            for r in chunk {
                if any {
                    hits += scene.opaque_blocked(r, f32::INFINITY) as usize;
                } else if let Some((_, h)) = scene.intersect(r, f32::INFINITY) {
                    hits += 1;
                    sum += h.t as f64;
                }
            }
            (hits, sum)
        })
        .reduce(|| (0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}
