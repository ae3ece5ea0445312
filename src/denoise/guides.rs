//! The auxiliary images a denoiser is guided by, made as Intel Open Image Denoise asks: per
//! pixel, the albedo (linear, in [0, 1]; a light's is its emission's colour, brightest
//! channel 1) and the world-space shading normal (each component in [-1, 1]) of the first
//! surface that is not a perfect mirror or smooth glass, reached
//! through those (their tint kept in the albedo), averaged over the pixel's samples placed as
//! the render places them (the same filter and sampler): so they are anti-aliased as the
//! picture is, and a mirror or a window shows what is behind it. A ray that meets nothing
//! gives the background's colour (clamped to 1) and a zero normal.
//!
//! The light a pixel sees emitted (a lamp seen directly or in a mirror) is kept too: the
//! denoiser leaves it out of what it filters, as the render sampled it, and adds it back
//! sharp: where it changes within a pixel's 3 x 3 neighbourhood (a lamp's edge, or the sharp
//! edges of a textured light's pattern) taken again over [`EDGE_SAMPLES`] samples, each a
//! guide's ray (through mirrors and glass, no shading), so that the edge's place in its
//! pixels is as exact as a converged render's instead of 16 samples'.
//!
//! Each ray goes on deterministically (glass by its refraction, unless that is total
//! internal reflection), so the guides carry no noise of their own, only the pixels' edges:
//! OIDN takes them as clean (`cleanAux`), which is what its prefiltering of noisy guides
//! would give them.

use crate::math::{Color, Frame, Ray, Vec2, Vec3A, offset_ray_origin};
use crate::render::{
    RenderError, RenderOptions, camera_ray, for_each_sample, start_sample, whitted_lens_sample,
};
use crate::sampler::Sampler;
use crate::scene::{Scene, Skip};

/// Samples a pixel's guides take at most (fewer where the render takes fewer), where the
/// render takes its samples from a sampler; Whitted's guides take all its strata.
pub const GUIDE_SAMPLES: u32 = 16;

/// Samples a pixel on a light's edge takes for [`Guides::sharp_light`].
pub const EDGE_SAMPLES: u32 = 256;

/// How much the light seen emitted must change within a pixel's 3 x 3 neighbourhood, as a
/// share of its brightest there, for the pixel to be on an edge: a sixteenth, one sample of
/// sixteen's coverage, so that the smooth changes of a textured light are not edges.
const EDGE_STEP: f32 = 1.0 / 16.0;

/// Perfect mirrors and smooth glass followed before a guide gives up (and records the last).
const MAX_DELTA_BOUNCES: u32 = 8;

/// A denoiser's guides, row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Guides {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Albedo, linear RGB in [0, 1].
    pub albedo: Vec<Color>,
    /// World-space shading normal facing the camera ray, averaged (so shorter than 1 where a
    /// pixel's samples disagree); zero where nothing is hit.
    pub normal: Vec<Vec3A>,
    /// The light the pixel's samples see emitted (directly, or through mirrors and glass),
    /// linear RGB, over the picture's own samples: the part of the picture that is not
    /// denoised (see [`super::denoise`]). Zero for a picture of no samples.
    pub light: Vec<Color>,
    /// The same light, where it changes within the pixel's 3 x 3 neighbourhood taken over
    /// [`EDGE_SAMPLES`] samples (elsewhere `light`'s): what the denoiser adds back.
    pub sharp_light: Vec<Color>,
}

/// What one sample's ray found.
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Zeroable)]
struct GuideSample {
    albedo: Color,
    normal: Vec3A,
    light: Color,
}

/// The guides of `scene`'s picture when it has `samples` samples a pixel (the fewest any
/// pixel has: a render stopped by its time limit, a preview's pass, has fewer than the
/// scene asks), on `options.threads` (through the render loop every render takes, so its
/// tiles, threads and cancellation are the picture's). The light seen emitted is taken over
/// the picture's own first samples (up to [`EDGE_SAMPLES`] on an edge, [`GUIDE_SAMPLES`]
/// elsewhere, where it changes too little to matter; under Whitted over all its strata),
/// so that the picture less that light is what it reflects.
pub fn guides(scene: &Scene, samples: u32, options: &RenderOptions) -> Result<Guides, RenderError> {
    let s = &scene.settings;
    let (width, height) = (s.width, s.height);
    let mut film: crate::film::Film<GuideSample> = crate::film::Film::new(width, height);
    let camera = scene.camera.raster(width, height);
    // Whitted's samples are the strata of an n x n grid, all of them in every picture
    // (`for_each_sample`), not a sampler's sequence: its guides and its light are taken over
    // the very strata its picture took, so that the light taken out is the light in it.
    let whitted = s.integrator.kind == crate::scene::IntegratorKind::Whitted;
    // Samples `samples` of pixel (x, y), as the render places them (`as_rendered`; else, for
    // the light taken again on an edge, the sampler's, for any integrator), averaged with
    // their filter weights.
    let average = |x: u32, y: u32, samples: std::ops::Range<u32>, as_rendered: bool| {
        let mut sampler = Sampler::new(s.integrator.sampler, s.seed);
        let (mut albedo, mut normal, mut weight) = (Color::ZERO, Vec3A::ZERO, 0.0f32);
        let mut light = Color::ZERO;
        let mut strata = Vec::new();
        if whitted && as_rendered {
            for_each_sample(s, x, y, |px, py, sign| strata.push((px, py, sign)));
        }
        for index in samples {
            let (ray, sign) = match strata.get(index as usize) {
                Some(&(px, py, sign)) if camera.has_lens() => (
                    camera.ray_lens(px, py, whitted_lens_sample(s, x, y, index)),
                    sign,
                ),
                Some(&(px, py, sign)) => (camera.ray(px, py), sign),
                None => {
                    let (px, py, sign) = start_sample(s, &mut sampler, x, y, index);
                    (camera_ray(&camera, &mut sampler, px, py), sign)
                }
            };
            let g = follow(scene, ray);
            albedo += g.albedo * sign;
            normal += g.normal * sign;
            light += g.light * sign;
            weight += sign;
        }
        if weight > 0.0 {
            GuideSample {
                albedo: (albedo / weight).clamp(Color::ZERO, Color::ONE),
                normal: (normal / weight).clamp(Vec3A::splat(-1.0), Vec3A::ONE),
                light: (light / weight).max(Color::ZERO),
            }
        } else {
            GuideSample::default()
        }
    };
    // Whitted's picture takes all its strata, and so do its guides.
    let n = if whitted {
        samples.max(1)
    } else {
        samples.clamp(1, GUIDE_SAMPLES)
    };
    let work = |x: u32, y: u32, out: &mut GuideSample, _: &mut ()| *out = average(x, y, 0..n, true);
    crate::render::for_each_tile(&mut film, options, |_| false, work, |_, _| {})?;
    let rows = film.into_rows();
    let first: Vec<Color> = rows.iter().map(|g| g.light).collect();
    let edges = edges(&first, width, height);
    // On an edge, the light as the picture took it (its own first samples, up to
    // EDGE_SAMPLES) and as EDGE_SAMPLES take it; elsewhere the first samples' for both. A
    // picture of no samples has no light in it, and gets none added.
    let mut lights: crate::film::Film<EdgeLight> = crate::film::Film::new(width, height);
    let index = |x: u32, y: u32| (y * width + x) as usize;
    let work = |x: u32, y: u32, out: &mut EdgeLight, _: &mut ()| {
        let i = index(x, y);
        *out = if samples == 0 {
            EdgeLight::default()
        } else if edges[i] {
            let sharp = average(x, y, 0..EDGE_SAMPLES, false).light;
            let taken = match samples {
                s if s <= n => first[i],
                s if s >= EDGE_SAMPLES => sharp,
                s => average(x, y, 0..s, true).light,
            };
            EdgeLight { taken, sharp }
        } else {
            EdgeLight {
                taken: first[i],
                sharp: first[i],
            }
        };
    };
    crate::render::for_each_tile(&mut lights, options, |_| false, work, |_, _| {})?;
    let lights = lights.into_rows();
    Ok(Guides {
        width,
        height,
        albedo: rows.iter().map(|g| g.albedo).collect(),
        normal: rows.iter().map(|g| g.normal).collect(),
        light: lights.iter().map(|l| l.taken).collect(),
        sharp_light: lights.iter().map(|l| l.sharp).collect(),
    })
}

/// A pixel's light seen emitted: as its picture took it, and sharp.
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Zeroable)]
struct EdgeLight {
    taken: Color,
    sharp: Color,
}

/// Which pixels of `light` (rows from the top) are on a light's edge: where the light in the
/// pixel's 3 x 3 neighbourhood changes by more than [`EDGE_STEP`] of its brightest there.
fn edges(light: &[Color], width: u32, height: u32) -> Vec<bool> {
    let (w, h) = (width as usize, height as usize);
    let mut out = vec![false; light.len()];
    for y in 0..h {
        for x in 0..w {
            let (mut lo, mut hi) = (Color::splat(f32::INFINITY), Color::ZERO);
            for ny in y.saturating_sub(1)..(y + 2).min(h) {
                for nx in x.saturating_sub(1)..(x + 2).min(w) {
                    let c = light[ny * w + nx];
                    (lo, hi) = (lo.min(c), hi.max(c));
                }
            }
            out[y * w + x] = (hi - lo).max_element() > EDGE_STEP * hi.max_element();
        }
    }
    out
}

/// A lobe choice that takes the last lobe of a mix, and a smooth glass's refraction over its
/// reflection wherever there is one.
const LAST_LOBE: f32 = 1.0 - f32::EPSILON;

/// The albedo and normal along `ray`: through perfect mirrors and smooth glass (the weight of
/// each bounce tinting the albedo) to the first surface with some scattering that is not a
/// delta.
fn follow(scene: &Scene, mut ray: Ray) -> GuideSample {
    let mut tint = Color::ONE;
    let mut skip = Skip::NONE;
    for bounce in 0..=MAX_DELTA_BOUNCES {
        let Some(mut hit) = scene.closest_hit_skipping(&ray, f32::INFINITY, skip) else {
            let background = match scene.environment() {
                Some(env) if env.visible || bounce > 0 => env.radiance(ray.dir),
                _ => scene.background,
            };
            return GuideSample {
                albedo: tint * background.clamp(Color::ZERO, Color::ONE),
                normal: Vec3A::ZERO,
                light: Color::ZERO,
            };
        };
        let m = scene.material_at(&hit);
        let tex = hit.tex;
        scene.with_detail(&mut hit, &tex);
        let base = scene.base_color(&hit, &tex);
        let facing = if ray.dir.dot(hit.shading_normal) > 0.0 {
            -hit.shading_normal
        } else {
            hit.shading_normal
        };
        // A light: its emission's colour, brightest channel 1, so that the guide shows the
        // light's edge where its surface's colour would not (the Cornell box's lamp is as
        // white as its ceiling), and the denoiser keeps it sharp.
        let front = ray.dir.dot(hit.normal) < 0.0;
        if let Some(e) = &m.emission {
            let le = e.emitted(front, &scene.textures, &tex);
            if le.max_element() > 0.0 {
                return GuideSample {
                    albedo: tint * (le / le.max_element()),
                    normal: facing,
                    light: tint * le,
                };
            }
        }
        let bsdf = m.bsdf_at(&scene.textures, &tex, base, None);
        if bsdf.has_non_delta() || bounce == MAX_DELTA_BOUNCES {
            return GuideSample {
                albedo: tint * base.clamp(Color::ZERO, Color::ONE),
                normal: facing,
                light: Color::ZERO,
            };
        }
        let frame = Frame::from_axis(hit.shading_normal);
        let wo = frame.to_local(-ray.dir);
        let Some(bs) = bsdf.sample(wo, Vec2::splat(0.5), LAST_LOBE) else {
            return GuideSample {
                albedo: Color::ZERO,
                normal: facing,
                light: Color::ZERO,
            };
        };
        if bs.pdf.is_nan() || bs.pdf <= 0.0 {
            return GuideSample {
                albedo: Color::ZERO,
                normal: facing,
                light: Color::ZERO,
            };
        }
        tint *= (bs.f * (bs.wi.z.abs() / bs.pdf)).clamp(Color::ZERO, Color::ONE);
        let dir = frame.to_world(bs.wi).normalize_or_zero();
        let outward = dir.dot(hit.normal) > 0.0;
        let side = if outward { hit.normal } else { -hit.normal };
        ray = Ray::new(offset_ray_origin(hit.point, side), dir);
        skip = scene.leaving(&hit, outward);
    }
    GuideSample::default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Format, load_str};

    fn scene(objects: &str) -> Scene {
        let text = format!(
            "[image]\nwidth = 12\nheight = 8\nsamples = 4\nbackground = [0.2, 0.4, 3]\n\
             [integrator]\ntype = \"path\"\n\
             [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 20\n\
             [materials.red]\ntype = \"diffuse\"\ncolor = [0.8, 0.1, 0.1]\n\
             [materials.mirror]\ntype = \"conductor\"\n\
             [materials.lamp]\ntype = \"diffuse\"\ncolor = 0.8\nemission = [4, 2, 1]\n\
             {objects}"
        );
        load(&text)
    }

    fn load(text: &str) -> Scene {
        load_str(
            text,
            std::path::Path::new("t.toml"),
            std::path::Path::new("."),
            Format::Toml,
        )
        .unwrap()
    }

    fn options() -> RenderOptions<'static> {
        RenderOptions {
            threads: Some(2),
            progress: &|_| {},
            cancel: None,
            region: None,
        }
    }

    /// A wall filling the view: its albedo and its normal toward the camera everywhere; the
    /// background's colour (clamped) where nothing is hit.
    #[test]
    fn a_diffuse_wall_gives_its_albedo_and_normal() {
        let g = guides(
            &scene("[[objects]]\ntype = \"plane\"\npoint = [0, 0, -1]\nnormal = [0, 0, 1]\nmaterial = \"red\"\n"),
            4,
            &options(),
        )
        .unwrap();
        assert_eq!((g.width, g.height, g.albedo.len()), (12, 8, 96));
        let mut checked = 0;
        for (a, n) in g.albedo.iter().zip(&g.normal) {
            assert!(
                (*a - Color::new(0.8, 0.1, 0.1)).abs().max_element() < 1e-5,
                "{a:?}"
            );
            assert!((*n - Vec3A::Z).length() < 1e-5, "{n:?}");
            checked += 1;
        }
        assert_eq!(checked, 96);
        let sky = guides(&scene(""), 4, &options()).unwrap();
        assert!(sky.albedo.iter().all(|a| *a == Color::new(0.2, 0.4, 1.0)));
        assert!(sky.normal.iter().all(|n| *n == Vec3A::ZERO));
        assert!(g.light.iter().chain(&sky.light).all(|l| *l == Color::ZERO));
    }

    /// A perfect mirror facing the camera is seen through: the guides show what it reflects
    /// (here the red wall behind the camera, facing it), tinted by the mirror.
    #[test]
    fn a_mirror_shows_what_it_reflects() {
        let g = guides(
            &scene(
                "[[objects]]\ntype = \"plane\"\npoint = [0, 0, -1]\nnormal = [0, 0, 1]\nmaterial = \"mirror\"\n\
                 [[objects]]\ntype = \"plane\"\npoint = [0, 0, 9]\nnormal = [0, 0, -1]\nmaterial = \"red\"\n",
            ),
            4,
            &options(),
        )
        .unwrap();
        let mut checked = 0;
        for (a, n) in g.albedo.iter().zip(&g.normal) {
            assert!(
                (*a - Color::new(0.8, 0.1, 0.1)).abs().max_element() < 1e-4,
                "{a:?}"
            );
            assert!((*n - Vec3A::NEG_Z).length() < 1e-4, "{n:?}");
            checked += 1;
        }
        assert_eq!(checked, 96);
    }

    /// A lamp seen in a mirror: its light kept as seen (for the denoiser to add back), its
    /// emission's colour as the albedo.
    #[test]
    fn a_lamp_keeps_its_light() {
        let g = guides(
            &scene(
                "[[objects]]\ntype = \"plane\"\npoint = [0, 0, -1]\nnormal = [0, 0, 1]\nmaterial = \"mirror\"\n\
                 [[objects]]\ntype = \"plane\"\npoint = [0, 0, 9]\nnormal = [0, 0, -1]\nmaterial = \"lamp\"\n",
            ),
            4,
            &options(),
        )
        .unwrap();
        let mut checked = 0;
        for (a, l) in g.albedo.iter().zip(&g.light) {
            assert!(
                (*l - Color::new(4.0, 2.0, 1.0)).abs().max_element() < 1e-4,
                "{l:?}"
            );
            assert!(
                (*a - Color::new(1.0, 0.5, 0.25)).abs().max_element() < 1e-5,
                "{a:?}"
            );
            checked += 1;
        }
        assert_eq!(checked, 96);
    }

    /// A lamp's edge across a row of pixels: the sharp light there is the converged render's
    /// (4096 samples, where only the lamp gives light), far closer than the 16 samples' light
    /// the render would add back, and the same as that light away from the edge.
    #[test]
    fn a_lamps_edge_is_sharp() {
        let text = "[image]\nwidth = 12\nheight = 8\nsamples = 16\nbackground = [0, 0, 0]\n\
             filter = { type = \"box\" }\nmax_depth = 2\n[integrator]\ntype = \"path\"\n\
             [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 20\n\
             [materials.black]\ntype = \"diffuse\"\ncolor = 0\nemission = [4, 2, 1]\n\
             [[objects]]\ntype = \"rectangle\"\ncorner = [-9, -9, 0]\nedge_u = [9.137, 0, 0]\n\
             edge_v = [0, 18, 0]\nmaterial = \"black\"\n";
        let scene = load(text);
        let g = guides(&scene, 16, &options()).unwrap();
        let mut converged = scene.clone();
        converged.settings.spp = 4096;
        let reference =
            crate::render::render(&converged, &crate::integrator::Path, Some(2), &|_| {})
                .unwrap()
                .image;
        let (mut sharp_off, mut sampled_off, mut edge, mut checked) = (0.0, 0.0, 0, 0);
        for ((r, sharp), sampled) in reference.pixels.iter().zip(&g.sharp_light).zip(&g.light) {
            let (a, b) = (
                (*sharp - *r).abs().max_element(),
                (*sampled - *r).abs().max_element(),
            );
            assert!(a < 0.03, "sharp {sharp:?}, converged {r:?}");
            if sharp != sampled {
                edge += 1;
            }
            sharp_off += a;
            sampled_off += b;
            checked += 1;
        }
        assert_eq!(checked, 96);
        // The light taken out is the picture's own, over its first samples: a render of 16
        // and of 64 samples (only the lamp gives light, so a pixel is the light it sees).
        let mut compared = 0;
        for (spp, light) in [
            (16, &g.light),
            (64, &guides(&scene, 64, &options()).unwrap().light),
        ] {
            let mut picture = scene.clone();
            picture.settings.spp = spp;
            let img = crate::render::render(&picture, &crate::integrator::Path, Some(2), &|_| {})
                .unwrap()
                .image;
            for (p, l) in img.pixels.iter().zip(light) {
                assert!(
                    (*p - *l).abs().max_element() < 1e-4,
                    "{spp} spp: {p:?} against {l:?}"
                );
                compared += 1;
            }
        }
        assert_eq!(compared, 192);
        // A picture of no samples has no light to take out or add back.
        let none = guides(&scene, 0, &options()).unwrap();
        assert!(
            none.light
                .iter()
                .chain(&none.sharp_light)
                .all(|l| *l == Color::ZERO)
        );
        // Under Whitted, whose samples are the strata of a grid, the light taken out is its
        // picture's too, over those strata (16 and 64 of them), where the sampler's film
        // positions would place the edge elsewhere in its pixels.
        let mut compared = 0;
        for spp in [16, 64] {
            let mut picture = scene.clone();
            picture.settings.spp = spp;
            picture.settings.integrator.kind = crate::scene::IntegratorKind::Whitted;
            let light = guides(&picture, spp, &options()).unwrap().light;
            let img =
                crate::render::render(&picture, &crate::integrator::Whitted, Some(2), &|_| {})
                    .unwrap()
                    .image;
            let mut apart = 0;
            for ((p, l), sampled) in img.pixels.iter().zip(&light).zip(&g.light) {
                assert!(
                    (*p - *l).abs().max_element() < 1e-5,
                    "Whitted, {spp} spp: {p:?} against {l:?}"
                );
                if (*p - *sampled).abs().max_element() > 1e-3 {
                    apart += 1;
                }
                compared += 1;
            }
            // At the edge, the path tracer's placement of the same 16 samples (what was
            // taken out of a Whitted picture before) gives other light.
            if spp == 16 {
                assert!(apart >= 4, "{apart} edge pixels apart");
            }
        }
        assert_eq!(compared, 192);
        // The edge's column and its neighbours, all eight rows.
        assert!(edge >= 8, "{edge} pixels taken again");
        assert!(
            sampled_off > 0.05,
            "16 samples place the edge exactly: {sampled_off}"
        );
        assert!(
            sharp_off < 0.25 * sampled_off,
            "{sharp_off} against {sampled_off}"
        );
    }
}
