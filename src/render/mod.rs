//! Rendering an image: a film's tiles over all cores (tiles.rs, the one loop every render
//! goes through), each pixel's samples seeded from `(seed, x, y)` (pixel.rs), so the result
//! is the same bytes at any thread count; a whole render here, passes of some samples at a
//! time in pass.rs.

use crate::film::{Film, FilmPixel, Image};
use crate::integrator::{Integrator, RayStats};
use crate::math::Color;
use crate::scene::Scene;
use std::collections::BTreeMap;
use std::sync::Mutex;
use std::sync::atomic::AtomicBool;

pub mod adaptive;
mod aov;
pub mod bdpt;
pub mod estimate;
pub mod light;
pub mod lpe;
pub mod pass;
mod passes;
mod pixel;
pub mod progressive;
mod tiles;
pub mod to_files;

pub use crate::film::Region;
pub use crate::film::TILE;
pub use aov::render_aovs;
pub use pass::{PassError, PassStats, render_pass, render_pass_adaptive, render_pass_to};
pub use pixel::{
    PixelJob, camera_ray, for_each_sample, sample_position, start_sample, whitted_lens_sample,
};
pub(crate) use tiles::for_each_tile;

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
    /// Tiles finished (before, in a resumed render, included).
    pub tiles_done: u32,
    /// Tiles to render: all of the image's, or those that share a pixel with the region.
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

    /// Adds `other`'s count and as many of its examples as there is room for.
    pub fn add(&mut self, other: BadSamples) {
        self.count += other.count;
        for e in other.examples {
            if self.examples.len() < Self::EXAMPLES {
                self.examples.push(e);
            }
        }
    }
}

/// Tiles already rendered, by tile index (row-major over the image's 16 x 16 tiles), each
/// its finished pixels row by row. A whole render skips the tiles it holds and adds the
/// ones it finishes, so a render can be checkpointed while it runs and resumed later with
/// the same result.
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
#[derive(Clone, Copy)]
pub struct RenderOptions<'a> {
    /// Render threads; `None` uses every core.
    pub threads: Option<usize>,
    /// Called from the worker threads with the number of pixels finished so far.
    pub progress: &'a (dyn Fn(u64) + Sync),
    /// Set to stop: tiles not yet started are skipped, tiles under way finish.
    pub cancel: Option<&'a AtomicBool>,
    /// Only the tiles that share a pixel with this region are rendered, if given (the
    /// others are left as they were); it must lie within the film ([`Region::check`]).
    /// Passes then count samples over it.
    pub region: Option<Region>,
}

/// Renders `scene` with its settings. `threads` = `None` uses every core. `progress` is
/// called from the worker threads with the number of pixels finished so far.
pub fn render(
    scene: &Scene,
    integrator: &dyn Integrator,
    threads: Option<usize>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Rendered, RenderError> {
    let options = RenderOptions {
        threads,
        progress,
        cancel: None,
        region: None,
    };
    render_with(scene, integrator, &options, None)
}

/// Renders `scene` as `options` say: every sample of each pixel at once, tile by tile, into
/// a film of finished colours (a whole render keeps no sums: it adds nothing later, and the
/// sums would double the film). Tiles `store` holds are taken from it, and tiles finished
/// are added to it. Tiles skipped because of `cancel` are black in the image;
/// [`Rendered::complete`] says whether every tile is there.
pub fn render_with(
    scene: &Scene,
    integrator: &dyn Integrator,
    options: &RenderOptions,
    store: Option<&TileStore>,
) -> Result<Rendered, RenderError> {
    let s = &scene.settings;
    let mut film: Film<Color> = Film::new(s.width, s.height);
    let grid = film.grid();
    // Tiles the store holds whole are done: copied in and skipped.
    let earlier: BTreeMap<_, _> = store
        .map(|st| st.snapshot())
        .unwrap_or_default()
        .into_iter()
        .filter(|(i, t)| *i < grid.count() && t.len() == grid.len(*i))
        .collect();
    for (&i, tile) in &earlier {
        film.tile_mut(i).copy_from_slice(tile);
    }
    let camera = scene.camera.raster(s.width, s.height);
    let job = PixelJob {
        scene,
        integrator,
        camera: &camera,
    };
    let tiles = for_each_tile(
        &mut film,
        options,
        |i| earlier.contains_key(&i),
        |x, y, color, (rays, bad): &mut (RayStats, BadSamples)| {
            let mut pixel = FilmPixel::default();
            job.add_pixel(x, y, 0..s.spp, &mut pixel, rays, bad);
            *color = pixel.value();
        },
        |i, tile| {
            if let Some(st) = store {
                st.lock().insert(i, tile.to_vec());
            }
        },
    )?;
    let done = TilesDone::gather(tiles, grid);
    // On the render's own threads, as many as it was given.
    let pixels = thread_pool(options.threads)?.install(|| film.into_rows());
    Ok(Rendered {
        image: Image {
            width: s.width,
            height: s.height,
            pixels,
        },
        rays: done.rays,
        bad_samples: done.bad_samples,
        tiles_done: (earlier.len() + done.tiles) as u32,
        // A region's: the tiles that share a pixel with it.
        tiles_total: grid.tiles_in(options.region),
        pixels_rendered: done.pixels,
    })
}

/// What the tiles a loop rendered add up to.
#[derive(Default)]
struct TilesDone {
    rays: RayStats,
    bad_samples: BadSamples,
    tiles: usize,
    pixels: u64,
}

impl TilesDone {
    /// The tiles' stats, in tile order, so the examples of bad samples are the same at any
    /// thread count.
    fn gather(tiles: Vec<(u32, (RayStats, BadSamples))>, grid: crate::film::TileGrid) -> Self {
        let mut done = TilesDone::default();
        for (i, (rays, bad)) in tiles {
            done.rays += rays;
            done.bad_samples.add(bad);
            done.tiles += 1;
            done.pixels += grid.len(i) as u64;
        }
        done
    }
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
