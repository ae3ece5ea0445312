//! The ray explainer: the tree behind a pixel of the seed scene's diamond must show the ray
//! entering, bending by Snell's law, leaving by the far side and reaching the floor, with the
//! same colour the renderer computes; its JSON must parse; big trees are cut and say so.

use super::repo;
use snell::integrator::explain::{RayKind, RayNode, TreeRecorder};
use snell::integrator::{Integrator, RayStats, Whitted};
use snell::math::Vec3A;
use snell::scene::load;
use std::process::Command;

fn v(a: [f32; 3]) -> Vec3A {
    Vec3A::from_array(a)
}

/// The tree behind the centre of pixel (512, 760) of the seed scene: a diamond pixel.
fn diamond_tree(max_rays: usize) -> (RayNode, snell::math::Color) {
    let scene = load(&repo("scenes/seed.toml")).unwrap();
    let s = &scene.settings;
    let ray = scene.camera.ray(512.5, 760.5, s.width, s.height);
    let mut rec = TreeRecorder::new(max_rays);
    let c = Whitted.explain(&scene, &ray, &mut RayStats::default(), &mut rec);
    // Recording changes nothing.
    let plain = Whitted.radiance(&scene, &ray, &mut RayStats::default());
    assert_eq!(c, plain, "explaining changed the colour");
    (rec.finish().unwrap(), c)
}

/// sin of the angle between a unit direction and a unit normal's line.
fn sin_to(d: Vec3A, n: Vec3A) -> f32 {
    d.cross(n).length()
}

#[test]
fn a_diamond_pixel_shows_snells_law_and_the_way_out() {
    let (root, colour) = diamond_tree(1000);
    assert_eq!(root.kind, RayKind::Camera);
    let hit = root.hit.as_ref().unwrap();
    assert_eq!(hit.object, "diamond sphere");
    assert_eq!(hit.side, "outside");
    // The ray enters: Snell's law between the camera ray and the refracted one.
    let f = root.fresnel.as_ref().unwrap();
    assert!((f.eta - 1.0 / 2.42).abs() < 1e-6);
    let inside = root
        .children
        .iter()
        .find(|c| c.kind == RayKind::Refraction)
        .expect("a refracted ray");
    let n = v(hit.normal);
    let (sin_i, sin_t) = (sin_to(v(root.direction), n), sin_to(v(inside.direction), n));
    assert!((sin_i - f.sin_i).abs() < 1e-5, "{sin_i} vs {}", f.sin_i);
    assert!(
        (sin_t - sin_i / 2.42).abs() < 1e-5,
        "Snell: sin t = {sin_t}, sin i / 2.42 = {}",
        sin_i / 2.42
    );
    assert!((f.sin_t.unwrap() - sin_t).abs() < 1e-5);
    // Its weight is the transmitted part of the Fresnel split.
    assert!((inside.weight[0] - (1.0 - f.reflectance)).abs() < 1e-6);
    // Inside, it meets the far side of the same sphere, from inside, and leaves.
    let far = inside.hit.as_ref().unwrap();
    assert_eq!(
        (far.object.as_str(), far.side),
        ("diamond sphere", "inside")
    );
    let chord = (v(far.point) - v(hit.point)).length();
    assert!(
        (chord - far.t).abs() < 1e-3,
        "t along a unit ray is the distance"
    );
    let out = inside
        .children
        .iter()
        .find(|c| c.kind == RayKind::Refraction)
        .expect("a ray leaving the diamond");
    let floor = out.hit.as_ref().expect("the leaving ray hits something");
    assert_eq!(floor.object, "floor");
    assert!(
        (floor.point[1] + 15.0).abs() < 1e-3,
        "the floor is at y = -15"
    );
    // Leaving, Snell's law the other way: sin t = 2.42 sin i.
    let fo = inside.fresnel.as_ref().unwrap();
    let no = v(far.normal);
    let (si, st) = (
        sin_to(v(inside.direction), no),
        sin_to(v(out.direction), no),
    );
    assert!((st - 2.42 * si).abs() < 1e-4, "{st} vs {}", 2.42 * si);
    assert!((fo.eta - 2.42).abs() < 1e-6);
    // The root returns the sample's colour.
    assert_eq!(root.color, colour.to_array());
}

#[test]
fn big_trees_are_cut_and_say_so() {
    let (root, _) = diamond_tree(3);
    fn count(n: &RayNode) -> usize {
        1 + n.children.iter().map(count).sum::<usize>()
    }
    assert_eq!(count(&root), 3);
    assert!(
        root.notes
            .iter()
            .any(|n| n.contains("the tree was cut at 3 rays")),
        "{:?}",
        root.notes
    );
}

#[test]
fn the_command_prints_the_tree_and_its_json_parses() {
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_snell"))
            .args(args)
            .current_dir(repo(""))
            .output()
            .unwrap()
    };
    let text = run(&["explain", "scenes/seed.toml", "--pixel", "512,760"]);
    assert_eq!(text.status.code(), Some(0));
    let out = String::from_utf8_lossy(&text.stdout);
    for needle in [
        "camera ray (depth 1)",
        "hits \"diamond sphere\"",
        "from the outside",
        "from the inside",
        "sin t = eta sin i",
        "hits \"floor\"",
        "shadow ray",
    ] {
        assert!(out.contains(needle), "missing `{needle}` in\n{out}");
    }
    let json = run(&[
        "explain",
        "scenes/seed.toml",
        "--pixel",
        "512,760",
        "--sample",
        "3",
        "--spp",
        "16",
        "--json",
    ]);
    assert_eq!(json.status.code(), Some(0));
    let doc: serde_json::Value = serde_json::from_slice(&json.stdout).expect("valid JSON");
    assert_eq!(doc["pixel"], serde_json::json!([512, 760]));
    assert_eq!(doc["tree"]["kind"], "camera");
    assert!(doc["tree"]["children"].is_array());
    // Output cut short (| head) is no reason to panic.
    let mut child = Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["explain", "scenes/seed.toml", "--pixel", "512,760"])
        .current_dir(repo(""))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let done = child.wait_with_output().unwrap();
    assert!(!String::from_utf8_lossy(&done.stderr).contains("panicked"));
    for bad in [
        &["explain", "scenes/seed.toml", "--pixel", "1024,0"][..],
        &["explain", "scenes/seed.toml", "--pixel", "12"],
        &[
            "explain",
            "scenes/seed.toml",
            "--pixel",
            "1,1",
            "--sample",
            "1",
            "--spp",
            "1",
        ],
    ] {
        let o = run(bad);
        assert_eq!(o.status.code(), Some(2), "{bad:?}");
        assert!(!String::from_utf8_lossy(&o.stderr).contains("panicked"));
    }
}

#[test]
fn a_sample_past_the_last_is_told_the_range_in_words() {
    let err = |spp: &str, k: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_snell"))
            .current_dir(repo(""))
            .args([
                "explain",
                "scenes/seed.toml",
                "--pixel",
                "10,10",
                "--spp",
                spp,
                "--sample",
                k,
            ])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let one = err("1", "3");
    assert!(
        one.contains("sample 3 does not exist: the pixel has 1 sample\n")
            && one.contains("use --sample 0 (its only one), or more samples with --spp"),
        "{one}"
    );
    let four = err("4", "4");
    assert!(
        four.contains("the pixel has 4 samples") && four.contains("use --sample 0 to 3,"),
        "{four}"
    );
}

/// Under the path tracer `explain` follows the one path of a sample: every vertex's
/// contributions add up to the sample's value, which is what the renderer gives that pixel
/// at one sample per pixel (the same sample 0, to the bit), and recording changes nothing.
#[test]
fn a_path_tracers_sample_is_explained_and_adds_up() {
    use snell::integrator::Path;
    use snell::integrator::path_explain::{PathEnd, PathRecord};
    let dir = super::scratch("explain-path");
    let scene_path = repo("scenes/cornell.toml");
    let mut scene = load(&scene_path).unwrap();
    (
        scene.settings.width,
        scene.settings.height,
        scene.settings.spp,
    ) = (64, 64, 1);
    let img = snell::render::render(&scene, &Path, Some(1), &|_| {})
        .unwrap()
        .image;
    let mut bounced = 0;
    let mut lit = 0;
    for (x, y) in [
        (32u32, 40u32),
        (20, 50),
        (45, 30),
        (10, 10),
        (32, 5),
        (50, 55),
    ] {
        let s = &scene.settings;
        let mut sampler = snell::sampler::Sampler::new(s.integrator.sampler, s.seed);
        let (px, py, _) = snell::render::start_sample(s, &mut sampler, x, y, 0);
        let ray = scene.camera.ray(px, py, s.width, s.height);
        let mut again = sampler.clone();
        let mut rec = PathRecord::default();
        let c = Path.trace(
            &scene,
            &ray,
            &mut sampler,
            &mut RayStats::default(),
            &mut rec,
        );
        let plain = Path.radiance(&scene, &ray, &mut again, &mut RayStats::default());
        assert_eq!(c, plain, "recording changed the value at ({x}, {y})");
        assert_eq!(c, img.pixels[(y * 64 + x) as usize], "pixel ({x}, {y})");
        let total = rec.total();
        for ch in 0..3 {
            let want = c.to_array()[ch];
            assert!(
                (total[ch] - want).abs() <= 1e-5 * want.max(1.0),
                "({x}, {y}): the vertices add {total:?}, the sample is {c}"
            );
        }
        assert!(rec.end.is_some(), "({x}, {y}): the path's end is said");
        bounced += rec.vertices.iter().filter(|v| v.bounce.is_some()).count();
        lit += rec
            .vertices
            .iter()
            .filter(|v| v.light.as_ref().is_some_and(|l| l.blocked.is_none()))
            .count();
        if let Some(PathEnd::Escaped { contribution }) = rec.end {
            assert_eq!(contribution, [0.0; 3], "the box's outside is black");
        }
    }
    assert!(
        bounced > 6 && lit > 3,
        "{bounced} bounces, {lit} lit light samples"
    );
    // The command line prints the same path, as text and as JSON.
    let run = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_snell"))
            .args(args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout).unwrap()
    };
    let file = scene_path.to_str().unwrap();
    let flags = [
        "--width", "64", "--height", "64", "--spp", "1", "--pixel", "32,40",
    ];
    let text = run(&[&["explain", file][..], &flags].concat());
    for word in [
        "vertex 0",
        "light sample",
        "MIS weight",
        "bounce",
        "the sample's value",
    ] {
        assert!(text.contains(word), "{word}: {text}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&run(&[&["explain", file, "--json"][..], &flags].concat())).unwrap();
    let color = &json["color"];
    assert_eq!(
        color[0].as_f64().unwrap() as f32,
        img.pixels[40 * 64 + 32].x,
        "{json}"
    );
    assert!(
        json["path"]["vertices"][0]["light"]["mis_weight"].is_number(),
        "{json}"
    );
}

/// docs/debugging.md's explain examples are what `snell explain` prints: each line of a
/// block under `$ snell explain ...` (cut short with ` ...` where the page shortens it, or
/// with `...` standing for what it leaves out) is a line of the command's output, in order.
#[test]
fn the_debugging_guides_examples_are_what_explain_prints() {
    let page = std::fs::read_to_string(repo("docs/debugging.md")).unwrap();
    let (mut commands, mut lines) = (0, 0);
    for block in page.split("```text\n").skip(1) {
        let block = block.split("```").next().unwrap();
        let mut rest = block.lines().peekable();
        while let Some(line) = rest.next() {
            let Some(args) = line.strip_prefix("$ snell explain ") else {
                continue;
            };
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
                .arg("explain")
                .args(args.split_whitespace())
                .current_dir(repo(""))
                .output()
                .unwrap();
            assert!(out.status.success(), "{line}");
            let printed = String::from_utf8(out.stdout).unwrap();
            let mut printed = printed.lines();
            commands += 1;
            while let Some(expected) = rest.next_if(|l| !l.starts_with("$ ")) {
                // `...` stands for what the page leaves out of a line.
                let parts: Vec<&str> = expected
                    .trim_end_matches(" ...")
                    .split("...")
                    .map(str::trim_end)
                    .collect();
                let fits = |l: &str| {
                    let mut at = 0;
                    parts.iter().enumerate().all(|(i, p)| {
                        let p = if i > 0 { p.trim_start() } else { p };
                        match l[at..].find(p) {
                            Some(j) if i > 0 || j == 0 => {
                                at += j + p.len();
                                true
                            }
                            _ => false,
                        }
                    })
                };
                assert!(
                    printed.any(fits),
                    "docs/debugging.md: `{expected}` is not printed by `snell explain {args}` (in order)"
                );
                lines += 1;
            }
        }
    }
    assert!(
        commands >= 5 && lines >= 15,
        "{commands} commands, {lines} lines checked"
    );
}
