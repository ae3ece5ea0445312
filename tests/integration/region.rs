//! `snell render --region`: a region's pixels are the same, bit for bit, as that part of
//! the whole render, under both integrators; a PNG holds the region alone, an EXR holds it
//! at its place in the whole image (its data window).

use super::{repo, scratch};
use std::path::Path;
use std::process::{Command, Output};

fn snell(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(args)
        .output()
        .expect("snell runs")
}

/// An EXR's pixels (R, G, B of each, row by row), its size and where its data window
/// starts in the whole image.
fn read_exr(path: &Path) -> (Vec<f32>, (usize, usize), (i32, i32)) {
    use exr::prelude::*;
    let image = read_first_flat_layer_from_file(path).unwrap();
    let layer = image.layer_data;
    let size = (layer.size.0, layer.size.1);
    let at = (
        layer.attributes.layer_position.0,
        layer.attributes.layer_position.1,
    );
    let channel = |name: &str| {
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == *name)
            .unwrap();
        c.sample_data.values_as_f32().collect::<Vec<f32>>()
    };
    let (r, g, b) = (channel("R"), channel("G"), channel("B"));
    let pixels = (0..r.len()).flat_map(|i| [r[i], g[i], b[i]]).collect();
    (pixels, size, at)
}

#[test]
fn a_region_is_the_same_pixels_as_that_part_of_the_whole_render() {
    let dir = scratch("region");
    // The seed scene (Whitted, all samples at once) and the Cornell box (the path tracer
    // in passes), at a size whose region cuts across tiles.
    for (scene, name) in [
        ("scenes/seed.toml", "seed"),
        ("scenes/cornell.toml", "cornell"),
    ] {
        let scene = repo(scene).to_string_lossy().into_owned();
        let size = ["--width", "45", "--height", "37", "--spp", "4", "--quiet"];
        let whole = dir.join(format!("{name}-whole.exr"));
        let part = dir.join(format!("{name}-part.exr"));
        let mut args = vec!["render", &scene, "-o"];
        let w = whole.to_string_lossy().into_owned();
        let p = part.to_string_lossy().into_owned();
        let o = snell(&[&args[..], &[&w], &size].concat());
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        args.push(&p);
        let o = snell(&[&args[..], &size, &["--region", "7,5,30,21"]].concat());
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let (all, (aw, ah), at) = read_exr(&whole);
        assert_eq!(((aw, ah), at), ((45, 37), (0, 0)));
        let (region, size_of, at) = read_exr(&part);
        assert_eq!((size_of, at), ((23, 16), (7, 5)), "{name}");
        for y in 0..16 {
            for x in 0..23 {
                for c in 0..3 {
                    let a = all[((y + 5) * 45 + x + 7) * 3 + c];
                    let b = region[(y * 23 + x) * 3 + c];
                    assert_eq!(
                        a.to_bits(),
                        b.to_bits(),
                        "{name}: pixel ({}, {})",
                        x + 7,
                        y + 5
                    );
                }
            }
        }
        // A PNG holds the region alone: the whole PNG's pixels there.
        let (wp, pp) = (
            dir.join(format!("{name}.png")),
            dir.join(format!("{name}-part.png")),
        );
        let (wp_s, pp_s) = (wp.to_string_lossy(), pp.to_string_lossy());
        assert!(
            snell(&[&["render", &scene, "-o", &wp_s][..], &size].concat())
                .status
                .success()
        );
        let o = snell(
            &[
                &["render", &scene, "-o", &pp_s][..],
                &size,
                &["--region", "7,5,30,21"],
            ]
            .concat(),
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let whole_png = image::open(&wp).unwrap().into_rgb8();
        let part_png = image::open(&pp).unwrap().into_rgb8();
        assert_eq!(part_png.dimensions(), (23, 16));
        for (x, y, p) in part_png.enumerate_pixels() {
            assert_eq!(p, whole_png.get_pixel(x + 7, y + 5), "{name}: ({x}, {y})");
        }
    }
}

#[test]
fn bad_regions_are_refused_before_rendering() {
    let dir = scratch("region-bad");
    let scene = repo("scenes/seed.toml").to_string_lossy().into_owned();
    let out = dir.join("x.png").to_string_lossy().into_owned();
    let base = [
        "render", &scene, "-o", &out, "--width", "40", "--height", "30",
    ];
    for (extra, message) in [
        (
            &["--region", "0,0,41,30"][..],
            "reaches past the 40 x 30 image",
        ),
        (&["--region", "5,5,5,9"][..], "is empty"),
        (&["--region", "1,2,3"][..], "X0,Y0,X1,Y1"),
        (
            &["--region", "0,0,8,8", "--checkpoint", "c.snellcp"][..],
            "--region cannot be combined with --checkpoint",
        ),
        (
            &["--region", "0,0,8,8", "--time", "2s"][..],
            "--region cannot be combined with --time",
        ),
        (
            &["--region", "0,0,8,8", "--aov", "normal"][..],
            "--region cannot be combined with --aov",
        ),
    ] {
        let o = snell(&[&base[..], extra].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(message), "{extra:?}: {err}");
        assert!(!Path::new(&out).exists());
    }
}

/// Renders `scene` at 45 x 37, 4 spp, with `extra` flags, to `out`.
fn render_to(scene: &str, out: &Path, extra: &[&str]) {
    let out = out.to_string_lossy();
    let o = snell(
        &[
            &[
                "render", scene, "-o", &out, "--width", "45", "--height", "37", "--spp", "4",
                "--quiet",
            ][..],
            extra,
        ]
        .concat(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn merged_regions_are_the_bytes_of_one_render() {
    let dir = scratch("merge");
    for (scene, name) in [
        ("scenes/seed.toml", "seed"),
        ("scenes/cornell.toml", "cornell"),
    ] {
        let scene = repo(scene).to_string_lossy().into_owned();
        let quarters = ["0,0,20,16", "20,0,45,16", "0,16,20,37", "20,16,45,37"];
        let mut parts = vec![];
        for (k, q) in quarters.iter().enumerate() {
            let p = dir.join(format!("{name}-{k}.exr"));
            render_to(&scene, &p, &["--region", q]);
            parts.push(p.to_string_lossy().into_owned());
        }
        for ext in ["png", "exr"] {
            let whole = dir.join(format!("{name}-whole.{ext}"));
            render_to(&scene, &whole, &[]);
            let merged = dir.join(format!("{name}-merged.{ext}"));
            let m = merged.to_string_lossy().into_owned();
            // Any order.
            let list: Vec<&str> = parts.iter().rev().map(String::as_str).collect();
            let o = snell(&[&["merge", "-o", &m][..], &list].concat());
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            assert_eq!(
                std::fs::read(&whole).unwrap(),
                std::fs::read(&merged).unwrap(),
                "{name}: the merged {ext} differs from one render's"
            );
        }
        // Refused: a quarter missing, a quarter twice, a quarter of another render, and a
        // whole render's EXR (no fingerprint).
        let middle = dir.join(format!("{name}-middle.exr"));
        render_to(&scene, &middle, &["--region", "10,10,30,30"]);
        let middle = middle.to_string_lossy().into_owned();
        let other = dir.join(format!("{name}-other.exr"));
        render_to(&scene, &other, &["--region", quarters[3], "--seed", "9"]);
        let plain = dir
            .join(format!("{name}-whole.exr"))
            .to_string_lossy()
            .into_owned();
        let out = dir.join("refused.png").to_string_lossy().into_owned();
        let o_s = other.to_string_lossy().into_owned();
        let png = dir
            .join(format!("{name}-whole.png"))
            .to_string_lossy()
            .into_owned();
        for (list, message) in [
            (
                vec![&parts[0], &parts[1], &parts[2]],
                "uncovered, the first at (20, 16)",
            ),
            (
                vec![&parts[0], &parts[1], &parts[2], &parts[3], &parts[1]],
                "is given twice",
            ),
            (
                vec![&parts[0], &parts[1], &parts[2], &parts[3], &middle],
                "overlap (both hold pixel (10, 10))",
            ),
            (
                vec![&parts[0], &parts[1], &parts[2], &o_s],
                "are of different renders",
            ),
            (vec![&parts[0], &plain], "no snell fingerprint"),
            (vec![&parts[0], &png], "not an EXR snell can read"),
        ] {
            let list: Vec<&str> = list.iter().map(|s| s.as_str()).collect();
            let o = snell(&[&["merge", "-o", &out][..], &list].concat());
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{err}");
            assert!(err.contains(message), "{message}: {err}");
            assert!(!Path::new(&out).exists());
        }
    }
}

/// A hostile region file: a 1 x 1 data window in a display window of 100,000 x 100,000
/// (what `snell merge` would otherwise allocate for), with the attributes of a real one.
#[test]
fn merge_refuses_a_region_file_of_an_enormous_image() {
    use exr::prelude::*;
    let dir = scratch("merge-hostile");
    let path = dir.join("huge.exr");
    let channel = |n: &str| AnyChannel::new(n, FlatSamples::F32(vec![0.5]));
    let mut layer = Layer::new(
        (1, 1),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(vec![
            channel("R"),
            channel("G"),
            channel("B"),
        ])),
    );
    layer.attributes.layer_position = Vec2(99_999, 99_999);
    let mut image = exr::image::Image::new(
        ImageAttributes::new(IntegerBounds::new(Vec2(0, 0), Vec2(100_000, 100_000))),
        layer,
    );
    for (k, v) in [
        ("snell.fingerprint", "00000000000000ff"),
        ("snell.tone", "0 clamp"),
    ] {
        image
            .attributes
            .other
            .insert(Text::from(k), AttributeValue::Text(Text::from(v)));
    }
    image.write().to_file(&path).unwrap();
    let out = dir.join("out.exr").to_string_lossy().into_owned();
    let o = snell(&["merge", "-o", &out, &path.to_string_lossy()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("100000 x 100000"), "{err}");
}

/// A merge that cannot write its output fails as a render does (exit 1), and a name of no
/// known format is a bad command line (exit 2).
#[test]
fn merge_exits_as_render_does_when_it_cannot_write() {
    let dir = scratch("merge-exit");
    std::fs::write(dir.join("a.exr"), b"not read: the output fails first").unwrap();
    let no_folder = dir.join("no/such/folder/whole.png");
    let cd = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_snell"))
            .args(args)
            .current_dir(&dir)
            .output()
            .unwrap()
    };
    let o = cd(&["merge", "-o", &no_folder.to_string_lossy(), "a.exr"]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let o = cd(&["merge", "-o", "whole.tiff", "a.exr"]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}
