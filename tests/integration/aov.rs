//! Debug views: on the seed scene each must show what it claims (the floor's normal is up,
//! the cylinder's side is horizontal and its cap vertical, the Earth's uv runs smoothly,
//! depth grows with distance along the floor, ids name the right objects), and the command
//! line must write them as PNGs or as layers of one EXR.

use super::{repo, scratch};
use snell::integrator::aov::{Aov, AovBuffers};
use snell::render::render_aovs;
use snell::scene::load;
use std::process::Command;

const SIZE: u32 = 128;

fn seed_aovs() -> (snell::Scene, AovBuffers) {
    let mut scene = load(&repo("scenes/seed.toml")).unwrap();
    scene.settings.width = SIZE;
    scene.settings.height = SIZE;
    let b = render_aovs(&scene, Some(2)).unwrap();
    (scene, b)
}

fn object_index(scene: &snell::Scene, name: &str) -> i32 {
    scene.objects.iter().position(|o| o.name == name).unwrap() as i32
}

#[test]
fn views_of_the_seed_scene_show_what_they_claim() {
    let (scene, b) = seed_aovs();
    let at = |x: u32, y: u32| (y * SIZE + x) as usize;
    let floor = object_index(&scene, "floor");
    let cylinder = object_index(&scene, "green cylinder");
    let earth = object_index(&scene, "earth");
    // The floor's normal is straight up wherever it is seen.
    let floor_px: Vec<usize> = (0..b.object.len())
        .filter(|&i| b.object[i] == floor)
        .collect();
    assert!(floor_px.len() > 1000);
    for &i in &floor_px {
        assert!((b.normal[i] - snell::math::Vec3A::Y).length() < 1e-5);
    }
    // The cylinder: horizontal normals on its side, vertical on its cap.
    let cyl: Vec<usize> = (0..b.object.len())
        .filter(|&i| b.object[i] == cylinder)
        .collect();
    let (side, cap): (Vec<usize>, Vec<usize>) =
        cyl.iter().partition(|&&i| b.normal[i].y.abs() < 1e-4);
    assert!(side.len() > 20, "side seen: {}", side.len());
    // The cap (y = -7, 92 away, seen from 7 above it) is a sliver one pixel tall: the
    // centres of pixels 100 to 110 of row 83 fall on it, and no others.
    assert_eq!(cap.len(), 11, "cap pixels");
    assert!(
        cap.iter().all(|&i| (b.normal[i].y - 1.0).abs() < 1e-4),
        "cap normals vertical"
    );
    // Depth grows up the image along the floor (the column where the most floor shows,
    // from the bottom row up until something stands in the way), and misses are infinite.
    let run = |x: u32| {
        (0..SIZE)
            .rev()
            .take_while(|&y| b.object[at(x, y)] == floor)
            .map(|y| b.depth[at(x, y)])
            .collect::<Vec<f32>>()
    };
    let depths = (0..SIZE).map(run).max_by_key(|r| r.len()).unwrap();
    assert!(depths.len() > 10);
    assert!(
        depths.windows(2).all(|w| w[1] >= w[0]),
        "depth monotone: {depths:?}"
    );
    assert!(b.depth[at(0, 0)].is_infinite() && b.object[at(0, 0)] == -1);
    // The Earth's uv: u grows left to right and v top to bottom across its disk, smoothly
    // (no seam on the side facing the camera).
    let earth_px: Vec<(u32, u32)> = (0..SIZE)
        .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
        .filter(|&(x, y)| b.object[at(x, y)] == earth)
        .collect();
    assert!(earth_px.len() > 50);
    let (mut u_steps, mut v_steps) = (0, 0);
    for &(x, y) in &earth_px {
        if x + 1 < SIZE && b.object[at(x + 1, y)] == earth {
            let du = b.uv[at(x + 1, y)].x - b.uv[at(x, y)].x;
            assert!(
                du > 0.0 && du < 0.2,
                "u step {du} at {x},{y} (a seam jumps by about -1)"
            );
            u_steps += 1;
        }
        if y + 1 < SIZE && b.object[at(x, y + 1)] == earth {
            let dv = b.uv[at(x, y + 1)].y - b.uv[at(x, y)].y;
            assert!(dv > 0.0 && dv < 0.2, "v step {dv} at {x},{y}");
            v_steps += 1;
        }
    }
    // The Earth's disk is 521 pixels in 26 rows and 26 columns, nothing in front of it:
    // 521 - 26 neighbours to the right and as many below.
    assert_eq!((u_steps, v_steps), (495, 495), "steps checked");
    // The diamond shows the deepest trees; the floor none.
    let diamond = object_index(&scene, "diamond sphere");
    let deepest = (0..b.object.len())
        .filter(|&i| b.object[i] == diamond)
        .map(|i| b.bounces[i])
        .max()
        .unwrap();
    assert_eq!(deepest, scene.settings.max_depth - 1);
    assert!(floor_px.iter().all(|&i| b.bounces[i] == 0));
    // Display: normals as 0.5 + 0.5 n, exactly, in the PNG's bytes.
    let img = b.display(Aov::Normal, scene.settings.max_depth);
    let bytes = snell::output::to_srgb8(&img);
    let i = floor_px[0];
    assert_eq!(&bytes[i * 3..i * 3 + 3], &[128, 255, 128]);
}

#[test]
fn the_command_writes_pngs_or_exr_layers() {
    let dir = scratch("aov-cli");
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_snell"))
            .args(args)
            .current_dir(&dir)
            .output()
            .unwrap()
    };
    let scene = repo("scenes/seed.toml");
    let scene = scene.to_str().unwrap();
    let common = ["--width", "40", "--height", "30", "-q"];
    let o = run(&[
        &["render", scene, "-o", "s.png", "--aov", "all"][..],
        &common,
    ]
    .concat());
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let mut written = 0;
    for a in Aov::ALL {
        let p = dir.join(format!("s.{}.png", a.name()));
        if a.from_film() {
            // The seed is Whitted's, whose `all` has no variance or spp.
            assert!(!p.exists());
            continue;
        }
        let img = image::open(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        assert_eq!((img.width(), img.height()), (40, 30));
        written += 1;
    }
    // Normal, uv, depth, albedo, object, material and bounces.
    assert_eq!(written, 7, "views written");
    let o = run(&[
        &["render", scene, "-o", "v.png", "--aov", "variance"][..],
        &common,
    ]
    .concat());
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("the variance view is the path tracer's"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let o = run(&[
        &[
            "render",
            scene,
            "-o",
            "s.exr",
            "--aov",
            "normal,depth,object",
        ][..],
        &common,
    ]
    .concat());
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let exr = exr::prelude::read_all_flat_layers_from_file(dir.join("s.exr")).unwrap();
    let mut names: Vec<String> = exr.layer_data[0]
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "B",
            "G",
            "R",
            "depth.Z",
            "normal.X",
            "normal.Y",
            "normal.Z",
            "object.id"
        ]
    );
    let o = run(&["render", scene, "-o", "s.png", "--aov", "normals"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is not a debug view"));
}

/// The views of a scene at `SIZE` x `SIZE`.
fn views_of(path: &str) -> (snell::Scene, AovBuffers) {
    let mut scene = load(&repo(path)).unwrap();
    scene.settings.width = SIZE;
    scene.settings.height = SIZE;
    let b = render_aovs(&scene, Some(2)).unwrap();
    (scene, b)
}

#[test]
fn the_debugging_guides_broken_scenes_show_their_bugs() {
    // docs/debugging.md: each broken scene and what gives it away.
    // 1. The Earth turned half round: its uv seam (u jumping by about 1) faces the camera.
    let (scene, b) = views_of("scenes/debugging/earth-turned.toml");
    let earth = object_index(&scene, "earth");
    let seam_in_view = (0..b.object.len() - 1).any(|i| {
        b.object[i] == earth
            && b.object[i + 1] == earth
            && (b.uv[i + 1].x - b.uv[i].x).abs() > 0.5
            && b.normal[i].z > 0.5
    });
    assert!(seam_in_view, "the seam faces the camera");
    let (_, fixed) = views_of("scenes/seed.toml");
    let seam_in_fixed = (0..fixed.object.len() - 1).any(|i| {
        fixed.object[i] == earth
            && fixed.object[i + 1] == earth
            && (fixed.uv[i + 1].x - fixed.uv[i].x).abs() > 0.5
    });
    assert!(!seam_in_fixed, "no seam in view once fixed");
    // 2. The floor mapped along the wrong axis: v is the same all over the floor.
    let (scene, b) = views_of("scenes/debugging/floor-stripes.toml");
    let floor = object_index(&scene, "floor");
    let vs: Vec<f32> = (0..b.object.len())
        .filter(|&i| b.object[i] == floor)
        .map(|i| b.uv[i].y)
        .collect();
    // The seed scene's geometry and camera: its floor fills over 1000 pixels (as
    // `views_of_the_seed_scene_show_what_they_claim` checks).
    assert!(vs.len() > 1000, "floor pixels: {}", vs.len());
    assert!(
        vs.iter().all(|v| (v - vs[0]).abs() < 1e-3),
        "v is constant on the floor"
    );
    // 3. The sunken cylinder is nowhere in the object view.
    let (scene, b) = views_of("scenes/debugging/sunken-cylinder.toml");
    let cylinder = object_index(&scene, "green cylinder");
    assert!(!b.object.contains(&cylinder));
    // 4. The glass disk: a ray through it is never refracted back out from the inside.
    let scene = load(&repo("scenes/debugging/glass-disk.toml")).unwrap();
    let ray = scene.camera.ray(512.5, 858.5, 1024, 1024);
    let mut rec = snell::integrator::explain::TreeRecorder::new(500);
    snell::integrator::Whitted.explain(
        &scene,
        &ray,
        &mut snell::integrator::RayStats::default(),
        &mut rec,
    );
    let tree = rec.finish().unwrap();
    assert_eq!(tree.hit.as_ref().unwrap().object, "diamond disk");
    fn any_inside(n: &snell::integrator::explain::RayNode) -> bool {
        n.hit.as_ref().is_some_and(|h| h.side == "inside") || n.children.iter().any(any_inside)
    }
    assert!(
        !any_inside(&tree),
        "no surface is ever left from the inside"
    );
}

/// `bounces` follows the integrator: the Cornell box's walls reflect no ray of Whitted's
/// (0 everywhere), while the path tracer's paths bounce on, up to `max_depth - 1` (the
/// camera ray counts as 1, as Mitsuba counts) and no further.
#[test]
fn bounces_count_the_path_tracers_path_under_path() {
    let mut scene = load(&repo("scenes/cornell.toml")).unwrap();
    (scene.settings.width, scene.settings.height) = (24, 24);
    scene.settings.integrator.kind = snell::scene::IntegratorKind::Whitted;
    let whitted = render_aovs(&scene, Some(2)).unwrap();
    assert!(whitted.bounces.iter().all(|&b| b == 0));
    scene.settings.integrator.kind = snell::scene::IntegratorKind::Path;
    for max_depth in [2u32, 8] {
        scene.settings.max_depth = max_depth;
        let path = render_aovs(&scene, Some(2)).unwrap();
        let most = *path.bounces.iter().max().unwrap();
        let mean = path.bounces.iter().map(|&b| b as f64).sum::<f64>() / path.bounces.len() as f64;
        assert_eq!(most, max_depth - 1, "max_depth {max_depth}");
        assert!(mean > 0.4 * (max_depth - 1) as f64, "mean {mean}");
        // The same numbers again: sample 0 of each pixel, not a new draw.
        assert_eq!(render_aovs(&scene, Some(1)).unwrap().bounces, path.bounces);
    }
}

/// The variance view of a path-traced Cornell box: an EXR layer of each pixel's variance
/// (none where every sample is the same, as on the light and outside the box; some on the
/// walls, more where fewer samples were taken), and a PNG on the ramp.
#[test]
fn the_variance_view_shows_the_pictures_noise() {
    let dir = scratch("aov-variance");
    let scene = repo("scenes/cornell.toml");
    let variance = |spp: &str, out: &str| -> Vec<f32> {
        let o = Command::new(env!("CARGO_BIN_EXE_snell"))
            .args(["render", scene.to_str().unwrap(), "-o", out, "-q"])
            .args(["--width", "32", "--height", "32", "--spp", spp])
            .args(["--aov", "variance"])
            .current_dir(&dir)
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let exr = exr::prelude::read_all_flat_layers_from_file(dir.join(out)).unwrap();
        let ch = exr.layer_data[0]
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == "variance.Y")
            .expect("a variance.Y channel");
        ch.sample_data.values_as_f32().collect()
    };
    let v16 = variance("16", "c16.exr");
    assert_eq!(v16.len(), 32 * 32);
    assert!(v16.iter().all(|v| v.is_finite() && *v >= 0.0));
    let zero = v16.iter().filter(|v| **v == 0.0).count();
    assert!(zero > 0 && zero < 200, "{zero} pixels without noise");
    let v64 = variance("64", "c64.exr");
    let (a, b): (f32, f32) = (v16.iter().sum(), v64.iter().sum());
    assert!(
        b < 0.5 * a,
        "the variance falls with the samples: {a} then {b}"
    );
    let o = Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["render", scene.to_str().unwrap(), "-o", "c.png", "-q"])
        .args([
            "--width", "32", "--height", "32", "--spp", "4", "--aov", "variance",
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let img = image::open(dir.join("c.variance.png")).unwrap().to_rgb8();
    assert_eq!((img.width(), img.height()), (32, 32));
}
