//! A pixel's samples: where each is placed on the film, and how its colour is added to the
//! pixel's sums. Whitted's are jittered in an n x n grid fixed by the sample count, all
//! taken at once ([`PixelJob::add_stratified`]); a sampler's integrator takes any of them
//! by index ([`PixelJob::add_samples`]), so that passes can add more later.

use super::{BadSample, BadSamples};
use crate::camera::RasterCamera;
use crate::film::FilmPixel;
use crate::integrator::{Escape, Integrator, RayStats, Traced};
use crate::math::{Color, Ray, Rng, Vec2, Vec3A, hash_seed};
use crate::sampler::Sampler;
use crate::scene::{Reach, RenderSettings, Scene};
use std::ops::Range;

/// What stays the same for every pixel of a render: the scene, its integrator, and the
/// scene's camera set up for the image's size. Held together so that each pixel's call
/// names only what is its own: where it is, which samples, and the sums it adds to.
#[derive(Clone, Copy)]
pub struct PixelJob<'a> {
    /// The scene rendered.
    pub scene: &'a Scene,
    /// The integrator that traces each sample.
    pub integrator: &'a dyn Integrator,
    /// The scene's camera for the image's size (set up once per render).
    pub camera: &'a RasterCamera,
}

impl PixelJob<'_> {
    /// Adds samples `samples` of pixel `(x, y)` to `pixel`: by index for an integrator that
    /// takes a sampler, or all of Whitted's strata (whose grid the sample count fixes, so
    /// they are added all at once whatever `samples` says).
    #[inline]
    pub fn add_pixel(
        &self,
        x: u32,
        y: u32,
        samples: Range<u32>,
        pixel: &mut FilmPixel,
        rays: &mut RayStats,
        bad: &mut BadSamples,
    ) {
        if self.integrator.uses_sampler() {
            self.add_samples(x, y, samples, pixel, rays, bad);
        } else {
            self.add_stratified(x, y, pixel, rays, bad);
        }
    }

    /// Adds every sample of one pixel (see [`for_each_sample`]) to `pixel`, with the sign
    /// of its filter weight.
    pub fn add_stratified(
        &self,
        x: u32,
        y: u32,
        pixel: &mut FilmPixel,
        rays: &mut RayStats,
        bad: &mut BadSamples,
    ) {
        let (scene, integrator, camera) = (self.scene, self.integrator, self.camera);
        let s = &scene.settings;
        let reach = self.reach(x, y);
        if reach.is_none()
            && let Some(c) = integrator.camera_miss(scene)
            && c.is_finite()
        {
            self.add_misses(x, y, c, pixel, rays);
            return;
        }
        let (mut sum, mut weight, mut unsigned, mut sum_sq) =
            (Color::ZERO, 0.0f32, Color::ZERO, 0.0f32);
        let mut colors = [Color::ZERO; CAMERA_BATCH];
        let mut trace = |batch: &[Ray], first: u32, signs: &[f32]| {
            let colors = &mut colors[..batch.len()];
            let start = crate::integrator::BatchStart {
                x,
                y,
                index: first,
                reach,
            };
            integrator.radiance_batch(scene, batch, start, colors, rays);
            // The sums in locals for the batch, not through the closure's references, so
            // that they stay in registers across the loop.
            let (mut s, mut w, mut u, mut q) = (sum, weight, unsigned, sum_sq);
            for ((ray, sign), &c) in batch.iter().zip(signs).zip(colors.iter()) {
                let Some(c) = checked(scene, c, ray, x, y, bad) else {
                    continue;
                };
                s += c * *sign;
                w += sign;
                u += c;
                let l = crate::math::luminance(c);
                q += l * l;
            }
            (sum, weight, unsigned, sum_sq) = (s, w, u, q);
        };
        // The camera rays of several samples are made before any is traced, so that their
        // square roots and divisions overlap instead of each waiting behind the previous
        // sample's whole tree of rays, and handed to the integrator together, which finds
        // their first hits as packets. The order of the samples is unchanged.
        let mut batch = [Ray::new(Vec3A::ZERO, Vec3A::Z); CAMERA_BATCH];
        let mut film = [(0.0f32, 0.0f32, 0u32); CAMERA_BATCH];
        let mut signs = [0.0f32; CAMERA_BATCH];
        let mut len = 0;
        // A batch's film positions first, then its rays in a loop of their own: making each
        // ray as its sample was drawn interleaved the filter's table lookups with the ray
        // stores (3.8 % of the seed scene's time, with the changes to `for_each_sample`).
        let make = |film: &[(f32, f32, u32)], batch: &mut [Ray]| {
            if camera.has_lens() {
                for (r, &(px, py, i)) in batch.iter_mut().zip(film) {
                    *r = camera.ray_lens(px, py, whitted_lens_sample(s, x, y, i));
                }
            } else {
                for (r, &(px, py, _)) in batch.iter_mut().zip(film) {
                    *r = camera.ray(px, py);
                }
            }
        };
        let mut index = 0;
        for_each_sample(s, x, y, |px, py, sign| {
            film[len] = (px, py, index);
            index += 1;
            signs[len] = sign;
            len += 1;
            if len == CAMERA_BATCH {
                make(&film, &mut batch);
                trace(&batch, film[0].2, &signs);
                len = 0;
            }
        });
        make(&film[..len], &mut batch[..len]);
        trace(&batch[..len], film[0].2, &signs[..len]);
        pixel.add_sums(sum, weight, unsigned, sum_sq, s.spp);
    }

    /// Which objects the camera rays of pixel `(x, y)` may meet: those whose bounds (or,
    /// for a sphere, itself) are not wholly beside the pyramid of rays through every film
    /// position the filter may put a sample at, widened by an eighth of a pixel. Where that
    /// is none (and the integrator gives such rays one colour), every sample takes the
    /// background without a ray: a sky or a black backdrop costs a test of the pixel.
    #[inline]
    fn reach(&self, x: u32, y: u32) -> Reach {
        let reach = self.scene.settings.filter.radius + 0.125;
        let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
        let rect = [cx - reach, cx + reach, cy - reach, cy + reach];
        match self.camera.film_frustum(rect, self.scene.extent()) {
            Some(f) => self.scene.reach(&f),
            None => Reach::ALL,
        }
    }

    /// Adds `c` for every sample of pixel `(x, y)`, in [`PixelJob::add_stratified`]'s
    /// order and with its sums (the same bits as tracing each sample to `c`), and counts
    /// the camera rays it stands for.
    fn add_misses(&self, x: u32, y: u32, c: Color, pixel: &mut FilmPixel, rays: &mut RayStats) {
        let s = &self.scene.settings;
        let l = crate::math::luminance(c);
        let (mut sum, mut weight, mut unsigned, mut sum_sq) =
            (Color::ZERO, 0.0f32, Color::ZERO, 0.0f32);
        let mut add = |sign: f32| {
            sum += c * sign;
            weight += sign;
            unsigned += c;
            sum_sq += l * l;
        };
        if s.filter.has_negative_lobes() {
            for_each_sample(s, x, y, |_, _, sign| add(sign));
        } else {
            // Every sign is +1: where the samples go does not matter.
            (0..s.spp).for_each(|_| add(1.0));
        }
        rays.camera += s.spp as u64;
        rays.deepest = rays.deepest.max(1);
        pixel.add_sums(sum, weight, unsigned, sum_sq, s.spp);
    }

    /// Adds samples `samples` (by index) of pixel `(x, y)` to `pixel`, for an integrator
    /// that takes its numbers from a [`Sampler`]: each placed on the film by its sampler's
    /// first two numbers through the filter's distribution. Sample `k` is the same
    /// whichever pass adds it, and the sums are added in index order, so passes `0..a` then
    /// `a..b` leave the pixel as `0..b` at once does, to the bit.
    pub fn add_samples(
        &self,
        x: u32,
        y: u32,
        samples: Range<u32>,
        pixel: &mut FilmPixel,
        rays: &mut RayStats,
        bad: &mut BadSamples,
    ) {
        let (scene, integrator) = (self.scene, self.integrator);
        self.add_samples_with(
            x,
            y,
            samples,
            (pixel, rays, bad),
            |ray, sampler, rays| integrator.radiance_deferred(scene, ray, sampler, rays),
            |_| {},
        );
    }

    /// [`PixelJob::add_samples`] with each sample's colour from `trace` (given the camera
    /// ray, the sampler started at the sample, and the ray counts), and `kept(sign)` called
    /// after each sample whose colour is added to the pixel (finite), with the sign of its
    /// filter weight: for a render that gathers more of each sample than its colour.
    ///
    /// A sample `trace` hands back unfinished ([`Traced::Escaping`]) is finished after the
    /// next sample is traced, while its memory comes in; samples are still added to the
    /// pixel in index order, and one that comes back finished is added (and `kept` called)
    /// before the next is traced.
    pub fn add_samples_with<T>(
        &self,
        x: u32,
        y: u32,
        samples: Range<u32>,
        (pixel, rays, bad): (&mut FilmPixel, &mut RayStats, &mut BadSamples),
        mut trace: impl FnMut(&Ray, &mut Sampler, &mut RayStats) -> T,
        mut kept: impl FnMut(f32),
    ) where
        T: Into<Traced>,
    {
        let (scene, camera) = (self.scene, self.camera);
        let s = &scene.settings;
        let mut sampler = Sampler::new(s.integrator.sampler, s.seed);
        let signed = s.filter.has_negative_lobes();
        let mut add = |c: Color, ray: &Ray, sign: f32, bad: &mut BadSamples| {
            match checked(scene, c, ray, x, y, bad) {
                Some(c) => {
                    pixel.add(c, sign);
                    kept(sign);
                }
                // Counted among the pixel's samples (passes take each index once), but not
                // in its value.
                None => pixel.add_sums(Color::ZERO, 0.0, Color::ZERO, 0.0, 1),
            }
        };
        // The sample traced before this one, if it came back unfinished.
        let mut waiting: Option<(Escape, Ray, f32)> = None;
        for index in samples {
            let (px, py, filter_sign) = start_sample(s, &mut sampler, x, y, index);
            let sign = if signed { filter_sign } else { 1.0 };
            let ray = camera_ray(camera, &mut sampler, px, py);
            let traced = trace(&ray, &mut sampler, rays).into();
            if let Some((e, before, sign)) = waiting.take() {
                add(e.resolve(scene), &before, sign, bad);
            }
            match traced {
                Traced::Done(c) => add(c, &ray, sign, bad),
                Traced::Escaping(e) => waiting = Some((e, ray, sign)),
            }
        }
        if let Some((e, before, sign)) = waiting {
            add(e.resolve(scene), &before, sign, bad);
        }
    }
}

/// The film positions of pixel `(x, y)`'s samples, in the order they are taken, each with
/// the sign of its filter weight: `spp = n * n` samples, one jittered in each cell of an
/// n x n grid and placed by the filter's distribution. One sample per pixel goes through the
/// centre.
#[inline]
pub fn for_each_sample(s: &RenderSettings, x: u32, y: u32, mut f: impl FnMut(f32, f32, f32)) {
    let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
    if s.spp == 1 {
        f(cx, cy, 1.0);
        return;
    }
    let n = (s.spp as f32).sqrt().round() as u32;
    let mut rng = Rng::new(hash_seed(&[s.seed, x as u64, y as u64]));
    // Where `n` is a power of two (4, 16, 64 ... samples), dividing by it is multiplying by
    // its exact reciprocal: the same result, without a division per coordinate.
    let (n_f, scale, exact) = (n as f32, 1.0 / n as f32, n.is_power_of_two());
    let stratum = |k: u32, r: f32| {
        let v = k as f32 + r;
        if exact { v * scale } else { v / n_f }
    };
    // Offsets and signs are worked out apart: a filter that is never negative (all but
    // Mitchell) gives every sample the sign +1.
    let signed = s.filter.has_negative_lobes();
    for j in 0..n {
        for i in 0..n {
            // Stratified in the filter's own distribution (filter importance sampling). A
            // stratum lies in [0, 1], which the filter's table needs no clamping for.
            let dx = s.filter.offset_in_unit(stratum(i, rng.next_f32()));
            let dy = s.filter.offset_in_unit(stratum(j, rng.next_f32()));
            let sign = if signed {
                s.filter.sign_at(dx) * s.filter.sign_at(dy)
            } else {
                1.0
            };
            f(cx + dx, cy + dy, sign);
        }
    }
}

/// The film position of Whitted's sample `k` of pixel `(x, y)` (the `k`-th of
/// [`for_each_sample`]); `None` past the last.
pub fn sample_position(s: &RenderSettings, x: u32, y: u32, k: u32) -> Option<(f32, f32)> {
    let (mut at, mut i) = (None, 0);
    for_each_sample(s, x, y, |px, py, _| {
        if i == k {
            at = Some((px, py));
        }
        i += 1;
    });
    at
}

/// The point of the lens (in the unit square) Whitted's sample `i` of pixel `(x, y)` passes
/// through, for a camera with a lens: from a generator of its own, so that a pinhole's
/// samples are the same with or without this.
#[inline]
pub fn whitted_lens_sample(s: &RenderSettings, x: u32, y: u32, i: u32) -> Vec2 {
    const LENS: u64 = 0x6c65_6e73;
    let mut rng = Rng::new(hash_seed(&[s.seed, x as u64, y as u64, i as u64, LENS]));
    Vec2::new(rng.next_f32(), rng.next_f32())
}

/// The camera ray of a sampled film position: through the lens at the sampler's next two
/// numbers when the camera has one (a pinhole takes none, so its samples' numbers are as
/// they were).
#[inline]
pub fn camera_ray(camera: &RasterCamera, sampler: &mut Sampler, px: f32, py: f32) -> Ray {
    if camera.has_lens() {
        camera.ray_lens(px, py, sampler.next_2d())
    } else {
        camera.ray(px, py)
    }
}

/// Camera rays made at once by [`PixelJob::add_stratified`] before they are traced.
const CAMERA_BATCH: usize = 16;

/// `c`, or `None` where it is NaN or infinite: a non-finite sample would poison the whole
/// pixel, so it is left out of the pixel's value (the pixel is the mean of its other
/// samples), counted, and its place kept as an example.
/// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
#[inline(always)]
fn checked(
    scene: &Scene,
    c: Color,
    ray: &Ray,
    x: u32,
    y: u32,
    bad: &mut BadSamples,
) -> Option<Color> {
    if c.is_finite() {
        return Some(c);
    }
    bad.count += 1;
    if bad.examples.len() < BadSamples::EXAMPLES {
        bad.examples.push(BadSample {
            x,
            y,
            object: scene.closest_hit(ray, f32::INFINITY).map(|h| h.object),
            nan: c.is_nan(),
        });
    }
    None
}

/// Starts sample `index` of pixel `(x, y)` in `sampler` and places it on the film by the
/// sampler's first two numbers, through the filter's distribution: the film position and
/// the sign of the filter's weight there. What the rest of the sample's numbers are for is
/// the integrator's.
#[inline]
pub fn start_sample(
    s: &RenderSettings,
    sampler: &mut Sampler,
    x: u32,
    y: u32,
    index: u32,
) -> (f32, f32, f32) {
    sampler.start(x, y, index);
    let u = sampler.next_2d();
    let (dx, dy) = (s.filter.offset_in_unit(u.x), s.filter.offset_in_unit(u.y));
    (
        x as f32 + 0.5 + dx,
        y as f32 + 0.5 + dy,
        s.filter.sign_at(dx) * s.filter.sign_at(dy),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Whitted;
    use crate::scene::{Format, load_str};
    use std::path::Path;

    /// Camera rays are made in batches: with 25 samples (a full batch and a part), a pixel
    /// is still the signed average of every sample, each traced on its own, in order.
    #[test]
    fn batched_camera_rays_give_every_sample_once() {
        let text = "[image]\nwidth = 8\nheight = 8\nsamples = 25\nfilter = { type = \"mitchell\" }\n\
                    [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 30\n\
                    [materials.m]\ncolor = [0.8, 0.3, 0.1]\nspecular = 1\nshininess = 20\n\
                    [[lights]]\ntype = \"point\"\nposition = [2, 3, 4]\n\
                    [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n";
        let scene = load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap();
        assert_eq!(scene.settings.spp, 25);
        let camera = scene.camera.raster(8, 8);
        for (x, y) in [(4, 4), (3, 5), (0, 0)] {
            let (mut sum, mut weight, mut count) = (Color::ZERO, 0.0f32, 0);
            for_each_sample(&scene.settings, x, y, |px, py, sign| {
                let c = Whitted.radiance(&scene, &camera.ray(px, py), &mut RayStats::default());
                sum += c * sign;
                weight += sign;
                count += 1;
            });
            assert_eq!(count, 25);
            let mut rays = RayStats::default();
            let mut pixel = FilmPixel::default();
            let job = PixelJob {
                scene: &scene,
                integrator: &Whitted,
                camera: &scene.camera.raster(8, 8),
            };
            job.add_stratified(x, y, &mut pixel, &mut rays, &mut BadSamples::default());
            assert_eq!(rays.camera, 25, "pixel ({x}, {y})");
            assert_eq!(pixel.samples, 25);
            assert_eq!(
                pixel.value(),
                (sum / weight).max(Color::ZERO),
                "pixel ({x}, {y})"
            );
        }
    }

    /// A pixel none of whose rays can meet anything takes the background for each sample
    /// without tracing: only where every ray through the filter's reach misses (checked by
    /// tracing a grid of them), and with the sums, to the bit, that tracing each sample
    /// gives, for every filter, with fog and without, and counting the same rays.
    #[test]
    fn pixels_that_see_nothing_are_the_background_without_tracing() {
        let (mut skipped, mut traced, mut alone) = (0, 0, 0);
        for (filter, fog) in [
            ("gaussian", ""),
            ("mitchell", ""),
            (
                "box",
                "\n[fog]\nmode = \"exponential\"\ncolor = [0.5, 0.6, 0.7]\ndensity = 0.02",
            ),
        ] {
            let text = format!(
                "[image]\nwidth = 24\nheight = 16\nsamples = 9\nfilter = {{ type = \"{filter}\" }}\n\
                 background = [0.2, 0.1, 0.3]\n\
                 [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\
                 [materials.m]\ncolor = [0.8, 0.3, 0.1]\n\
                 [[lights]]\ntype = \"point\"\nposition = [2, 3, 4]\n\
                 [[objects]]\ntype = \"sphere\"\nradius = 0.6\nmaterial = \"m\"\n\
                 [[objects]]\ntype = \"box\"\nmin = [1.0, 0.5, -1]\nmax = [1.4, 0.9, 0]\nmaterial = \"m\"\n\
                 [[objects]]\ntype = \"rectangle\"\ncorner = [-1.5, -1, 1]\nedge_u = [3, 0, 0]\nedge_v = [0, 0, -3]\nmaterial = \"m\"{fog}\n"
            );
            let scene = load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap();
            let camera = scene.camera.raster(24, 16);
            let job = PixelJob {
                scene: &scene,
                integrator: &Whitted,
                camera: &camera,
            };
            for y in 0..16 {
                for x in 0..24 {
                    let shortcut = job.reach(x, y).is_none();
                    alone += (job.reach(x, y).count() == 1) as u32;
                    if shortcut {
                        skipped += 1;
                        // A 9 x 9 grid of rays over the filter's reach: none meets anything.
                        let r = scene.settings.filter.radius;
                        for j in 0..9 {
                            for i in 0..9 {
                                let px = x as f32 + 0.5 - r + 2.0 * r * i as f32 / 8.0;
                                let py = y as f32 + 0.5 - r + 2.0 * r * j as f32 / 8.0;
                                let ray = camera.ray(px, py);
                                assert!(scene.closest_hit(&ray, f32::INFINITY).is_none());
                            }
                        }
                    } else {
                        traced += 1;
                    }
                    let mut pixel = FilmPixel::default();
                    let mut rays = RayStats::default();
                    job.add_stratified(x, y, &mut pixel, &mut rays, &mut BadSamples::default());
                    // Each sample traced on its own, summed as the film sums them.
                    let mut want = FilmPixel::default();
                    let mut want_rays = RayStats::default();
                    let (mut sum, mut weight, mut unsigned, mut sum_sq) =
                        (Color::ZERO, 0.0f32, Color::ZERO, 0.0f32);
                    for_each_sample(&scene.settings, x, y, |px, py, sign| {
                        let c = Whitted.radiance(&scene, &camera.ray(px, py), &mut want_rays);
                        sum += c * sign;
                        weight += sign;
                        unsigned += c;
                        let l = crate::math::luminance(c);
                        sum_sq += l * l;
                    });
                    want.add_sums(sum, weight, unsigned, sum_sq, 9);
                    let bits = |p: &FilmPixel| {
                        format!("{:?}", (p.sum, p.weight, p.unsigned, p.sum_sq, p.samples))
                    };
                    assert_eq!(bits(&pixel), bits(&want), "{filter} ({x}, {y})");
                    assert_eq!(rays.camera, 9);
                    if shortcut {
                        assert_eq!(
                            rays,
                            RayStats {
                                camera: 9,
                                deepest: 1,
                                ..Default::default()
                            }
                        );
                    }
                }
            }
        }
        // Both kinds of pixel, in every scene.
        assert_eq!(skipped + traced, 3 * 24 * 16);
        assert!(
            skipped > 3 * 100 && traced > 3 * 20,
            "{skipped} skipped, {traced} traced"
        );
        // And pixels whose rays may meet one object only, tested against it alone.
        assert!(alone > 3 * 20, "{alone} pixels see one object");
    }

    /// The sampler's shortcuts (a multiplication for a power-of-two stratum count, no clamp,
    /// no signs for filters that are never negative) place every sample where dividing,
    /// clamping and signing did, to the bit.
    #[test]
    fn samples_are_placed_as_by_the_plain_formula() {
        use crate::film::{Filter, FilterKind};
        use crate::scene::RenderSettings;
        for kind in [FilterKind::Box, FilterKind::Gaussian, FilterKind::Mitchell] {
            let mut negative = 0;
            for spp in [1u32, 4, 9, 16, 25, 64] {
                let s = RenderSettings {
                    width: 64,
                    height: 64,
                    spp,
                    max_depth: 5,
                    seed: 3,
                    filter: Filter::new(kind, None),
                    integrator: Default::default(),
                    tone: Default::default(),
                    filter_textures: true,
                    noise: None,
                };
                for (x, y) in [(0, 0), (17, 5), (63, 40)] {
                    let mut got = vec![];
                    for_each_sample(&s, x, y, |px, py, sign| got.push((px, py, sign)));
                    let n = (spp as f32).sqrt().round() as u32;
                    let mut want = vec![];
                    let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
                    if spp == 1 {
                        want.push((cx, cy, 1.0));
                    } else {
                        let mut rng = Rng::new(hash_seed(&[s.seed, x as u64, y as u64]));
                        for j in 0..n {
                            for i in 0..n {
                                let (dx, sx) =
                                    s.filter.sample((i as f32 + rng.next_f32()) / n as f32);
                                let (dy, sy) =
                                    s.filter.sample((j as f32 + rng.next_f32()) / n as f32);
                                want.push((cx + dx, cy + dy, sx * sy));
                            }
                        }
                    }
                    let bits = |v: &[(f32, f32, f32)]| {
                        v.iter()
                            .map(|(a, b, c)| (a.to_bits(), b.to_bits(), c.to_bits()))
                            .collect::<Vec<_>>()
                    };
                    assert_eq!(
                        bits(&got),
                        bits(&want),
                        "{kind:?}, {spp} spp, pixel ({x}, {y})"
                    );
                    negative += got.iter().filter(|g| g.2 < 0.0).count();
                }
            }
            // Only Mitchell's lobes are negative, and some samples land in them.
            assert_eq!(negative > 0, kind == FilterKind::Mitchell, "{kind:?}");
        }
    }
}
