//! Ray query throughput: one triangle, and whole scenes through their BVHs (the Stanford
//! bunny's 69,451 triangles, and the seed scene's eight objects).
//!
//! `cargo bench --bench rays`; criterion reports time per batch and rays per second
//! ("elem/s"). Each batch is 4,096 rays, traced on one thread.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use snell::geometry::{Shape, Triangle};
use snell::math::{Ray, Rng, Vec3A};
use snell::scene::{Format, Scene, load, load_str};
use std::hint::black_box;
use std::path::Path;

const BATCH: usize = 4096;

fn repo(p: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(p)
}

/// The bunny as the only object of a scene.
fn bunny() -> Scene {
    let file = repo("assets/models/stanford-bunny.obj");
    let text = format!(
        "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\n[materials.m]\ncolor = 1\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0, -1, 0]\n\
         [[objects]]\ntype = \"mesh\"\nmaterial = \"m\"\nfile = {:?}\n",
        file.to_string_lossy()
    );
    load_str(&text, Path::new("bench.toml"), Path::new("."), Format::Toml)
        .expect("the bunny scene loads")
}

/// Camera rays: a 64 x 64 grid of pinhole rays from +z framing the box `lo..hi`.
fn camera_rays(lo: Vec3A, hi: Vec3A) -> Vec<Ray> {
    let centre = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    let eye = centre + Vec3A::Z * (radius / 20f32.to_radians().sin());
    let half = 20f32.to_radians().tan();
    (0..BATCH)
        .map(|k| {
            let (i, j) = ((k % 64) as f32, (k / 64) as f32);
            let x = ((i + 0.5) / 64.0 * 2.0 - 1.0) * half;
            let y = (1.0 - (j + 0.5) / 64.0 * 2.0) * half;
            Ray::new(eye, Vec3A::new(x, y, -1.0).normalize())
        })
        .collect()
}

/// Incoherent rays: origins uniform in the box, directions uniform on the sphere.
fn random_rays(lo: Vec3A, hi: Vec3A) -> Vec<Ray> {
    let mut rng = Rng::new(1);
    (0..BATCH)
        .map(|_| {
            let o = lo + (hi - lo) * Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            let z = 1.0 - 2.0 * rng.next_f32();
            let phi = std::f32::consts::TAU * rng.next_f32();
            let r = (1.0 - z * z).max(0.0).sqrt();
            Ray::new(o, Vec3A::new(r * phi.cos(), r * phi.sin(), z))
        })
        .collect()
}

fn closest_hits(scene: &Scene, rays: &[Ray]) -> usize {
    rays.iter()
        .filter(|r| scene.intersect(r, f32::INFINITY).is_some())
        .count()
}

fn bench_triangle(c: &mut Criterion) {
    let tri = Shape::Triangle(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::Y).expect("has area"));
    // Rays toward the triangle's plane from above, half of them hitting it.
    let mut rng = Rng::new(2);
    let rays: Vec<Ray> = (0..BATCH)
        .map(|_| {
            let target = Vec3A::new(rng.next_f32(), rng.next_f32(), 0.0);
            let origin = Vec3A::new(rng.next_f32(), rng.next_f32(), 1.0 + rng.next_f32());
            Ray::new(origin, (target - origin).normalize())
        })
        .collect();
    let mut g = c.benchmark_group("triangle");
    g.throughput(Throughput::Elements(BATCH as u64));
    g.bench_function("watertight", |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| black_box(&tri).intersect(r, f32::INFINITY).is_some())
                .count()
        })
    });
    g.finish();
}

fn bench_bvh(c: &mut Criterion) {
    let bunny = bunny();
    let (lo, hi) = (
        Vec3A::new(-0.095, 0.033, -0.062),
        Vec3A::new(0.061, 0.187, 0.059),
    );
    let seed = load(&repo("scenes/seed.toml")).expect("the seed scene loads");
    let seed_rays: Vec<Ray> = (0..BATCH)
        .map(|k| {
            let (x, y) = ((k % 64) as f32 * 16.0 + 8.0, (k / 64) as f32 * 16.0 + 8.0);
            seed.camera.ray(x, y, 1024, 1024)
        })
        .collect();
    let mut g = c.benchmark_group("bvh");
    g.throughput(Throughput::Elements(BATCH as u64));
    for (name, scene, rays) in [
        ("bunny camera", &bunny, camera_rays(lo, hi)),
        ("bunny incoherent", &bunny, random_rays(lo, hi)),
        ("seed camera", &seed, seed_rays),
    ] {
        g.bench_with_input(BenchmarkId::new("closest", name), &rays, |b, rays| {
            b.iter(|| closest_hits(scene, black_box(rays)))
        });
    }
    let shadow = random_rays(lo, hi);
    g.bench_with_input(
        BenchmarkId::new("any", "bunny incoherent"),
        &shadow,
        |b, rays| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| bunny.opaque_blocked(r, f32::INFINITY))
                    .count()
            })
        },
    );
    g.finish();
}

criterion_group!(benches, bench_triangle, bench_bvh);
criterion_main!(benches);
