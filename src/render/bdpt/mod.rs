//! A bidirectionally path-traced render ([`crate::integrator::Bdpt`]): each pixel's camera
//! samples, their strategies with more than one camera vertex added to the pixel (through
//! the filter, as the path tracer's are), and the strategies that join a light subpath to
//! the eye splatted on a [`SplatFilm`] where they land (spread by the same filter); the
//! picture is the two together, in passes that a time limit may stop. The same bytes
//! at any thread count.

mod strategies;

pub use strategies::{STRATEGY_DEPTH, strategy_list, strategy_names};

use super::passes::{PassDone, in_passes};
use super::{PixelJob, RenderError, RenderOptions, Rendered, TilesDone, for_each_tile};
use crate::film::{Film, Image, SplatFilm};
use crate::integrator::{Bdpt, LightView, Path, Paths, RayStats};
use crate::math::Color;
use crate::render::BadSamples;
use crate::scene::Scene;
use std::time::{Duration, Instant};

/// Why a scene cannot be rendered bidirectionally.
#[derive(Debug, thiserror::Error)]
pub enum BdptError {
    /// The render could not run.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// A camera light paths cannot reach.
    #[error(
        "bdpt needs a perspective camera (not an orthographic one): its light paths end at the eye"
    )]
    Camera,
}

/// A bidirectional render and how many samples a pixel it holds.
#[derive(Clone, Debug)]
pub struct BdptRendered {
    /// The picture (of the passes finished) and what rendering it took.
    pub rendered: Rendered,
    /// Samples a pixel in the picture.
    pub spp: u32,
    /// The strategy images, if asked for, in [`strategy_names`]' order.
    pub strategies: Vec<Image>,
}

/// What a tile gathers: ray counts, bad samples, and the subpaths' memory its pixels reuse.
#[derive(Default)]
struct TileWork {
    rays: RayStats,
    bad: BadSamples,
    paths: Paths,
}

/// Renders `scene` bidirectionally, `scene.settings.spp` samples a pixel.
pub fn render_bdpt(scene: &Scene, options: &RenderOptions) -> Result<Rendered, BdptError> {
    Ok(render_bdpt_for(scene, options, None, false)?.rendered)
}

/// Renders `scene` bidirectionally in passes of 1, 2, 4 ... samples a pixel, until its
/// `spp`, until a pass ends after `time` (from the start), or until `options.cancel` stops
/// it; a pass cancelled part way is left out of the picture (the film and its splats are
/// put back as they were), so the picture is always that of whole passes, and a render
/// stopped by `time` at `n` samples a pixel is the render of `spp = n`, to the bit. With
/// `strategies`, each strategy's images too (strategies.rs).
pub fn render_bdpt_for(
    scene: &Scene,
    options: &RenderOptions,
    time: Option<Duration>,
    strategies: bool,
) -> Result<BdptRendered, BdptError> {
    let start = Instant::now();
    let s = &scene.settings;
    if scene.camera.view().projection != crate::camera::Projection::Perspective {
        return Err(BdptError::Camera);
    }
    let view = LightView::of(scene);
    let splats = SplatFilm::new(s.width, s.height, &s.filter);
    let by_strategy =
        strategies.then(|| strategies::StrategyFilms::new(s.width, s.height, s.max_depth));
    let mut film: Film = Film::new(s.width, s.height);
    let grid = film.grid();
    let pixels = grid.pixels_in(None);
    let camera = scene.camera.raster(s.width, s.height);
    // The job places each sample on the film; the integrator it names is not called.
    let job = PixelJob {
        scene,
        integrator: &Path,
        camera: &camera,
    };
    let done = in_passes(s.spp, time, start, pixels, options, |samples, pass| {
        let (before, kept) = (splats.snapshot(), film.clone());
        let strategies_before = by_strategy.as_ref().map(|f| f.snapshot());
        let tiles = for_each_tile(
            &mut film,
            pass,
            |_| false,
            |x, y, pixel, tile: &mut TileWork| {
                let TileWork { rays, bad, paths } = tile;
                job.add_samples_with(
                    x,
                    y,
                    samples.clone(),
                    (pixel, rays, bad),
                    |ray, sampler, rays| {
                        Bdpt.sample_with(
                            scene,
                            &view,
                            ray,
                            sampler,
                            paths,
                            rays,
                            &mut |px, py, c| splats.add(px, py, c),
                            &mut |st| {
                                if let Some(f) = &by_strategy {
                                    f.add(st, x, y);
                                }
                            },
                        )
                    },
                    |_| {},
                );
            },
            |_, _| {},
        )?;
        let stats = tiles
            .into_iter()
            .map(|(i, t)| (i, (t.rays, t.bad)))
            .collect();
        let pass_done = TilesDone::gather(stats, grid);
        let whole = pass_done.tiles == grid.count() as usize;
        if !whole {
            // Cancelled: the pass's samples and splats are taken back.
            splats.restore(&before);
            film = kept;
            if let (Some(f), Some(b)) = (&by_strategy, &strategies_before) {
                f.restore(b);
            }
        }
        Ok(PassDone {
            rays: pass_done.rays,
            bad: pass_done.bad_samples,
            whole,
        })
    })?;
    let mut image: Image = film.image();
    let light = splats.image(1.0 / done.spp.max(1) as f32);
    for (p, l) in image.pixels.iter_mut().zip(&light.pixels) {
        // A filter's negative lobes may take a pixel below 0, which the camera's part of it
        // is cut at too.
        *p = (*p + *l).max(Color::ZERO);
    }
    Ok(BdptRendered {
        rendered: Rendered {
            image,
            rays: done.rays,
            bad_samples: done.bad,
            tiles_done: if done.complete { grid.count() } else { 0 },
            tiles_total: grid.count(),
            pixels_rendered: pixels * done.spp as u64 / s.spp.max(1) as u64,
        },
        spp: done.spp,
        strategies: by_strategy.map_or(vec![], |f| f.images(done.spp)),
    })
}

#[cfg(test)]
mod caustic_tests;
#[cfg(test)]
mod tests;
