//! A light-traced render ([`crate::integrator::LightTracer`]): `spp` paths from the lights
//! for each pixel's worth of the film (the paths of pixel `(x, y)` are seeded by it, as a
//! camera path is, though they land anywhere), their connections to the eye splatted on a
//! [`SplatFilm`], and the picture their sum over the paths taken, in passes that a time
//! limit may stop. The same bytes at any thread count.

use super::passes::{PassDone, in_passes};
use super::{BadSamples, RenderError, RenderOptions, Rendered, TilesDone, for_each_tile};
use crate::checkpoint::Splatted;
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
    /// Passes to resume that are not this render's.
    #[error("the checkpoint's passes do not fit this render: {0}")]
    Resume(&'static str),
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
    /// The passes' state, to resume from ([`render_light_from`]).
    pub state: Splatted,
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
    render_light_from(scene, options, time, None, &mut |_| {})
}

/// [`render_light_for`], its passes going on from `earlier` (a render's
/// [`LightRendered::state`], or a checkpoint's) if given, and `on_pass` told after each
/// whole pass, with a way to take the state then (to save it). The passes give the bytes
/// of a render never stopped: the splats are integers.
pub fn render_light_from(
    scene: &Scene,
    options: &RenderOptions,
    time: Option<Duration>,
    earlier: Option<Splatted>,
    on_pass: &mut dyn FnMut(&dyn Fn() -> Splatted),
) -> Result<LightRendered, LightTraceError> {
    let start = Instant::now();
    let s = &scene.settings;
    if scene.camera.view().projection != crate::camera::Projection::Perspective {
        return Err(LightTraceError::Camera);
    }
    let view = LightView::of(scene);
    let splats = SplatFilm::new(s.width, s.height, &s.filter);
    let first = match earlier {
        None => 0,
        Some(e) => {
            e.fits(s, false).map_err(LightTraceError::Resume)?;
            splats.restore(&e.splats);
            e.spp
        }
    };
    // A film of nothing: the loop's tiles are the units of work and of progress.
    let mut film: Film<()> = Film::new(s.width, s.height);
    let grid = film.grid();
    let pixels = grid.pixels_in(None);
    let done = in_passes(
        first,
        s.spp,
        time,
        start,
        pixels,
        options,
        |samples, pass| {
            let before = splats.snapshot();
            let tiles = for_each_tile(
                &mut film,
                pass,
                |_| false,
                |x, y, _, (rays, _): &mut (RayStats, BadSamples)| {
                    let mut sampler = crate::sampler::Sampler::new(s.integrator.sampler, s.seed);
                    for k in samples.clone() {
                        sampler.start(x, y, k);
                        LightTracer.trace(scene, &view, &mut sampler, rays, &mut |px, py, c| {
                            splats.add(px, py, c)
                        });
                    }
                },
                |_, _| {},
            )?;
            let pass_done = TilesDone::gather(tiles, grid);
            let whole = pass_done.tiles == grid.count() as usize;
            if whole {
                on_pass(&|| Splatted {
                    spp: samples.end,
                    film: None,
                    splats: splats.snapshot(),
                });
            } else {
                // Cancelled: the pass's splats are taken back.
                splats.restore(&before);
            }
            Ok(PassDone {
                rays: pass_done.rays,
                bad: pass_done.bad_samples,
                whole,
            })
        },
    )?;
    let mut image = splats.image(1.0 / done.spp.max(1) as f32);
    for p in &mut image.pixels {
        // A filter's negative lobes may take a pixel below 0: cut there, as the camera's are.
        *p = p.max(crate::math::Color::ZERO);
    }
    Ok(LightRendered {
        rendered: Rendered {
            image,
            rays: done.rays,
            bad_samples: done.bad,
            tiles_done: if done.complete { grid.count() } else { 0 },
            tiles_total: grid.count(),
            pixels_rendered: pixels * done.spp as u64 / s.spp.max(1) as u64,
        },
        spp: done.spp,
        state: Splatted {
            spp: done.spp,
            film: None,
            splats: splats.snapshot(),
        },
    })
}

#[cfg(test)]
mod tests;
