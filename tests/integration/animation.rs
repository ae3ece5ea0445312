//! `[animation]`: keyed values at frames against values worked by hand, the object BVH after
//! motion, files read once over the frames, and `snell render --frames` (patterns, ranges,
//! --skip-existing, each frame equal to its own render, frames told apart in merges).

use super::{repo, scratch};
use snell::math::{Ray, Vec3A};
use snell::scene::{AssetCache, Limits, load_frame};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn snell(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(args)
        .output()
        .expect("snell runs")
}

const BASE: &str = r#"
[image]
width = 24
height = 16
samples = 1
[camera]
position = [0, 0, 10]
look_at = [0, 0, 0]
fov = 40
[materials.m]
color = 0.5
[[lights]]
name = "lamp"
type = "point"
position = [0, 5, 5]
intensity = 1
[[objects]]
name = "ball"
type = "sphere"
radius = 1
material = "m"
"#;

fn scene(name: &str, animation: &str) -> PathBuf {
    let dir = scratch(name);
    let path = dir.join("s.toml");
    std::fs::write(&path, format!("{BASE}{animation}")).unwrap();
    path
}

fn at(path: &Path, frame: u32) -> snell::Scene {
    load_frame(path, &Limits::default(), frame, &mut AssetCache::default())
        .unwrap_or_else(|e| panic!("frame {frame}: {e:?}"))
}

fn centre(s: &snell::Scene) -> Vec3A {
    let b = s.objects[0].world_bounds.unwrap();
    0.5 * (b.min + b.max)
}

fn close(a: Vec3A, b: [f32; 3]) -> bool {
    (a - Vec3A::from_array(b)).abs().max_element() < 1e-4
}

#[test]
fn linear_keys_move_an_object_by_hand_worked_amounts_and_the_bvh_follows() {
    // Enough still objects beside it (far below) that the scene has an object BVH.
    let others: String = (0..12)
        .map(|i| format!("[[objects]]\ntype = \"sphere\"\ncenter = [{i}, -50, -20]\nradius = 0.3\nmaterial = \"m\"\n"))
        .collect();
    let path = scene(
        "anim-linear",
        &format!(
            r#"
[animation]
frames = 11
interpolation = "linear"
[[animation.objects]]
object = "ball"
frame = 0
translate = [0, 0, 0]
[[animation.objects]]
object = "ball"
frame = 10
translate = [5, 0, 0]
{others}"#
        ),
    );
    for (frame, x) in [(0, 0.0), (2, 1.0), (5, 2.5), (10, 5.0)] {
        let s = at(&path, frame);
        assert!(
            close(centre(&s), [x, 0.0, 0.0]),
            "frame {frame}: {}",
            centre(&s)
        );
        // A ray down at the moved centre hits the ball's top; one at where it was does not
        // (past frame 0): the object BVH is the frame's.
        let down = |x: f32| Ray::new(Vec3A::new(x, 5.0, 0.0), -Vec3A::Y);
        let hit = s
            .closest_hit(&down(x), f32::INFINITY)
            .expect("hits the moved ball");
        assert!((hit.t - 4.0).abs() < 1e-4, "t = {}", hit.t);
        if x > 2.0 {
            assert!(s.closest_hit(&down(0.0), f32::INFINITY).is_none());
        }
    }
}

#[test]
fn smooth_keys_follow_catmull_rom_and_step_keys_hold() {
    let path = scene(
        "anim-smooth",
        r#"
[animation]
frames = 31
[[animation.objects]]
object = "ball"
frame = 0
translate = [0, 0, 0]
[[animation.objects]]
object = "ball"
frame = 10
translate = [0, 1, 0]
[[animation.objects]]
object = "ball"
frame = 20
translate = [0, 4, 0]
interpolation = "step"
[[animation.objects]]
object = "ball"
frame = 30
translate = [0, 9, 0]
"#,
    );
    // y: 0, 1, 4 at frames 0, 10, 20. Slopes per frame: 0.05 at frame 0 (half of
    // 1 / 10), (4 - 0) / 20 = 0.2 at frame 10. Halfway through the first segment (s = 0.5,
    // segment 10 frames): 0.125 * 0.5 + 0.5 * 1 - 0.125 * 2 = 0.3125.
    assert!(close(centre(&at(&path, 5)), [0.0, 0.3125, 0.0]));
    // Frame 15: slopes 0.2 at 10 and (9 - 1) / 20 = 0.4 at 20:
    // 0.5 * 1 + 0.125 * 2 + 0.5 * 4 - 0.125 * 4 = 2.25.
    assert!(close(centre(&at(&path, 15)), [0.0, 2.25, 0.0]));
    // The key at 20 holds until 30.
    assert!(close(centre(&at(&path, 29)), [0.0, 4.0, 0.0]));
    assert!(close(centre(&at(&path, 30)), [0.0, 9.0, 0.0]));
}

#[test]
fn camera_and_light_keys_by_frame_and_by_time() {
    let path = scene(
        "anim-camera-light",
        r#"
[animation]
frames = 25
fps = 12
interpolation = "linear"
[[animation.camera]]
time = 0
position = [0, 0, 10]
fov = 40
[[animation.camera]]
time = 2
position = [10, 0, 0]
fov = 60
[[animation.lights]]
light = "lamp"
frame = 0
intensity = 0
color = [1, 0, 0]
[[animation.lights]]
light = "lamp"
frame = 12
intensity = 2
"#,
    );
    let s = at(&path, 6); // a quarter of two seconds at 12 fps
    let view = s.camera.view();
    assert!(close(view.position, [2.5, 0.0, 7.5]), "{}", view.position);
    assert!((view.fov - 45.0).abs() < 1e-4);
    assert!(
        close(view.look_at, [0.0, 0.0, 0.0]),
        "an unkeyed value stays"
    );
    // Intensity 0 -> 2 over frames 0..12: 1 at frame 6; the colour has one key: held.
    match s.lights[0] {
        snell::light::Light::Point(snell::light::PointLight {
            color, position, ..
        }) => {
            assert!(close(color, [1.0, 0.0, 0.0]), "{color}");
            assert!(close(position, [0.0, 5.0, 5.0]));
        }
        ref l => panic!("{l:?}"),
    }
    match at(&path, 24).lights[0] {
        snell::light::Light::Point(snell::light::PointLight { color, .. }) => {
            assert!(close(color, [2.0, 0.0, 0.0]))
        }
        ref l => panic!("{l:?}"),
    }
    assert_eq!(s.animation.map(|a| (a.frames, a.fps)), Some((25, 12.0)));
    assert_eq!(s.frame, 6);
}

#[test]
fn frames_reuse_the_meshes_and_images_read_for_the_first() {
    let dir = scratch("anim-assets");
    std::fs::write(
        dir.join("s.toml"),
        format!(
            r#"
[camera]
look_at = [0, 0, -1]
[textures.earth]
type = "image"
file = "{earth}"
[materials.m]
texture = "earth"
[[objects]]
name = "bunny"
type = "mesh"
file = "{mesh}"
material = "m"
[animation]
frames = 3
[[animation.objects]]
object = "bunny"
frame = 0
rotate = [0, 0, 0]
[[animation.objects]]
object = "bunny"
frame = 2
rotate = [0, 90, 0]
"#,
            earth = repo("assets/earth.jpg").display(),
            mesh = repo("assets/models/teapot.obj").display(),
        ),
    )
    .unwrap();
    let mut assets = AssetCache::default();
    let limits = Limits::default();
    let a = load_frame(&dir.join("s.toml"), &limits, 0, &mut assets).unwrap();
    let b = load_frame(&dir.join("s.toml"), &limits, 2, &mut assets).unwrap();
    let mesh = |s: &snell::Scene| match &s.objects[0].shape {
        snell::geometry::Shape::Mesh(m) => m.clone(),
        other => panic!("{other:?}"),
    };
    assert!(
        std::sync::Arc::ptr_eq(&mesh(&a), &mesh(&b)),
        "the mesh was read again"
    );
    let image = |s: &snell::Scene| match &s.textures[0].pattern {
        snell::texture::Pattern::Image(i) => i.clone(),
        _ => panic!("not an image"),
    };
    assert!(
        std::sync::Arc::ptr_eq(&image(&a), &image(&b)),
        "the image was read again"
    );
    assert_eq!(b.stats.mesh_bvh_time, std::time::Duration::ZERO);
    // The frames differ where the keys say.
    assert_ne!(a.objects[0].transform, b.objects[0].transform);
    assert_eq!(a.materials.len(), b.materials.len());
    assert_eq!(a.files, b.files);
}

#[test]
fn render_frames_writes_each_frame_as_its_own_render_would() {
    let path = scene(
        "anim-cli",
        r#"
[animation]
frames = 4
[[animation.objects]]
object = "ball"
frame = 0
translate = [-2, 0, 0]
[[animation.objects]]
object = "ball"
frame = 3
translate = [2, 0, 0]
"#,
    );
    let dir = path.parent().unwrap();
    let s = path.to_str().unwrap();
    let pattern = dir.join("out/f_##.png");
    let out = snell(&[
        "render",
        s,
        "--frames",
        "0..3",
        "-o",
        pattern.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let frames: Vec<Vec<u8>> = (0..4)
        .map(|f| std::fs::read(dir.join(format!("out/f_{f:02}.png"))).unwrap())
        .collect();
    assert!(frames.windows(2).all(|w| w[0] != w[1]), "the ball moves");
    for f in [1u32, 3] {
        let one = dir.join(format!("one{f}.png"));
        let out = snell(&[
            "render",
            s,
            "--frames",
            &f.to_string(),
            "-o",
            one.to_str().unwrap(),
        ]);
        assert!(out.status.success());
        assert_eq!(
            std::fs::read(&one).unwrap(),
            frames[f as usize],
            "frame {f}"
        );
    }
    // --skip-existing leaves a finished frame alone and renders a missing one.
    std::fs::write(dir.join("out/f_01.png"), b"kept").unwrap();
    std::fs::remove_file(dir.join("out/f_02.png")).unwrap();
    let out = snell(&[
        "render",
        s,
        "--frames",
        "0..3",
        "--skip-existing",
        "-o",
        pattern.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("frame 1:"));
    // One frame rendered is one frame, not "1 frames".
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(said.contains("rendered 1 frame (3 skipped"), "{said}");
    assert_eq!(std::fs::read(dir.join("out/f_01.png")).unwrap(), b"kept");
    assert_eq!(std::fs::read(dir.join("out/f_02.png")).unwrap(), frames[2]);
}

#[test]
fn render_frames_refuses_what_it_cannot_do() {
    let path = scene("anim-cli-bad", "[animation]\nframes = 4\n");
    let s = path.to_str().unwrap();
    let dir = path.parent().unwrap();
    let cases: [(&[&str], &str); 4] = [
        (
            &["--frames", "0..3", "-o", "x.png"],
            "would all be written to",
        ),
        (
            &["--frames", "2..9", "-o", "f_#.png"],
            "goes past the scene's last frame, 3",
        ),
        (&["--frames", "3..1", "-o", "f_#.png"], "runs backwards"),
        (&["--frames", "a..b"], "is not a frame range"),
    ];
    for (flags, message) in cases {
        let out = Command::new(env!("CARGO_BIN_EXE_snell"))
            .arg("render")
            .arg(s)
            .args(flags)
            .current_dir(dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flags:?}: {err}");
        assert!(err.contains(message), "{flags:?}: {err}");
        assert!(!err.contains("panicked"));
    }
    // A scene without [animation] is frame 0 alone.
    let still = repo("scenes/seed.toml");
    let out = snell(&["check", still.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["frames"], 1);
    // Its integrator and adaptive sampling's threshold, after the command line's.
    assert_eq!(
        (&v["integrator"], &v["noise"]),
        (&serde_json::json!("whitted"), &serde_json::Value::Null)
    );
    let out = snell(&[
        "check",
        still.to_str().unwrap(),
        "--json",
        "--integrator",
        "bdpt",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["integrator"], "bdpt");
    let out = snell(&[
        "render",
        still.to_str().unwrap(),
        "--frames",
        "1",
        "-o",
        "/dev/null",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no [animation]"));
}

#[test]
fn regions_of_different_frames_do_not_merge() {
    let path = scene(
        "anim-merge",
        r#"
[animation]
frames = 2
[[animation.camera]]
frame = 0
position = [0, 0, 10]
[[animation.camera]]
frame = 1
position = [0, 1, 10]
"#,
    );
    let dir = path.parent().unwrap();
    let s = path.to_str().unwrap();
    let part = |frame: &str, region: &str, name: &str| {
        let p = dir.join(name);
        let out = snell(&[
            "render",
            s,
            "--frames",
            frame,
            "--region",
            region,
            "-o",
            p.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        p
    };
    let top0 = part("0", "0,0,24,8", "top0.exr");
    let bottom0 = part("0", "0,8,24,16", "bottom0.exr");
    let bottom1 = part("1", "0,8,24,16", "bottom1.exr");
    let whole = dir.join("whole.png");
    let merged = |parts: [&Path; 2]| {
        Command::new(env!("CARGO_BIN_EXE_snell"))
            .arg("merge")
            .args(parts)
            .arg("-o")
            .arg(&whole)
            .output()
            .unwrap()
    };
    assert!(merged([&top0, &bottom0]).status.success());
    let single = dir.join("single.png");
    assert!(
        snell(&["render", s, "--frames", "0", "-o", single.to_str().unwrap()])
            .status
            .success()
    );
    assert_eq!(
        std::fs::read(&whole).unwrap(),
        std::fs::read(&single).unwrap()
    );
    let out = merged([&top0, &bottom1]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn check_names_the_frames_and_json_gives_them() {
    let orbit = repo("scenes/orbit.toml");
    let out = snell(&["check", orbit.to_str().unwrap()]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("animation: 48 frames at 24 frames a second (2.00 s)"),
        "{text}"
    );
    let out = snell(&["check", orbit.to_str().unwrap(), "--json", "--width", "64"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (v["frames"].as_u64(), v["fps"].as_f64()),
        (Some(48), Some(24.0))
    );
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(64), Some(480))
    );
    let files: Vec<&str> = v["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    assert_eq!(files.len(), 1);
    assert!(
        files[0].ends_with("assets/earth.jpg") && !files[0].contains(".."),
        "{files:?}"
    );
    // The sampling flags belong to --json.
    let out = snell(&["check", orbit.to_str().unwrap(), "--width", "64"]);
    assert_eq!(out.status.code(), Some(2));
}
