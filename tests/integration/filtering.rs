//! Texture filtering: the far-checker scene at one sample per pixel has no moire once
//! textures are read over each pixel's footprint, seen directly (both integrators) and in a
//! mirror (the differentials reflected with the ray).

use crate::repo;
use snell::film::Image;
use snell::integrator::{Integrator, Path as PathTracer, Whitted};
use snell::math::luminance;
use snell::render::render;
use snell::scene::{Format, load_str};

/// The far-checker scene with `filter_textures` as given and `extra` appended.
fn far_checker(
    filter: bool,
    edit: impl Fn(String) -> String,
    integrator: &dyn Integrator,
) -> Image {
    let text = std::fs::read_to_string(repo("scenes/far-checker.toml")).unwrap();
    let text = edit(text.replace(
        "filter_textures = true",
        &format!("filter_textures = {filter}"),
    ));
    let path = repo("scenes/far-checker.toml");
    let scene = load_str(&text, &path, &repo("scenes"), Format::Toml)
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    render(&scene, integrator, Some(2), &|_| {}).unwrap().image
}

/// The high-frequency energy of rows `rows` of an image: the mean square of each pixel's
/// luminance less the mean of its four neighbours (a discrete Laplacian), and the rows'
/// mean luminance.
fn energy(img: &Image, rows: std::ops::Range<u32>) -> (f64, f64) {
    let w = img.width;
    let l = |x: u32, y: u32| luminance(img.pixels[(y * w + x) as usize]) as f64;
    let (mut e, mut mean, mut n) = (0.0, 0.0, 0.0);
    for y in rows {
        for x in 1..w - 1 {
            let lap = l(x, y) - 0.25 * (l(x - 1, y) + l(x + 1, y) + l(x, y - 1) + l(x, y + 1));
            e += lap * lap;
            mean += l(x, y);
            n += 1.0;
        }
    }
    (e / n, mean / n)
}

/// The rows of the far floor: from just below the horizon (row 121 of 270, where the
/// camera's rays run parallel to the floor) to where a cell is still a few pixels tall.
const FAR: std::ops::Range<u32> = 124..150;

#[test]
fn a_far_checker_is_grey_not_moire() {
    for (name, integrator, edit) in [
        (
            "whitted",
            &Whitted as &dyn Integrator,
            (|t: String| t) as fn(String) -> String,
        ),
        // The path tracer with a black background: a directional light and nothing else,
        // so one sample per pixel is free of noise and only the texture varies.
        ("path", &PathTracer, |t: String| {
            t.replace(
                "background = [0.55, 0.65, 0.8]",
                "background = 0\nmax_depth = 2",
            ) + "\n[integrator]\ntype = \"path\"\n"
        }),
    ] {
        let (point, point_mean) = energy(&far_checker(false, edit, integrator), FAR);
        let (filtered, filtered_mean) = energy(&far_checker(true, edit, integrator), FAR);
        assert!(
            filtered < 0.1 * point,
            "{name}: high-frequency energy {filtered:.5} filtered, {point:.5} at points"
        );
        // The same light on average: filtering moves none, it only spreads it.
        assert!(
            (filtered_mean / point_mean - 1.0).abs() < 0.05,
            "{name}: mean {filtered_mean} filtered, {point_mean} at points"
        );
    }
}

#[test]
fn a_far_checker_in_a_mirror_is_grey_too() {
    // A mirror upright across the view, 3 in front, facing the camera: the floor behind the
    // camera is seen in it, and only reflected differentials can filter it.
    let mirror = |t: String| {
        t + "\n[materials.mirror]\ncolor = 0\ndiffuse = 0\nreflectivity = 1\n\
             [[objects]]\ntype = \"plane\"\npoint = [0, 0, -3]\nnormal = [0, 0, 1]\nmaterial = \"mirror\"\n"
    };
    let (point, _) = energy(&far_checker(false, mirror, &Whitted), FAR);
    let (filtered, _) = energy(&far_checker(true, mirror, &Whitted), FAR);
    assert!(
        filtered < 0.1 * point,
        "high-frequency energy {filtered:.5} filtered, {point:.5} at points"
    );
}

#[test]
fn differentials_off_a_curved_mirror_are_the_neighbours_reflected() {
    // A mirror ball filling part of a 400-pixel view; for pixels across it, the reflected
    // differentials against the neighbouring pixels' rays really traced and reflected.
    let text = "[image]\nwidth = 400\nheight = 300\nsamples = 1\n\
                [camera]\nposition = [0, 0.5, 6]\nlook_at = [0, 0, 0]\nfov = 30\n\
                [materials.mirror]\ncolor = 0\nreflectivity = 1\n\
                [[objects]]\ntype = \"sphere\"\ncenter = [0.2, 0, 0]\nradius = 1.2\nmaterial = \"mirror\"\n";
    let scene = load_str(text, &repo("t.toml"), &repo("."), Format::Toml).unwrap();
    let cam = scene.camera.raster(400, 300);
    let reflected = |x: f32, y: f32| {
        let ray = cam.ray(x, y);
        let hit = scene.closest_hit(&ray, f32::INFINITY).unwrap();
        (ray, hit, snell::math::reflect(ray.dir, hit.shading_normal))
    };
    let mut checked = 0;
    for (x, y) in [
        (200.0, 150.0),
        (230.5, 120.5),
        (160.5, 190.5),
        (250.5, 160.5),
    ] {
        let (ray, hit, dir) = reflected(x, y);
        let diff = scene.camera_differentials(&ray).unwrap();
        let patch = scene.patch(&hit, &ray, &diff, true).unwrap();
        let out = diff.reflected(&ray, patch.dp, patch.dn, hit.shading_normal);
        for (nx, ny, d_origin, d_dir) in [
            (x + 1.0, y, out.dx_origin, out.dx_dir),
            (x, y + 1.0, out.dy_origin, out.dy_dir),
        ] {
            let (_, n_hit, n_dir) = reflected(nx, ny);
            let (want_o, want_d) = (n_hit.point - hit.point, n_dir - dir);
            assert!(
                (d_origin - want_o).length() < 0.05 * want_o.length(),
                "({x}, {y}): origin {d_origin} vs {want_o}"
            );
            assert!(
                (d_dir - want_d).length() < 0.05 * want_d.length(),
                "({x}, {y}): direction {d_dir} vs {want_d}"
            );
            // The curve spreads the rays: far more than the camera's own spread.
            assert!(want_d.length() > 3.0 * (cam.ray(nx, ny).dir - ray.dir).length());
            checked += 1;
        }
    }
    assert_eq!(checked, 8);
}
