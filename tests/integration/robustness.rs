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
    // Left out, not counted as black: below the horizon (rows 11 and 12 mix floor and
    // sky), a pixel the ball's edge crosses is the mean of its floor samples, as bright as
    // the floor (lit almost only by the huge ambient term, the same everywhere), not darker
    // by the share of the ball's bad samples.
    let lit: Vec<f32> = r
        .image
        .pixels
        .iter()
        .enumerate()
        .filter(|(i, _)| i / 32 >= 14)
        .map(|(_, p)| p.max_element())
        .filter(|&v| v > 0.0)
        .collect();
    let brightest = lit.iter().cloned().fold(0.0f32, f32::max);
    let dim = lit.iter().filter(|&&v| v < 0.8 * brightest).count();
    assert!(lit.len() > 200, "{} lit pixels", lit.len());
    assert_eq!(
        dim,
        0,
        "{dim} of {} lit pixels darker than the floor",
        lit.len()
    );
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
    interrupted_render_resumes("interrupt", &[]);
}

/// The same under the path tracer chosen on the command line: the checkpoint keeps the
/// integrator, so `--resume` alone continues the same render.
#[cfg(unix)]
#[test]
fn an_interrupted_path_traced_render_resumes_without_its_flags() {
    interrupted_render_resumes("interrupt-path", &["--integrator", "path"]);
}

/// Light tracing and bdpt save their passes (the splats, and bdpt's camera film): an
/// interrupted render resumed gives the bytes of one never stopped.
#[cfg(unix)]
#[test]
fn an_interrupted_light_traced_or_bidirectional_render_resumes() {
    let mut checked = 0;
    for integrator in ["light", "bdpt"] {
        interrupted_render_resumes(
            &format!("interrupt-{integrator}"),
            &["--integrator", integrator],
        );
        checked += 1;
    }
    assert_eq!(checked, 2);
}

#[cfg(unix)]
fn interrupted_render_resumes(name: &str, flags: &[&str]) {
    let dir = scratch(name);
    let scene = super::repo("scenes/seed.toml");
    let scene = scene.to_str().unwrap();
    let size = [
        &["--width", "384", "--height", "384", "--spp", "16", "-q"],
        flags,
    ]
    .concat();
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
    assert!(
        err.contains("interrupted: wrote part.partial.png with"),
        "{err}"
    );
    assert!(err.contains("part.png was not written"), "{err}");
    assert!(err.contains("snell render --resume c.ckpt"), "{err}");
    // The partial image is a valid picture of the right size, beside the destination.
    let part = image::open(dir.join("part.partial.png")).unwrap();
    assert_eq!((part.width(), part.height()), (384, 384));
    assert!(!dir.join("part.png").exists());
    // Resume from the checkpoint alone: scene, size, samples and output come from it.
    let resumed = snell()
        .args(["render", "--resume", "c.ckpt"])
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
    assert!(
        !dir.join("part.partial.png").exists(),
        "a finished render removes the partial picture of the same output"
    );
    // The resumed run's rate counts the samples of this run, not the whole image's.
    let said = String::from_utf8_lossy(&resumed.stdout);
    let this_run: u64 = said
        .split_once("2359296 samples (")
        .and_then(|(_, rest)| rest.split_once(" of them in this run)"))
        .and_then(|(n, _)| n.parse().ok())
        .unwrap_or_else(|| panic!("no count of this run's samples in: {said}"));
    assert!(this_run > 0 && this_run < 384 * 384 * 16, "{said}");
    assert_eq!(this_run % 16, 0, "whole pixels of 16 samples: {said}");
}

/// Starts a render of the seed scene that takes minutes, to be interrupted: `size` pixels
/// square at `spp` samples.
fn long_render(dir: &Path, out: &str, size: u32, spp: u32) -> std::process::Child {
    let scene = super::repo("scenes/seed.toml");
    let (size, spp) = (size.to_string(), spp.to_string());
    Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["render", scene.to_str().unwrap(), "-o", out])
        .args(["--width", &size, "--height", &size, "--spp", &spp])
        .current_dir(dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap()
}

fn signal(child: &std::process::Child, sig: &str) {
    let sent = Command::new("kill")
        .args([sig, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
}

/// Waits until the render has started (its temporary file exists).
fn wait_for_tmp(dir: &Path) {
    let start = std::time::Instant::now();
    while files(dir).iter().all(|f| !f.ends_with(".tmp")) {
        assert!(start.elapsed().as_secs() < 60, "no temporary file appeared");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn an_interrupted_render_never_overwrites_the_old_image() {
    let dir = scratch("keep-old");
    std::fs::write(dir.join("keep.png"), b"a good old picture").unwrap();
    let child = long_render(&dir, "keep.png", 512, 1024);
    wait_for_tmp(&dir);
    std::thread::sleep(std::time::Duration::from_millis(300));
    signal(&child, "-INT");
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert!(
        err.contains("interrupted: wrote keep.partial.png with")
            && err.contains("keep.png was left as it was"),
        "{err}"
    );
    assert_eq!(
        std::fs::read(dir.join("keep.png")).unwrap(),
        b"a good old picture"
    );
    let part = image::open(dir.join("keep.partial.png")).unwrap();
    assert_eq!((part.width(), part.height()), (512, 512));
    assert_eq!(files(&dir), ["keep.partial.png", "keep.png"]);
}

#[test]
fn a_second_interrupt_leaves_no_temporary_file() {
    let dir = scratch("two-interrupts");
    // Tiles of 16 x 16 pixels at 65,536 samples take seconds each: the first interrupt waits
    // for them, and the second comes while it does.
    let child = long_render(&dir, "keep.png", 64, 65536);
    wait_for_tmp(&dir);
    signal(&child, "-INT");
    std::thread::sleep(std::time::Duration::from_millis(50));
    signal(&child, "-INT");
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted again"), "{err}");
    assert!(files(&dir).is_empty(), "left behind: {:?}", files(&dir));
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
        integrator: None,
        scene: scene.into(),
        output: dir.join("o.png"),
        tiles: Default::default(),
        film: None,
        splatted: None,
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
