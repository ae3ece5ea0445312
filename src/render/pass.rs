//! A pass over the film: some more samples of every pixel added to the sums a [`Film`]
//! holds, for a render that shows its picture as it improves (a preview) or stops and goes
//! on later. Passes of samples `0..a`, `a..b`, ... give the bytes one render of `0..b`
//! gives, at any thread count.

use super::adaptive::Convergence;
use super::tiles::for_each_tile;
use super::{BadSamples, PixelJob, RenderError, RenderOptions, TilesDone};
use crate::film::{Film, FilmPixel};
use crate::integrator::{Integrator, RayStats};
use crate::scene::Scene;
use std::ops::Range;

/// What a pass did.
#[derive(Clone, Debug, Default)]
pub struct PassStats {
    /// The rays traced.
    pub rays: RayStats,
    /// Samples that came out NaN or infinite (left out of their pixels).
    pub bad_samples: BadSamples,
    /// Tiles that took this pass's samples: fewer than the film's when the pass was
    /// cancelled (the others are as they were).
    pub tiles_done: u32,
}

/// Why a pass cannot run.
#[derive(Debug, thiserror::Error)]
pub enum PassError {
    /// The thread pool could not be made.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The film is not the scene's size.
    #[error("the film is {0} x {1}, the scene's image {2} x {3}")]
    Size(u32, u32, u32, u32),
    /// The integrator places its samples on a grid fixed by the sample count (Whitted's
    /// strata), so it cannot add some of them at a time.
    #[error(
        "this integrator renders all of a pixel's samples at once (samples 0..{0}); passes of some of them need one that takes a sampler (the path tracer)"
    )]
    NotProgressive(u32),
}

/// Adds samples `samples` of every pixel of `scene` to `film`, as `options` say (threads,
/// progress, cancellation). Whitted takes only the whole range `0..spp`, in one pass.
pub fn render_pass(
    scene: &Scene,
    integrator: &dyn Integrator,
    film: &mut Film,
    samples: Range<u32>,
    options: &RenderOptions,
) -> Result<PassStats, PassError> {
    if !integrator.uses_sampler() && samples != (0..scene.settings.spp) {
        return Err(PassError::NotProgressive(scene.settings.spp));
    }
    pass(
        scene,
        integrator,
        film,
        |_, _, _| samples.clone(),
        |_| false,
        options,
    )
}

/// Brings every pixel of `film` up to `target` samples: each takes the samples from the
/// number it has to `target` (none if it has as many), so a film left uneven by a
/// cancelled pass (or read back from a checkpoint) comes out as a render of `target`
/// samples would, to the bit. Only for integrators that take a sampler.
pub fn render_pass_to(
    scene: &Scene,
    integrator: &dyn Integrator,
    film: &mut Film,
    target: u32,
    options: &RenderOptions,
) -> Result<PassStats, PassError> {
    if !integrator.uses_sampler() {
        return Err(PassError::NotProgressive(scene.settings.spp));
    }
    pass(
        scene,
        integrator,
        film,
        |_, _, p| p.samples..target.max(p.samples),
        |_| false,
        options,
    )
}

/// [`render_pass_to`] for the pixels `going_on` names alone (an adaptive render's pass):
/// the others, and the tiles where none is, are left as they are.
pub fn render_pass_adaptive(
    scene: &Scene,
    integrator: &dyn Integrator,
    film: &mut Film,
    target: u32,
    going_on: &Convergence,
    options: &RenderOptions,
) -> Result<PassStats, PassError> {
    if !integrator.uses_sampler() {
        return Err(PassError::NotProgressive(scene.settings.spp));
    }
    pass(
        scene,
        integrator,
        film,
        |x, y, p| {
            if going_on.is_active(x, y) {
                p.samples..target.max(p.samples)
            } else {
                p.samples..p.samples
            }
        },
        |t| !going_on.tile_active(t),
        options,
    )
}

/// Adds to each pixel the samples `range` gives for it.
fn pass(
    scene: &Scene,
    integrator: &dyn Integrator,
    film: &mut Film,
    range: impl Fn(u32, u32, &FilmPixel) -> Range<u32> + Sync,
    skip: impl Fn(u32) -> bool + Sync,
    options: &RenderOptions,
) -> Result<PassStats, PassError> {
    let s = &scene.settings;
    if (film.width(), film.height()) != (s.width, s.height) {
        return Err(PassError::Size(
            film.width(),
            film.height(),
            s.width,
            s.height,
        ));
    }
    let grid = film.grid();
    let camera = scene.camera.raster(s.width, s.height);
    let job = PixelJob {
        scene,
        integrator,
        camera: &camera,
    };
    let tiles = for_each_tile(
        film,
        options,
        skip,
        |x, y, pixel, (rays, bad): &mut (RayStats, BadSamples)| {
            let samples = range(x, y, pixel);
            job.add_pixel(x, y, samples, pixel, rays, bad);
        },
        |_, _| {},
    )?;
    let done = TilesDone::gather(tiles, grid);
    Ok(PassStats {
        rays: done.rays,
        bad_samples: done.bad_samples,
        tiles_done: done.tiles as u32,
    })
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::integrator::{Path, Whitted};
    use crate::render::render;
    use crate::scene::{Format, load_str};

    fn scene(spp: u32) -> Scene {
        let text = format!(
            "[image]\nwidth = 20\nheight = 14\nsamples = {spp}\nfilter = {{ type = \"mitchell\" }}\n\
             [integrator]\ntype = \"path\"\n\
             [camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\
             [materials.lamp]\ntype = \"diffuse\"\ncolor = 0\nemission = 4\n\
             [materials.white]\ntype = \"diffuse\"\ncolor = 0.7\n\
             [materials.gold]\ntype = \"conductor\"\nmetal = \"Au\"\nroughness = 0.2\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [0, 3, 0]\nradius = 0.5\nmaterial = \"lamp\"\n\
             [[objects]]\ntype = \"sphere\"\nradius = 0.8\nmaterial = \"gold\"\n\
             [[objects]]\ntype = \"plane\"\npoint = [0, -0.8, 0]\nmaterial = \"white\"\n"
        );
        load_str(
            &text,
            std::path::Path::new("t.toml"),
            std::path::Path::new("."),
            Format::Toml,
        )
        .unwrap()
    }

    /// Options for a test render on `threads` threads, without progress or cancelling.
    pub(in crate::render) fn options(threads: usize) -> RenderOptions<'static> {
        RenderOptions {
            threads: Some(threads),
            progress: &|_| {},
            cancel: None,
            region: None,
        }
    }

    /// The pixels' bits, for comparing renders exactly.
    pub(in crate::render) fn bits(p: &[crate::math::Color]) -> Vec<u32> {
        p.iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .collect()
    }

    /// Passes of 1, 4 and 7 samples on one and on two threads leave the film as a render
    /// of all 12 at once does, to the bit; and the film is the image that render writes.
    #[test]
    fn passes_add_up_to_one_render() {
        let whole = render(&scene(12), &Path, Some(2), &|_| {}).unwrap();
        let scene = scene(12);
        let mut film = Film::new(20, 14);
        let mut rays = 0;
        for (range, threads) in [(0..1, 1), (1..5, 2), (5..12, 1)] {
            let stats = render_pass(&scene, &Path, &mut film, range, &options(threads)).unwrap();
            assert_eq!(stats.tiles_done, 2);
            rays += stats.rays.camera;
        }
        assert_eq!(rays, 12 * 20 * 14);
        assert!(film.pixels().iter().all(|p| p.samples == 12));
        assert_eq!(bits(&film.image().pixels), bits(&whole.image.pixels));
        // Fewer samples are another picture.
        let mut short = Film::new(20, 14);
        render_pass(&scene, &Path, &mut short, 0..5, &options(2)).unwrap();
        assert_ne!(bits(&short.image().pixels), bits(&whole.image.pixels));
    }

    /// A pass cancelled part way leaves tiles at two sample counts; bringing the film up to
    /// 12 from there gives the render of 12, to the bit.
    #[test]
    fn an_uneven_film_is_brought_up_to_one_render() {
        let whole = render(&scene(12), &Path, Some(2), &|_| {}).unwrap();
        let scene = scene(12);
        let mut film = Film::new(20, 14);
        render_pass_to(&scene, &Path, &mut film, 3, &options(2)).unwrap();
        // Cancelled after its first tile (one thread takes them in order).
        let stop = std::sync::atomic::AtomicBool::new(false);
        let progress = |_| stop.store(true, std::sync::atomic::Ordering::SeqCst);
        let cancelling = RenderOptions {
            threads: Some(1),
            progress: &progress,
            cancel: Some(&stop),
            region: None,
        };
        let stats = render_pass_to(&scene, &Path, &mut film, 7, &cancelling).unwrap();
        assert_eq!(stats.tiles_done, 1);
        let counts: std::collections::BTreeSet<u32> =
            film.pixels().iter().map(|p| p.samples).collect();
        assert_eq!(counts, [3, 7].into());
        render_pass_to(&scene, &Path, &mut film, 12, &options(1)).unwrap();
        assert_eq!(bits(&film.image().pixels), bits(&whole.image.pixels));
        assert!(matches!(
            render_pass_to(&scene, &Whitted, &mut film, 12, &options(1)),
            Err(PassError::NotProgressive(12))
        ));
    }

    /// Whitted goes through the same loop in one pass of all its samples: the image
    /// `render` gives.
    #[test]
    fn whitted_passes_all_its_samples_at_once() {
        let mut scene = scene(9);
        scene.settings.integrator.kind = crate::scene::IntegratorKind::Whitted;
        let whole = render(&scene, &Whitted, Some(1), &|_| {}).unwrap();
        let mut film = Film::new(20, 14);
        render_pass(&scene, &Whitted, &mut film, 0..9, &options(2)).unwrap();
        assert!(film.pixels().iter().all(|p| p.samples == 9));
        assert_eq!(bits(&film.image().pixels), bits(&whole.image.pixels));
        for range in [0..1, 1..9, 0..4] {
            assert!(matches!(
                render_pass(&scene, &Whitted, &mut film, range, &options(1)),
                Err(PassError::NotProgressive(9))
            ));
        }
    }

    #[test]
    fn a_pass_refuses_another_size() {
        let scene = scene(4);
        let mut film = Film::new(8, 8);
        assert!(matches!(
            render_pass(&scene, &Path, &mut film, 0..1, &options(1)),
            Err(PassError::Size(8, 8, 20, 14))
        ));
        assert!(film.pixels().iter().all(|p| p.samples == 0));
        assert_eq!(film.image().pixels[0], crate::math::Color::ZERO);
    }
}
