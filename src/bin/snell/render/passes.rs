//! The path tracer's render in passes over a film of sums (1, 2, 4 ... samples per pixel),
//! with `--time`, a progress bar in samples with the error estimated after each pass (in
//! an adaptive render, `--noise`, a bar of the pixels converged), checkpoints between
//! passes, and Ctrl-C writing the picture of the samples taken so far.

use super::{Adaptive, Outcome, PeriodicSaves, Run, STOP};
use snell::film::Film;
use snell::render::RenderOptions;
use snell::render::progressive::{
    Ended, PassEvent, SampleCount, Until, film_samples_in, render_progressive,
};
use std::time::Duration;

/// Renders `run`'s scene in passes, from `earlier` (a resumed film) if given, until its
/// samples or `time` are spent or Ctrl-C stops it.
pub(crate) fn render_passes(
    run: &Run,
    earlier: Option<Film>,
    time: Option<Duration>,
) -> Result<Outcome, String> {
    let s = &run.scene.settings;
    // The pixels of the tiles rendered (a region's), which the bar counts.
    let pixels = film_grid(s.width, s.height).pixels_in(run.region);
    let mut film = earlier.unwrap_or_else(|| Film::new(s.width, s.height));
    let first = film_samples_in(&film, run.region);
    // An adaptive render's bar counts the pixels that have converged (its samples are not
    // known ahead).
    let adaptive = s.noise.is_some();
    run.bar.set_length(if adaptive {
        pixels
    } else {
        pixels * s.spp as u64
    });
    // The ETA is this render's own: the samples left at the rate of the passes finished
    // (none before the first ends: a guess from the first samples of a pass was ten times
    // too long), and no more than what `--time` leaves.
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{spinner} rendering [{elapsed_precise}] {wide_bar} {percent:>3}%  {msg}",
    ) {
        run.bar.set_style(style);
    }
    let mut eta = String::from("ETA …");
    let count = SampleCount::default();
    let progress = |n: u64| {
        if !adaptive {
            run.bar.set_position(count.after(n))
        }
    };
    let options = RenderOptions {
        threads: run.threads,
        progress: &progress,
        cancel: Some(&STOP),
        region: run.region,
    };
    // The picture's estimated error after the last pass, shown on the bar (worked out only
    // where the bar is seen: it reads the whole film, or the region).
    let mut error: Option<f32> = None;
    let mut saves = PeriodicSaves::new();
    let until = Until {
        spp: s.spp,
        time,
        noise: s.noise,
    };
    let mut converged: Option<u64> = None;
    let done = render_progressive(
        run.scene,
        run.integrator,
        &mut film,
        until,
        &options,
        &mut |event, film| match event {
            PassEvent::Start {
                from,
                to,
                pixels: going_on,
            } => {
                count.pass(pixels, from, to);
                let error = error
                    .map(|e| format!(", error ≈ {:.2} %", 100.0 * e))
                    .unwrap_or_default();
                if adaptive {
                    let share = 100.0 * converged.unwrap_or(0) as f64 / pixels.max(1) as f64;
                    run.bar.set_message(format!(
                        "{from} → {to} spp for {going_on} pixels, {share:.1} % converged{error}"
                    ));
                } else {
                    run.bar
                        .set_message(format!("{from} → {to} spp{error}  {eta}"));
                }
            }
            PassEvent::Done {
                samples,
                elapsed,
                converged: now,
            } => {
                if let Some(c) = now {
                    converged = Some(c);
                    run.bar.set_position(c);
                }
                if !run.bar.is_hidden() {
                    error = film.estimated_error_in(run.region);
                    let taken = elapsed.as_secs_f64().max(1e-6);
                    let added = samples.saturating_sub(first) as f64;
                    if added > 0.0 {
                        let mut left = taken / added * s.spp.saturating_sub(samples) as f64;
                        if let Some(t) = time {
                            left = left.min((t.as_secs_f64() - taken).max(0.0));
                        }
                        eta = format!("ETA {}", snell::render::estimate::in_words(left));
                    }
                }
                saves.pass_done(run, || {
                    run.saver.checkpoint(Default::default(), Some(film.clone()))
                });
            }
        },
    )
    .map_err(|e| e.to_string())?;
    saves.warn(run);
    let spp = film_samples_in(&film, run.region);
    let most = film
        .pixels_in(run.region)
        .map(|p| p.samples)
        .max()
        .unwrap_or(0);
    let ended = done.ended.unwrap_or(Ended::Cancelled);
    let error = film.estimated_error_in(run.region);
    let adaptive = s.noise.map(|noise| {
        let taken: Vec<u32> = film.pixels_in(run.region).map(|p| p.samples).collect();
        Adaptive {
            noise,
            fewest: spp,
            most,
            total: taken.iter().map(|&n| n as u64).sum(),
            converged: film
                .pixels_in(run.region)
                .filter(|p| {
                    p.variance_of_mean().is_some_and(|v| {
                        snell::film::relative_error(v, snell::math::luminance(p.value())) <= noise
                    })
                })
                .count() as u64,
            pixels,
        }
    });
    let image = film.image();
    // The film goes to the checkpoint of an interrupted render, to the variance view, or
    // (copied) to both.
    let checkpoint = |film| run.saver.checkpoint(Default::default(), Some(film));
    let (checkpoint, kept) = match (ended == Ended::Cancelled, run.keep_film) {
        (true, true) => (Some(checkpoint(film.clone())), Some(film)),
        (true, false) => (Some(checkpoint(film)), None),
        (false, true) => (None, Some(film)),
        (false, false) => (None, None),
    };
    Ok(Outcome {
        image,
        rays: done.rays,
        bad_samples: done.bad_samples,
        complete: ended != Ended::Cancelled,
        spp,
        samples: done.samples_added,
        done: if let Some(a) = &adaptive {
            format!(
                "{} to {} samples per pixel ({:.1} on average), {:.1} % of pixels below the noise threshold",
                a.fewest,
                a.most,
                a.total as f64 / a.pixels.max(1) as f64,
                a.share()
            )
        } else if most > spp {
            format!(
                "{spp} samples per pixel ({most} in some tiles) of {}",
                s.spp
            )
        } else {
            format!("{spp} samples per pixel of {}", s.spp)
        },
        checkpoint,
        error,
        film: kept,
        layers: vec![],
        adaptive,
    })
}

/// The tile grid of a `width` x `height` film.
fn film_grid(width: u32, height: u32) -> snell::film::TileGrid {
    snell::film::TileGrid { width, height }
}
