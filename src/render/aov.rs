//! The debug views' render: the ray through the centre of every pixel, each recording what
//! it met for every view (`integrator::aov`), through the render loop every render takes.

use super::{RenderError, RenderOptions, for_each_tile, thread_pool};
use crate::film::Film;
use crate::integrator::aov::{AovBuffers, AovSample, sample};
use crate::scene::Scene;

/// Traces the ray through the centre of every pixel and records every view.
pub fn render_aovs(scene: &Scene, threads: Option<usize>) -> Result<AovBuffers, RenderError> {
    let (w, h) = (scene.settings.width, scene.settings.height);
    let mut film: Film<AovSample> = Film::new(w, h);
    let options = RenderOptions {
        threads,
        progress: &|_| {},
        cancel: None,
        region: None,
    };
    for_each_tile(
        &mut film,
        &options,
        |_| false,
        |x, y, pixel, _: &mut ()| *pixel = sample(scene, x, y),
        |_, _| {},
    )?;
    let all = thread_pool(threads)?.install(|| film.rows(|s| *s));
    Ok(AovBuffers::from_samples(w, h, &all))
}
