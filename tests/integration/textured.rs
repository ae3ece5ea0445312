//! Material parameters read from textures: every textured key gives, point by point, what the
//! same constant gives (a uniform texture renders the same bits as the constant; a texture
//! of two values renders each pixel as one of the two constants' renders), under both
//! integrators; a textured light lights the scene as the emitting parts it stands for, under
//! the path tracer, light tracing and bidirectional path tracing.

use snell::film::Image;
use snell::integrator::{Integrator, Path as PathTracer, Whitted};
use snell::render::render;
use snell::scene::{Format, Scene, load_str};
use std::path::Path;

fn load(text: &str) -> Scene {
    load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml)
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn image(text: &str, integrator: &dyn Integrator) -> Image {
    render(&load(text), integrator, Some(2), &|_| {})
        .unwrap()
        .image
}

fn bits(img: &Image) -> Vec<[u32; 3]> {
    img.pixels
        .iter()
        .map(|c| c.to_array().map(f32::to_bits))
        .collect()
}

/// A floor (and a ball, with `ball`) under point lights, an emitting panel and a bright
/// background, looking down; the material `m` on both, with `keys`, and the textures
/// `textures` (TOML). Without the ball no surface of `m` sees another: light reaches each
/// point of the floor without passing another point of it. Textures are read at points
/// (`filter_textures = false`), so that each pixel is one value or the other: filtering
/// blends them near an edge (tests/integration/filtering.rs).
fn scene(kind: &str, keys: &str, textures: &str, ball: bool) -> String {
    let ball = if ball {
        "[[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n"
    } else {
        ""
    };
    format!(
        "[image]\nwidth = 24\nheight = 24\nsamples = 1\nbackground = [0.4, 0.5, 0.6]\nmax_depth = 4\nfilter_textures = false\n\
         [integrator]\ntype = \"{kind}\"\n\
         [world]\nambient = 0.2\n\
         [camera]\nposition = [0.3, 3, 4]\nlook_at = [0, 0, 0]\nfov = 50\n\
         [[lights]]\ntype = \"point\"\nposition = [2, 4, 3]\nfalloff = \"none\"\n\
         [[lights]]\ntype = \"point\"\nposition = [-3, 2, 1]\ncolor = [0.3, 0.3, 0.6]\nfalloff = \"none\"\n\
         {textures}\n\
         [materials.m]\n{keys}\n\
         [materials.light]\ntype = \"diffuse\"\ncolor = 0\nemission = 3\n\
         [[objects]]\ntype = \"plane\"\npoint = [0, -1, 0]\nmaterial = \"m\"\n{ball}\
         [[objects]]\ntype = \"rectangle\"\ncorner = [-1, 3, -1]\nedge_u = [2, 0, 0]\nedge_v = [0, 0, 2]\nmaterial = \"light\"\n"
    )
}

/// A checker of one value in both cells, and stripes of two across the plane's x.
fn textures(a: &str, b: &str) -> String {
    format!(
        "[textures.same]\ntype = \"checker\"\neven = {a}\nodd = {a}\nsize = 0.5\n\
         [textures.two]\ntype = \"stripes\"\na = {a}\nb = {b}\nwidth = 0.7\n"
    )
}

/// Each textured key, under each integrator that reads it: a uniform texture gives the
/// constant's bits (floor and ball); stripes of two values give, pixel by pixel, one of the
/// two constants' renders, and both appear (the floor alone, and one sample a pixel, so that
/// no pixel sees both values). `base` holds the material's other keys.
fn check_key(key: &str, a: &str, b: &str, base: &str, kinds: &[&str]) {
    for &kind in kinds {
        let integrator: &dyn Integrator = if kind == "path" {
            &PathTracer
        } else {
            &Whitted
        };
        let render = |value: &str, ball| {
            let keys = format!("{base}\n{key} = {value}");
            bits(&image(
                &scene(kind, &keys, &textures(a, b), ball),
                integrator,
            ))
        };
        assert!(
            render("\"same\"", true) == render(a, true),
            "{kind} `{key}` from a uniform texture differs from the constant"
        );
        let (ca, cb) = (render(a, false), render(b, false));
        assert!(
            ca != cb,
            "{kind} `{key}`: {a} and {b} should look different"
        );
        let striped = render("\"two\"", false);
        let (mut from_a, mut from_b) = (0, 0);
        for (i, p) in striped.iter().enumerate() {
            // Pixels where the two constants agree (the background) count for neither.
            if ca[i] == cb[i] {
                assert_eq!(*p, ca[i], "{kind} `{key}`, pixel {i}");
                continue;
            }
            match (*p == ca[i], *p == cb[i]) {
                (true, _) => from_a += 1,
                (_, true) => from_b += 1,
                // A pixel's samples may fall on both sides of a stripe's edge.
                _ => {}
            }
        }
        let differ = (0..ca.len()).filter(|&i| ca[i] != cb[i]).count();
        assert!(
            from_a > differ / 5 && from_b > differ / 5 && from_a + from_b > differ / 2,
            "{kind} `{key}`: {from_a} pixels as {a}, {from_b} as {b}, of {differ}"
        );
    }
}

#[test]
fn phong_terms_read_their_textures() {
    let both = ["whitted", "path"];
    let base = "color = [0.8, 0.6, 0.4]\nspecular = 0.3";
    // Values whose sum of three is exact, so that a grey texture's mean is the value.
    check_key("ambient", "0.5", "2", base, &["whitted"]);
    check_key("diffuse", "0.25", "0.75", base, &both);
    check_key("shininess", "4", "64", base, &both);
    check_key("reflectivity", "0.125", "0.75", base, &both);
    check_key("transparency", "0.25", "0.875", base, &both);
    // The path tracer reads only whether `specular` is black (a clear coat or none).
    check_key(
        "specular",
        "[0.9, 0.2, 0.1]",
        "[0.1, 0.3, 0.9]",
        "color = [0.8, 0.6, 0.4]",
        &["whitted"],
    );
    check_key("specular", "0", "0.5", "color = [0.8, 0.6, 0.4]", &["path"]);
}

/// `emission` (and a rough `roughness`, whose texture a solid-coloured material once read
/// without the uv it needs) under both integrators; a conductor's `eta` and `k`. (A
/// plastic's textured roughness reads its coat's tables at knots of roughness, not the
/// exact table of a constant: [`a_plastic_reads_a_textured_roughness_within_its_knots`].)
#[test]
fn emission_roughness_and_index_read_their_textures() {
    let both = ["whitted", "path"];
    check_key(
        "emission",
        "0.2",
        "[1.5, 0.7, 0.1]",
        "type = \"diffuse\"\ncolor = 0.5",
        &both,
    );
    let gold_k = "k = [3.0, 2.4, 1.8]";
    check_key(
        "roughness",
        "0.0625",
        "0.5625",
        &format!("type = \"conductor\"\neta = [0.2, 0.4, 1.4]\n{gold_k}"),
        &["path"],
    );
    check_key(
        "eta",
        "[0.15, 0.4, 1.4]",
        "[1.2, 1.0, 0.5]",
        &format!("type = \"conductor\"\nroughness = 0.2\n{gold_k}"),
        &["path"],
    );
    check_key(
        "k",
        "[3.0, 2.4, 1.8]",
        "[6.0, 5.0, 4.0]",
        "type = \"conductor\"\nroughness = 0.2\neta = [0.2, 0.4, 1.4]",
        &["path"],
    );
}

/// A plastic whose roughness comes from a uniform texture renders as the constant does,
/// within what interpolating its coat's tables between knots of roughness allows (0.6 %),
/// and a texture of two roughnesses gives two looks.
#[test]
fn a_plastic_reads_a_textured_roughness_within_its_knots() {
    let base = "type = \"plastic\"\ncolor = 0.5";
    let mean = |value: &str, textures: &str| {
        let keys = format!("{base}\nroughness = {value}");
        let img = image(&scene("path", &keys, textures, true), &PathTracer);
        img.pixels
            .iter()
            .map(|c| c.element_sum() as f64)
            .sum::<f64>()
    };
    let mut checked = 0;
    for (a, b) in [("0.0625", "0.5625"), ("0.2", "0.03")] {
        let (constant, uniform) = (mean(a, ""), mean("\"same\"", &textures(a, b)));
        assert!(
            (uniform - constant).abs() < 0.006 * constant,
            "roughness {a}: {uniform} from a texture, {constant} as a constant"
        );
        let other = mean(b, "");
        assert!(
            (other - constant).abs() > 0.01 * constant,
            "{a} and {b} look alike"
        );
        checked += 1;
    }
    assert_eq!(checked, 2);
}

/// A rectangle light whose emission is stripes of 0 and 4 lights the floor as a rectangle
/// of half its size with emission 4 does: the light is sampled where it lies and its
/// radiance read there, not taken as the mean over all of it, by the path tracer, and by
/// the light tracer and bidirectional path tracing, whose paths start on it. Eight blocks
/// of the floor seen from above agree within 4 %, where the mean taken for the whole light
/// would be 25 % off near the dark half and the bright one.
#[test]
fn a_textured_light_lights_as_its_parts_do() {
    let floor = |lights: &str, textures: &str| {
        format!(
            "[image]\nwidth = 32\nheight = 16\nsamples = 256\n\
             [integrator]\ntype = \"path\"\n\
             [camera]\nposition = [0, 6, 0.001]\nlook_at = [0, 0, 0]\nfov = 60\n\
             {textures}\n\
             [materials.floor]\ntype = \"diffuse\"\ncolor = 0.8\n\
             [materials.lamp]\ntype = \"diffuse\"\ncolor = 0\n{lights}\n\
             [[objects]]\ntype = \"plane\"\npoint = [0, 0, 0]\nmaterial = \"floor\"\n"
        )
    };
    let halves = "[textures.halves]\ntype = \"stripes\"\na = 0\nb = 4\nwidth = 0.5\n";
    let textured = floor(
        "emission = \"halves\"\n[[objects]]\ntype = \"rectangle\"\ncorner = [-2, 1.5, -0.5]\nedge_u = [4, 0, 0]\nedge_v = [0, 0, 1]\nmaterial = \"lamp\"\n",
        halves,
    );
    // The same panel as two halves, the one emitting, the other not (but there, hiding
    // the floor from the camera as the textured panel's dark half does).
    let half = floor(
        "emission = 4\n[materials.dark]\ntype = \"diffuse\"\ncolor = 0\n\
         [[objects]]\ntype = \"rectangle\"\ncorner = [0, 1.5, -0.5]\nedge_u = [2, 0, 0]\nedge_v = [0, 0, 1]\nmaterial = \"lamp\"\n\
         [[objects]]\ntype = \"rectangle\"\ncorner = [-2, 1.5, -0.5]\nedge_u = [2, 0, 0]\nedge_v = [0, 0, 1]\nmaterial = \"dark\"\n",
        "",
    );
    let blocks = |img: &Image| {
        let mut sums = [0.0f64; 8];
        for y in 0..16 {
            for x in 0..32 {
                sums[(x / 4) as usize] += img.get(x, y).x as f64;
            }
        }
        sums
    };
    let options = snell::render::RenderOptions {
        threads: Some(2),
        progress: &|_| {},
        cancel: None,
        region: None,
    };
    // Paths from the light reach the floor's far, dim blocks less often than the path
    // tracer's reach the light: four times the paths.
    let more = |text: &str| {
        let mut scene = load(text);
        scene.settings.spp *= 4;
        scene
    };
    let light = |text: &str| {
        snell::render::light::render_light(&more(text), &options)
            .unwrap()
            .image
    };
    let bdpt = |text: &str| {
        snell::render::bdpt::render_bdpt(&more(text), &options)
            .unwrap()
            .image
    };
    let path = |text: &str| image(text, &PathTracer);
    let mut checked = 0;
    for (name, render) in [
        ("path", &path as &dyn Fn(&str) -> Image),
        ("light", &light),
        ("bdpt", &bdpt),
    ] {
        let (a, b) = (blocks(&render(&textured)), blocks(&render(&half)));
        for i in 0..8 {
            assert!(
                (a[i] / b[i] - 1.0).abs() < 0.04,
                "{name}, block {i}: textured {:.3}, half {:.3} (all {a:?} against {b:?})",
                a[i],
                b[i]
            );
            checked += 1;
        }
        // The floor below the bright half is lit more than below the dark half.
        assert!(b[6] > 1.5 * b[1], "{name}: {b:?}");
    }
    assert_eq!(checked, 24);
}

/// A texture name that is not defined is an error at its key, with a suggestion.
#[test]
fn a_missing_texture_is_named() {
    let text = scene(
        "whitted",
        "specular = \"tow\"",
        &textures("0.1", "0.2"),
        true,
    );
    let e = load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no texture named `tow`"), "{e}");
}
