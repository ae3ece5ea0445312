//! The command line: exit codes (0 done, 1 render or write failed, 2 bad command line or
//! scene), messages that point at the file, line and column, and outputs that are never
//! left broken.

mod check;
mod lab;
mod render;

use super::{repo, scratch};
use std::path::Path;
use std::process::{Command, Output};

pub(crate) fn snell(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("the snell binary runs")
}

pub(crate) fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

pub(crate) fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Runs snell and checks the exit code and that nothing panicked.
pub(crate) fn expect(args: &[&str], cwd: &Path, code: i32) -> Output {
    let o = snell(args, cwd);
    assert_eq!(
        o.status.code(),
        Some(code),
        "snell {args:?}\nstdout: {}\nstderr: {}",
        stdout(&o),
        stderr(&o)
    );
    assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
    o
}

pub(super) fn write_scene(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

pub(super) const GOOD: &str = "[image]\nwidth = 8\nheight = 6\n[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = 1\n[[lights]]\ntype = \"point\"\nposition = [0, 5, 0]\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -3]\nradius = 1\nmaterial = \"m\"\n";

#[test]
fn help_teaches_the_commands_and_exit_codes() {
    let dir = scratch("help");
    let o = expect(&["--help"], &dir, 0);
    let out = stdout(&o);
    for word in ["render", "check", "Exit codes", "docs/scene-format.md"] {
        assert!(out.contains(word), "{out}");
    }
    let o = expect(&["render", "--help"], &dir, 0);
    for word in ["--spp", "--threads", "--seed", "--width", "--output"] {
        assert!(stdout(&o).contains(word), "{}", stdout(&o));
    }
}

#[test]
fn bad_command_lines_exit_2() {
    let dir = scratch("badflags");
    let scene = write_scene(&dir, "s.toml", GOOD);
    expect(&["render"], &dir, 2);
    expect(&["render", &scene, "--bogus"], &dir, 2);
    expect(&["render", &scene, "--threads", "0"], &dir, 2);
    // A negative number is told what the flag takes, not clap's tip to write `-- -3`.
    for flag in ["--width", "--height", "--spp", "--threads", "--max-pixels"] {
        let o = expect(&["render", &scene, flag, "-3"], &dir, 2);
        assert!(
            stderr(&o).contains("`-3` is not a positive whole number")
                && !stderr(&o).contains("-- -3"),
            "{flag}: {}",
            stderr(&o)
        );
    }
    let o = expect(&["render", &scene, "--seed", "-1"], &dir, 2);
    assert!(
        stderr(&o).contains("`-1` is not a whole number from 0"),
        "{}",
        stderr(&o)
    );
    let o = expect(&["render", &scene, "--checkpoint-every", "-1"], &dir, 2);
    assert!(
        stderr(&o).contains("--checkpoint-every must be a positive number"),
        "{}",
        stderr(&o)
    );
    let o = expect(&["render", &scene, "--spp", "10"], &dir, 2);
    assert!(
        stderr(&o).contains("square number") && stderr(&o).contains("use 9 (3 x 3) or 16 (4 x 4)"),
        "{}",
        stderr(&o)
    );
    let o = expect(
        &["render", &scene, "--width", "60000", "--height", "60000"],
        &dir,
        2,
    );
    assert!(
        stderr(&o).contains("more than the 268435456 a render may have")
            && stderr(&o).contains("raise the limit with --max-pixels"),
        "{}",
        stderr(&o)
    );
    // Raised past what the machine holds: refused before rendering, with the estimate
    // (65536 x 65536 pixels need 224 GiB; skipped on a machine with more than that free).
    if snell::scene::available_memory().is_some_and(|a| a < 224 << 30) {
        let o = expect(
            &[
                "render",
                &scene,
                "--width",
                "65536",
                "--height",
                "65536",
                "--max-pixels",
                "4294967296",
            ],
            &dir,
            2,
        );
        assert!(
            stderr(&o).contains("this render would need about 224.0 GiB (image 224.0 GiB"),
            "{}",
            stderr(&o)
        );
    }
    // Texture and triangle limits, each with the flag that raises it.
    let seed = repo("scenes/seed.toml").to_string_lossy().into_owned();
    let o = expect(&["check", &seed, "--max-texture-pixels", "1000"], &dir, 2);
    assert!(
        stderr(&o).contains("2048 x 1024, more than the 1000 texels")
            && stderr(&o).contains("--max-texture-pixels"),
        "{}",
        stderr(&o)
    );
    let bunny = repo("scenes/bunny.toml").to_string_lossy().into_owned();
    let o = expect(&["check", &bunny, "--max-triangles", "1000"], &dir, 2);
    assert!(
        stderr(&o).contains("69451 triangles, more than the 1000 allowed")
            && stderr(&o).contains("--max-triangles"),
        "{}",
        stderr(&o)
    );
    // A limit cannot be raised past what snell can do.
    let o = expect(&["check", &scene, "--max-depth", "1000"], &dir, 2);
    assert!(stderr(&o).contains("--max-depth must be between 1 and 256"));
    let o = expect(&["render", &scene, "--width", "0"], &dir, 2);
    assert!(
        stderr(&o).contains("--width must be between 1 and"),
        "{}",
        stderr(&o)
    );
    let o = expect(&["render", &scene, "-o", "out.jpg"], &dir, 2);
    assert!(stderr(&o).contains(".png or .exr"), "{}", stderr(&o));
    expect(&["frobnicate"], &dir, 2);
}

#[test]
fn render_writes_png_and_exr_and_reports() {
    let dir = scratch("render");
    let scene = write_scene(&dir, "ball.toml", GOOD);
    let o = expect(&["render", &scene], &dir, 0);
    // Default output: the scene's name with .png, in the current folder.
    let png = image::open(dir.join("ball.png")).unwrap();
    assert_eq!((png.width(), png.height()), (8, 6));
    let line = stdout(&o);
    assert!(
        line.contains("8 x 6") && line.contains("1 spp") && line.contains("samples/s"),
        "{line}"
    );
    expect(
        &[
            "render", &scene, "-o", "b.exr", "--width", "4", "--height", "2", "--spp", "4", "-q",
        ],
        &dir,
        0,
    );
    let exr = image::open(dir.join("b.exr")).unwrap().into_rgb32f();
    assert_eq!((exr.width(), exr.height()), (4, 2));
    // Linear floats, not 8-bit steps: some light, nothing negative or NaN.
    let values: Vec<f32> = exr.pixels().flat_map(|p| p.0).collect();
    assert!(values.iter().all(|v| v.is_finite() && *v >= 0.0));
    assert!(
        values
            .iter()
            .any(|v| *v > 0.05 && (v * 255.0).fract() != 0.0),
        "{values:?}"
    );
    // A scene name with dots keeps them all: cap.day.toml writes cap.day.png.
    let dotted = write_scene(&dir, "cap.day.toml", GOOD);
    expect(&["render", &dotted, "-q"], &dir, 0);
    assert!(dir.join("cap.day.png").exists() && !dir.join("cap.png").exists());
    // No temporary files left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn scene_errors_point_at_the_line_and_exit_2() {
    let dir = scratch("scene-errors");
    let bad = GOOD.replace("radius = 1", "radus = 1");
    let scene = write_scene(&dir, "typo.toml", &bad);
    let o = expect(&["render", &scene], &dir, 2);
    let err = stderr(&o);
    assert!(err.contains("typo.toml:14:1"), "{err}");
    assert!(
        err.contains("unknown key `radus`") && err.contains("did you mean `radius`?"),
        "{err}"
    );
    assert!(
        err.contains("radus = 1"),
        "the offending line is shown: {err}"
    );
    // check reports the same, also with exit code 2.
    let o = expect(&["check", &scene], &dir, 2);
    assert!(stderr(&o).contains("typo.toml:14:1"));
    // Several problems are reported at once.
    let two = GOOD
        .replace("radius = 1", "radius = -1")
        .replace("look_at = [0, 0, -1]", "look_at = [0, 0, -1]\nfov = 0");
    let scene = write_scene(&dir, "two.toml", &two);
    let err = stderr(&expect(&["check", &scene], &dir, 2));
    assert!(
        err.contains("camera.fov")
            && err.contains("objects[0].radius")
            && err.contains("2 problems"),
        "{err}"
    );
}

#[test]
fn missing_and_unreadable_inputs_exit_2() {
    let dir = scratch("missing");
    let err = stderr(&expect(&["render", "nope.toml"], &dir, 2));
    assert!(
        err.contains("nope.toml") && err.contains("cannot read"),
        "{err}"
    );
    let err = stderr(&expect(&["check", "scene.yaml"], &dir, 2));
    assert!(err.contains(".toml or .json"), "{err}");
    std::fs::write(dir.join("binary.toml"), [0xff, 0xfe, 0x00, 0x41]).unwrap();
    let err = stderr(&expect(&["check", "binary.toml"], &dir, 2));
    assert!(err.contains("not UTF-8"), "{err}");
    let tex = GOOD.replace(
        "[materials.m]\ncolor = 1",
        "[textures.t]\ntype = \"image\"\nfile = \"missing.jpg\"\n[materials.m]\ntexture = \"t\"",
    );
    let scene = write_scene(&dir, "tex.toml", &tex);
    let err = stderr(&expect(&["render", &scene], &dir, 2));
    assert!(
        err.contains("tex.toml:8:8")
            && err.contains("missing.jpg")
            && err.contains("cannot load texture"),
        "{err}"
    );
    // A file that is not an image.
    std::fs::write(dir.join("missing.jpg"), "not a picture").unwrap();
    let err = stderr(&expect(&["render", &scene], &dir, 2));
    assert!(err.contains("cannot decode image"), "{err}");
}

#[test]
fn unwritable_output_exits_1_and_keeps_the_old_image() {
    let dir = scratch("unwritable");
    let scene = write_scene(&dir, "s.toml", GOOD);
    let err = stderr(&expect(
        &["render", &scene, "-o", "no/such/folder/x.png"],
        &dir,
        1,
    ));
    assert!(err.contains("cannot write no/such/folder/x.png"), "{err}");
    // A failed run (here: a bad scene) never touches an existing image.
    std::fs::write(dir.join("keep.png"), b"old bytes").unwrap();
    let broken = write_scene(&dir, "broken.toml", "[camera\n");
    expect(&["render", &broken, "-o", "keep.png"], &dir, 2);
    assert_eq!(std::fs::read(dir.join("keep.png")).unwrap(), b"old bytes");
    // A folder in the way is refused before rendering (the render's progress would be
    // written first), and no temporary file is left.
    std::fs::create_dir(dir.join("taken.png")).unwrap();
    let err = stderr(&expect(
        &["render", &scene, "-o", "taken.png", "--stats"],
        &dir,
        1,
    ));
    assert!(
        err.contains("cannot write taken.png: it is a folder"),
        "{err}"
    );
    let err = stderr(&expect(
        &["render", &scene, "-o", "no/such/folder/x.png"],
        &dir,
        1,
    ));
    assert!(
        err.contains("the folder no/such/folder does not exist"),
        "{err}"
    );
    let tmp = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .any(|e| e.file_name().to_string_lossy().ends_with(".tmp"));
    assert!(!tmp, "temporary file left behind");
}

#[test]
fn schema_prints_the_scene_format_as_json() {
    let dir = scratch("schema");
    let o = expect(&["schema"], &dir, 0);
    let printed: serde_json::Value =
        serde_json::from_str(&stdout(&o)).expect("`snell schema` prints JSON");
    assert_eq!(printed, snell::scene::schema());
    assert_eq!(printed["title"], "snell scene");
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
}

/// Regression: CI's checkout sat in a longer folder than the developer's, and miette wrapped
/// the texture-limit message in the middle of `--max-texture-pixels`, so a test looking for
/// the flag failed there only. Piped output is never wrapped, whatever the path's length.
#[test]
fn piped_messages_stay_on_one_line_however_long_the_path() {
    let long = "a-folder-name-long-enough-to-push-a-message-past-two-hundred-columns-".repeat(3);
    let dir = scratch("long-path").join(long);
    std::fs::create_dir_all(&dir).unwrap();
    let text = GOOD.replace(
        "[materials.m]\ncolor = 1",
        "[textures.t]\ntype = \"image\"\nfile = \"missing.png\"\n[materials.m]\ntexture = \"t\"",
    );
    let scene = write_scene(&dir, "s.toml", &text);
    let o = expect(&["check", &scene], &dir, 2);
    let err = stderr(&o);
    let missing = dir.join("missing.png").display().to_string();
    assert!(
        err.lines()
            .any(|l| l.contains(&format!("cannot read {missing}: ")) && l.contains("os error")),
        "{err}"
    );
}
