//! The camera in whole renders: a thin lens keeps the plane in focus sharp and blurs what is
//! off it (under both integrators, light neither made nor lost); an orthographic camera
//! shows a sphere at its true size, whatever its distance; bad cameras are refused in
//! tests/bad.

use snell::film::Image;
use snell::integrator::{Integrator, Path as PathTracer, Whitted};
use snell::math::Color;
use snell::render::render;
use snell::scene::{Format, load_str};
use std::path::Path;

fn image(text: &str, integrator: &dyn Integrator) -> Image {
    let scene = load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml)
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    render(&scene, integrator, Some(2), &|_| {}).unwrap().image
}

fn total(img: &Image) -> f32 {
    img.pixels.iter().map(|c| c.x + c.y + c.z).sum()
}

fn difference(a: &Image, b: &Image) -> f32 {
    let d: f32 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| (*p - *q).abs().element_sum())
        .sum();
    d / total(b)
}

fn lit(img: &Image) -> usize {
    img.pixels.iter().filter(|c| c.max_element() > 0.02).count()
}

/// A white ball 10 away on black, lit by a point light (Whitted) or a constant environment
/// seen only by the ball (path), through `lens` (camera keys).
fn ball(kind: &str, lens: &str) -> String {
    format!(
        "[image]\nwidth = 48\nheight = 48\nsamples = 64\nfilter = {{ type = \"box\" }}\n\
         [integrator]\ntype = \"{kind}\"\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 12\n{lens}\n\
         [environment]\ntype = \"constant\"\ncolor = 1\nvisible = false\n\
         [[lights]]\ntype = \"point\"\nposition = [0, 0, 0]\nfalloff = \"none\"\n\
         [materials.white]\ncolor = 1\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -10]\nradius = 0.5\nmaterial = \"white\"\n"
    )
}

#[test]
fn a_lens_keeps_the_focus_sharp_and_blurs_the_rest() {
    for (kind, integrator) in [
        ("whitted", &Whitted as &dyn Integrator),
        ("path", &PathTracer),
    ] {
        let pinhole = image(&ball(kind, ""), integrator);
        let sharp = image(
            &ball(kind, "aperture = 0.2\nfocus_distance = 9.6"),
            integrator,
        );
        let blurred = image(
            &ball(kind, "aperture = 0.4\nfocus_distance = 4"),
            integrator,
        );
        let (d_sharp, d_blur) = (difference(&sharp, &pinhole), difference(&blurred, &pinhole));
        assert!(d_sharp < 0.1, "{kind}: in focus, {d_sharp} off the pinhole");
        assert!(
            d_blur > 0.5,
            "{kind}: out of focus, only {d_blur} off the pinhole"
        );
        assert!(
            lit(&blurred) > lit(&pinhole) * 3 / 2,
            "{kind}: {} lit pixels blurred, {} sharp",
            lit(&blurred),
            lit(&pinhole)
        );
        // The blur moves light about the film; it makes and loses none (all of the blurred
        // ball stays on the film).
        let ratio = total(&blurred) / total(&pinhole);
        assert!((ratio - 1.0).abs() < 0.03, "{kind}: light x{ratio} blurred");
    }
}

#[test]
fn an_orthographic_camera_shows_true_size_at_any_distance() {
    let scene = |distance: f32| {
        format!(
            "[image]\nwidth = 64\nheight = 64\nsamples = 1\n\
             [camera]\ntype = \"orthographic\"\nheight = 4\nposition = [0, 0, {distance}]\nlook_at = [0, 0, 0]\n\
             [[lights]]\ntype = \"directional\"\ndirection = [0, 0, -1]\n\
             [materials.white]\ncolor = 1\n\
             [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"white\"\n"
        )
    };
    // Radius 1 on a film 4 tall of 64 pixels: a disk 16 pixels in radius, pi 16^2 pixels.
    let expect = std::f32::consts::PI * 256.0;
    for distance in [3.0, 50.0] {
        let img = image(&scene(distance), &Whitted);
        let covered = img.pixels.iter().filter(|c| **c != Color::ZERO).count() as f32;
        assert!(
            (covered - expect).abs() < 0.03 * expect,
            "at {distance}: {covered} pixels, not {expect}"
        );
    }
}
