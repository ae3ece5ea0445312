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
