//! A light-traced render ([`crate::integrator::LightTracer`]): `spp` paths from the lights
//! for each pixel's worth of the film (the paths of pixel `(x, y)` are seeded by it, as a
//! camera path is, though they land anywhere), their connections to the eye splatted on a
//! [`SplatFilm`], and the picture their sum over `spp`. The same bytes at any thread count.

use super::{RenderError, RenderOptions, Rendered, TilesDone, for_each_tile};
use crate::film::{Film, SplatFilm};
use crate::integrator::{LightTracer, LightView, RayStats};
use crate::scene::Scene;

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
    let s = &scene.settings;
    let camera = &scene.camera;
    let v = camera.view();
    if v.projection != crate::camera::Projection::Perspective {
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
    let tiles = for_each_tile(
        &mut film,
        options,
        |_| false,
        |x, y, _, (rays, _): &mut (RayStats, super::BadSamples)| {
            let mut sampler = crate::sampler::Sampler::new(s.integrator.sampler, s.seed);
            for k in 0..s.spp {
                sampler.start(x, y, k);
                LightTracer.trace(scene, &view, &mut sampler, rays, &mut |px, py, c| {
                    splats.add(px, py, c)
                });
            }
        },
        |_, _| {},
    )?;
    let done = TilesDone::gather(tiles, grid);
    Ok(Rendered {
        image: splats.image(1.0 / s.spp.max(1) as f32),
        rays: done.rays,
        bad_samples: done.bad_samples,
        tiles_done: done.tiles as u32,
        tiles_total: grid.tiles_in(options.region),
        pixels_rendered: done.pixels,
    })
}

#[cfg(test)]
mod tests;
