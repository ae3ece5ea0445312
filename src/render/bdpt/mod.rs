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
use crate::checkpoint::Splatted;
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
    /// Passes to resume that are not this render's.
    #[error("the checkpoint's passes do not fit this render: {0}")]
    Resume(&'static str),
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
    /// The passes' state, to resume from ([`render_bdpt_from`]).
    pub state: Splatted,
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
    render_bdpt_from(scene, options, time, strategies, None, &mut |_| {})
}

/// [`render_bdpt_for`], its passes going on from `earlier` (a render's
/// [`BdptRendered::state`], or a checkpoint's) if given, and `on_pass` told after each
/// whole pass, with a way to take the state then (to save it). The passes give the bytes
/// of a render never stopped. The strategy images are not kept in the state: they cannot
/// be asked for with `earlier`.
pub fn render_bdpt_from(
    scene: &Scene,
    options: &RenderOptions,
    time: Option<Duration>,
    strategies: bool,
    earlier: Option<Splatted>,
    on_pass: &mut dyn FnMut(&dyn Fn() -> Splatted),
) -> Result<BdptRendered, BdptError> {
    let start = Instant::now();
    let s = &scene.settings;
    let mut film = BdptFilm::new(scene, strategies)?;
    if let Some(e) = earlier {
        film.resume(scene, e)?;
    }
    let grid = film.film.grid();
    let pixels = grid.pixels_in(None);
    let done = in_passes(
        film.spp,
        s.spp,
        time,
        start,
        pixels,
        options,
        |samples, pass| {
            let done = film.pass(scene, samples, pass)?;
            if done.whole {
                on_pass(&|| film.state());
            }
            Ok(done)
        },
    )?;
    Ok(BdptRendered {
        rendered: Rendered {
            image: film.image(),
            rays: done.rays,
            bad_samples: done.bad,
            tiles_done: if done.complete { grid.count() } else { 0 },
            tiles_total: grid.count(),
            pixels_rendered: pixels * done.spp as u64 / s.spp.max(1) as u64,
        },
        spp: done.spp,
        strategies: film.strategy_images(),
        state: film.state(),
    })
}

/// A bidirectional render under way, which passes add samples to (the preview's, or one
/// render's): the film of the camera's strategies, the splats of the light paths joined to
/// the eye, the strategy images if asked for, and the samples a pixel they hold.
pub struct BdptFilm {
    film: Film,
    splats: SplatFilm,
    strategies: Option<strategies::StrategyFilms>,
    spp: u32,
}

impl BdptFilm {
    /// An empty film for `scene` (with strategy images, if `strategies`).
    pub fn new(scene: &Scene, strategies: bool) -> Result<Self, BdptError> {
        let s = &scene.settings;
        if scene.camera.view().projection != crate::camera::Projection::Perspective {
            return Err(BdptError::Camera);
        }
        Ok(BdptFilm {
            film: Film::new(s.width, s.height),
            splats: SplatFilm::new(s.width, s.height, &s.filter),
            strategies: strategies
                .then(|| strategies::StrategyFilms::new(s.width, s.height, s.max_depth)),
            spp: 0,
        })
    }

    /// Samples a pixel it holds.
    pub fn spp(&self) -> u32 {
        self.spp
    }

    /// What its passes have done, to resume from.
    pub fn state(&self) -> Splatted {
        Splatted {
            spp: self.spp,
            film: Some(self.film.clone()),
            splats: self.splats.snapshot(),
        }
    }

    /// Takes up `earlier`'s passes (a film of `scene` without strategy images).
    fn resume(&mut self, scene: &Scene, earlier: Splatted) -> Result<(), BdptError> {
        earlier
            .fits(&scene.settings, true)
            .map_err(BdptError::Resume)?;
        // (`fits` has checked that there is one, of the render's size.)
        let film = earlier
            .film
            .ok_or(BdptError::Resume("they are light tracing's"))?;
        if self.strategies.is_some() {
            return Err(BdptError::Resume(
                "the strategy images are not kept in them",
            ));
        }
        self.splats.restore(&earlier.splats);
        (self.film, self.spp) = (film, earlier.spp);
        Ok(())
    }

    /// The picture: the camera's strategies and the splats over the samples taken.
    pub fn image(&self) -> Image {
        let mut image: Image = self.film.image();
        let light = self.splats.image(1.0 / self.spp.max(1) as f32);
        for (p, l) in image.pixels.iter_mut().zip(&light.pixels) {
            // A filter's negative lobes may take a pixel below 0, which the camera's part of
            // it is cut at too.
            *p = (*p + *l).max(Color::ZERO);
        }
        image
    }

    /// The strategy images, in [`strategy_names`]' order (none if not asked for).
    pub fn strategy_images(&self) -> Vec<Image> {
        self.strategies
            .as_ref()
            .map_or(vec![], |f| f.images(self.spp))
    }

    /// Adds samples `samples` (from the number it holds) of every pixel of `scene`, whose
    /// settings and camera are the film's. Cancelled part way, the pass is taken back
    /// (`whole` false): the film is always that of whole passes.
    pub(crate) fn pass(
        &mut self,
        scene: &Scene,
        samples: std::ops::Range<u32>,
        options: &RenderOptions,
    ) -> Result<PassDone, RenderError> {
        let s = &scene.settings;
        let view = LightView::of(scene);
        let grid = self.film.grid();
        let camera = scene.camera.raster(s.width, s.height);
        // The job places each sample on the film; the integrator it names is not called.
        let job = PixelJob {
            scene,
            integrator: &Path,
            camera: &camera,
        };
        let (before, kept) = (self.splats.snapshot(), self.film.clone());
        let strategies_before = self.strategies.as_ref().map(|f| f.snapshot());
        let (splats, by_strategy) = (&self.splats, &self.strategies);
        let n = samples.len() as u32;
        let tiles = for_each_tile(
            &mut self.film,
            options,
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
                                if let Some(f) = by_strategy {
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
        if whole {
            self.spp += n;
        } else {
            // Cancelled: the pass's samples and splats are taken back.
            self.splats.restore(&before);
            self.film = kept;
            if let (Some(f), Some(b)) = (&self.strategies, &strategies_before) {
                f.restore(b);
            }
        }
        Ok(PassDone {
            rays: pass_done.rays,
            bad: pass_done.bad_samples,
            whole,
        })
    }

    /// Adds the next `n` samples a pixel as one pass (taken back if cancelled part way), for
    /// callers outside the crate (the preview): what it traced, and whether it was whole.
    pub fn add_samples(
        &mut self,
        scene: &Scene,
        n: u32,
        options: &RenderOptions,
    ) -> Result<(RayStats, bool), RenderError> {
        let from = self.spp;
        let done = self.pass(scene, from..from + n, options)?;
        Ok((done.rays, done.whole))
    }
}

#[cfg(test)]
mod caustic_tests;
#[cfg(test)]
mod tests;
