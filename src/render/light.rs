//! A light-traced render ([`crate::integrator::LightTracer`]): `spp` paths from the lights
//! for each pixel's worth of the film (the paths of pixel `(x, y)` are seeded by it, as a
//! camera path is, though they land anywhere), their connections to the eye splatted on a
//! [`SplatFilm`], and the picture their sum over the paths taken, in passes that a time
//! limit may stop. The same bytes at any thread count.

use super::progressive::next_pass_end;
use super::{BadSamples, RenderError, RenderOptions, Rendered, TilesDone, for_each_tile};
use crate::film::{Film, SplatFilm};
use crate::integrator::{LightTracer, LightView, RayStats};
use crate::scene::Scene;
use std::time::{Duration, Instant};

/// Why a scene cannot be light traced.
#[derive(Debug, thiserror::Error)]
pub enum LightTraceError {
    /// The render could not run.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// A camera light paths cannot reach.
    #[error("light tracing needs a perspective camera (not an orthographic one)")]
    Camera,
}

/// Renders `scene` by light tracing, `scene.settings.spp` paths a pixel.
pub fn render_light(scene: &Scene, options: &RenderOptions) -> Result<Rendered, LightTraceError> {
    Ok(render_light_for(scene, options, None)?.rendered)
}

/// A light-traced render and how many paths a pixel it holds.
#[derive(Clone, Debug)]
pub struct LightRendered {
    /// The picture (of the passes finished) and what rendering it took.
    pub rendered: Rendered,
    /// Paths a pixel in the picture.
    pub spp: u32,
}

/// Renders `scene` by light tracing in passes of 1, 2, 4 ... paths a pixel, until its
/// `spp`, until a pass ends after `time` (from the start), or until `options.cancel` stops
/// it; a pass cancelled part way is left out of the picture (its splats, which land
/// anywhere, are taken back), so the picture is always that of whole passes. Splats add
/// up as integers, so passes `0..a` then `a..b` give the bytes of `0..b` at once: a render
/// stopped by `time` at `n` paths a pixel is the render of `spp = n`.
pub fn render_light_for(
    scene: &Scene,
    options: &RenderOptions,
    time: Option<Duration>,
) -> Result<LightRendered, LightTraceError> {
    let start = Instant::now();
    let s = &scene.settings;
    let camera = &scene.camera;
    if camera.view().projection != crate::camera::Projection::Perspective {
        return Err(LightTraceError::Camera);
    }
    let world = scene
        .objects
        .iter()
        .filter_map(|o| o.world_bounds)
        .reduce(|a, b| a.union(&b))
        .map_or((crate::math::Vec3A::ZERO, 1.0), |b| {
            (
                (b.min + b.max) * 0.5,
                (0.5 * (b.max - b.min).length()).max(1e-3),
            )
        });
    let view = LightView {
        camera,
        size: (s.width, s.height),
        world,
    };
    let splats = SplatFilm::new(s.width, s.height);
    // A film of nothing: the loop's tiles are the units of work and of progress.
    let mut film: Film<()> = Film::new(s.width, s.height);
    let grid = film.grid();
    let pixels = grid.pixels_in(None);
    let (mut done, mut rays, mut bad) = (0u32, RayStats::default(), BadSamples::default());
    let mut per_sample = None;
    let mut complete = true;
    while done < s.spp {
        let elapsed = start.elapsed();
        if done > 0 && time.is_some_and(|t| elapsed >= t) {
            break;
        }
        let left = time.map(|t| t.saturating_sub(elapsed));
        let end = next_pass_end(done, s.spp, per_sample, left);
        // Progress in pixels of the whole render: the passes before, and this one's share.
        let progress = |n: u64| {
            let total = pixels * done as u64 + n * (end - done) as u64;
            (options.progress)(total / s.spp.max(1) as u64)
        };
        let pass = RenderOptions {
            progress: &progress,
            ..*options
        };
        let before = splats.snapshot();
        let pass_start = Instant::now();
        let tiles = for_each_tile(
            &mut film,
            &pass,
            |_| false,
            |x, y, _, (rays, _): &mut (RayStats, BadSamples)| {
                let mut sampler = crate::sampler::Sampler::new(s.integrator.sampler, s.seed);
                for k in done..end {
                    sampler.start(x, y, k);
                    LightTracer.trace(scene, &view, &mut sampler, rays, &mut |px, py, c| {
                        splats.add(px, py, c)
                    });
                }
            },
            |_, _| {},
        )?;
        let pass_done = TilesDone::gather(tiles, grid);
        rays += pass_done.rays;
        bad.add(pass_done.bad_samples);
        if pass_done.tiles < grid.count() as usize {
            // Cancelled: the pass's splats are taken back.
            splats.restore(&before);
            complete = false;
            break;
        }
        per_sample = Some(pass_start.elapsed() / (end - done));
        done = end;
    }
    Ok(LightRendered {
        rendered: Rendered {
            image: splats.image(1.0 / done.max(1) as f32),
            rays,
            bad_samples: bad,
            tiles_done: if complete { grid.count() } else { 0 },
            tiles_total: grid.count(),
            pixels_rendered: pixels * done as u64 / s.spp.max(1) as u64,
        },
        spp: done,
    })
}

#[cfg(test)]
mod tests;
