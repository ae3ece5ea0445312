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
//! denoiser leaves it out of what it filters and adds it back, exactly as sampled.
//!
//! Each ray goes on deterministically (glass by its refraction, unless that is total
//! internal reflection), so the guides carry no noise of their own, only the pixels' edges:
//! OIDN takes them as clean (`cleanAux`), which is what its prefiltering of noisy guides
//! would give them.

use crate::math::{Color, Frame, Ray, Vec2, Vec3A, offset_ray_origin};
use crate::render::{RenderError, RenderOptions, camera_ray, start_sample};
use crate::sampler::Sampler;
use crate::scene::{Scene, Skip};

/// Samples a pixel's guides take at most (fewer where the render takes fewer).
pub const GUIDE_SAMPLES: u32 = 16;

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
    /// linear RGB: the part of the picture that is not denoised (see [`super::denoise`]).
    pub light: Vec<Color>,
}

/// What one sample's ray found.
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Zeroable)]
struct GuideSample {
    albedo: Color,
    normal: Vec3A,
    light: Color,
}

/// The guides of `scene`'s picture, on `options.threads` (through the render loop every
/// render takes, so its tiles, threads and cancellation are the picture's).
pub fn guides(scene: &Scene, options: &RenderOptions) -> Result<Guides, RenderError> {
    let s = &scene.settings;
    let mut film: crate::film::Film<GuideSample> = crate::film::Film::new(s.width, s.height);
    let camera = scene.camera.raster(s.width, s.height);
    let n = s.spp.clamp(1, GUIDE_SAMPLES);
    let work = |x: u32, y: u32, out: &mut GuideSample, _: &mut ()| {
        let mut sampler = Sampler::new(s.integrator.sampler, s.seed);
        let (mut albedo, mut normal, mut weight) = (Color::ZERO, Vec3A::ZERO, 0.0f32);
        let mut light = Color::ZERO;
        for index in 0..n {
            let (px, py, sign) = start_sample(s, &mut sampler, x, y, index);
            let ray = camera_ray(&camera, &mut sampler, px, py);
            let g = follow(scene, ray);
            albedo += g.albedo * sign;
            normal += g.normal * sign;
            light += g.light * sign;
            weight += sign;
        }
        if weight > 0.0 {
            *out = GuideSample {
                albedo: (albedo / weight).clamp(Color::ZERO, Color::ONE),
                normal: (normal / weight).clamp(Vec3A::splat(-1.0), Vec3A::ONE),
                light: (light / weight).max(Color::ZERO),
            };
        }
    };
    crate::render::for_each_tile(&mut film, options, |_| false, work, |_, _| {})?;
    let rows = film.into_rows();
    Ok(Guides {
        width: s.width,
        height: s.height,
        albedo: rows.iter().map(|g| g.albedo).collect(),
        normal: rows.iter().map(|g| g.normal).collect(),
        light: rows.iter().map(|g| g.light).collect(),
    })
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
        load_str(
            &text,
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
        let sky = guides(&scene(""), &options()).unwrap();
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
}
