//! A camera ray's colour, or a path that left the scene with its environment light still to
//! be looked up. Under a large environment map that lookup waits on memory (the map's
//! texels and density, missing the cache), and nothing after it in the path depends on it:
//! the path tracer asks for that memory and hands the path back unfinished, and a pixel's
//! loop traces its next sample before finishing it (`PixelJob::add_samples_with`), so the
//! wait overlaps that work (docs/perf-log.md). The colour is the one the path would have
//! given at once, to the bit.

use crate::light::Toward;
use crate::math::Color;
use crate::scene::Scene;

/// A camera ray's colour, or what is left to find it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Traced {
    /// The colour.
    Done(Color),
    /// A path that left the scene, its light from the environment not yet looked up.
    Escaping(Escape),
}

/// A path that left the scene along `dir`: the light it had gathered, its throughput, and
/// how the environment's light it meets is weighed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Escape {
    /// The light gathered before it left.
    pub(super) gathered: Color,
    /// Its throughput.
    pub(super) beta: Color,
    /// The direction it left in, and where that is on the environment's map.
    pub(super) toward: Toward,
    /// Segments traced, the one that left included.
    pub(super) depth: u32,
    /// Whether its last bounce was a delta lobe (or the camera).
    pub(super) specular: bool,
    /// The density its last bounce sampled the direction with.
    pub(super) prev_pdf: f32,
}

impl Traced {
    /// The colour.
    #[inline]
    pub fn resolve(self, scene: &Scene) -> Color {
        match self {
            Traced::Done(c) => c,
            Traced::Escaping(e) => e.resolve(scene),
        }
    }
}

impl Escape {
    /// The path's colour, its environment light looked up now.
    #[inline]
    pub fn resolve(self, scene: &Scene) -> Color {
        let (le, _) =
            super::Path.escaped(scene, self.toward, self.depth, self.specular, self.prev_pdf);
        super::Path::clamped(scene, self.gathered + self.beta * le)
    }
}

impl From<Color> for Traced {
    fn from(c: Color) -> Self {
        Traced::Done(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::FilmPixel;
    use crate::integrator::{Path, RayStats};
    use crate::light::{Environment, EnvironmentMap, EnvironmentSource, Light};
    use crate::math::{Color, Vec3A};
    use crate::render::{BadSamples, PixelJob};
    use crate::sampler::Sampler;
    use crate::scene::{Format, load_str};
    use crate::texture::{ColorSpace, ImageData};
    use std::sync::Arc;

    /// A floor, a glass ball and a diffuse one under a map too large for the cache (a sky
    /// with a small bright sun), so that paths leave the scene after every kind of bounce.
    fn scene() -> crate::scene::Scene {
        let text = "[image]\nwidth = 6\nheight = 4\nsamples = 16\nmax_depth = 6\n\
                    [integrator]\ntype = \"path\"\n\
                    [camera]\nposition = [0, 1.5, 5]\nlook_at = [0, 0.5, 0]\nfov = 40\n\
                    [environment]\ntype = \"constant\"\ncolor = 1\n\
                    [materials.floor]\ntype = \"diffuse\"\ncolor = 0.5\n\
                    [materials.glass]\ntype = \"dielectric\"\nior = 1.5\n\
                    [[objects]]\ntype = \"disk\"\ncenter = [0, 0, 0]\nnormal = [0, 1, 0]\nradius = 3\nmaterial = \"floor\"\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [-0.6, 0.5, 0]\nradius = 0.5\nmaterial = \"glass\"\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [0.6, 0.5, 0]\nradius = 0.5\nmaterial = \"floor\"\n";
        let mut scene = load_str(
            text,
            std::path::Path::new("t.toml"),
            std::path::Path::new("."),
            Format::Toml,
        )
        .unwrap();
        let (w, h) = (1024u32, 512u32);
        let img = ::image::Rgb32FImage::from_fn(w, h, |x, y| {
            let sun = if (x as i32 - 300).abs() < 4 && (y as i32 - 150).abs() < 4 {
                5000.0
            } else {
                0.0
            };
            let sky = 0.2 + 0.8 * (1.0 - y as f32 / h as f32);
            ::image::Rgb([0.5 * sky + sun, 0.7 * sky + sun, sky + sun])
        });
        let data = Arc::new(ImageData::from_dynamic(
            &::image::DynamicImage::ImageRgb32F(img),
            ColorSpace::Linear,
        ));
        let map = EnvironmentMap::new(data, Vec3A::ZERO, Color::ONE);
        assert!(map.is_large(), "the map must be past the cache's size");
        let i = scene.environment_light.unwrap();
        scene.lights[i] = Light::Environment(Environment {
            source: EnvironmentSource::Map(Box::new(map)),
            visible: true,
        });
        scene
    }

    /// A path handed back unfinished comes to the colour the path tracer gives at once, to
    /// the bit, and a pixel whose escapes wait for the next sample is the pixel added one
    /// sample at a time.
    #[test]
    fn an_unfinished_path_finishes_as_it_would_have() {
        let scene = scene();
        let camera = scene.camera.raster(6, 4);
        let job = PixelJob {
            scene: &scene,
            integrator: &Path,
            camera: &camera,
        };
        let (mut escaping, mut done) = (0, 0);
        for y in 0..4 {
            for x in 0..6 {
                for index in 0..16 {
                    let mut sampler =
                        Sampler::new(scene.settings.integrator.sampler, scene.settings.seed);
                    let (px, py, _) =
                        crate::render::start_sample(&scene.settings, &mut sampler, x, y, index);
                    let ray = crate::render::camera_ray(&camera, &mut sampler, px, py);
                    let mut again = sampler.clone();
                    let traced = Path.radiance_deferred(
                        &scene,
                        &ray,
                        &mut sampler,
                        &mut RayStats::default(),
                    );
                    let at_once = Path.radiance(&scene, &ray, &mut again, &mut RayStats::default());
                    match traced {
                        Traced::Escaping(_) => escaping += 1,
                        Traced::Done(_) => done += 1,
                    }
                    assert_eq!(
                        traced.resolve(&scene).to_array().map(f32::to_bits),
                        at_once.to_array().map(f32::to_bits),
                        "pixel ({x}, {y}), sample {index}"
                    );
                }
                let (mut deferred, mut one_by_one) = (FilmPixel::default(), FilmPixel::default());
                let mut rays = RayStats::default();
                job.add_samples(
                    x,
                    y,
                    0..16,
                    &mut deferred,
                    &mut rays,
                    &mut BadSamples::default(),
                );
                job.add_samples_with(
                    x,
                    y,
                    0..16,
                    (&mut one_by_one, &mut rays, &mut BadSamples::default()),
                    |ray, sampler, rays| Path.radiance(&scene, ray, sampler, rays),
                    |_| {},
                );
                assert_eq!(deferred, one_by_one, "pixel ({x}, {y})");
                assert_eq!(deferred.samples, 16);
            }
        }
        assert_eq!(escaping + done, 6 * 4 * 16);
        // Most paths leave the scene (the sky fills the top of the picture, and the floor
        // and the balls send light up); some end otherwise (roulette, the depth).
        assert!(
            escaping > 200 && done > 0,
            "{escaping} escaping, {done} done"
        );
    }
}
