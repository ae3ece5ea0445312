//! `snell render`: a scene to an image, with progress, interruption, checkpoints, debug
//! views and statistics. This is the command's flow; an animation's frames, the path
//! tracer's passes, Whitted's whole render of tiles, the output files and what is printed
//! are each in a file of their own.

use crate::args::RenderArgs;
use crate::{job_error, usage_error};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use snell::checkpoint::{Checkpoint, CheckpointIntegrator};
use snell::integrator::aov::Aov;
use snell::job::RenderJob;
use snell::output::OutputError;
use snell::render::to_files::Outputs;

mod frames;
mod light;
mod lpe;
mod outputs;
mod passes;
mod report;
mod tiles;
use std::io::IsTerminal;
use std::path::Path;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::time::Instant;

/// Exit code of a render stopped by Ctrl-C or SIGTERM (after writing what was done).
const EXIT_INTERRUPTED: u8 = 130;

/// Set by the first Ctrl-C or SIGTERM: tiles not yet started are skipped.
static STOP: AtomicBool = AtomicBool::new(false);
/// Signals received.
static SIGNALS: AtomicU32 = AtomicU32::new(0);

/// First Ctrl-C (or SIGTERM): stop after the tiles under way and write what is done.
/// Second: exit at once.
fn handle_interrupts() {
    let _ = ctrlc::set_handler(|| {
        if SIGNALS.fetch_add(1, Ordering::SeqCst) > 0 {
            // `exit` runs no destructors: the temporary files are removed here.
            snell::output::atomic::remove_pending_files();
            eprintln!("\ninterrupted again: stopping now, without writing the image");
            std::process::exit(EXIT_INTERRUPTED as i32);
        }
        STOP.store(true, Ordering::SeqCst);
        eprintln!(
            "\ninterrupted: finishing the tiles under way, then writing what is done (Ctrl-C again stops at once)"
        );
    });
}

pub(crate) fn render(args: RenderArgs) -> ExitCode {
    if let Some(range) = args.frames {
        return frames::render_frames(&args, range);
    }
    let resumed = match &args.resume {
        None => None,
        Some(path) => match Checkpoint::load(path) {
            Ok(c) => Some(c),
            Err(e) => return usage_error(&e, None),
        },
    };
    let scene_path = match (&args.scene, &resumed) {
        (Some(p), _) => p.clone(),
        (None, Some(c)) => c.scene.clone(),
        (None, None) => return usage_error("give a scene file", None),
    };
    let limits = match args.limits.get() {
        Ok(l) => l,
        Err(code) => return code,
    };
    let overrides = overrides(&args);
    let job = match RenderJob::prepare(&scene_path, &overrides, &limits, resumed.as_ref()) {
        Ok(job) => job,
        Err(e) => return job_error(e),
    };
    let out_path = args
        .output
        .clone()
        .or_else(|| resumed.as_ref().map(|c| c.output.clone()))
        .unwrap_or_else(|| RenderJob::default_output(&scene_path));
    render_job(&args, job, &out_path, resumed)
}

/// The command line's overrides of the scene's settings.
fn overrides(args: &RenderArgs) -> snell::job::Overrides {
    snell::job::Overrides {
        exposure: args.exposure,
        tonemap: args.tonemap,
        noise: args.noise,
        ..args.image.overrides(args.seed)
    }
}

/// Renders a prepared job to `out_path`: the picture, or what an interruption leaves.
fn render_job(
    args: &RenderArgs,
    job: RenderJob,
    out_path: &Path,
    resumed: Option<Checkpoint>,
) -> ExitCode {
    let scene_path = job.scene_path.clone();
    let (scene, fingerprint, load_time) = (job.scene, job.fingerprint, job.load_time);
    let out_path = out_path.to_path_buf();
    let checkpoint_path = args.checkpoint.clone().or_else(|| args.resume.clone());
    if !(args.checkpoint_every > 0.0 && args.checkpoint_every.is_finite()) {
        return usage_error(
            "--checkpoint-every must be a positive number of seconds",
            None,
        );
    }
    if let Some(code) = outputs::refuse_outputs_over_inputs(args, &scene, &scene_path, &out_path) {
        return code;
    }
    // A denoiser that cannot run fails before any work.
    if args.denoise {
        match snell::denoise::ready() {
            Ok(()) => {}
            Err(snell::denoise::DenoiseError::NotBuilt) => {
                return usage_error(
                    "--denoise needs a snell built with the `denoise` feature",
                    Some(snell::denoise::HOW_TO_BUILD),
                );
            }
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
    }
    let mut pending = match Outputs::reserve(&out_path, &[]) {
        Ok(p) => p,
        Err(e @ OutputError::UnknownFormat(_)) => return usage_error(&e.to_string(), None),
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    if let Some(r) = args.region {
        if let Err(e) = r.check(scene.settings.width, scene.settings.height) {
            return usage_error(&e, None);
        }
        // --time would stop a region at its own count of samples, not the whole render's.
        let other = [
            (args.checkpoint.is_some(), "--checkpoint"),
            (args.resume.is_some(), "--resume"),
            (!args.aov.is_empty(), "--aov"),
            (args.time.is_some(), "--time"),
            (args.denoise, "--denoise"),
            // A pixel at the region's edge would read its neighbours outside.
            (
                scene.settings.noise.is_some(),
                "adaptive sampling (--noise, [image] noise)",
            ),
        ];
        if let Some((_, flag)) = other.iter().find(|(given, _)| *given) {
            return usage_error(
                &format!("--region cannot be combined with {flag} yet"),
                Some("render the region without it"),
            );
        }
    }
    let kind = scene.settings.integrator.kind;
    let random = kind == snell::scene::IntegratorKind::Path;
    let mut aovs: Vec<Aov> = vec![];
    for list in &args.aov {
        // `all` is every view the integrator has: Whitted has no variance or spp.
        let all = list.views() == Aov::ALL;
        for a in list.views() {
            let unavailable = all && a.from_film() && !random;
            if !aovs.contains(a) && !unavailable {
                aovs.push(*a);
            }
        }
    }
    if let Some(a) = aovs.iter().find(|a| a.from_film())
        && !random
    {
        return usage_error(
            &format!(
                "the {} view is the path tracer's: Whitted's samples are fixed strata, not random ones whose spread estimates an error",
                a.name()
            ),
            Some("render with --integrator path (or [integrator] type = \"path\")"),
        );
    }
    let strategies = args.aov.contains(&crate::args::AovArg::Strategies);
    if matches!(
        kind,
        snell::scene::IntegratorKind::Light | snell::scene::IntegratorKind::Bdpt
    ) && let Err(code) = light::check(args, kind, strategies)
    {
        return code;
    }
    if strategies && kind != snell::scene::IntegratorKind::Bdpt {
        return usage_error(
            "the strategy images are bidirectional path tracing's",
            Some("render with --integrator bdpt (or [integrator] type = \"bdpt\")"),
        );
    }
    let lpe = match lpe::prepare(args, &scene, &aovs) {
        Ok(l) => l,
        Err(code) => return code,
    };
    let mut layer_names: Vec<String> = lpe
        .iter()
        .flat_map(|set| set.named.iter().map(|n| n.name.clone()))
        .collect();
    if strategies {
        layer_names.extend(snell::render::bdpt::strategy_names(
            scene.settings.max_depth,
        ));
    }
    if args.denoise {
        if layer_names.iter().any(|n| n == DENOISED) {
            return usage_error(
                "a light path expression named `denoised` would take the denoised picture's file",
                Some("name the expression otherwise"),
            );
        }
        layer_names.push(DENOISED.into());
    }
    // Separate PNGs are reserved now, like the picture, so a bad path fails before rendering.
    if let Err(e) = pending
        .add_views(&aovs)
        .and_then(|()| pending.add_layers(&layer_names))
    {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    if !args.quiet {
        for w in &scene.warnings {
            eprintln!("warning: {w}");
        }
        report::warn_if_long(&scene, args.threads.map(usize::from), args.time);
    }
    let (w, h) = (scene.settings.width, scene.settings.height);
    // The bar counts the pixels of the tiles rendered (a region's).
    let bar_pixels = snell::film::TileGrid {
        width: w,
        height: h,
    }
    .pixels_in(args.region);
    let bar = if !args.quiet && std::io::stderr().is_terminal() {
        let bar = ProgressBar::with_draw_target(Some(bar_pixels), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} rendering [{elapsed_precise}] {wide_bar} {percent:>3}%  {msg}ETA {eta}",
            )
            .expect("the template is valid"),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let start = Instant::now();
    let threads = args.threads.map(usize::from);
    handle_interrupts();
    let integrator = snell::integrator::chosen(scene.settings.integrator.kind);
    let saver = Saver {
        fingerprint,
        scene: &scene,
        scene_path: &scene_path,
        out_path: &out_path,
    };
    let run = Run {
        scene: &scene,
        integrator,
        threads,
        bar: &bar,
        checkpoint: checkpoint_path.as_deref(),
        every: std::time::Duration::from_secs_f64(args.checkpoint_every),
        saver: &saver,
        keep_film: aovs.iter().any(|a| a.from_film()),
        region: args.region,
    };
    // The path tracer renders in passes, unless it resumes a checkpoint of tiles (an
    // earlier snell's).
    let by_passes = integrator.uses_sampler()
        && resumed
            .as_ref()
            .is_none_or(|c| c.film.is_some() || c.tiles.is_empty());
    let outcome = if let Some(set) = &lpe {
        lpe::render_with_lpe(&run, set)
    } else if matches!(
        kind,
        snell::scene::IntegratorKind::Light | snell::scene::IntegratorKind::Bdpt
    ) {
        light::render_splatted(
            kind,
            strategies,
            &run,
            args.time,
            resumed.and_then(|c| c.splatted),
        )
    } else if by_passes {
        passes::render_passes(&run, resumed.and_then(|c| c.film), args.time)
    } else {
        if args.time.is_some() && !args.quiet {
            eprintln!(
                "warning: --time is for the path tracer's passes; this render takes all its samples at once"
            );
        }
        tiles::render_tiles(&run, resumed.map(|c| c.tiles).unwrap_or_default())
    };
    let outcome = match outcome {
        Ok(o) => o,
        Err(e) => {
            bar.abandon();
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    bar.finish_and_clear();
    let elapsed = start.elapsed().as_secs_f64();
    let mut outcome = outcome;
    let (mut denoise_time, mut denoise_failed) = (None, false);
    if args.denoise {
        let t = Instant::now();
        let options = snell::render::RenderOptions {
            threads,
            progress: &|_| {},
            cancel: None,
            region: None,
        };
        let denoised = snell::denoise::guides(&scene, outcome.spp, &options)
            .map_err(|e| e.to_string())
            .and_then(|g| snell::denoise::denoise(&outcome.image, &g).map_err(|e| e.to_string()));
        match denoised {
            Ok(img) => {
                outcome.layers.push(img);
                denoise_time = Some(t.elapsed().as_secs_f64());
            }
            Err(e) => {
                // The picture is still written; the exit status says what failed.
                eprintln!("error: cannot denoise the picture: {e}");
                pending.drop_layer(DENOISED);
                denoise_failed = true;
            }
        }
    }
    pending.set_layer_images(std::mem::take(&mut outcome.layers));
    if !outcome.complete {
        // An unfinished picture never replaces a finished one: it goes beside it.
        pending.make_partial();
    }
    let written = if let Some(r) = args.region {
        pending
            // An unfinished region is not one `snell merge` may take: no fingerprint.
            .commit_region(
                &outcome.image,
                r,
                &scene.settings.tone,
                outcome.complete.then_some(fingerprint),
            )
            .map_err(|e| e.to_string())
    } else {
        pending
            .commit(&scene, &outcome.image, outcome.film.as_ref(), threads)
            .map_err(|e| e.to_string())
    };
    if let Err(e) = written {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    if !outcome.complete {
        let resume = match (&checkpoint_path, &outcome.checkpoint) {
            (Some(path), Some(c)) => match c.save(path) {
                Ok(()) => format!("; continue with: snell render --resume {}", path.display()),
                Err(e) => format!("; the checkpoint could not be saved: {e}"),
            },
            _ => String::new(),
        };
        let old = if out_path.exists() {
            "was left as it was"
        } else {
            "was not written"
        };
        eprintln!(
            "interrupted: wrote {} with {}; {} {old}{resume}",
            snell::output::partial_path(&out_path).display(),
            outcome.done,
            out_path.display(),
        );
        return ExitCode::from(EXIT_INTERRUPTED);
    }
    // The picture is whole: an interrupted run's partial pictures of it are out of date.
    let _ = std::fs::remove_file(snell::output::partial_path(&out_path));
    for &a in &aovs {
        let _ = std::fs::remove_file(snell::output::partial_path(&Outputs::view_path(
            &out_path, a,
        )));
    }
    for name in &layer_names {
        let _ = std::fs::remove_file(snell::output::partial_path(&Outputs::layer_path(
            &out_path, name,
        )));
    }
    if let Some(path) = &checkpoint_path
        && std::fs::remove_file(path).is_ok()
        && !args.quiet
    {
        // The render is whole: its checkpoint has nothing left to continue.
        eprintln!(
            "removed the checkpoint {}: the render is whole",
            path.display()
        );
    }
    if !args.quiet {
        report::print_written(
            &out_path,
            args.region,
            &scene.settings,
            &outcome,
            elapsed,
            threads,
        );
        if let Some(t) = denoise_time {
            let to = if snell::output::OutputFormat::from_path(&out_path)
                .is_ok_and(|f| f == snell::output::OutputFormat::Exr)
            {
                format!("the layer `{DENOISED}` of {}", out_path.display())
            } else {
                Outputs::layer_path(&out_path, DENOISED)
                    .display()
                    .to_string()
            };
            outln!("denoised it in {t:.2} s (guides and Open Image Denoise): {to}");
        }
        report::warn_bad_samples(&scene, &outcome.bad_samples);
    }
    if denoise_failed {
        return ExitCode::from(1);
    }
    if args.stats {
        report::print_stats(&scene.stats, load_time, &outcome.rays, elapsed);
    }
    ExitCode::SUCCESS
}

/// The denoised picture's name: its layer in an EXR, `NAME.denoised.png` beside a PNG.
const DENOISED: &str = "denoised";

/// What a render came to, whichever way it went (tiles or passes).
pub(crate) struct Outcome {
    pub(crate) image: snell::film::Image,
    pub(crate) rays: snell::integrator::RayStats,
    pub(crate) bad_samples: snell::render::BadSamples,
    /// Whether the picture is whole: every tile, or every pass its samples or time allow.
    pub(crate) complete: bool,
    /// Samples per pixel in the picture (the fewest any pixel has).
    pub(crate) spp: u32,
    /// Samples traced in this run (a resumed render's earlier ones not counted).
    pub(crate) samples: u64,
    /// What an interrupted render had done, in words.
    pub(crate) done: String,
    /// Where it stopped, to save when interrupted.
    pub(crate) checkpoint: Option<Checkpoint>,
    /// The picture's estimated mean relative difference from the converged one (passes).
    pub(crate) error: Option<f32>,
    /// The film of sums, kept for the variance view when it is asked for.
    pub(crate) film: Option<snell::film::Film>,
    /// The light path expressions' images, in order (none without expressions).
    pub(crate) layers: Vec<snell::film::Image>,
    /// Where adaptive sampling took the samples (`--noise`).
    pub(crate) adaptive: Option<Adaptive>,
}

/// Where an adaptive render took its samples.
pub(crate) struct Adaptive {
    /// The threshold.
    pub(crate) noise: f32,
    /// The fewest and the most samples a pixel took.
    pub(crate) fewest: u32,
    pub(crate) most: u32,
    /// The samples of all the pixels.
    pub(crate) total: u64,
    /// The pixels whose estimated relative error is below `noise`, of `pixels`.
    pub(crate) converged: u64,
    pub(crate) pixels: u64,
}

impl Adaptive {
    /// The share of pixels below the threshold, in per cent.
    pub(crate) fn share(&self) -> f64 {
        100.0 * self.converged as f64 / self.pixels.max(1) as f64
    }
}

/// What a render is, for its checkpoints.
pub(crate) struct Saver<'a> {
    fingerprint: u64,
    scene: &'a snell::Scene,
    scene_path: &'a Path,
    out_path: &'a Path,
}

impl Saver<'_> {
    /// The checkpoint of a render that has done `tiles` (whole) or `film` (passes).
    pub(crate) fn checkpoint(
        &self,
        tiles: std::collections::BTreeMap<u32, Vec<snell::math::Color>>,
        film: Option<snell::film::Film>,
    ) -> Checkpoint {
        let s = &self.scene.settings;
        Checkpoint {
            fingerprint: self.fingerprint,
            width: s.width,
            height: s.height,
            spp: s.spp,
            seed: s.seed,
            integrator: Some(CheckpointIntegrator::of(s)),
            scene: std::fs::canonicalize(self.scene_path)
                .unwrap_or_else(|_| self.scene_path.to_path_buf()),
            output: std::path::absolute(self.out_path)
                .unwrap_or_else(|_| self.out_path.to_path_buf()),
            tiles,
            film,
            splatted: None,
        }
    }

    /// The checkpoint of a light-traced or bidirectional render's passes.
    pub(crate) fn splatted(&self, passes: snell::checkpoint::Splatted) -> Checkpoint {
        Checkpoint {
            splatted: Some(passes),
            ..self.checkpoint(Default::default(), None)
        }
    }
}

/// Checkpoints between passes: one saved when `--checkpoint-every` has passed since the
/// last, and the first error in saving one kept to be told once the render ends.
pub(crate) struct PeriodicSaves {
    last: Instant,
    error: Option<String>,
}

impl PeriodicSaves {
    /// None saved yet; the first after `run.every` from now.
    pub(crate) fn new() -> Self {
        PeriodicSaves {
            last: Instant::now(),
            error: None,
        }
    }

    /// At a pass's end: saves `make()`'s checkpoint where `run` saves them and it is time.
    pub(crate) fn pass_done(&mut self, run: &Run, make: impl FnOnce() -> Checkpoint) {
        if let Some(path) = run.checkpoint
            && self.last.elapsed() >= run.every
        {
            if let Err(e) = make().save(path) {
                self.error.get_or_insert(e.to_string());
            }
            self.last = Instant::now();
        }
    }

    /// After the render: a warning if a checkpoint could not be saved.
    pub(crate) fn warn(self, run: &Run) {
        if let (Some(e), Some(path)) = (self.error, run.checkpoint) {
            eprintln!(
                "warning: cannot save the checkpoint {}: {e}",
                path.display()
            );
        }
    }
}

/// A render's parts, as both ways of rendering take them.
pub(crate) struct Run<'a> {
    pub(crate) scene: &'a snell::Scene,
    pub(crate) integrator: &'a dyn snell::integrator::Integrator,
    pub(crate) threads: Option<usize>,
    pub(crate) bar: &'a ProgressBar,
    /// Where checkpoints go, and how often.
    pub(crate) checkpoint: Option<&'a Path>,
    pub(crate) every: std::time::Duration,
    pub(crate) saver: &'a Saver<'a>,
    /// Whether the variance view wants the film of sums kept.
    pub(crate) keep_film: bool,
    /// The pixels to render, where not all.
    pub(crate) region: Option<snell::render::Region>,
}
