//! Rendering an image: tiles over all cores (rayon), stratified jittered samples per pixel
//! seeded from `(seed, x, y)`, so the result is the same bytes at any thread count.

use crate::film::Image;
use crate::integrator::{Integrator, RayStats};
use crate::math::{Color, Ray, Rng, Vec3A, hash_seed};
use crate::sampler::Sampler;
use crate::scene::{RenderSettings, Scene};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

pub mod estimate;

/// Side of a square tile, in pixels.
pub const TILE: u32 = 16;

/// Why a render could not run.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The thread pool could not be created.
    #[error("cannot start {threads} render threads: {source}")]
    Threads {
        /// How many were asked for.
        threads: usize,
        /// The cause.
        source: rayon::ThreadPoolBuildError,
    },
}

/// A finished render.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The picture.
    pub image: Image,
    /// The rays traced for it.
    pub rays: RayStats,
    /// Samples that came out NaN or infinite (left out of their pixels).
    pub bad_samples: BadSamples,
    /// Tiles in the image (finished before, in a resumed render, included).
    pub tiles_done: u32,
    /// Tiles in all.
    pub tiles_total: u32,
    /// Pixels rendered in this run (those of tiles from an earlier run not counted).
    pub pixels_rendered: u64,
}

impl Rendered {
    /// Whether every tile was rendered (a cancelled render leaves some black).
    pub fn complete(&self) -> bool {
        self.tiles_done == self.tiles_total
    }
}

/// Samples whose colour came out NaN or infinite. They are left out of their pixel (which
/// would otherwise be a black or white speck) and reported, with where they happened.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BadSamples {
    /// How many.
    pub count: u64,
    /// The first few: pixel and the object the camera ray hit first (`None`: nothing).
    pub examples: Vec<BadSample>,
}

/// Where a bad sample happened.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BadSample {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// Index of the object the camera ray hit first.
    pub object: Option<usize>,
    /// Whether the colour was NaN (otherwise infinite).
    pub nan: bool,
}

impl BadSamples {
    /// Examples kept.
    pub const EXAMPLES: usize = 8;

    fn add(&mut self, other: BadSamples) {
        self.count += other.count;
        for e in other.examples {
            if self.examples.len() < Self::EXAMPLES {
                self.examples.push(e);
            }
        }
    }
}

/// Tiles already rendered, by tile index (row-major over the image's 16 x 16 tiles), each
/// its pixels row by row. A render skips the tiles it holds and adds the ones it finishes, so
/// a render can be checkpointed while it runs and resumed later with the same result.
#[derive(Debug, Default)]
pub struct TileStore {
    tiles: Mutex<BTreeMap<u32, Vec<Color>>>,
}

impl TileStore {
    /// A store holding `tiles`.
    pub fn new(tiles: BTreeMap<u32, Vec<Color>>) -> Self {
        TileStore {
            tiles: Mutex::new(tiles),
        }
    }

    /// A copy of the tiles finished so far.
    pub fn snapshot(&self) -> BTreeMap<u32, Vec<Color>> {
        self.lock().clone()
    }

    /// How many tiles are finished.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// Whether no tile is finished.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, BTreeMap<u32, Vec<Color>>> {
        // A panic elsewhere cannot leave a half-inserted tile: the map is still whole.
        self.tiles.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// How a render is run.
pub struct RenderOptions<'a> {
    /// Render threads; `None` uses every core.
    pub threads: Option<usize>,
    /// Called from the worker threads with the number of pixels finished so far.
    pub progress: &'a (dyn Fn(u64) + Sync),
    /// Set to stop: tiles not yet started are skipped, tiles under way finish.
    pub cancel: Option<&'a AtomicBool>,
    /// Tiles done before (skipped), and where finished tiles are added.
    pub store: Option<&'a TileStore>,
}

/// Renders `scene` with its settings. `threads` = `None` uses every core. `progress` is
/// called from the worker threads with the number of pixels finished so far.
pub fn render(
    scene: &Scene,
    integrator: &dyn Integrator,
    threads: Option<usize>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Rendered, RenderError> {
    render_with(
        scene,
        integrator,
        &RenderOptions {
            threads,
            progress,
            cancel: None,
            store: None,
        },
    )
}

/// Renders `scene` as `options` say. Tiles skipped because of `cancel` are black in the
/// image; [`Rendered::complete`] says whether every tile is there.
pub fn render_with(
    scene: &Scene,
    integrator: &dyn Integrator,
    options: &RenderOptions,
) -> Result<Rendered, RenderError> {
    let pool = thread_pool(options.threads)?;
    let s = &scene.settings;
    let (w, h) = (s.width, s.height);
    let tiles_x = w.div_ceil(TILE);
    let tiles_y = h.div_ceil(TILE);
    let n = tiles_x * tiles_y;
    let tile_rect = |i: u32| {
        let (x0, y0) = ((i % tiles_x) * TILE, (i / tiles_x) * TILE);
        (x0, y0, (x0 + TILE).min(w), (y0 + TILE).min(h))
    };
    let earlier = options.store.map(|st| st.snapshot()).unwrap_or_default();
    let done = AtomicU64::new(
        earlier
            .keys()
            .filter(|&&i| i < n)
            .map(|&i| {
                let (x0, y0, x1, y1) = tile_rect(i);
                ((x1 - x0) * (y1 - y0)) as u64
            })
            .sum(),
    );
    // Visit the tiles in a scattered order, so every stretch of work mixes sky and busy
    // regions and the progress bar's ETA holds steady; results are placed by tile index, so
    // the image does not depend on the order.
    let step = scatter_step(n);
    let tile_of = |k: u32| ((k as u64 * step as u64) % n as u64) as u32;
    let tiles: Vec<Option<(Vec<Color>, RayStats, BadSamples)>> = pool.install(|| {
        (0..n)
            .into_par_iter()
            // One tile per job: rayon otherwise hands threads long runs of tiles that cannot
            // be split once started, and near the end one core would sit idle while the other
            // finishes its run (a quarter of a second of the seed scene).
            .with_max_len(1)
            .map(|k| {
                let i = tile_of(k);
                if earlier.contains_key(&i)
                    || options.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
                {
                    return None;
                }
                let (x0, y0, x1, y1) = tile_rect(i);
                let mut out = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
                let mut rays = RayStats::default();
                let mut bad = BadSamples::default();
                for y in y0..y1 {
                    for x in x0..x1 {
                        out.push(render_pixel(scene, integrator, x, y, &mut rays, &mut bad));
                    }
                }
                if let Some(st) = options.store {
                    st.lock().insert(i, out.clone());
                }
                let n = done.fetch_add(out.len() as u64, Ordering::Relaxed) + out.len() as u64;
                (options.progress)(n);
                Some((out, rays, bad))
            })
            .collect()
    });
    let mut rays = RayStats::default();
    let mut bad_samples = BadSamples::default();
    // Each finished tile by its index: from an earlier run (if whole), or from this one.
    let mut by_index: Vec<Option<&[Color]>> = vec![None; n as usize];
    for (&i, tile) in earlier.iter().filter(|(i, _)| **i < n) {
        let (x0, y0, x1, y1) = tile_rect(i);
        if tile.len() == ((x1 - x0) * (y1 - y0)) as usize {
            by_index[i as usize] = Some(tile);
        }
    }
    // In tile index order, so the examples are the same at any thread count.
    let mut ordered: Vec<(u32, BadSamples)> = vec![];
    let mut pixels_rendered = 0;
    for (k, t) in tiles.iter().enumerate() {
        let Some((tile, tile_rays, tile_bad)) = t else {
            continue;
        };
        let i = tile_of(k as u32);
        rays += *tile_rays;
        pixels_rendered += tile.len() as u64;
        if tile_bad.count > 0 {
            ordered.push((i, tile_bad.clone()));
        }
        by_index[i as usize] = Some(tile);
    }
    let finished = by_index.iter().filter(|t| t.is_some()).count() as u32;
    // The tiles copied into the image a band of tile rows at a time, on every core.
    let mut image = Image::new(w, h);
    pool.install(|| {
        image
            .pixels
            .par_chunks_mut((w * TILE) as usize)
            .enumerate()
            .for_each(|(ty, band)| {
                for tx in 0..tiles_x {
                    let i = ty as u32 * tiles_x + tx;
                    let Some(tile) = by_index[i as usize] else {
                        continue;
                    };
                    let (x0, _, x1, _) = tile_rect(i);
                    let tw = (x1 - x0) as usize;
                    for (row, src) in tile.chunks_exact(tw).enumerate() {
                        let start = row * w as usize + x0 as usize;
                        band[start..start + tw].copy_from_slice(src);
                    }
                }
            });
    });
    ordered.sort_by_key(|(i, _)| *i);
    for (_, b) in ordered {
        bad_samples.add(b);
    }
    Ok(Rendered {
        image,
        rays,
        bad_samples,
        tiles_done: finished,
        tiles_total: n,
        pixels_rendered,
    })
}

/// A pool of `threads` render threads (`None`: one per core).
pub(crate) fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, RenderError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|source| RenderError::Threads {
            threads: threads.unwrap_or(0),
            source,
        })
}

/// A step coprime with `n` near `n / phi`: `k * step mod n` then visits every index once,
/// spread evenly over the range.
fn scatter_step(n: u32) -> u32 {
    fn gcd(a: u32, b: u32) -> u32 {
        if b == 0 { a } else { gcd(b, a % b) }
    }
    let mut step = ((n as f64 / 1.618_034) as u32).max(1);
    while gcd(step, n) != 1 {
        step += 1;
    }
    step
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

/// Camera rays made at once by [`render_pixel`] before they are traced.
const CAMERA_BATCH: usize = 16;

/// One pixel: its samples (see [`for_each_sample`]) averaged with the signs of their filter
/// weights.
pub fn render_pixel(
    scene: &Scene,
    integrator: &dyn Integrator,
    x: u32,
    y: u32,
    rays: &mut RayStats,
    bad: &mut BadSamples,
) -> Color {
    if integrator.uses_sampler() {
        return render_pixel_sampled(scene, integrator, x, y, rays, bad);
    }
    let s = &scene.settings;
    let (mut sum, mut weight, mut unsigned) = (Color::ZERO, 0.0f32, Color::ZERO);
    let camera = scene.camera.raster(s.width, s.height);
    let mut colors = [Color::ZERO; CAMERA_BATCH];
    let mut trace = |batch: &[Ray], signs: &[f32]| {
        let colors = &mut colors[..batch.len()];
        integrator.radiance_batch(scene, batch, colors, rays);
        // The sums in locals for the batch, not through the closure's references, so that
        // they stay in registers across the loop.
        let (mut s, mut w, mut u) = (sum, weight, unsigned);
        for ((ray, sign), &c) in batch.iter().zip(signs).zip(colors.iter()) {
            let c = checked(scene, c, ray, x, y, bad);
            s += c * *sign;
            w += sign;
            u += c;
        }
        (sum, weight, unsigned) = (s, w, u);
    };
    // The camera rays of several samples are made before any is traced, so that their
    // square roots and divisions overlap instead of each waiting behind the previous
    // sample's whole tree of rays, and handed to the integrator together, which finds their
    // first hits as packets. The order of the samples is unchanged.
    let mut batch = [Ray::new(Vec3A::ZERO, Vec3A::Z); CAMERA_BATCH];
    let mut film = [(0.0f32, 0.0f32); CAMERA_BATCH];
    let mut signs = [0.0f32; CAMERA_BATCH];
    let mut len = 0;
    // A batch's film positions first, then its rays in a loop of their own: making each ray
    // as its sample was drawn interleaved the filter's table lookups with the ray stores
    // (3.8 % of the seed scene's time, with the changes to `for_each_sample`).
    let make = |film: &[(f32, f32)], batch: &mut [Ray]| {
        for (r, &(px, py)) in batch.iter_mut().zip(film) {
            *r = camera.ray(px, py);
        }
    };
    for_each_sample(s, x, y, |px, py, sign| {
        film[len] = (px, py);
        signs[len] = sign;
        len += 1;
        if len == CAMERA_BATCH {
            make(&film, &mut batch);
            trace(&batch, &signs);
            len = 0;
        }
    });
    make(&film[..len], &mut batch[..len]);
    trace(&batch[..len], &signs[..len]);
    if weight > 0.0 {
        (sum / weight).max(Color::ZERO)
    } else {
        // Only possible when most samples fall in Mitchell's negative lobes.
        unsigned / s.spp as f32
    }
}

/// `c`, or black where it is NaN or infinite: a non-finite sample would poison the whole
/// pixel, so it is left out, counted and its place kept as an example.
#[inline]
fn checked(scene: &Scene, c: Color, ray: &Ray, x: u32, y: u32, bad: &mut BadSamples) -> Color {
    if c.is_finite() {
        return c;
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
    Color::ZERO
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

/// A pixel of an integrator that takes its numbers from a [`Sampler`]: any number of
/// samples, each placed on the film by its sampler's first two numbers through the filter's
/// distribution, averaged with the signs of their filter weights.
fn render_pixel_sampled(
    scene: &Scene,
    integrator: &dyn Integrator,
    x: u32,
    y: u32,
    rays: &mut RayStats,
    bad: &mut BadSamples,
) -> Color {
    let s = &scene.settings;
    let camera = scene.camera.raster(s.width, s.height);
    let mut sampler = Sampler::new(s.integrator.sampler, s.seed);
    let signed = s.filter.has_negative_lobes();
    let (mut sum, mut weight, mut unsigned) = (Color::ZERO, 0.0f32, Color::ZERO);
    for index in 0..s.spp {
        let (px, py, filter_sign) = start_sample(s, &mut sampler, x, y, index);
        let sign = if signed { filter_sign } else { 1.0 };
        let ray = camera.ray(px, py);
        let c = integrator.radiance_sampled(scene, &ray, &mut sampler, rays);
        let c = checked(scene, c, &ray, x, y, bad);
        sum += c * sign;
        weight += sign;
        unsigned += c;
    }
    if weight > 0.0 {
        (sum / weight).max(Color::ZERO)
    } else {
        unsigned / s.spp as f32
    }
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
            let got = render_pixel(
                &scene,
                &Whitted,
                x,
                y,
                &mut rays,
                &mut BadSamples::default(),
            );
            assert_eq!(rays.camera, 25, "pixel ({x}, {y})");
            assert_eq!(got, (sum / weight).max(Color::ZERO), "pixel ({x}, {y})");
        }
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

    #[test]
    fn scattered_order_visits_every_tile_once() {
        for n in [1u32, 2, 7, 64, 100, 4096, 4097] {
            let step = scatter_step(n);
            let mut seen = vec![false; n as usize];
            for k in 0..n {
                let i = ((k as u64 * step as u64) % n as u64) as usize;
                assert!(!seen[i], "n = {n}: tile {i} twice");
                seen[i] = true;
            }
        }
    }
}
