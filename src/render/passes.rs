//! The schedule of a render whose light lands anywhere on the film (light tracing,
//! bidirectional path tracing): passes of 1, 2, 4 ... samples a pixel until the render's
//! `spp`, until a pass ends after a time limit, or until it is cancelled. A pass cancelled
//! part way is taken back by its caller, so the picture is always that of whole passes.

use super::progressive::next_pass_end;
use super::{BadSamples, RenderError, RenderOptions};
use crate::integrator::RayStats;
use std::ops::Range;
use std::time::{Duration, Instant};

/// What one pass did.
pub(crate) struct PassDone {
    /// The rays it traced.
    pub rays: RayStats,
    /// Its samples that came out NaN or infinite.
    pub bad: BadSamples,
    /// Whether every tile took it (not cancelled part way; the caller took it back).
    pub whole: bool,
}

/// What the passes did, together.
pub(crate) struct PassesDone {
    /// Samples a pixel of the passes kept.
    pub spp: u32,
    /// The rays traced.
    pub rays: RayStats,
    /// Samples that came out NaN or infinite.
    pub bad: BadSamples,
    /// Whether no pass was cancelled.
    pub complete: bool,
}

/// Runs `pass(samples, options)` for each pass, from the render's `start`, over an image
/// of `pixels` pixels, the first pass starting at sample `first` (0, or where a resumed
/// render's passes ended); each pass's options report progress in pixels of the whole
/// render.
pub(crate) fn in_passes(
    first: u32,
    spp: u32,
    time: Option<Duration>,
    start: Instant,
    pixels: u64,
    options: &RenderOptions,
    mut pass: impl FnMut(Range<u32>, &RenderOptions) -> Result<PassDone, RenderError>,
) -> Result<PassesDone, RenderError> {
    let mut done = PassesDone {
        spp: first,
        rays: RayStats::default(),
        bad: BadSamples::default(),
        complete: true,
    };
    let mut per_sample = None;
    while done.spp < spp {
        let elapsed = start.elapsed();
        if done.spp > first && time.is_some_and(|t| elapsed >= t) {
            break;
        }
        let left = time.map(|t| t.saturating_sub(elapsed));
        let from = done.spp;
        let end = next_pass_end(from, spp, per_sample, left);
        // Progress in pixels of the whole render: the passes before, and this one's share.
        let progress = |n: u64| {
            let total = pixels * from as u64 + n * (end - from) as u64;
            (options.progress)(total / spp.max(1) as u64)
        };
        let pass_options = RenderOptions {
            progress: &progress,
            ..*options
        };
        let pass_start = Instant::now();
        let p = pass(from..end, &pass_options)?;
        done.rays += p.rays;
        done.bad.add(p.bad);
        if !p.whole {
            done.complete = false;
            break;
        }
        per_sample = Some(pass_start.elapsed() / (end - from));
        done.spp = end;
    }
    Ok(done)
}
