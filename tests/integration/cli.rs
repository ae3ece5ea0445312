//! The command line: exit codes (0 done, 1 render or write failed, 2 bad command line or
//! scene), messages that point at the file, line and column, and outputs that are never
//! left broken.

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

fn write_scene(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

const GOOD: &str = "[image]\nwidth = 8\nheight = 6\n[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = 1\n[[lights]]\ntype = \"point\"\nposition = [0, 5, 0]\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -3]\nradius = 1\nmaterial = \"m\"\n";

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
fn check_counts_each_meshs_triangles_loaded_and_placed() {
    let dir = scratch("check-meshes");
    let field = repo("scenes/field.toml").to_string_lossy().into_owned();
    let out = stdout(&expect(&["check", &field], &dir, 0));
    assert!(
        out.contains("meshes:    2 (75771 triangles loaded, 1212336 placed)")
            && out.contains(
                "stanford-bunny.obj: 69451 triangles, placed 16 times (1111216 triangles)"
            )
            && out.contains("teapot.obj: 6320 triangles, placed 16 times (101120 triangles)"),
        "{out}"
    );
    // A scene without meshes says nothing of them.
    let scene = write_scene(&dir, "s.toml", GOOD);
    assert!(!stdout(&expect(&["check", &scene], &dir, 0)).contains("meshes:"));
}

/// `check` names the environment a scene is lit by (its image, colour or sun) and the share
/// of light samples it gets, and counts emitting objects among the lights.
#[test]
fn check_names_the_environment_and_the_area_lights() {
    let dir = scratch("check-env");
    let hdr = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/env/studio.hdr");
    let only_env = GOOD.replace(
        "[[lights]]\ntype = \"point\"\nposition = [0, 5, 0]\n",
        &format!(
            "[environment]\ntype = \"image\"\nfile = {:?}\n",
            hdr.display().to_string()
        ),
    );
    let out = stdout(&expect(
        &["check", &write_scene(&dir, "e.toml", &only_env)],
        &dir,
        0,
    ));
    assert!(out.contains("lights:    none\n"), "{out}");
    assert!(
        out.contains(&format!(
            "environment: image {}, 512 x 256; 100 % of light samples",
            hdr.display()
        )),
        "{out}"
    );
    let mixed = GOOD.to_string()
        + "[environment]\ntype = \"constant\"\ncolor = 0.5\n\
           [materials.lamp]\ncolor = 0\nemission = 4\n\
           [[objects]]\ntype = \"sphere\"\ncenter = [0, 3, -3]\nradius = 0.5\nmaterial = \"lamp\"\n";
    let out = stdout(&expect(
        &["check", &write_scene(&dir, "m.toml", &mixed)],
        &dir,
        0,
    ));
    assert!(out.contains("lights:    2 (1 area, 1 point)\n"), "{out}");
    assert!(
        out.contains("environment: constant [0.5, 0.5, 0.5]; "),
        "{out}"
    );
    let sky = GOOD.to_string() + "[environment]\ntype = \"sky\"\nsun_elevation = 30\n";
    let out = stdout(&expect(
        &["check", &write_scene(&dir, "s.toml", &sky)],
        &dir,
        0,
    ));
    assert!(
        out.contains("environment: sky, the sun 30.0° above the horizon; "),
        "{out}"
    );
}

#[test]
fn check_prints_a_summary_and_warnings() {
    let dir = scratch("check");
    let inside = GOOD.replace("position = [0, 5, 0]", "position = [0, 0, -3]")
        + "[materials.unused]\ncolor = 0.5\n";
    let scene = write_scene(&dir, "w.toml", &inside);
    let o = expect(&["check", &scene], &dir, 0);
    let out = stdout(&o);
    assert!(
        out.contains("objects:   1 (1 sphere)") && out.contains("lights:    1 (1 point)"),
        "{out}"
    );
    assert!(
        out.contains("warning: light 0") && out.contains("inside object `sphere #0`"),
        "{out}"
    );
    assert!(
        out.contains("warning: material `unused` is defined but no object uses it"),
        "{out}"
    );
    let seed = repo("scenes/seed.toml");
    let out = stdout(&expect(&["check", seed.to_str().unwrap()], &dir, 0));
    assert!(
        out.contains("objects:   8") && out.contains("textures:  2 (checkerboard, earth)"),
        "{out}"
    );
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

/// A render that will plainly take very long says so, with an estimate, before it starts.
/// (The process is killed once it has said it: the render itself would take weeks.)
#[test]
fn a_render_of_days_is_told_so_before_it_starts() {
    use std::io::BufRead;
    let dir = scratch("long-render");
    let seed = repo("scenes/seed.toml");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["render", seed.to_str().unwrap(), "-o", "huge.png"])
        .args(["--width", "16384", "--height", "16384", "--spp", "65536"])
        .current_dir(&dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut said = String::new();
    let mut lines = std::io::BufReader::new(child.stderr.take().unwrap()).lines();
    for line in lines.by_ref().take(2) {
        said += &line.unwrap();
        said.push('\n');
    }
    let _ = child.kill();
    let _ = child.wait();
    assert!(
        said.starts_with("warning: this render will take about ")
            && said.contains("(16384 x 16384 at 65536 spp, about ")
            && said.contains("help: fewer samples (--spp) or a smaller image"),
        "{said}"
    );
    let estimate = said["warning: this render will take about ".len()..]
        .split(" on ")
        .next()
        .unwrap();
    assert!(
        ["hours", "days", "years"]
            .iter()
            .any(|u| estimate.ends_with(u)),
        "{estimate}"
    );
    // A quick render says nothing of its time.
    let scene = write_scene(&dir, "s.toml", GOOD);
    assert!(!stderr(&expect(&["render", &scene, "--spp", "64"], &dir, 0)).contains("will take"));
    // Neither does a path-traced render of hours cut to a second by --time.
    let o = expect(
        &[
            "render",
            &scene,
            "-o",
            "capped.png",
            "--integrator",
            "path",
            "--width",
            "1024",
            "--height",
            "1024",
            "--spp",
            "65536",
            "--time",
            "1s",
        ],
        &dir,
        0,
    );
    assert!(!stderr(&o).contains("will take"), "{}", stderr(&o));
}

/// `--integrator`, `--sampler` and `--clamp`: the path tracer renders any sample count,
/// bad names and values are told what to give, and `explain` follows a path.
#[test]
fn integrator_flags_choose_the_path_tracer_and_refuse_bad_values() {
    let dir = scratch("integrator-flags");
    let scene = write_scene(&dir, "s.toml", GOOD);
    // Five samples: not a square, which only the path tracer takes.
    let o = expect(
        &[
            "render",
            &scene,
            "--integrator",
            "path",
            "--spp",
            "5",
            "--sampler",
            "independent",
            "--clamp",
            "4",
            "-o",
            "p.png",
        ],
        &dir,
        0,
    );
    assert!(stdout(&o).contains("5 spp"), "{}", stdout(&o));
    assert!(dir.join("p.png").exists());
    let o = expect(&["render", &scene, "--spp", "5", "-o", "w.png"], &dir, 2);
    assert!(stderr(&o).contains("square"), "{}", stderr(&o));
    let cases: [(&[&str], &str); 4] = [
        (&["--integrator", "pathh"], "use whitted or path"),
        (&["--sampler", "halton"], "use sobol or independent"),
        (&["--clamp", "-1"], "positive number"),
        (&["--clamp", "inf"], "positive number"),
    ];
    for (flags, message) in cases {
        let mut args = vec!["render", scene.as_str(), "-o", "x.png"];
        args.extend_from_slice(flags);
        let o = expect(&args, &dir, 2);
        assert!(stderr(&o).contains(message), "{flags:?}: {}", stderr(&o));
    }
    assert!(!dir.join("x.png").exists());
    let o = expect(
        &["explain", &scene, "--pixel", "3,3", "--integrator", "path"],
        &dir,
        0,
    );
    assert!(
        stdout(&o).contains("path-traced sample 0"),
        "{}",
        stdout(&o)
    );
}

/// `[integrator] type = "path"` in the file chooses the path tracer (an emitting rectangle
/// lights the scene, which Whitted would only show as a glowing patch), and a bad value in
/// the table is reported at its line.
#[test]
fn the_scene_file_chooses_the_integrator() {
    let dir = scratch("integrator-table");
    let bad = write_scene(
        &dir,
        "bad.toml",
        "[integrator]\ntype = \"path\"\nsampler = \"halton\"\n[camera]\nlook_at = [0, 0, -1]\n",
    );
    let o = expect(&["render", &bad, "-o", "b.png"], &dir, 2);
    assert!(stderr(&o).contains("bad.toml:3"), "{}", stderr(&o));
    let cornell = repo("scenes/cornell.toml");
    let o = expect(
        &[
            "render",
            cornell.to_str().unwrap(),
            "--width",
            "16",
            "--height",
            "16",
            "--spp",
            "3",
            "-o",
            "c.exr",
        ],
        &dir,
        0,
    );
    assert!(stdout(&o).contains("3 spp"), "{}", stdout(&o));
}

/// `--exposure` and `--tonemap` (and the scene's `[image] exposure` and `tonemap`) change a
/// PNG and leave an EXR linear; bad values are told what they should be.
#[test]
fn exposure_and_tone_curve_shape_the_png_only() {
    let dir = scratch("tone");
    let scene = write_scene(
        &dir,
        "s.toml",
        "[image]\nwidth = 24\nheight = 16\n[camera]\nlook_at = [0, 0, -1]\n\
         [materials.m]\ncolor = [0.9, 0.6, 0.3]\n[[lights]]\ntype = \"point\"\nposition = [3, 3, 0]\nintensity = 3\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -3]\nradius = 1\nmaterial = \"m\"\n",
    );
    let png = |args: &[&str], name: &str| {
        expect(
            &[&["render", scene.as_str(), "-o", name, "-q"], args].concat(),
            &dir,
            0,
        );
        image::open(dir.join(name)).unwrap().to_rgb8()
    };
    let sum = |i: &image::RgbImage| i.pixels().map(|p| p.0[2] as u64).sum::<u64>();
    let plain = png(&[], "plain.png");
    let bright = png(&["--exposure", "1"], "bright.png");
    let dark = png(&["--exposure", "-1.5"], "dark.png");
    assert!(sum(&bright) > sum(&plain) && sum(&dark) < sum(&plain));
    // A curve brings the clipped highlight back below white.
    let clipped = |i: &image::RgbImage| i.pixels().filter(|p| p.0[0] == 255).count();
    assert!(clipped(&plain) > 0, "the light is bright enough to clip");
    for curve in ["reinhard", "aces"] {
        assert_eq!(clipped(&png(&["--tonemap", curve], "c.png")), 0, "{curve}");
    }
    // The scene's own keys do the same as the flags; the flags win.
    let keyed = write_scene(
        &dir,
        "k.toml",
        &std::fs::read_to_string(&scene).unwrap().replace(
            "height = 16\n",
            "height = 16\nexposure = 1\ntonemap = \"clamp\"\n",
        ),
    );
    expect(&["render", keyed.as_str(), "-o", "k.png", "-q"], &dir, 0);
    assert_eq!(image::open(dir.join("k.png")).unwrap().to_rgb8(), bright);
    expect(
        &[
            "render",
            keyed.as_str(),
            "-o",
            "k0.png",
            "-q",
            "--exposure",
            "0",
        ],
        &dir,
        0,
    );
    assert_eq!(image::open(dir.join("k0.png")).unwrap().to_rgb8(), plain);
    // An EXR is linear, whatever the exposure.
    expect(&["render", scene.as_str(), "-o", "a.exr", "-q"], &dir, 0);
    expect(
        &[
            "render",
            scene.as_str(),
            "-o",
            "b.exr",
            "-q",
            "--exposure",
            "3",
            "--tonemap",
            "aces",
        ],
        &dir,
        0,
    );
    assert_eq!(
        std::fs::read(dir.join("a.exr")).unwrap(),
        std::fs::read(dir.join("b.exr")).unwrap()
    );
    // Bad values.
    let o = expect(&["render", scene.as_str(), "--exposure", "99"], &dir, 2);
    assert!(stderr(&o).contains("not an exposure"), "{}", stderr(&o));
    let o = expect(&["render", scene.as_str(), "--tonemap", "filmic"], &dir, 2);
    assert!(
        stderr(&o).contains("use clamp, reinhard or aces"),
        "{}",
        stderr(&o)
    );
    for (keys, at, says) in [
        ("exposure = 40\n", "bad.toml:4:12", "between -20 and 20"),
        ("tonemap = \"sepia\"\n", "bad.toml:4:11", "sepia"),
    ] {
        let text = std::fs::read_to_string(&scene)
            .unwrap()
            .replace("height = 16\n", &format!("height = 16\n{keys}"));
        let bad = write_scene(&dir, "bad.toml", &text);
        let o = expect(&["check", bad.as_str()], &dir, 2);
        assert!(
            stderr(&o).contains(at) && stderr(&o).contains(says),
            "{}",
            stderr(&o)
        );
    }
}

/// `--time` stops the path tracer's passes once the time is spent (here, short of 65536
/// samples per pixel): the picture is written whole, as a render of the samples it reached
/// (the same bytes as `--spp` of that many), and the message says so. A bad time is told
/// what a time is; Whitted, which takes all its samples at once, is warned.
#[test]
fn time_stops_the_passes_and_writes_the_picture() {
    let dir = scratch("time");
    let scene = write_scene(
        &dir,
        "s.toml",
        "[image]\nwidth = 32\nheight = 24\n[integrator]\ntype = \"path\"\n\
         [camera]\nposition = [0, 1, 4]\nlook_at = [0, 0, 0]\n\
         [environment]\ntype = \"constant\"\ncolor = 0.8\n\
         [materials.m]\ncolor = [0.9, 0.6, 0.3]\n\
         [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n",
    );
    let o = expect(
        &[
            "render", &scene, "-o", "t.exr", "--spp", "65536", "--time", "0.2s",
        ],
        &dir,
        0,
    );
    let out = stdout(&o);
    assert!(out.contains("(--time stopped it short of 65536)"), "{out}");
    let spp: u32 = out
        .split(" spp")
        .next()
        .and_then(|s| s.rsplit(", ").next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no spp in {out}"));
    assert!((1..65536).contains(&spp), "{out}");
    expect(
        &[
            "render",
            &scene,
            "-o",
            "n.exr",
            "--spp",
            &spp.to_string(),
            "-q",
        ],
        &dir,
        0,
    );
    assert_eq!(
        std::fs::read(dir.join("t.exr")).unwrap(),
        std::fs::read(dir.join("n.exr")).unwrap()
    );
    for bad in ["abc", "-3s", "0", "5 parsecs", "1e30h"] {
        let o = expect(&["render", &scene, "--time", bad], &dir, 2);
        assert!(
            stderr(&o).contains("is not a time"),
            "{bad}: {}",
            stderr(&o)
        );
    }
    let o = expect(
        &[
            "render",
            &scene,
            "-o",
            "w.png",
            "--integrator",
            "whitted",
            "--time",
            "1m",
        ],
        &dir,
        0,
    );
    assert!(
        stderr(&o).contains("--time is for the path tracer"),
        "{}",
        stderr(&o)
    );
}

/// Messages that say what is wrong and what to do: a port past 65535 is out of range (not
/// "not a whole number"); a negative width says what a width takes (0 is refused too); an
/// empty file asks for a `[camera]` table, the way TOML writes one; too many samples names
/// --max-spp; Whitted on a scene lit only by its environment or by emitting surfaces says
/// that it lights nothing by them.
#[test]
fn messages_say_what_the_value_takes() {
    let dir = scratch("messages");
    let o = expect(&["serve", "x.toml", "--port", "99999"], &dir, 2);
    assert!(
        stderr(&o).contains("`99999` is too large: give a whole number from 0 to 65535"),
        "{}",
        stderr(&o)
    );
    let o = expect(&["serve", "x.toml", "--port", "-1"], &dir, 2);
    assert!(
        stderr(&o).contains("not a whole number from 0"),
        "{}",
        stderr(&o)
    );
    let o = expect(&["serve", "x.toml", "--port", "eighty"], &dir, 2);
    assert!(stderr(&o).contains("not a whole number"), "{}", stderr(&o));
    let negative = write_scene(&dir, "n.toml", &GOOD.replace("width = 8", "width = -5"));
    let o = expect(&["check", &negative], &dir, 2);
    assert!(
        stderr(&o).contains("`-5` is not allowed here: a whole number from 1 to 65536 pixels"),
        "{}",
        stderr(&o)
    );
    let empty = write_scene(&dir, "e.toml", "");
    let o = expect(&["check", &empty], &dir, 2);
    assert!(
        stderr(&o).contains("add a `[camera]` table"),
        "{}",
        stderr(&o)
    );
    let scene = write_scene(&dir, "s.toml", GOOD);
    let o = expect(
        &["render", &scene, "--spp", "70000", "-o", "x.png"],
        &dir,
        2,
    );
    assert!(stderr(&o).contains("--max-spp"), "{}", stderr(&o));
    let lit_by_env = GOOD.replace(
        "[[lights]]\ntype = \"point\"\nposition = [0, 5, 0]\n",
        "[environment]\ntype = \"constant\"\ncolor = 1\n[integrator]\ntype = \"path\"\n",
    );
    let env = write_scene(&dir, "env.toml", &lit_by_env);
    // The file's path tracer is lit: no warning; Whitted from the command line: one.
    let o = expect(&["render", &env, "-o", "a.png"], &dir, 0);
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    let o = expect(
        &["render", &env, "-o", "b.png", "--integrator", "whitted"],
        &dir,
        0,
    );
    assert!(
        stderr(&o).contains("no lights Whitted uses")
            && stderr(&o).contains("does not light with it")
            && stderr(&o).contains("--integrator path"),
        "{}",
        stderr(&o)
    );
}

/// A render that finishes removes its checkpoint, which has nothing left to continue, and
/// says so (unless quiet).
#[test]
fn a_finished_render_says_it_removed_its_checkpoint() {
    let dir = scratch("checkpoint-removed");
    let scene = write_scene(&dir, "s.toml", GOOD);
    // The path tracer saves after its first pass once the interval is past.
    let every = [
        "--integrator",
        "path",
        "--spp",
        "64",
        "--checkpoint-every",
        "0.000001",
    ];
    let o = expect(
        &[
            &["render", &scene, "-o", "x.png", "--checkpoint", "c.ckpt"][..],
            &every[..],
        ]
        .concat(),
        &dir,
        0,
    );
    assert!(
        stderr(&o).contains("removed the checkpoint c.ckpt: the render is whole"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("c.ckpt").exists());
    let o = expect(
        &[
            &[
                "render",
                &scene,
                "-o",
                "y.png",
                "--checkpoint",
                "d.ckpt",
                "-q",
            ][..],
            &every[..],
        ]
        .concat(),
        &dir,
        0,
    );
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
}
