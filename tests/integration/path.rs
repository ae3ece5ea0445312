//! The path tracer proven on scenes with known answers: white furnaces (a convex object
//! under a uniform environment of radiance 1, whose every pixel must come out as the
//! environment or, for surfaces that lose energy, just under it), pbrt's closed emitting
//! sphere, and the Cornell box against a stored reference made by snell itself (a per-pixel
//! z-test), with the Sobol and the independent sampler agreeing.

use super::repo;
use snell::film::Image;
use snell::integrator::Path as PathTracer;
use snell::math::Color;
use snell::render::render;
use snell::sampler::SamplerKind;
use snell::scene::{Format, load_str};
use std::path::Path;

/// Renders a scene given as TOML text with the path tracer.
fn render_text(text: &str) -> Image {
    let scene = load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    render(&scene, &PathTracer, Some(2), &|_| {}).unwrap().image
}

/// A sphere of `material` (TOML keys) in a uniform environment of radiance 1, seen from 4
/// units away through a field of view of `fov` degrees (25: the whole sphere and some
/// environment around it; 2: only the middle of the sphere, seen head-on).
fn furnace(material: &str, spp: u32, fov: f32) -> Image {
    render_text(&format!(
        "[image]\nwidth = 12\nheight = 12\nsamples = {spp}\nbackground = 1\nmax_depth = 64\n\
         [integrator]\ntype = \"path\"\n\
         [camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov = {fov}\n\
         [materials.m]\n{material}\n\
         [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n"
    ))
}

fn mean(img: &Image) -> Color {
    img.pixels.iter().copied().sum::<Color>() / img.pixels.len() as f32
}

/// A white Lambertian sphere returns every bit of the environment it is lit by: each path
/// bounces once, with weight exactly 1, and leaves; every pixel is 1 to rounding.
#[test]
fn white_furnace_diffuse() {
    let img = furnace("type = \"diffuse\"\ncolor = 1", 16, 25.0);
    for (i, p) in img.pixels.iter().enumerate() {
        assert!(
            (*p - Color::ONE).abs().max_element() < 1e-4,
            "pixel {i}: {p}"
        );
    }
    // A grey one returns its albedo.
    let img = furnace("type = \"diffuse\"\ncolor = 0.5", 16, 25.0);
    // The corners see the environment (1), the middle the sphere (0.5).
    let centre = img.pixels[(6 * 12 + 6) as usize];
    assert!(
        (centre - Color::splat(0.5)).abs().max_element() < 1e-4,
        "{centre}"
    );
}

/// Smooth glass without absorption loses nothing: light is split between reflection and
/// refraction, concentrated going in and spread coming out, and all of it leaves again. The
/// image converges to 1 (Russian roulette and depth 64 add noise and a negligible loss).
#[test]
fn white_furnace_smooth_and_rough_dielectric() {
    let img = furnace("type = \"dielectric\"\nior = 1.5", 64, 25.0);
    let m = mean(&img);
    assert!(
        (m - Color::ONE).abs().max_element() < 0.01,
        "smooth glass: {m}"
    );
    for (i, p) in img.pixels.iter().enumerate() {
        assert!(
            (*p - Color::ONE).abs().max_element() < 0.1,
            "pixel {i}: {p}"
        );
    }
    // A rough one loses what single-scattering microfacets lose (light that would bounce
    // between facets) at each of the crossings a path makes: never a gain, and at this
    // roughness less than a tenth.
    let m = mean(&furnace(
        "type = \"dielectric\"\nior = 1.5\nroughness = 0.1",
        64,
        25.0,
    ));
    assert!(
        m.max_element() < 1.005 && m.min_element() > 0.9,
        "rough glass: {m}"
    );
}

/// The directional albedo at normal incidence of a GGX conductor with Fresnel 1, by
/// sampling the BSDF on its own (the scene-free answer the furnace must reproduce).
fn rough_mirror_albedo(alpha: f32) -> f32 {
    use snell::bsdf::{Bsdf, Conductor, ConductorFresnel, microfacet::Ggx};
    let b = Bsdf::Conductor(Conductor {
        fresnel: ConductorFresnel::One,
        distribution: Ggx::isotropic(alpha),
        tint: Color::ONE,
    });
    let mut rng = snell::math::Rng::new(3);
    let n = 1 << 20;
    let mut sum = 0.0f64;
    for _ in 0..n {
        let u = snell::math::Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(s) = b.sample(snell::math::Vec3A::Z, u, 0.5) {
            sum += (s.f.x * s.wi.z / s.pdf) as f64;
        }
    }
    (sum / n as f64) as f32
}

/// A rough conductor whose Fresnel term is 1 (no `metal`, no `eta` and `k`) reflects all
/// but the energy single-scattering GGX loses between facets. Seen head-on through a narrow
/// field of view, every pixel is the BSDF's albedo at normal incidence (each path bounces
/// once off the convex sphere and leaves); smooth, it is a perfect mirror, exactly 1.
#[test]
fn white_furnace_rough_conductor() {
    for alpha in [0.1f32, 0.3] {
        let want = rough_mirror_albedo(alpha);
        assert!(want < 1.0 && want > 0.8, "alpha {alpha}: {want}");
        let img = furnace(
            &format!("type = \"conductor\"\nroughness = {alpha}"),
            256,
            2.0,
        );
        for (i, p) in img.pixels.iter().enumerate() {
            assert!(
                (*p - Color::splat(want)).abs().max_element() < 0.01,
                "alpha {alpha}, pixel {i}: {p}, the albedo {want}"
            );
        }
    }
    let img = furnace("type = \"conductor\"", 4, 25.0);
    for (i, p) in img.pixels.iter().enumerate() {
        assert!(
            (*p - Color::ONE).abs().max_element() < 1e-4,
            "pixel {i}: {p}"
        );
    }
}

/// The `metallic` type (glTF's material) is linear in its metallic value: in a furnace, a
/// sphere that is 0.3 metal returns 0.3 of what the metal returns and 0.7 of what the
/// plastic does, for a coloured rough surface seen head-on.
#[test]
fn white_furnace_metallic_blends_its_parts() {
    let at = |metallic: f32| {
        mean(&furnace(
            &format!(
                "type = \"metallic\"\ncolor = [0.9, 0.5, 0.2]\nroughness = 0.3\nmetallic = {metallic}"
            ),
            256,
            2.0,
        ))
    };
    let (plastic, metal, blend) = (at(0.0), at(1.0), at(0.3));
    let want = metal * 0.3 + plastic * 0.7;
    assert!(
        (blend - want).abs().max_element() < 0.01,
        "{blend} against {want} (metal {metal}, plastic {plastic})"
    );
    // The two parts differ enough for that to say something.
    assert!(
        (metal - plastic).abs().max_element() > 0.1,
        "{metal} {plastic}"
    );
}

/// pbrt's closed sphere: seen from inside, a sphere of albedo 0.5 emitting 0.5 shows
/// 0.5 (1 + 0.5 + 0.25 + ...) = 1 everywhere. Light sampling (the sphere is an area light,
/// sampled by area from inside) and BSDF sampling both find the emission, so this tests
/// their MIS weights summing to one.
#[test]
fn closed_sphere_sees_exactly_one() {
    let img = render_text(
        "[image]\nwidth = 8\nheight = 8\nsamples = 64\nbackground = 0\nmax_depth = 64\n\
         [integrator]\ntype = \"path\"\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 60\n\
         [materials.m]\ntype = \"diffuse\"\ncolor = 0.5\nemission = 0.5\ntwo_sided = true\n\
         [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n",
    );
    let m = mean(&img);
    assert!((m - Color::ONE).abs().max_element() < 0.01, "{m}");
    for (i, p) in img.pixels.iter().enumerate() {
        assert!(
            (*p - Color::ONE).abs().max_element() < 0.06,
            "pixel {i}: {p}"
        );
    }
}

/// The Cornell box (scenes/cornell.toml, the same as Mitsuba's) at 32 x 32.
fn cornell(spp: u32, seed: u64, sampler: SamplerKind) -> Image {
    let mut scene = snell::scene::load(&repo("scenes/cornell.toml")).unwrap();
    let s = &mut scene.settings;
    (s.width, s.height, s.spp, s.seed) = (32, 32, spp, seed);
    s.integrator.sampler = sampler;
    render(&scene, &PathTracer, Some(2), &|_| {}).unwrap().image
}

/// tests/data/cornell-32-ref.exr: the Cornell box at 32 x 32, 65536 samples per pixel of the
/// independent sampler, made by
/// `snell render scenes/cornell.toml --width 32 --height 32 --spp 65536 --sampler independent --seed 1000 -o tests/data/cornell-32-ref.exr`.
fn cornell_reference() -> Vec<[f32; 3]> {
    read_32("tests/data/cornell-32-ref.exr")
}

/// A 32 x 32 EXR of the repository.
fn read_32(path: &str) -> Vec<[f32; 3]> {
    let img = image::open(repo(path))
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .to_rgb32f();
    assert_eq!((img.width(), img.height()), (32, 32));
    img.pixels().map(|p| p.0).collect()
}

/// Sixteen independent renders of the Cornell box give each pixel a mean and a standard
/// error; against the stored reference, each channel's z-score must be what noise alone
/// gives: only a handful beyond 4, none beyond 8, and no shift of their mean (a bias of a
/// few percent anywhere in the image fails this).
#[test]
fn cornell_box_agrees_per_pixel_with_its_reference() {
    let scene = snell::scene::load(&repo("scenes/cornell.toml")).unwrap();
    agrees_with_the_reference(scene);
}

/// The Cornell box against Mitsuba 3.9.1's own render of its `cornell_box()`
/// (tests/data/mitsuba/cornell-32.exr, 65536 samples a pixel, written by
/// cornell_fixture.py beside it), by the same per-pixel z-test: snell's path tracer gives
/// Mitsuba's picture, up to noise, pixel by pixel.
#[test]
fn cornell_box_agrees_per_pixel_with_mitsubas() {
    let scene = snell::scene::load(&repo("scenes/cornell.toml")).unwrap();
    agrees_with(scene, &read_32("tests/data/mitsuba/cornell-32.exr"));
}

/// [`cornell_box_agrees_per_pixel_with_its_reference`]'s z-test of `scene` (the Cornell box,
/// perhaps built another way) against the stored reference.
fn agrees_with_the_reference(scene: snell::scene::Scene) {
    agrees_with(scene, &cornell_reference());
}

/// The z-test of `scene` against `reference`.
fn agrees_with(mut scene: snell::scene::Scene, reference: &[[f32; 3]]) {
    const K: usize = 16;
    let renders: Vec<Image> = (0..K)
        .map(|k| {
            let s = &mut scene.settings;
            (s.width, s.height, s.spp, s.seed) = (32, 32, 64, k as u64);
            s.integrator.sampler = SamplerKind::Independent;
            render(&scene, &PathTracer, Some(2), &|_| {}).unwrap().image
        })
        .collect();
    let (mut z_sum, mut z_count, mut beyond4, mut worst) = (0.0f64, 0usize, 0usize, 0.0f64);
    for (i, want) in reference.iter().enumerate() {
        for c in 0..3 {
            let v: Vec<f64> = renders
                .iter()
                .map(|r| r.pixels[i].to_array()[c] as f64)
                .collect();
            let m = v.iter().sum::<f64>() / K as f64;
            let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (K - 1) as f64;
            let want = want[c] as f64;
            if var == 0.0 {
                // Outside the box, and inside the light: the same in every sample.
                assert!(
                    (m - want).abs() <= 1e-4 * want.max(1.0),
                    "pixel {i}: {m} vs {want}"
                );
                continue;
            }
            let z = (m - want) / (var / K as f64).sqrt();
            z_sum += z;
            z_count += 1;
            beyond4 += (z.abs() > 4.0) as usize;
            worst = worst.max(z.abs());
        }
    }
    let z_mean = z_sum / z_count as f64;
    assert!(z_count > 2500, "{z_count} noisy values");
    assert!(
        beyond4 <= z_count / 100 && worst < 8.0 && z_mean.abs() < 0.15,
        "{beyond4} of {z_count} beyond 4, worst {worst:.2}, mean z {z_mean:.3}"
    );
}

/// The Cornell box's light as a mesh of two emitting triangles (an OBJ file), whose
/// triangles light sampling picks by power: the picture is the reference's, whether the
/// light's emission comes from the scene's material or from the MTL file's `Ke`, and for a
/// mesh mirrored by its transform (its file's winding reversed to face down all the same).
#[test]
fn cornell_box_with_a_mesh_light_agrees_with_its_reference() {
    let dir = super::scratch("mesh-light");
    let text = std::fs::read_to_string(repo("scenes/cornell.toml")).unwrap();
    let rect = "type = \"rectangle\"\ncorner = [-0.23, 0.99, -0.18]\nedge_u = [0.46, 0, 0]\nedge_v = [0, 0, 0.38]\nmaterial = \"light\"\n";
    assert!(
        text.contains(rect),
        "the light is where this test expects it"
    );
    // The quad's corners, x mirrored or not; faces wound to face down in the world.
    let quad = |mirror: f32, faces: &str| {
        let x = |v: f32| v * mirror;
        format!(
            "mtllib lamp.mtl\nv {} 0.99 -0.18\nv {} 0.99 -0.18\nv {} 0.99 0.20\nv {} 0.99 0.20\nusemtl lamp\n{faces}\n",
            x(-0.23),
            x(0.23),
            x(0.23),
            x(-0.23)
        )
    };
    std::fs::write(dir.join("lamp.obj"), quad(1.0, "f 1 2 3 4")).unwrap();
    std::fs::write(dir.join("mirrored.obj"), quad(-1.0, "f 1 4 3 2")).unwrap();
    std::fs::write(
        dir.join("lamp.mtl"),
        "newmtl lamp\nKd 0.885809 0.698859 0.666422\nKe 18.387 13.9873 6.75357\nillum 1\n",
    )
    .unwrap();
    for object in [
        "type = \"mesh\"\nfile = \"lamp.obj\"\nmaterial = \"light\"\n",
        "type = \"mesh\"\nfile = \"lamp.obj\"\n",
        "type = \"mesh\"\nfile = \"mirrored.obj\"\ntransform = { scale = [-1, 1, 1] }\n",
    ] {
        let scene = load_str(
            &text.replace(rect, object),
            &dir.join("cornell.toml"),
            &dir,
            Format::Toml,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let unused = "material `light` is defined but no object uses it";
        assert!(
            scene.warnings.iter().all(|w| w == unused),
            "{:?}",
            scene.warnings
        );
        let light = scene.objects.len() - 3;
        assert_eq!(scene.objects[light].name, "light");
        let lamps: Vec<_> = scene.area_lights().filter(|l| l.object == light).collect();
        assert_eq!(lamps.len(), 2, "one light per triangle: {object}");
        let area: f32 = lamps.iter().map(|l| l.emitter.area()).sum();
        assert!((area - 0.46 * 0.38).abs() < 1e-5, "{area}");
        agrees_with_the_reference(scene);
    }
}

/// The Sobol and the independent sampler estimate the same image: their means over the
/// Cornell box agree within their noise, and Sobol's error against the reference is the
/// smaller at the same sample count.
#[test]
fn sobol_and_independent_agree() {
    let reference = cornell_reference();
    let rmse = |img: &Image| {
        let sum: f64 = img
            .pixels
            .iter()
            .zip(&reference)
            .map(|(p, r)| {
                (0..3)
                    .map(|c| (p.to_array()[c] as f64 - r[c] as f64).powi(2))
                    .sum::<f64>()
            })
            .sum();
        (sum / (3 * reference.len()) as f64).sqrt()
    };
    let sobol = cornell(256, 1, SamplerKind::Sobol);
    let independent = cornell(256, 1, SamplerKind::Independent);
    let (ms, mi) = (mean(&sobol), mean(&independent));
    assert!(
        ((ms - mi).abs() / mi).max_element() < 0.01,
        "Sobol {ms}, independent {mi}"
    );
    let (es, ei) = (rmse(&sobol), rmse(&independent));
    assert!(es < ei, "RMSE Sobol {es}, independent {ei}");
}

/// Any number of samples per pixel, and the same bytes at any thread count.
#[test]
fn any_sample_count_and_the_same_image_at_any_thread_count() {
    let mut scene = snell::scene::load(&repo("scenes/cornell.toml")).unwrap();
    let s = &mut scene.settings;
    (s.width, s.height, s.spp) = (20, 12, 7);
    let one = render(&scene, &PathTracer, Some(1), &|_| {}).unwrap();
    let two = render(&scene, &PathTracer, Some(2), &|_| {}).unwrap();
    assert_eq!(one.image.pixels, two.image.pixels);
    assert_eq!(one.rays.camera, 20 * 12 * 7);
    assert_eq!(one.bad_samples.count, 0);
}

/// The error the progress bar shows, estimated from each pixel's spread, is the error the
/// picture has: the Cornell box after 16 and after 64 samples, against the stored reference
/// (whose own noise is a thirtieth of theirs), by the mean relative difference in luminance,
/// averaged over eight seeds (one picture's error swings with its fireflies), within 15 %;
/// and it falls as the samples grow.
#[test]
fn the_estimated_error_is_the_pictures_error() {
    use snell::film::Film;
    use snell::math::luminance;
    use snell::render::RenderOptions;
    use snell::render::progressive::{Until, render_progressive};
    let reference = cornell_reference();
    let mut scene = snell::scene::load(&repo("scenes/cornell.toml")).unwrap();
    let options = RenderOptions {
        threads: Some(2),
        progress: &|_| {},
        cancel: None,
        region: None,
    };
    let mut last = f64::INFINITY;
    for spp in [16, 64] {
        let (mut estimated, mut actual) = (0.0f64, 0.0f64);
        for seed in 0..8 {
            let s = &mut scene.settings;
            (s.width, s.height, s.spp, s.seed) = (32, 32, spp, seed);
            s.integrator.sampler = SamplerKind::Independent;
            let mut film = Film::new(32, 32);
            let until = Until {
                spp,
                time: None,
                noise: None,
            };
            render_progressive(
                &scene,
                &PathTracer,
                &mut film,
                until,
                &options,
                &mut |_, _| {},
            )
            .unwrap();
            estimated += film.estimated_error().unwrap() as f64;
            let (mut diff, mut sum) = (0.0f64, 0.0f64);
            for (p, r) in film.image().pixels.iter().zip(&reference) {
                let want = luminance(Color::from(*r)) as f64;
                diff += (luminance(*p) as f64 - want).abs();
                sum += want;
            }
            actual += diff / sum;
        }
        assert!(
            (estimated / actual - 1.0).abs() < 0.15,
            "{spp} spp: estimated {}, actual {}",
            estimated / 8.0,
            actual / 8.0
        );
        assert!(estimated < 0.6 * last, "{estimated} after {last}");
        last = estimated;
    }
}

/// Russian roulette is first played after bounce `rr_depth`, as Mitsuba's `depth >= rr_depth`
/// does (a path that never leaves a closed box, so every bounce happens): the first vertex
/// that records it is the `rr_depth`-th surface met, whose bounce is bounce `rr_depth`.
#[test]
fn roulette_starts_after_rr_depth_bounces_as_mitsubas() {
    let dir = super::scratch("roulette");
    let mut checked = 0;
    for rr in [1u32, 2, 5] {
        let scene = format!(
            "[image]\nwidth = 4\nheight = 4\nsamples = 1\nmax_depth = 40\n\
             [integrator]\ntype = \"path\"\nrr_depth = {rr}\n\
             [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\n\
             [materials.white]\ntype = \"diffuse\"\ncolor = 0.99\nemission = 0.1\n\
             [[objects]]\ntype = \"sphere\"\nradius = 5\nmaterial = \"white\"\n"
        );
        std::fs::write(dir.join("box.toml"), scene).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
            .args(["explain", "box.toml", "--pixel", "1,1", "--json"])
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let vertices = doc["path"]["vertices"].as_array().unwrap();
        assert!(
            vertices.len() > rr as usize,
            "rr_depth {rr}: {} vertices",
            vertices.len()
        );
        let first = vertices.iter().position(|v| !v["roulette"].is_null());
        assert_eq!(first, Some(rr as usize - 1), "rr_depth {rr}");
        checked += 1;
    }
    assert_eq!(checked, 3);
}
