//! snell: a ray tracer for learning, teaching and making images from scene files.
//!
//! The data flows one way: a scene file is parsed and checked ([`scene::load`]) into an
//! immutable [`Scene`], rendered over all cores ([`render::render`]) by an integrator
//! ([`integrator::Whitted`]) into an [`film::Image`], and written atomically
//! ([`output::write_image`]). [`render::to_files::render_to_files`] does all of it for a
//! prepared [`job::RenderJob`], as `snell render` does, with progress and cancellation as
//! callbacks:
//!
//! ```no_run
//! use snell::render::to_files::{RunOptions, render_to_files};
//! use std::path::Path;
//! let job = snell::job::RenderJob::prepare(
//!     Path::new("scenes/seed.toml"),
//!     &Default::default(), // no overrides of the scene's settings
//!     &Default::default(), // the default limits
//!     None,                // no checkpoint to resume
//! )?;
//! let progress = |p: snell::render::to_files::JobProgress| eprint!("\r{} of {}", p.done, p.total);
//! let options = RunOptions { threads: None, progress: &progress, cancel: None, time: None, lpe: &[] };
//! render_to_files(&job, Path::new("seed.png"), &[], &options)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Or step by step:
//!
//! ```no_run
//! let scene = snell::scene::load(std::path::Path::new("scenes/seed.toml"))?;
//! let image = snell::render::render(&scene, &snell::integrator::Whitted, None, &|_| {})?.image;
//! snell::output::write_image(&image, std::path::Path::new("seed.png"))?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod closed_set;

pub mod accel;
pub mod bsdf;
pub mod camera;
pub mod checkpoint;
pub mod denoise;
pub mod explain_pixel;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod job;
pub mod lab;
pub mod light;
pub mod lpe;
pub mod material;
pub mod math;
pub mod mesh_file;
pub mod output;
pub mod render;
pub mod sampler;
pub mod scene;
pub mod texture;

pub use scene::Scene;

/// Reads a whole file that must be a regular file: a device such as `/dev/zero` or
/// `/dev/random`, named by a scene, a `mtllib` line or a `map_Kd`, would otherwise be read
/// forever. Folders and other special files get the same clear error.
pub fn read_regular_file(path: &std::path::Path) -> std::io::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            if meta.is_dir() {
                "it is a folder, not a file"
            } else {
                "it is not a regular file (a device or pipe would be read forever)"
            },
        ));
    }
    std::fs::read(path)
}
