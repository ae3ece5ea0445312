//! A render that splits its light by light path expressions: the path tracer's picture and,
//! for each expression, an image of the light that came by the paths it matches, all from
//! the same samples (so expressions that share out every path add up to the picture).
//! Every sample of each pixel at once, tile by tile, through the one render loop.

use super::tiles::for_each_tile;
use super::{BadSamples, PixelJob, RenderError, RenderOptions, Rendered, TilesDone, thread_pool};
use crate::film::{Film, FilmPixel, Image};
use crate::integrator::{Path, RayStats};
use crate::lpe::{LpeSet, MAX_LAYERS, Tracker};
use crate::math::Color;
use crate::scene::{IntegratorKind, Scene};
use std::cell::Cell;

/// A render with an image for each expression.
#[derive(Clone, Debug)]
pub struct LpeRendered {
    /// The picture and what rendering it took.
    pub rendered: Rendered,
    /// Each expression's image, in the set's order (linear, unclamped: with a filter that
    /// has negative lobes an image may dip below 0 where the picture is cut at 0).
    pub layers: Vec<Image>,
}

/// Why a render with expressions cannot run.
#[derive(Debug, thiserror::Error)]
pub enum LpeRenderError {
    /// The render could not run.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The scene is not rendered by the path tracer.
    #[error(
        "light path expressions follow the path tracer's paths; this scene is rendered by Whitted's ray tracer"
    )]
    NotPathTracer,
}

/// What a tile gathers besides its pixels: ray counts, bad samples, and each pixel's
/// value of every expression, pixel by pixel in the order the tile is rendered.
#[derive(Default)]
struct TileLayers {
    rays: RayStats,
    bad: BadSamples,
    values: Vec<Color>,
}

/// Renders `scene` with the path tracer, every sample of each pixel at once, and each of
/// `set`'s expressions beside it.
pub fn render_lpe(
    scene: &Scene,
    set: &LpeSet,
    options: &RenderOptions,
) -> Result<LpeRendered, LpeRenderError> {
    render_lpe_samples(scene, set, scene.settings.spp, options)
}

/// [`render_lpe`] with samples `0..spp` of each pixel (the first of the render's, for a
/// quicker look).
pub fn render_lpe_samples(
    scene: &Scene,
    set: &LpeSet,
    spp: u32,
    options: &RenderOptions,
) -> Result<LpeRendered, LpeRenderError> {
    let s = &scene.settings;
    if s.integrator.kind != IntegratorKind::Path {
        return Err(LpeRenderError::NotPathTracer);
    }
    let n = set.len();
    let mut film: Film<Color> = Film::new(s.width, s.height);
    let grid = film.grid();
    let camera = scene.camera.raster(s.width, s.height);
    let job = PixelJob {
        scene,
        integrator: &Path,
        camera: &camera,
    };
    let tiles = for_each_tile(
        &mut film,
        options,
        |_| false,
        |x, y, color, tile: &mut TileLayers| {
            let mut pixel = FilmPixel::default();
            let (mut signed, mut unsigned) = ([Color::ZERO; MAX_LAYERS], [Color::ZERO; MAX_LAYERS]);
            let last = Cell::new([Color::ZERO; MAX_LAYERS]);
            job.add_samples_with(
                x,
                y,
                0..spp,
                (&mut pixel, &mut tile.rays, &mut tile.bad),
                |ray, sampler, rays| {
                    let mut tracker = Tracker::new(set);
                    let c = Path.trace(scene, ray, sampler, rays, &mut tracker);
                    last.set(tracker.sums);
                    c
                },
                |sign| {
                    let last = last.get();
                    for k in 0..n {
                        signed[k] += last[k] * sign;
                        unsigned[k] += last[k];
                    }
                },
            );
            *color = pixel.value();
            // Each expression's value as the pixel's is made (`FilmPixel::value`), but
            // not cut at 0, so that the parts still add up.
            for k in 0..n {
                tile.values.push(if pixel.weight > 0.0 {
                    signed[k] / pixel.weight
                } else if pixel.samples > 0 {
                    unsigned[k] / pixel.samples as f32
                } else {
                    Color::ZERO
                });
            }
        },
        |_, _| {},
    )?;
    let mut layers = vec![Image::new(s.width, s.height); n];
    for (i, tile) in &tiles {
        let (x0, y0, x1, y1) = grid.rect(*i);
        let mut values = tile.values.chunks_exact(n.max(1));
        for y in y0..y1 {
            for x in x0..x1 {
                let Some(v) = values.next() else { break };
                for (layer, value) in layers.iter_mut().zip(v) {
                    layer.pixels[(y * s.width + x) as usize] = *value;
                }
            }
        }
    }
    let stats: Vec<_> = tiles
        .into_iter()
        .map(|(i, t)| (i, (t.rays, t.bad)))
        .collect();
    let done = TilesDone::gather(stats, grid);
    let pixels = thread_pool(options.threads)?.install(|| film.rows(|c| *c));
    Ok(LpeRendered {
        rendered: Rendered {
            image: Image {
                width: s.width,
                height: s.height,
                pixels,
            },
            rays: done.rays,
            bad_samples: done.bad_samples,
            tiles_done: done.tiles as u32,
            tiles_total: grid.tiles_in(options.region),
            pixels_rendered: done.pixels,
        },
        layers,
    })
}

#[cfg(test)]
mod tests;
