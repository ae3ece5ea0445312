//! Dispersion: glass whose index changes with wavelength, proven against Snell's law (a
//! prism's deviation per wavelength, through the renderer's own BSDF), the white furnace
//! (a dispersive ball under a uniform sky stays white under the path tracer and
//! bidirectionally), and a slab with parallel faces, which must pass white light white.

use snell::film::Image;
use snell::integrator::{Path as PathTracer, Whitted};
use snell::material::dispersion::Dispersion;
use snell::math::{Color, Vec2, Vec3A, Wavelength};
use snell::render::{RenderOptions, render, render_with};
use snell::scene::{Format, Scene, load_str};
use std::path::Path;

fn scene(text: &str) -> Scene {
    load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// A whole render on two threads.
fn two_threads() -> RenderOptions<'static> {
    RenderOptions {
        threads: Some(2),
        progress: &|_| {},
        cancel: None,
        region: None,
    }
}

fn mean(img: &Image, x: std::ops::Range<u32>, y: std::ops::Range<u32>) -> Color {
    let mut sum = Color::ZERO;
    let mut n = 0;
    for y in y {
        for x in x.clone() {
            sum += img.get(x, y);
            n += 1;
        }
    }
    sum / n as f32
}

/// The direction a ray along `d` takes into (or out of) glass across a face of outward
/// normal `n`, by sampling the material's BSDF at wavelength `nm` (the refracted lobe
/// chosen): the renderer's own refraction, in a frame about the normal.
fn refract_by_bsdf(scene: &Scene, d: Vec3A, n: Vec3A, nm: f32) -> Vec3A {
    let m = &scene.materials[0];
    let p = snell::texture::TexturePoint::at(Vec3A::ZERO);
    let bsdf = m.bsdf_at(&scene.textures, &p, Color::ONE, Some(nm));
    let frame = snell::math::Frame::from_axis(n);
    // The BSDF's `wo` points back along the ray; the ray goes on along the sampled `wi`
    // (where its light comes from).
    let wo = frame.to_local(-d);
    let s = bsdf
        .sample(wo, Vec2::new(0.5, 0.5), 0.999_999)
        .expect("a smooth dielectric samples");
    assert!(s.wi.z * wo.z < 0.0, "the refracted lobe, through the face");
    frame.to_world(s.wi).normalize()
}

/// A 60-degree prism of BK7 in the plane z = 0: a ray meets its first face at 50 degrees
/// and leaves by the second. Its deviation, found by the BSDF's refraction at the two faces,
/// is the textbook prism formula's with the glass's Sellmeier index at each wavelength, and
/// violet bends more than red by the catalogue's amount.
#[test]
fn a_prism_deviates_each_wavelength_as_snell_says() {
    let scene = scene(
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
         [materials.g]\ntype = \"dielectric\"\nior = \"BK7\"\n\
         [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"g\"\n",
    );
    let bk7 = Dispersion::named("BK7").unwrap();
    let apex = 60f32.to_radians();
    // The faces' outward normals: the first tilted back by half the apex from -x, the
    // second forward.
    let half = apex / 2.0;
    let n1 = Vec3A::new(-half.cos(), half.sin(), 0.0);
    let n2 = Vec3A::new(half.cos(), half.sin(), 0.0);
    let theta1 = 50f32.to_radians();
    // The incoming ray makes theta1 with -n1, turned toward the base.
    let d = {
        let t = Vec3A::new(-n1.y, n1.x, 0.0); // along the face, toward the apex
        (-n1 * theta1.cos() - t * theta1.sin()).normalize()
    };
    let mut deviations = vec![];
    for nm in [400.0f32, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0] {
        let inside = refract_by_bsdf(&scene, d, n1, nm);
        let out = refract_by_bsdf(&scene, inside, n2, nm);
        let measured = d.dot(out).clamp(-1.0, 1.0).acos();
        let n = bk7.ior(nm);
        let r1 = (theta1.sin() / n).asin();
        let r2 = apex - r1;
        let theta2 = (n * r2.sin()).asin();
        let expected = theta1 + theta2 - apex;
        assert!(
            (measured - expected).abs() < 2e-4,
            "{nm} nm: deviation {} degrees against {}",
            measured.to_degrees(),
            expected.to_degrees()
        );
        deviations.push(measured);
    }
    assert_eq!(deviations.len(), 7);
    assert!(deviations.windows(2).all(|w| w[0] > w[1]), "{deviations:?}");
    // Violet (400 nm) to red (700 nm): about 1.2 degrees for BK7 at this incidence.
    let spread = (deviations[0] - deviations[6]).to_degrees();
    assert!((0.9..1.6).contains(&spread), "spread {spread} degrees");
}

/// A furnace: a ball of `ior` in a uniform environment of radiance 1 with `integrator`;
/// the mean of the middle 4 x 4 pixels, which see the ball.
fn furnace(ior: &str, integrator: &str, spp: u32) -> Color {
    let text = format!(
        "[image]\nwidth = 12\nheight = 12\nsamples = {spp}\nmax_depth = 64\n\
         [integrator]\ntype = \"{integrator}\"\n\
         [camera]\nposition = [0, 0, 6]\nlook_at = [0, 0, 0]\nfov = 30\n\
         [environment]\ntype = \"constant\"\ncolor = 1\n\
         [materials.ball]\ntype = \"dielectric\"\nior = {ior}\n\
         [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"ball\"\n"
    );
    let scene = scene(&text);
    assert!(scene.disperses());
    let img = match integrator {
        "path" => render(&scene, &PathTracer, Some(2), &|_| {}).unwrap().image,
        _ => {
            let options = two_threads();
            snell::render::bdpt::render_bdpt(&scene, &options)
                .unwrap()
                .image
        }
    };
    mean(&img, 4..8, 4..8)
}

/// Lossless dispersive glass loses nothing and adds no colour: each wavelength's paths all
/// come out to the same sky, and the wavelengths' weights average to white. Within 1 % per
/// channel, for a crown glass, a dense flint and diamond, under the path tracer and
/// bidirectionally.
#[test]
fn a_dispersive_ball_in_the_white_furnace_stays_white() {
    let mut checked = 0;
    for (ior, integrator, spp) in [
        ("\"BK7\"", "path", 256),
        ("\"SF11\"", "path", 256),
        ("\"diamond\"", "path", 256),
        ("\"diamond\"", "bdpt", 256),
        ("{ cauchy = [1.5, 0.02] }", "path", 256),
    ] {
        let m = furnace(ior, integrator, spp);
        assert!(
            (m - Color::ONE).abs().max_element() < 0.01,
            "{ior} under {integrator}: {m}"
        );
        checked += 1;
    }
    assert_eq!(checked, 5);
}

/// A slab of dense flint with parallel faces in front of a white light: every wavelength
/// leaves parallel to how it came, so the light through it is white but for the two faces'
/// Fresnel reflections, which take a little more blue (the index is higher there). Each
/// channel is the transmission at each wavelength, `(1 - F) / (1 + F)` with all the
/// reflections between the faces, weighed by the channel's basis: about 0.85, blue 1.5 %
/// under red. Under the path tracer, and under Whitted (whose samples each follow one
/// wavelength).
#[test]
fn white_light_through_a_parallel_slab_stays_white() {
    let text = |integrator: &str, spp: u32| {
        format!(
            "[image]\nwidth = 8\nheight = 8\nsamples = {spp}\nmax_depth = 16\nbackground = 0\n\
             [integrator]\ntype = \"{integrator}\"\n\
             [camera]\nposition = [0, 0, 10]\nlook_at = [0, 0, 0]\nfov = 10\n\
             [materials.flint]\ntype = \"dielectric\"\nior = \"SF11\"\n\
             [materials.lamp]\ntype = \"diffuse\"\ncolor = 0\nemission = 1\n\
             [[objects]]\ntype = \"box\"\nmin = [-5, -5, -0.5]\nmax = [5, 5, 0.5]\nmaterial = \"flint\"\n\
             [[objects]]\ntype = \"rectangle\"\ncorner = [-20, -20, -5]\nedge_u = [40, 0, 0]\nedge_v = [0, 40, 0]\nmaterial = \"lamp\"\n"
        )
    };
    let sf11 = Dispersion::named("SF11").unwrap();
    let mut expected = Color::ZERO;
    for nm in 360..830 {
        let nm = nm as f32 + 0.5;
        let n = sf11.ior(nm);
        let f = ((n - 1.0) / (n + 1.0)).powi(2);
        expected += Wavelength::basis(nm) * ((1.0 - f) / (1.0 + f));
    }
    assert!(expected.x - expected.z > 0.005, "{expected}");
    let mut checked = 0;
    for (integrator, spp) in [("whitted", 4096u32), ("path", 4096)] {
        let scene = scene(&text(integrator, spp));
        let img = match integrator {
            "path" => render(&scene, &PathTracer, Some(2), &|_| {}).unwrap().image,
            _ => {
                let options = two_threads();
                render_with(&scene, &Whitted, &options, None).unwrap().image
            }
        };
        let m = mean(&img, 2..6, 2..6);
        assert!(
            (m - expected).abs().max_element() < 0.006,
            "{integrator}: {m} against {expected}"
        );
        checked += 1;
    }
    assert_eq!(checked, 2);
}

/// scenes/prism.toml: the beam through the prism lands on the screen as a spectrum, violet
/// bent most (toward the screen's far, left edge in the picture), red least. Light tracing
/// finds the beam on the screen alone; the centroids of the picture's blue and red light
/// there lie apart in that order.
#[test]
fn the_prism_scene_splits_white_light_in_order() {
    let mut scene = snell::scene::load(&super::repo("scenes/prism.toml")).unwrap();
    assert!(scene.disperses());
    scene.settings.width = 240;
    scene.settings.height = 160;
    scene.settings.spp = 8;
    let options = two_threads();
    let img = snell::render::light::render_light(&scene, &options)
        .unwrap()
        .image;
    // Where the beam lands: the brightest pixels, far above the room's light.
    let peak = img
        .pixels
        .iter()
        .map(|c| c.max_element())
        .fold(0.0, f32::max);
    let (mut red, mut blue) = ((0.0f64, 0.0f64), (0.0f64, 0.0f64));
    let mut lit = 0;
    for y in 0..img.height {
        for x in 0..img.width {
            let c = img.get(x, y);
            if c.max_element() < 0.2 * peak {
                continue;
            }
            lit += 1;
            red.0 += (c.x * x as f32) as f64;
            red.1 += c.x as f64;
            blue.0 += (c.z * x as f32) as f64;
            blue.1 += c.z as f64;
        }
    }
    assert!(lit > 20, "{lit} pixels of beam");
    let (red_x, blue_x) = (red.0 / red.1, blue.0 / blue.1);
    assert!(red_x - blue_x > 4.0, "red at x = {red_x}, blue at {blue_x}");
}

/// `snell explain --sample K` of a pixel seen through dispersive glass under Whitted follows
/// the wavelength the render gave that sample: the mean of a pixel's samples explained is
/// the rendered pixel, to rounding. A ray through a pixel's centre, which is no sample,
/// follows a wavelength of its own, and through the glass its colour is another.
#[test]
fn whitted_explains_each_sample_at_the_renders_wavelength() {
    let scene = scene(
        "[image]\nwidth = 12\nheight = 12\nsamples = 4\nmax_depth = 8\nbackground = 0\n\
         filter = { type = \"box\" }\n\
         [camera]\nposition = [0, 0, 6]\nlook_at = [0, 0, 0]\nfov = 20\n\
         [materials.diamond]\ntype = \"dielectric\"\nior = \"diamond\"\n\
         [textures.stripes]\ntype = \"stripes\"\na = [1, 0.1, 0.1]\nb = [0.1, 0.2, 1]\nwidth = 0.15\n\
         mapping = { type = \"planar\", u = [1, 0, 0], v = [0, 1, 0] }\n\
         [materials.stripes]\ntype = \"diffuse\"\ntexture = \"stripes\"\n\
         [[lights]]\ntype = \"point\"\nposition = [0, 0, 8]\nintensity = 80\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.9\nmaterial = \"diamond\"\n\
         [[objects]]\ntype = \"rectangle\"\ncorner = [-6, -6, -3]\nedge_u = [12, 0, 0]\nedge_v = [0, 12, 0]\nmaterial = \"stripes\"\n",
    );
    assert!(scene.disperses());
    let img = render_with(&scene, &Whitted, &two_threads(), None)
        .unwrap()
        .image;
    let s = &scene.settings;
    let (mut checked, mut centre_differs) = (0, 0);
    for y in 0..s.height {
        for x in 0..s.width {
            let mut films = vec![];
            snell::render::for_each_sample(s, x, y, |px, py, _| films.push((px, py)));
            assert_eq!(films.len(), 4);
            let mut sum = Color::ZERO;
            for (k, &film) in films.iter().enumerate() {
                let sample = Some(((x, y), k as u32));
                sum += snell::explain_pixel::whitted(&scene, film, sample, 10_000)
                    .unwrap()
                    .color;
            }
            let (explained, rendered) = (sum / 4.0, img.get(x, y));
            assert!(
                (explained - rendered).abs().max_element() <= 1e-5 * rendered.max_element() + 1e-7,
                "pixel {x},{y}: explained {explained}, rendered {rendered}"
            );
            // The same rays at the wavelengths of rays that are no samples.
            let mut other = Color::ZERO;
            for &film in &films {
                other += snell::explain_pixel::whitted(&scene, film, None, 10_000)
                    .map_or(Color::ZERO, |e| e.color);
            }
            if ((other / 4.0) - rendered).abs().max_element() > 1e-3 {
                centre_differs += 1;
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 144);
    assert!(centre_differs >= 10, "{centre_differs} pixels");
}
