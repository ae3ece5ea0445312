//! How long a render will take, told before it starts: camera samples traced on one thread
//! at random places in the image (64, or for a render that looks long, up to 30 ms' worth),
//! their cost scaled to the whole render.

use crate::integrator::{Integrator, RayStats};
use crate::math::Rng;
use crate::scene::Scene;
use std::time::{Duration, Instant};

/// The estimated time of a render, and what it was worked out from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeEstimate {
    /// Estimated wall-clock time of the whole render, in seconds.
    pub seconds: f64,
    /// Samples traced to estimate it.
    pub probe_samples: u32,
    /// Samples a second on all the threads, as the probe measured them.
    pub samples_per_second: f64,
}

/// The probe stops after this long (once it has `MIN_PROBE` samples) ...
const PROBE_TIME: Duration = Duration::from_millis(30);
/// ... or after this many samples.
const MAX_PROBE: u32 = 4096;
const MIN_PROBE: u32 = 64;

/// Renders under this many samples are not probed at all: at any plausible speed they take
/// seconds.
pub const PROBE_FROM_SAMPLES: u64 = 1_000_000;
/// Where the first samples' estimate is under this, it is taken as it is.
const REFINE_FROM_SECONDS: f64 = 600.0;

/// Estimates the render of `scene` on `threads` threads with `integrator`, by tracing camera
/// samples at random places (from a fixed seed) on one thread. Assumes the threads scale
/// perfectly, so it errs short; the aim is to tell an hour from a day, not a second.
pub fn render_time(scene: &Scene, integrator: &dyn Integrator, threads: usize) -> TimeEstimate {
    let s = &scene.settings;
    let camera = scene.camera.raster(s.width, s.height);
    let mut rng = Rng::new(0x5eed_e571_3a7e);
    let mut rays = RayStats::default();
    let start = Instant::now();
    let mut n = 0;
    while n < MAX_PROBE && (n < MIN_PROBE || start.elapsed() < PROBE_TIME) {
        let px = rng.next_f32() * s.width as f32;
        let py = rng.next_f32() * s.height as f32;
        std::hint::black_box(integrator.radiance(scene, &camera.ray(px, py), &mut rays));
        n += 1;
        // A render that the first samples show to be short is not probed further: the
        // probe costs it microseconds, not the full budget.
        if n == MIN_PROBE {
            let rough =
                TimeEstimate::scaled(start.elapsed().as_secs_f64() / n as f64, n, s, threads);
            if rough.seconds < REFINE_FROM_SECONDS {
                return rough;
            }
        }
    }
    let per_sample = start.elapsed().as_secs_f64() / n as f64;
    TimeEstimate::scaled(per_sample, n, s, threads)
}

impl TimeEstimate {
    /// The whole render's time from one sample's cost on one thread.
    fn scaled(
        per_sample: f64,
        probe_samples: u32,
        s: &crate::scene::RenderSettings,
        threads: usize,
    ) -> Self {
        let samples = s.width as f64 * s.height as f64 * s.spp as f64;
        let threads = threads.max(1) as f64;
        let per_sample = per_sample.max(1e-12);
        TimeEstimate {
            seconds: samples * per_sample / threads,
            probe_samples,
            samples_per_second: threads / per_sample,
        }
    }
}

/// A duration in words a person reads at a glance: `45 s`, `12 minutes`, `3.5 hours`,
/// `9 days`, `2.3 years`.
pub fn in_words(seconds: f64) -> String {
    const MINUTE: f64 = 60.0;
    const HOUR: f64 = 3600.0;
    const DAY: f64 = 86_400.0;
    const YEAR: f64 = 365.25 * DAY;
    let (value, unit) = match seconds {
        s if s < MINUTE => return format!("{s:.0} s"),
        s if s < HOUR => (s / MINUTE, "minutes"),
        s if s < 2.0 * DAY => (s / HOUR, "hours"),
        s if s < YEAR => (s / DAY, "days"),
        s => (s / YEAR, "years"),
    };
    if value < 10.0 {
        format!("{value:.1} {unit}")
    } else {
        format!("{value:.0} {unit}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Whitted;
    use crate::scene::{Format, load_str};
    use std::path::Path;

    fn scene(width: u32, spp: u32) -> Scene {
        let text = format!(
            "[image]\nwidth = {width}\nheight = 64\nsamples = {spp}\n\
             [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
             [materials.m]\ncolor = 0.5\n[[lights]]\ntype = \"point\"\nposition = [2, 3, 4]\n\
             [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n"
        );
        load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap()
    }

    #[test]
    fn the_probe_traces_a_bounded_number_of_samples() {
        let e = render_time(&scene(64, 1), &Whitted, 1);
        assert!(
            e.probe_samples >= MIN_PROBE && e.probe_samples <= MAX_PROBE,
            "{e:?}"
        );
        assert!(e.seconds > 0.0 && e.seconds.is_finite(), "{e:?}");
    }

    /// The estimate is one sample's cost times the render's samples, over the threads.
    #[test]
    fn the_estimate_scales_with_samples_and_threads() {
        let s = &scene(128, 16).settings;
        let e = TimeEstimate::scaled(1e-6, 100, s, 2);
        let samples = 128.0 * 64.0 * 16.0;
        assert!((e.seconds - samples * 1e-6 / 2.0).abs() < 1e-12, "{e:?}");
        assert!((e.samples_per_second - 2e6).abs() < 1e-3, "{e:?}");
        // 16384 x 16384 at 65,536 samples, even at a billion samples a second on 2 threads:
        // five hours.
        let mut big = s.clone();
        (big.width, big.height, big.spp) = (16384, 16384, 65536);
        let e = TimeEstimate::scaled(2e-9, 100, &big, 2);
        assert!(e.seconds > 4.0 * 3600.0, "{e:?}");
    }

    #[test]
    fn durations_read_in_words() {
        assert_eq!(in_words(42.4), "42 s");
        assert_eq!(in_words(150.0), "2.5 minutes");
        assert_eq!(in_words(5400.0), "1.5 hours");
        assert_eq!(in_words(30.0 * 3600.0), "30 hours");
        assert_eq!(in_words(9.0 * 86_400.0), "9.0 days");
        assert_eq!(in_words(3.0 * 365.25 * 86_400.0), "3.0 years");
    }
}
