//! A progressive render: passes over the whole film, each bringing every pixel to more
//! samples (1, 2, 4, 8 ...), so that a picture of every pixel exists early and improves,
//! until the sample count is reached, a time is spent, or the render is cancelled. A pass
//! cancelled part way leaves its finished tiles with more samples than the rest; the film
//! is still a picture (each pixel the average of its own samples), and the next pass brings
//! them level, so stopping and going on (a checkpoint between passes) gives the bytes of a
//! render never stopped. An adaptive render's pass (`Until::noise`) cancelled part way is
//! left out instead, for the same reason (see `render_progressive`).

use super::adaptive::Convergence;
use super::pass::{PassError, render_pass_adaptive, render_pass_to};
use super::{BadSamples, RenderOptions};
use crate::film::Film;
use crate::integrator::{Integrator, RayStats};
use crate::scene::Scene;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// When a progressive render stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Until {
    /// Samples per pixel.
    pub spp: u32,
    /// After the pass that spends this much time (from the render's start), if given; the
    /// first pass (one sample of every pixel) is always taken.
    pub time: Option<Duration>,
    /// Adaptive sampling: once every pixel has
    /// [`FIRST_DECISION`](super::adaptive::FIRST_DECISION) samples, only those whose relative
    /// error (or a neighbour's) is above this take more (`spp` the most any takes).
    pub noise: Option<f32>,
}

/// Why it stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ended {
    /// Every pixel has its samples.
    Complete,
    /// The time was spent: every pixel has the samples of the passes done.
    TimeSpent,
    /// Cancelled: some pixels may have a pass more than others.
    Cancelled,
}

/// What the callback is told between passes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PassEvent {
    /// A pass starts, taking every pixel to `to` samples.
    Start {
        /// The fewest samples any pixel that takes some has.
        from: u32,
        /// The pass's end.
        to: u32,
        /// The pixels that take samples: all of them (or of the region), but in an adaptive
        /// render, where the others have converged (or reached the samples' cap).
        pixels: u64,
    },
    /// A pass is over.
    Done {
        /// The fewest samples any pixel has (below the pass's end if it was cancelled).
        samples: u32,
        /// In an adaptive render, the pixels that have converged (or reached the samples'
        /// cap) and take no more.
        converged: Option<u64>,
        /// Since the render started.
        elapsed: Duration,
    },
}

/// What the passes did.
#[derive(Clone, Debug, Default)]
pub struct Progressive {
    /// Why they stopped (`None` only before the first).
    pub ended: Option<Ended>,
    /// Passes run (a cancelled one included).
    pub passes: u32,
    /// Samples added to the film, over all pixels.
    pub samples_added: u64,
    /// The rays traced.
    pub rays: RayStats,
    /// Samples that came out NaN or infinite (left out of their pixels).
    pub bad_samples: BadSamples,
}

/// Samples taken over all passes, for progress in samples: a pass reports the pixels it
/// has finished ([`RenderOptions::progress`]); told when each pass starts, this turns that
/// count into the samples of the whole render. Shared with the render threads.
#[derive(Debug, Default)]
pub struct SampleCount {
    /// Samples taken before the pass under way.
    base: AtomicU64,
    /// Samples the pass under way adds to each pixel.
    step: AtomicU64,
}

impl SampleCount {
    /// A pass starts, taking each of `pixels` pixels from `from` to `to` samples.
    pub fn pass(&self, pixels: u64, from: u32, to: u32) {
        self.base.store(pixels * from as u64, Ordering::Relaxed);
        self.step.store((to - from) as u64, Ordering::Relaxed);
    }

    /// A pass of an adaptive render starts, the film holding `taken` samples in all, its
    /// pixels that go on taking `step` more each (the bar then counts a finished tile's
    /// pixels that have converged as taking them too: an estimate).
    pub fn adaptive_pass(&self, taken: u64, step: u32) {
        self.base.store(taken, Ordering::Relaxed);
        self.step.store(step as u64, Ordering::Relaxed);
    }

    /// The samples taken once `n` pixels of the pass under way are finished.
    pub fn after(&self, n: u64) -> u64 {
        self.base.load(Ordering::Relaxed) + n * self.step.load(Ordering::Relaxed)
    }
}

/// The fewest samples any pixel of `film` has.
pub fn film_samples(film: &Film) -> u32 {
    film_samples_in(film, None)
}

/// [`film_samples`] of the pixels of `region` (all where `None`).
pub fn film_samples_in(film: &Film, region: Option<crate::film::Region>) -> u32 {
    film.pixels_in(region).map(|p| p.samples).min().unwrap_or(0)
}

/// Where the pass from `done` samples ends: twice as many (1 first), no further than `spp`,
/// and, when `time_left` is given and a sample per pixel is known to take `per_sample`,
/// no further than fits in it (but always one sample more).
pub fn next_pass_end(
    done: u32,
    spp: u32,
    per_sample: Option<Duration>,
    time_left: Option<Duration>,
) -> u32 {
    let mut end = done.saturating_mul(2).max(1);
    if let (Some(each), Some(left)) = (per_sample, time_left)
        && each > Duration::ZERO
    {
        let fit = (left.as_secs_f64() / each.as_secs_f64())
            .floor()
            .min(u32::MAX as f64) as u32;
        end = end.min(done.saturating_add(fit));
    }
    end.min(spp).max(done.saturating_add(1))
}

/// Renders `film` in passes until `until` (or `options.cancel`) stops it, calling `event`
/// before and after each pass (to show progress, save a checkpoint, send a picture). A
/// film that already holds samples (a resumed render) goes on from them.
pub fn render_progressive(
    scene: &Scene,
    integrator: &dyn Integrator,
    film: &mut Film,
    until: Until,
    options: &RenderOptions,
    event: &mut dyn FnMut(PassEvent, &Film),
) -> Result<Progressive, PassError> {
    let start = Instant::now();
    let mut out = Progressive::default();
    // Seconds a sample of one pixel takes, from the last pass that finished.
    let mut per_pixel_sample: Option<f64> = None;
    let cancelled = || options.cancel.is_some_and(|c| c.load(Ordering::SeqCst));
    let all_pixels = film.grid().pixels_in(options.region);
    let converge = |film: &Film| {
        until
            .noise
            .map(|n| Convergence::of(film, n, until.spp, options.region))
    };
    let mut going_on = converge(film);
    loop {
        let (done, pixels) = match &going_on {
            Some(c) => (c.fewest_samples().unwrap_or(until.spp), c.active()),
            None => (film_samples_in(film, options.region), all_pixels),
        };
        let elapsed = start.elapsed();
        out.ended = if done >= until.spp {
            Some(Ended::Complete)
        } else if cancelled() {
            Some(Ended::Cancelled)
        } else if done > 0 && until.time.is_some_and(|t| elapsed >= t) {
            Some(Ended::TimeSpent)
        } else {
            None
        };
        if out.ended.is_some() {
            return Ok(out);
        }
        let time_left = until.time.map(|t| t.saturating_sub(elapsed));
        let per_sample = per_pixel_sample.map(|t| Duration::from_secs_f64(t * pixels as f64));
        let end = next_pass_end(done, until.spp, per_sample, time_left);
        event(
            PassEvent::Start {
                from: done,
                to: end,
                pixels,
            },
            film,
        );
        let before: u64 = film.pixels().iter().map(|p| p.samples as u64).sum();
        let t0 = Instant::now();
        let (stats, tiles) = match &going_on {
            Some(c) => {
                let grid = film.grid();
                let tiles = (0..grid.count()).filter(|&t| c.tile_active(t)).count() as u32;
                // A pass cancelled part way is left out: the next decisions read the film
                // as this one did, so a resumed render goes on as one never stopped would
                // (finished tiles' new samples would change their neighbours' windows).
                let start = film.clone();
                let stats = render_pass_adaptive(scene, integrator, film, end, c, options)?;
                if stats.tiles_done < tiles {
                    *film = start;
                }
                (stats, tiles)
            }
            None => {
                let stats = render_pass_to(scene, integrator, film, end, options)?;
                (stats, film.grid().tiles_in(options.region))
            }
        };
        let after: u64 = film.pixels().iter().map(|p| p.samples as u64).sum();
        out.passes += 1;
        out.samples_added += after - before;
        out.rays += stats.rays;
        out.bad_samples.add(stats.bad_samples);
        if stats.tiles_done == tiles && after > before {
            per_pixel_sample = Some(t0.elapsed().as_secs_f64() / (after - before) as f64);
        }
        going_on = converge(film);
        event(
            PassEvent::Done {
                samples: film_samples_in(film, options.region),
                converged: going_on.as_ref().map(|c| all_pixels - c.active()),
                elapsed: start.elapsed(),
            },
            film,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::super::pass::tests::{bits, options};
    use super::*;

    /// Pixels finished in a pass count as samples of the whole: the passes before it in
    /// full, then this pass's samples for each finished pixel.
    #[test]
    fn a_sample_count_adds_the_passes_before() {
        let count = SampleCount::default();
        count.pass(10, 0, 1);
        assert_eq!(count.after(4), 4);
        count.pass(10, 1, 2);
        assert_eq!(count.after(10), 20);
        count.pass(10, 2, 4);
        assert_eq!((count.after(0), count.after(10)), (20, 40));
    }
    use crate::integrator::Path;
    use crate::render::render;
    use crate::scene::{Format, load_str};
    use std::sync::atomic::AtomicBool;

    #[test]
    fn passes_double_and_stop_at_the_count_and_the_time() {
        let ends: Vec<u32> = std::iter::successors(Some(0), |&d| {
            (d < 100).then(|| next_pass_end(d, 100, None, None))
        })
        .collect();
        assert_eq!(ends, [0, 1, 2, 4, 8, 16, 32, 64, 100]);
        let ms = Duration::from_millis;
        // 10 ms a sample and 35 ms left: three more samples.
        assert_eq!(next_pass_end(8, 100, Some(ms(10)), Some(ms(35))), 11);
        // No time left still takes one more (the caller stops before a pass once it is spent).
        assert_eq!(next_pass_end(8, 100, Some(ms(10)), Some(ms(0))), 9);
        assert_eq!(next_pass_end(u32::MAX - 1, u32::MAX, None, None), u32::MAX);
    }

    fn scene() -> Scene {
        let text = "[image]\nwidth = 24\nheight = 20\nsamples = 13\n\
             [integrator]\ntype = \"path\"\n\
             [camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\
             [environment]\ntype = \"constant\"\ncolor = [0.5, 0.6, 0.8]\n\
             [materials.white]\ntype = \"diffuse\"\ncolor = 0.7\n\
             [[objects]]\ntype = \"sphere\"\nradius = 0.8\nmaterial = \"white\"\n\
             [[objects]]\ntype = \"plane\"\npoint = [0, -0.8, 0]\nmaterial = \"white\"\n";
        load_str(
            text,
            std::path::Path::new("t.toml"),
            std::path::Path::new("."),
            Format::Toml,
        )
        .unwrap()
    }

    /// Passes to 13 give the render of 13, to the bit; cancelled in its third pass and
    /// taken up again, too; every event comes in order.
    #[test]
    fn passes_and_a_cancelled_one_give_one_render() {
        let scene = scene();
        let whole = render(&scene, &Path, Some(2), &|_| {}).unwrap();
        let options = options(2);
        let until = Until {
            spp: 13,
            time: None,
            noise: None,
        };
        let mut film = Film::new(24, 20);
        let mut events = vec![];
        let p = render_progressive(&scene, &Path, &mut film, until, &options, &mut |e, _| {
            events.push(e)
        })
        .unwrap();
        assert_eq!(p.ended, Some(Ended::Complete));
        assert_eq!((p.passes, p.samples_added), (5, 13 * 24 * 20));
        let starts: Vec<_> = events
            .iter()
            .filter_map(|e| match e {
                PassEvent::Start { from, to, .. } => Some((*from, *to)),
                _ => None,
            })
            .collect();
        assert_eq!(starts, [(0, 1), (1, 2), (2, 4), (4, 8), (8, 13)]);
        assert_eq!(bits(&film.image().pixels), bits(&whole.image.pixels));

        // Cancelled from the third pass's first tile on (one thread takes them in order).
        let stop = AtomicBool::new(false);
        let passes = std::sync::atomic::AtomicU32::new(0);
        let progress = |_| {
            if passes.load(Ordering::SeqCst) == 3 {
                stop.store(true, Ordering::SeqCst);
            }
        };
        let cancelling = RenderOptions {
            threads: Some(1),
            progress: &progress,
            cancel: Some(&stop),
            region: None,
        };
        let mut film = Film::new(24, 20);
        let p = render_progressive(&scene, &Path, &mut film, until, &cancelling, &mut |e, _| {
            if let PassEvent::Start { .. } = e {
                passes.fetch_add(1, Ordering::SeqCst);
            }
        })
        .unwrap();
        assert_eq!((p.ended, p.passes), (Some(Ended::Cancelled), 3));
        assert_eq!(film_samples(&film), 2);
        assert!(film.pixels().iter().any(|p| p.samples == 4));
        let p =
            render_progressive(&scene, &Path, &mut film, until, &options, &mut |_, _| {}).unwrap();
        assert_eq!(p.ended, Some(Ended::Complete));
        assert_eq!(bits(&film.image().pixels), bits(&whole.image.pixels));
    }

    /// No time at all: the first pass, one sample of every pixel, then it stops.
    #[test]
    fn a_spent_time_stops_after_a_pass() {
        let scene = scene();
        let options = options(2);
        let until = Until {
            spp: 13,
            time: Some(Duration::ZERO),
            noise: None,
        };
        let mut film = Film::new(24, 20);
        let p =
            render_progressive(&scene, &Path, &mut film, until, &options, &mut |_, _| {}).unwrap();
        assert_eq!((p.ended, p.passes), (Some(Ended::TimeSpent), 1));
        assert!(film.pixels().iter().all(|p| p.samples == 1));
    }
}
