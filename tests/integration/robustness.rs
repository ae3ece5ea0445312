//! Numerical safety: samples that come out NaN or infinite are left out of their pixels and
//! reported with the pixel and the object, instead of becoming black or white specks.

use super::scratch;
use snell::integrator::Whitted;
use snell::scene::{Format, load_str};
use std::path::Path;
use std::process::Command;

/// Ambient light, ambient coefficient and colour, each at the 1e15 a scene file allows,
/// multiply to 1e45: more than an f32 holds.
const OVERFLOWING: &str = r#"
[image]
width = 32
height = 24
samples = 4
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
[world]
ambient = 1e15
[materials.hot]
color = 1e15
ambient = 1e15
[materials.ok]
color = 0.5
[[lights]]
type = "point"
position = [0, 5, 5]
[[objects]]
name = "blazing ball"
type = "sphere"
radius = 1
material = "hot"
[[objects]]
type = "plane"
point = [0, -1, 0]
material = "ok"
"#;

#[test]
fn non_finite_samples_are_left_out_and_reported_with_pixel_and_object() {
    let scene = load_str(
        OVERFLOWING,
        Path::new("t.toml"),
        Path::new("."),
        Format::Toml,
    )
    .unwrap();
    let r = snell::render::render(&scene, &Whitted, Some(2), &|_| {}).unwrap();
    let bad = &r.bad_samples;
    assert!(bad.count > 0);
    assert!(!bad.examples.is_empty());
    let ball = scene.objects.iter().position(|o| o.name == "blazing ball");
    for e in &bad.examples {
        assert_eq!(e.object, ball, "reported on the ball: {e:?}");
        assert!(e.x < 32 && e.y < 24);
    }
    assert!(
        r.image.pixels.iter().all(|p| p.is_finite()),
        "no non-finite pixel reaches the image"
    );
    // The floor is unaffected.
    assert!(r.image.pixels[(23 * 32) as usize].max_element() > 0.0);
    // Same report at any thread count.
    let one = snell::render::render(&scene, &Whitted, Some(1), &|_| {}).unwrap();
    assert_eq!(one.bad_samples, r.bad_samples);
}

#[test]
fn the_command_warns_about_them() {
    let dir = scratch("non-finite");
    std::fs::write(dir.join("hot.toml"), OVERFLOWING).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["render", "hot.toml"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("came out NaN or infinite") && err.contains("on object `blazing ball`"),
        "{err}"
    );
    assert!(dir.join("hot.png").exists());
}

/// Ctrl-C or SIGTERM during a render writes the tiles finished so far, saves the
/// checkpoint and exits 130; resuming gives the same bytes as a render never stopped.
#[cfg(unix)]
#[test]
fn an_interrupted_render_resumes_to_the_same_bytes() {
    let dir = scratch("interrupt");
    let scene = super::repo("scenes/seed.toml");
    let scene = scene.to_str().unwrap();
    let size = ["--width", "384", "--height", "384", "--spp", "16", "-q"];
    let snell = || Command::new(env!("CARGO_BIN_EXE_snell"));
    let whole = snell()
        .args([&["render", scene, "-o", "whole.png"][..], &size].concat())
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(whole.status.code(), Some(0));
    let child = snell()
        .args(
            [
                &["render", scene, "-o", "part.png", "--checkpoint", "c.ckpt"][..],
                &["--checkpoint-every", "0.05"],
                &size,
            ]
            .concat(),
        )
        .current_dir(&dir)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Stop it once it has saved some progress.
    let start = std::time::Instant::now();
    while !dir.join("c.ckpt").exists() && start.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted: wrote part.png with"), "{err}");
    assert!(err.contains("snell render --resume c.ckpt"), "{err}");
    // The partial image is a valid picture of the right size.
    let part = image::open(dir.join("part.png")).unwrap();
    assert_eq!((part.width(), part.height()), (384, 384));
    // Resume from the checkpoint alone: scene, size, samples and output come from it.
    let resumed = snell()
        .args(["render", "--resume", "c.ckpt", "-q"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(
        resumed.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    assert!(
        std::fs::read(dir.join("part.png")).unwrap()
            == std::fs::read(dir.join("whole.png")).unwrap(),
        "the resumed render differs from the uninterrupted one"
    );
    assert!(
        !dir.join("c.ckpt").exists(),
        "a finished render removes its checkpoint"
    );
}

#[test]
fn a_checkpoint_of_another_scene_or_size_is_refused() {
    let dir = scratch("resume-mismatch");
    let scene = super::repo("tests/scenes/small.toml");
    let scene = scene.to_str().unwrap();
    let snell = || Command::new(env!("CARGO_BIN_EXE_snell"));
    // A checkpoint saved for this scene at 40 x 30 (a complete render removes it, so make
    // one by hand from an empty render).
    let c = snell::checkpoint::Checkpoint {
        fingerprint: 1,
        width: 40,
        height: 30,
        spp: 1,
        seed: 0,
        scene: scene.into(),
        output: dir.join("o.png"),
        tiles: Default::default(),
    };
    c.save(&dir.join("c.ckpt")).unwrap();
    let o = snell()
        .args(["render", "--resume", "c.ckpt"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("changed since the checkpoint"));
    std::fs::write(dir.join("junk.ckpt"), b"not a checkpoint").unwrap();
    let o = snell()
        .args(["render", "--resume", "junk.ckpt"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is not a snell checkpoint"));
}

/// A file name can point at a device: /dev/zero would be read forever.
#[cfg(unix)]
#[test]
fn devices_named_as_files_are_refused_not_read_forever() {
    let dir = scratch("devices");
    std::fs::write(
        dir.join("m.obj"),
        "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let text = "[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = 1\n\
        [[lights]]\ntype = \"point\"\nposition = [0, 5, 0]\n\
        [[objects]]\ntype = \"mesh\"\nfile = \"m.obj\"\nmaterial = \"m\"\n";
    let scene = load_str(text, &dir.join("t.toml"), &dir, Format::Toml).unwrap();
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("not a regular file")),
        "{:?}",
        scene.warnings
    );
}
