//! `[environment]`: a constant environment is a white furnace for the path tracer; an image
//! of one value lights as that constant does; a sky with a sun lights a floor with the
//! integral of its radiance over the floor's hemisphere (worked out here by quadrature); the
//! image faces the way docs/scene-format.md says, and `rotate` turns it; a hidden
//! environment still lights; Whitted shows it behind the scene and in mirrors.

use super::scratch;
use snell::film::Image;
use snell::integrator::{Integrator, Path as PathTracer, Whitted};
use snell::math::{Color, Vec3A};
use snell::render::render;
use snell::scene::{Format, Scene, load_str};
use std::f32::consts::PI;
use std::path::Path;

fn load(text: &str, dir: &Path) -> Scene {
    let scene = load_str(text, &dir.join("t.toml"), dir, Format::Toml)
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    scene
}

fn image(scene: &Scene, integrator: &dyn Integrator) -> Image {
    render(scene, integrator, Some(2), &|_| {}).unwrap().image
}

fn mean(pixels: &[Color]) -> Color {
    pixels.iter().copied().sum::<Color>() / pixels.len() as f32
}

/// Writes a `w` x `h` float EXR whose texel `(x, y)` is `f(x, y)`.
fn write_exr(path: &Path, w: u32, h: u32, f: impl Fn(u32, u32) -> [f32; 3]) {
    image::Rgb32FImage::from_fn(w, h, |x, y| image::Rgb(f(x, y)))
        .save(path)
        .unwrap();
}

/// A sphere of `material` in `[environment]` `env`, seen head-on through a narrow field so
/// that every pixel is the sphere.
fn sphere_in(env: &str, material: &str, spp: u32) -> String {
    format!(
        "[image]\nwidth = 8\nheight = 8\nsamples = {spp}\nmax_depth = 64\n\
         [integrator]\ntype = \"path\"\n\
         [camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov = 8\n\
         [environment]\n{env}\n\
         [materials.m]\n{material}\n\
         [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n"
    )
}

#[test]
fn a_constant_environment_is_a_white_furnace() {
    let dir = scratch("env-furnace");
    // A convex surface sees only the environment: a Lambertian one of albedo r returns r
    // times the environment's radiance, a smooth dielectric all of it.
    for (material, expect) in [
        ("type = \"diffuse\"\ncolor = 1", 1.0f32),
        ("type = \"diffuse\"\ncolor = 0.5", 0.5),
        ("type = \"dielectric\"\nior = 1.5", 1.0),
    ] {
        let text = sphere_in("type = \"constant\"\ncolor = 1", material, 64);
        let img = image(&load(&text, &dir), &PathTracer);
        for (i, p) in img.pixels.iter().enumerate() {
            for c in p.to_array() {
                assert!(
                    (c - expect).abs() < 0.05 * expect,
                    "{material}: pixel {i} is {p:?}, not {expect}"
                );
            }
        }
        let m = mean(&img.pixels).x;
        assert!((m - expect).abs() < 0.005, "{material}: mean {m}");
    }
}

#[test]
fn an_image_of_one_value_lights_as_that_constant() {
    let dir = scratch("env-uniform");
    write_exr(&dir.join("grey.exr"), 32, 16, |_, _| [0.7, 0.7, 0.7]);
    let material = "type = \"plastic\"\ncolor = [0.8, 0.3, 0.1]\nroughness = 0.3";
    let from_image = image(
        &load(
            &sphere_in("type = \"image\"\nfile = \"grey.exr\"", material, 64),
            &dir,
        ),
        &PathTracer,
    );
    let constant = image(
        &load(
            &sphere_in("type = \"constant\"\ncolor = 0.7", material, 64),
            &dir,
        ),
        &PathTracer,
    );
    let (a, b) = (mean(&from_image.pixels), mean(&constant.pixels));
    for (x, y) in a.to_array().into_iter().zip(b.to_array()) {
        assert!((x - y).abs() < 0.01 * y, "image {a:?}, constant {b:?}");
    }
}

/// A sky of 64 x 32 texels: blue brightening toward the top, a sun of 3 x 3 texels about
/// 48 degrees from straight up in the +x half, and a ground below the horizon.
fn sky(x: u32, y: u32) -> [f32; 3] {
    if (x as i32 - 44).abs() <= 1 && (y as i32 - 8).abs() <= 1 {
        [300.0, 280.0, 250.0]
    } else if y < 16 {
        let t = 1.0 - y as f32 / 16.0;
        [0.2 + 0.3 * t, 0.3 + 0.4 * t, 0.6 + 0.6 * t]
    } else {
        [0.3, 0.25, 0.2]
    }
}

/// The irradiance on an upward floor of light arriving with `radiance(direction)`: the
/// integral of L cos(theta) over the upper hemisphere by the midpoint rule, on a grid of
/// 720 x 1440 directions (far finer than an environment map's texels).
pub(super) fn floor_irradiance(radiance: impl Fn(Vec3A) -> Color) -> Color {
    let (nt, np) = (720, 1440);
    let mut e = Color::ZERO;
    for i in 0..nt {
        let theta = (i as f32 + 0.5) / nt as f32 * PI / 2.0;
        let (st, ct) = theta.sin_cos();
        for j in 0..np {
            let phi = (j as f32 + 0.5) / np as f32 * 2.0 * PI;
            let d = Vec3A::new(st * phi.cos(), ct, st * phi.sin());
            e += radiance(d) * (ct * st);
        }
    }
    e * (PI / 2.0 / nt as f32) * (2.0 * PI / np as f32)
}

#[test]
fn a_sky_with_a_sun_lights_a_floor_with_its_integral() {
    let dir = scratch("env-sky");
    write_exr(&dir.join("sky.exr"), 64, 32, sky);
    let albedo = 0.5;
    for rotate in ["[0, 0, 0]", "[0, 120, 0]"] {
        let text = format!(
            "[image]\nwidth = 8\nheight = 8\nsamples = 64\nmax_depth = 2\n\
             [integrator]\ntype = \"path\"\n\
             [camera]\nposition = [0, 5, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nfov = 20\n\
             [environment]\ntype = \"image\"\nfile = \"sky.exr\"\nrotate = {rotate}\n\
             [materials.m]\ntype = \"diffuse\"\ncolor = {albedo}\n\
             [[objects]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"m\"\n"
        );
        let scene = load(&text, &dir);
        // Irradiance on the floor, E = integral of L cos(theta) over the upper hemisphere,
        // by the midpoint rule on a grid far finer than the texels; out goes albedo E / pi.
        let env = scene.environment().unwrap();
        let e = floor_irradiance(|d| env.radiance(d));
        let expect = e * (albedo / PI);
        let got = mean(&image(&scene, &PathTracer).pixels);
        for (g, x) in got.to_array().into_iter().zip(expect.to_array()) {
            assert!(
                (g - x).abs() < 0.01 * x,
                "rotate {rotate}: floor {got:?}, the integral gives {expect:?}"
            );
        }
    }
}

/// The radiance seen straight along `look` from the origin, through one pixel, with
/// `rotate`, where the image's red is u and its green v.
fn seen(dir: &Path, look: [f32; 3], up: [f32; 3], rotate: &str) -> Color {
    let text = format!(
        "[image]\nwidth = 1\nheight = 1\nsamples = 1\nfilter = {{ type = \"box\" }}\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = {look:?}\nup = {up:?}\nfov = 1\n\
         [environment]\ntype = \"image\"\nfile = \"uv.exr\"\nrotate = {rotate}\n\
         [[lights]]\ntype = \"point\"\nposition = [0, -90, 0]\n\
         [materials.m]\ncolor = 1\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, -100, 0]\nradius = 1\nmaterial = \"m\"\n"
    );
    image(&load(&text, dir), &Whitted).pixels[0]
}

#[test]
fn the_image_faces_as_documented_and_rotate_turns_it() {
    let dir = scratch("env-uv");
    // Red is u and green v at each texel's centre: bilinear lookup gives back (u, v) exactly
    // away from the seam.
    let (w, h) = (64u32, 32u32);
    write_exr(&dir.join("uv.exr"), w, h, |x, y| {
        [
            (x as f32 + 0.5) / w as f32,
            (y as f32 + 0.5) / h as f32,
            1.0,
        ]
    });
    let close = |c: Color, u: f32, v: f32, what: &str| {
        assert!(
            (c.x - u).abs() < 0.01 && (c.y - v).abs() < 0.01,
            "{what}: sees (u, v) = ({}, {}), not ({u}, {v})",
            c.x,
            c.y
        );
    };
    let none = "[0, 0, 0]";
    close(
        seen(&dir, [0.0, 0.0, -1.0], [0.0, 1.0, 0.0], none),
        0.5,
        0.5,
        "-z",
    );
    close(
        seen(&dir, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], none),
        0.75,
        0.5,
        "+x",
    );
    close(
        seen(&dir, [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], none),
        0.25,
        0.5,
        "-x",
    );
    close(
        seen(&dir, [0.0, 1.0, -1.0], [0.0, 1.0, 0.0], none),
        0.5,
        0.25,
        "45 degrees up",
    );
    close(
        seen(&dir, [1.0, -1.0, 0.0], [0.0, 1.0, 0.0], none),
        0.75,
        0.75,
        "45 degrees down",
    );
    // `[0, 90, 0]` brings what faced -z to face -x.
    let turned = "[0, 90, 0]";
    close(
        seen(&dir, [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], turned),
        0.5,
        0.5,
        "turned, -x",
    );
    // The same turn brings what faced +x (u = 3/4) to face -z, and -x (u = 1/4) to +z.
    close(
        seen(&dir, [0.0, 0.0, -1.0], [0.0, 1.0, 0.0], turned),
        0.75,
        0.5,
        "turned, -z",
    );
    close(
        seen(&dir, [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], turned),
        0.25,
        0.5,
        "turned, +z",
    );
}

#[test]
fn a_hidden_environment_still_lights_the_scene() {
    let dir = scratch("env-hidden");
    write_exr(&dir.join("sky.exr"), 64, 32, sky);
    let text = |visible: bool| {
        format!(
            "[image]\nwidth = 16\nheight = 16\nsamples = 1\nfilter = {{ type = \"box\" }}\nbackground = [1, 0, 1]\n\
             [integrator]\ntype = \"path\"\n\
             [camera]\nposition = [0, 2, 4]\nlook_at = [0, 0, 0]\nfov = 60\n\
             [environment]\ntype = \"image\"\nfile = \"sky.exr\"\nvisible = {visible}\n\
             [materials.m]\ncolor = 0.5\n\
             [[objects]]\ntype = \"rectangle\"\ncorner = [-2, 0, -2]\nedge_u = [4, 0, 0]\nedge_v = [0, 0, 4]\nmaterial = \"m\"\n"
        )
    };
    let shown = image(&load(&text(true), &dir), &PathTracer);
    let hidden = image(&load(&text(false), &dir), &PathTracer);
    let (mut floor, mut sky, mut lit) = (0, 0, Color::ZERO);
    for (a, b) in shown.pixels.iter().zip(&hidden.pixels) {
        if *b == Color::new(1.0, 0.0, 1.0) {
            // Where the camera sees past the floor: the background, not the sky.
            assert_ne!(a, b);
            sky += 1;
        } else {
            // The floor: lit the same, bit for bit.
            assert_eq!(a, b);
            lit += *a;
            floor += 1;
        }
    }
    assert!(floor > 20 && sky > 20, "{floor} floor and {sky} sky pixels");
    let lit = lit / floor as f32;
    assert!(lit.min_element() > 0.1, "the floor is unlit: {lit:?}");
}

#[test]
fn whitted_shows_it_behind_the_scene_and_in_mirrors() {
    let dir = scratch("env-whitted");
    write_exr(&dir.join("uv.exr"), 64, 32, |x, y| {
        [(x as f32 + 0.5) / 64.0, (y as f32 + 0.5) / 32.0, 1.0]
    });
    let text = "[image]\nwidth = 9\nheight = 9\nsamples = 1\nfilter = { type = \"box\" }\n\
         [camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov = 40\n\
         [environment]\ntype = \"image\"\nfile = \"uv.exr\"\n\
         [[lights]]\ntype = \"point\"\nposition = [0, 5, 5]\n\
         [materials.mirror]\ncolor = 0\ndiffuse = 0\nspecular = 0\nambient = 0\nreflectivity = 1\n\
         [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"mirror\"\n";
    let img = image(&load(text, &dir), &Whitted);
    // The middle pixel looks at the mirror head-on and sees straight back, along +z: v is
    // 1/2 there (u is at the seam).
    let middle = img.pixels[4 * 9 + 4];
    assert!(
        (middle.y - 0.5).abs() < 0.01,
        "the mirror's middle: {middle:?}"
    );
    // A corner pixel misses the mirror and sees the environment itself, above and to the
    // left of -z: u below 1/2, v below 1/2.
    let corner = img.pixels[0];
    assert!(
        corner.x < 0.5 && corner.y < 0.5 && corner.z == 1.0,
        "the corner: {corner:?}"
    );
}
