//! Bidirectional path tracing against the path tracer, on scenes the path tracer handles
//! (the Cornell box, every kind of light, the studio environment): the same picture, block by
//! block, within the noise two seeds of each show; the white furnace; the same bytes at any
//! thread count.

use super::*;
use crate::render::pass::tests::{bits, options};
use crate::render::render;
use crate::scene::{Format, MisHeuristic, load_str};

fn scene(text: &str) -> Scene {
    load_str(
        text,
        std::path::Path::new("t.toml"),
        std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes")),
        Format::Toml,
    )
    .unwrap()
}

fn sized(mut s: Scene, size: u32, spp: u32, seed: u64) -> Scene {
    s.settings.width = size;
    s.settings.height = size;
    s.settings.spp = spp;
    s.settings.seed = seed;
    s
}

fn cornell() -> Scene {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cornell.toml"))
        .unwrap();
    scene(&text)
}

/// How far a bidirectional picture is from the path-traced one, 4 x 4-pixel blocks
/// compared: each block's difference over its noise, the noise estimated from two renders
/// of each with different seeds (the 16 pixels' differences, a box filter keeping the
/// pixels' noise apart). The largest `|z|` and the mean `z` (a bias shows as a mean away
/// from 0, whose spread is `1 / sqrt(blocks)`).
fn z_test(make: impl Fn(u64) -> Scene, spp: u32, path_spp: u32) -> (f64, f64) {
    let boxed = |seed| {
        let mut s = make(seed);
        s.settings.filter = crate::film::Filter::new(crate::film::FilterKind::Box, None);
        s
    };
    let bdpt = |seed| {
        render_bdpt(&sized_spp(boxed(seed), spp), &options(2))
            .unwrap()
            .image
    };
    let path = |seed| {
        let s = sized_spp(boxed(seed), path_spp);
        render(&s, &Path, Some(2), &|_| {}).unwrap().image
    };
    let (b1, b2, p1, p2) = (bdpt(1), bdpt(2), path(3), path(4));
    let size = b1.width;
    let lum = |img: &Image, x, y| crate::math::luminance(img.get(x, y)) as f64;
    let mut z = vec![];
    for by in 0..size / 4 {
        for bx in 0..size / 4 {
            let (mut sum, mut var) = ([0.0f64; 4], [0.0f64; 2]);
            for y in by * 4..by * 4 + 4 {
                for x in bx * 4..bx * 4 + 4 {
                    let v = [&b1, &b2, &p1, &p2].map(|i| lum(i, x, y));
                    for k in 0..4 {
                        sum[k] += v[k] / 16.0;
                    }
                    // Each pixel's variance, from two samples of it; the block's mean's is
                    // the sum over 16^2.
                    var[0] += (v[0] - v[1]).powi(2) / 2.0 / 256.0;
                    var[1] += (v[2] - v[3]).powi(2) / 2.0 / 256.0;
                }
            }
            let reference = (sum[2] + sum[3]) / 2.0;
            // The means of two renders each: half the variance.
            let sigma = ((var[0] + var[1]) / 2.0).sqrt();
            if reference > 1e-3 && sigma > 0.0 {
                z.push(((sum[0] + sum[1]) / 2.0 - reference) / sigma);
            }
        }
    }
    assert!(z.len() as u32 >= (size / 4) * (size / 4) / 2, "{}", z.len());
    let worst = z.iter().fold(0.0f64, |m, z| m.max(z.abs()));
    (worst, z.iter().sum::<f64>() / z.len() as f64)
}

fn sized_spp(mut s: Scene, spp: u32) -> Scene {
    s.settings.spp = spp;
    s
}

/// The worst block and the mean of [`z_test`] within what noise allows.
fn assert_unbiased(what: &str, (worst, mean): (f64, f64), blocks: u32) {
    let limit = 4.0 / (blocks as f64).sqrt();
    assert!(worst < 4.5, "{what}: worst block z = {worst:.2}");
    assert!(
        mean.abs() < limit,
        "{what}: mean z = {mean:.3} (limit {limit:.3})"
    );
}

/// The Cornell box (every surface diffuse, an area light seen directly): bidirectional and
/// path-traced pictures agree block by block within noise, with either heuristic.
#[test]
fn the_cornell_box_is_the_path_traced_one() {
    for mis in [MisHeuristic::Power, MisHeuristic::Balance] {
        let make = |seed| {
            let mut s = sized(cornell(), 24, 256, seed);
            s.settings.integrator.mis = mis;
            s
        };
        let r = z_test(make, 256, 1024);
        eprintln!("{mis:?}: {r:?}");
        assert_unbiased(&format!("{mis:?}"), r, 36);
    }
}

/// A floor, a diffuse ball and a rough metal one, lit by `light` (TOML), seen from above.
fn lit_by(light: &str) -> String {
    format!(
        "[image]\nwidth = 16\nheight = 16\nsamples = 64\nmax_depth = 6\n\
         [integrator]\ntype = \"bdpt\"\n\
         [camera]\nposition = [0, 3, 4]\nlook_at = [0, 0.4, 0]\nfov = 50\n\
         [materials.floor]\ntype = \"diffuse\"\ncolor = 0.6\n\
         [materials.red]\ntype = \"diffuse\"\ncolor = [0.7, 0.2, 0.1]\n\
         [materials.metal]\ntype = \"conductor\"\nmetal = \"Cu\"\nroughness = 0.3\n\
         [materials.lamp]\ntype = \"diffuse\"\ncolor = 0\nemission = 20\n\
         [[objects]]\ntype = \"plane\"\npoint = [0, 0, 0]\nmaterial = \"floor\"\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [-0.6, 0.5, 0]\nradius = 0.5\nmaterial = \"red\"\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0.6, 0.5, 0.2]\nradius = 0.5\nmaterial = \"metal\"\n\
         {light}\n"
    )
}

/// Every kind of light, bidirectionally and path traced, agrees block by block within
/// noise: point lights that fall off and that do not, a spot, the sun (directional), an
/// emitting ball and a two-sided emitting disk, a constant environment and a daylight sky.
#[test]
fn every_light_is_the_path_traced_one() {
    let lights = [
        (
            "point",
            "[[lights]]\ntype = \"point\"\nposition = [1, 3, 2]\nintensity = 20",
        ),
        (
            "point without falloff",
            "[[lights]]\ntype = \"point\"\nposition = [1, 3, 2]\nfalloff = \"none\"",
        ),
        (
            "spot",
            "[[lights]]\ntype = \"spot\"\nposition = [-1, 3, 1]\nlook_at = [0, 0, 0]\nangle = 40\nintensity = 30",
        ),
        (
            "sun",
            "[[lights]]\ntype = \"directional\"\ndirection = [-0.4, -1, -0.3]\ncolor = 2",
        ),
        (
            "emitting ball",
            "[[objects]]\ntype = \"sphere\"\ncenter = [1, 2.5, 1.5]\nradius = 0.3\nmaterial = \"lamp\"",
        ),
        (
            "environment",
            "[environment]\ntype = \"constant\"\ncolor = [0.8, 0.9, 1.0]",
        ),
        (
            "sky",
            "[environment]\ntype = \"sky\"\nlatitude = 45\nday = 172\nhour = 15",
        ),
    ];
    let mut checked = 0;
    for (what, light) in lights {
        let text = lit_by(light);
        let make = |seed| sized(scene(&text), 16, 64, seed);
        let r = z_test(make, 64, 256);
        assert_unbiased(what, r, 16);
        checked += 1;
    }
    assert_eq!(checked, 7);
}

/// The white furnace: in a constant environment of radiance 1, a lossless glass ball is
/// invisible (every path through it comes out to the same sky) and a diffuse ball of albedo
/// 0.5 reflects 0.5 (a convex surface sees only the sky). Bidirectionally, with light
/// subpaths that start at the sky, both hold within 1 %.
#[test]
fn the_white_furnace_holds() {
    let furnace = |material: &str| {
        let text = format!(
            "[image]\nwidth = 12\nheight = 12\nsamples = 512\nmax_depth = 64\n\
             [integrator]\ntype = \"bdpt\"\n\
             [camera]\nposition = [0, 0, 6]\nlook_at = [0, 0, 0]\nfov = 30\n\
             [environment]\ntype = \"constant\"\ncolor = 1\n\
             [materials.ball]\n{material}\n\
             [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"ball\"\n"
        );
        let img = render_bdpt(&scene(&text), &options(2)).unwrap().image;
        assert!(
            (img.get(0, 0).element_sum() / 3.0 - 1.0).abs() < 1e-4,
            "the sky"
        );
        // The 4 x 4 pixels in the middle see the ball.
        let mut sum = 0.0;
        for y in 4..8 {
            for x in 4..8 {
                sum += img.get(x, y).element_sum() / 3.0;
            }
        }
        sum / 16.0
    };
    let grey = furnace("type = \"diffuse\"\ncolor = 0.5");
    let glass = furnace("type = \"dielectric\"\nior = 1.5");
    assert!((grey - 0.5).abs() < 0.005, "grey {grey}");
    assert!((glass - 1.0).abs() < 0.01, "glass {glass}");
}

#[test]
fn the_same_bytes_at_any_thread_count() {
    let a = render_bdpt(&sized(cornell(), 16, 8, 1), &options(1))
        .unwrap()
        .image;
    let b = render_bdpt(&sized(cornell(), 16, 8, 1), &options(2))
        .unwrap()
        .image;
    assert_eq!(bits(&a.pixels), bits(&b.pixels));
    assert!(a.pixels.iter().any(|c| c.max_element() > 0.0));
}

/// A render stopped by its time after some passes is the render of that many samples a
/// pixel, to the bit; the first pass is always taken.
#[test]
fn a_render_stopped_by_time_is_the_render_of_its_samples() {
    let make = |spp| sized(cornell(), 16, spp, 1);
    let stopped = render_bdpt_for(&make(4096), &options(2), Some(Duration::ZERO), false).unwrap();
    assert_eq!(stopped.spp, 1, "only the first pass");
    assert!(stopped.rendered.complete());
    let short = render_bdpt_for(
        &make(4096),
        &options(2),
        Some(Duration::from_millis(30)),
        false,
    )
    .unwrap();
    assert!(short.spp >= 1 && short.spp < 4096, "{}", short.spp);
    for r in [stopped, short] {
        let whole = render_bdpt(&make(r.spp), &options(1)).unwrap();
        assert_eq!(
            bits(&r.rendered.image.pixels),
            bits(&whole.image.pixels),
            "{}",
            r.spp
        );
    }
}

/// Passes resumed from a render stopped after its first passes give the bytes of the render
/// never stopped (the camera's film and the splats both carried over); a light-traced
/// state is refused, and so are strategy images, which the state does not keep.
#[test]
fn passes_resumed_are_the_render_never_stopped() {
    let make = |spp| sized(cornell(), 16, spp, 1);
    let stopped = render_bdpt_for(&make(2), &options(2), None, false).unwrap();
    assert_eq!(stopped.state.spp, 2);
    let mut told = vec![];
    let resumed = render_bdpt_from(
        &make(8),
        &options(1),
        None,
        false,
        Some(stopped.state.clone()),
        &mut |state| told.push(state().spp),
    )
    .unwrap();
    assert_eq!(told, [4, 8]);
    assert_eq!(resumed.spp, 8);
    let whole = render_bdpt(&make(8), &options(2)).unwrap();
    assert_eq!(
        bits(&resumed.rendered.image.pixels),
        bits(&whole.image.pixels)
    );
    let light = crate::checkpoint::Splatted {
        film: None,
        ..stopped.state.clone()
    };
    let mut refused = 0;
    for (state, strategies, says) in [
        (light, false, "light tracing's"),
        (stopped.state, true, "strategy images"),
    ] {
        let e = render_bdpt_from(
            &make(8),
            &options(1),
            None,
            strategies,
            Some(state),
            &mut |_| {},
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains(says), "{e}");
        refused += 1;
    }
    assert_eq!(refused, 2);
}

/// Every BSDF, the deltas too, under area lights (scenes/materials.toml: smooth and rough
/// metals, clear and rough glass, plastics, a thin pane; and a Phong ball that mirrors part
/// of its light and a Phong glass one): bidirectional and path-traced pictures agree block
/// by block within noise.
#[test]
fn every_material_is_the_path_traced_one() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/materials.toml"
    ))
    .unwrap();
    let make = |seed| sized(scene(&text), 24, 64, seed);
    assert_unbiased("materials.toml", z_test(make, 64, 256), 36);
    let phong = lit_by(
        "[materials.shiny]\ncolor = [0.2, 0.4, 0.9]\ndiffuse = 0.6\nspecular = 1\nshininess = 40\nreflectivity = 0.4\n\
         [materials.clear]\ncolor = 1\ndiffuse = 0\nspecular = 1\nshininess = 50\ntransparency = 1\nior = 1.5\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0.35, 1.2]\nradius = 0.35\nmaterial = \"shiny\"\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [-0.2, 1.2, 0.6]\nradius = 0.3\nmaterial = \"clear\"\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [1, 2.5, 1.5]\nradius = 0.3\nmaterial = \"lamp\"",
    );
    let make = |seed| sized(scene(&phong), 16, 64, seed);
    assert_unbiased("Phong", z_test(make, 64, 256), 16);
}

/// The weighted strategy images add up to the picture (box-filtered, paths no longer than
/// the images show), each strategy's light once; the unweighted ones each estimate the
/// light of all the strategies of their length, so those of one length agree in mean.
#[test]
fn the_weighted_strategies_add_up_to_the_picture() {
    let mut scene = sized(cornell(), 16, 64, 1);
    scene.settings.max_depth = STRATEGY_DEPTH;
    let r = render_bdpt_for(&scene, &options(2), None, true).unwrap();
    let names = strategy_names(STRATEGY_DEPTH);
    assert_eq!(r.strategies.len(), names.len());
    assert_eq!(names.len(), 2 * 13);
    let mut sum = vec![Color::ZERO; 16 * 16];
    for (name, img) in names.iter().zip(&r.strategies) {
        if !name.ends_with("-unweighted") {
            for (s, p) in sum.iter_mut().zip(&img.pixels) {
                *s += *p;
            }
        }
    }
    let mut checked = 0;
    for (s, p) in sum.iter().zip(&r.rendered.image.pixels) {
        assert!(
            (*s - *p).abs().max_element() < 1e-4 + 1e-4 * p.max_element(),
            "{s} vs {p}"
        );
        checked += 1;
    }
    assert_eq!(checked, 256);
    // Direct light (2 segments): the camera path hitting the light, a light sampled, the
    // light's path joined to the eye; each alone estimates all of it.
    let mean = |name: &str| {
        let i = names.iter().position(|n| n == name).unwrap();
        let img = &r.strategies[i];
        img.pixels
            .iter()
            .map(|c| c.element_sum() as f64)
            .sum::<f64>()
            / img.pixels.len() as f64
    };
    let direct = mean("s1-t2-unweighted");
    for other in ["s0-t3-unweighted", "s2-t1-unweighted"] {
        let m = mean(other);
        assert!(
            (m - direct).abs() < 0.15 * direct,
            "{other}: {m} against {direct}"
        );
    }
}
