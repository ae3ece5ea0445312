//! `snell render`'s flags and what it tells: the warning before a long render, the integrator
//! chosen by flag or scene, exposure and tone curve, `--time`, messages about values, and the
//! checkpoint removed at the end.

use super::*;

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
        (
            &["--integrator", "pathh"],
            "use whitted, path, light or bdpt",
        ),
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

/// `--integrator light` and `bdpt`: the Cornell box to an EXR whose mean is the path
/// tracer's within a few percent; the flags they do not take yet refused with exit 2 and no
/// picture; `explain` on a light-traced scene shows the path tracer's path and says so.
#[test]
fn light_tracing_renders_and_refuses_what_it_cannot_do() {
    let dir = scratch("cli-light");
    let scene = repo("scenes/cornell.toml");
    let scene = scene.to_str().unwrap();
    let small = ["--width", "16", "--height", "16", "--spp", "256", "-q"];
    let mut means = vec![];
    for (integrator, out) in [("light", "l.exr"), ("bdpt", "b.exr"), ("path", "p.exr")] {
        expect(
            &[
                &["render", scene, "-o", out, "--integrator", integrator][..],
                &small,
            ]
            .concat(),
            &dir,
            0,
        );
        let img = snell::texture::ImageData::load(&dir.join(out), snell::texture::ColorSpace::Srgb)
            .unwrap();
        let mut sum = 0.0f32;
        for y in 0..16 {
            for x in 0..16 {
                sum += img.texel(x, y).element_sum();
            }
        }
        means.push(sum / 256.0);
    }
    for (k, integrator) in ["light", "bdpt"].iter().enumerate() {
        assert!(
            (means[k] - means[2]).abs() < 0.03 * means[2],
            "{integrator} {} against path {}",
            means[k],
            means[2]
        );
    }
    // A clamp, the path tracer's: `--clamp` is refused under light tracing and bdpt, which
    // never clamp; a path-traced scene's own clamp is not used, and a warning says so.
    let clamped = dir.join("clamped.toml");
    std::fs::write(
        &clamped,
        std::fs::read_to_string(scene)
            .unwrap()
            .replace("[integrator]", "[integrator]\nclamp = 4"),
    )
    .unwrap();
    assert!(
        std::fs::read_to_string(&clamped)
            .unwrap()
            .contains("clamp = 4")
    );
    let mut clamps = 0;
    for (integrator, name) in [("light", "light tracing"), ("bdpt", "bdpt")] {
        let o = expect(
            &[
                &["render", scene, "-o", "c.png", "--integrator", integrator][..],
                &["--clamp", "4"],
                &small,
            ]
            .concat(),
            &dir,
            2,
        );
        assert!(
            stderr(&o).contains(&format!(
                "--clamp is the path tracer's: {name} does not clamp"
            )),
            "{}",
            stderr(&o)
        );
        let o = expect(
            &[
                "render",
                clamped.to_str().unwrap(),
                "-o",
                "c.png",
                "--integrator",
                integrator,
            ]
            .iter()
            .chain(&small[..small.len() - 1])
            .copied()
            .collect::<Vec<_>>(),
            &dir,
            0,
        );
        assert!(
            stderr(&o).contains(&format!(
                "warning: the scene's `clamp` is the path tracer's: {name} does not clamp"
            )),
            "{}",
            stderr(&o)
        );
        clamps += 1;
    }
    assert_eq!(clamps, 2);
    // A region (whose pixels take light from every pixel's paths), and bdpt's strategy
    // images with a checkpoint (which does not keep them), are refused.
    let mut refused = 0;
    for (integrator, flags, says) in [
        (
            "light",
            &["--region", "0,0,8,8"][..],
            "light tracing cannot be combined with --region",
        ),
        (
            "bdpt",
            &["--region", "0,0,8,8"],
            "bdpt cannot be combined with --region",
        ),
        (
            "bdpt",
            &["--aov", "strategies", "--checkpoint", "c.ckpt"],
            "the strategy images cannot be combined with --checkpoint",
        ),
    ] {
        let o = expect(
            &[
                &["render", scene, "-o", "x.png", "--integrator", integrator][..],
                flags,
                &small,
            ]
            .concat(),
            &dir,
            2,
        );
        assert!(stderr(&o).contains(says), "{}", stderr(&o));
        assert!(!dir.join("x.png").exists() && !dir.join("c.ckpt").exists());
        refused += 1;
    }
    assert_eq!(refused, 3);
    // bdpt's strategy images: one file each beside a PNG; refused by another integrator.
    expect(
        &[
            &[
                "render",
                scene,
                "-o",
                "s.png",
                "--integrator",
                "bdpt",
                "--aov",
                "strategies",
            ][..],
            &small,
        ]
        .concat(),
        &dir,
        0,
    );
    for name in [
        "s.png",
        "s.s0-t2.png",
        "s.s1-t2.png",
        "s.s2-t1-unweighted.png",
    ] {
        assert!(dir.join(name).exists(), "{name}");
    }
    let o = expect(
        &[
            &[
                "render",
                scene,
                "-o",
                "t.png",
                "--integrator",
                "path",
                "--aov",
                "strategies",
            ][..],
            &small,
        ]
        .concat(),
        &dir,
        2,
    );
    assert!(
        stderr(&o).contains("the strategy images are bidirectional path tracing's"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("t.png").exists());
    let o = expect(
        &[
            "explain",
            scene,
            "--pixel",
            "8,8",
            "--integrator",
            "light",
            "--width",
            "16",
            "--height",
            "16",
        ],
        &dir,
        0,
    );
    assert!(
        stdout(&o).contains("light tracing traces no camera paths"),
        "{}",
        stdout(&o)
    );
    assert!(
        stdout(&o).contains("path-traced sample 0"),
        "{}",
        stdout(&o)
    );
    // `explain --json` of pixel (8, 8) under an integrator.
    let json = |integrator: &str| -> serde_json::Value {
        let args = [
            "explain",
            scene,
            "--integrator",
            integrator,
            "--json",
            "--pixel",
            "8,8",
            "--width",
            "16",
            "--height",
            "16",
        ];
        serde_json::from_str(&stdout(&expect(&args, &dir, 0))).unwrap()
    };
    let doc = json("light");
    assert_eq!(doc["integrator"], "path");
    assert!(
        doc["note"]
            .as_str()
            .unwrap()
            .starts_with("light tracing traces no camera paths"),
        "{doc}"
    );
    // Under bdpt: the sample's two subpaths, vertex by vertex, from the eye and from the
    // light, in words and in the JSON.
    let o = expect(
        &[
            "explain",
            scene,
            "--integrator",
            "bdpt",
            "--pixel",
            "8,8",
            "--width",
            "16",
            "--height",
            "16",
        ],
        &dir,
        0,
    );
    let text = stdout(&o);
    assert!(text.contains("  the eye's: the eye -> `"), "{text}");
    assert!(
        text.contains("  the light's: area light on `light`"),
        "{text}"
    );
    let doc = json("bdpt");
    let (eye, light) = (
        doc["camera_path"].as_array().unwrap(),
        doc["light_path"].as_array().unwrap(),
    );
    assert_eq!(eye.len() as u64, doc["camera_vertices"].as_u64().unwrap());
    assert_eq!(light.len() as u64, doc["light_vertices"].as_u64().unwrap());
    assert_eq!(eye[0]["what"], "the eye");
    // The eye at the camera's position, (0, 0, 3.9) in single precision.
    assert_eq!(
        eye[0]["point"],
        serde_json::json!([0.0, 0.0, 3.9f32 as f64])
    );
    assert_eq!(light[0]["what"], "area light on `light`");
    // The light's first vertex lies on the light: the rectangle at y = 0.99.
    let y = light[0]["point"][1].as_f64().unwrap();
    assert!((y - 0.99).abs() < 1e-4, "{doc}");
}
