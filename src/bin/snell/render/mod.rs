//! `snell render`: a scene to an image, with progress, interruption, checkpoints, debug
//! views and statistics.

use crate::args::RenderArgs;
use crate::{job_error, usage_error};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use snell::checkpoint::{Checkpoint, CheckpointIntegrator};
use snell::integrator::aov::{Aov, render_aovs};
use snell::job::RenderJob;
use snell::output::{ExrLayer, OutputError, OutputFormat, PendingOutput, encode_exr_layers};
use snell::render::{RenderOptions, TileStore};

mod frames;
mod passes;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
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

/// `out.png` with a view's name before the extension: `out.normal.png`.
fn aov_path(out: &Path, aov: Aov) -> PathBuf {
    let mut name = out.file_stem().unwrap_or_default().to_os_string();
    name.push(format!(".{}.", aov.name()));
    name.push(out.extension().unwrap_or_default());
    out.with_file_name(name)
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

/// Refuses (exit 2, before any work) a render whose picture, its partial picture, a view
/// (`--aov`) or its checkpoint would replace a file the render reads: the scene file, its
/// textures, meshes, glTF buffers and images, environment map, or the checkpoint it
/// resumes.
fn refuse_outputs_over_inputs(
    args: &RenderArgs,
    scene: &snell::Scene,
    scene_path: &Path,
    out_path: &Path,
) -> Option<ExitCode> {
    let mut outputs = vec![
        out_path.to_path_buf(),
        snell::output::partial_path(out_path),
    ];
    for list in &args.aov {
        for &a in list {
            let p = aov_path(out_path, a);
            outputs.push(snell::output::partial_path(&p));
            outputs.push(p);
        }
    }
    let mut inputs: Vec<&Path> = vec![scene_path];
    inputs.extend(scene.files.iter().map(PathBuf::as_path));
    if let Some(r) = &args.resume {
        inputs.push(r);
    }
    // A checkpoint may replace the one it resumes (that is how --resume goes on).
    if let Some(c) = &args.checkpoint
        && args.resume.as_ref() != Some(c)
    {
        outputs.push(c.clone());
    }
    let (out, input) = snell::output::inputs::output_over_input(
        outputs.iter().map(PathBuf::as_path),
        inputs.iter().copied(),
    )?;
    Some(usage_error(
        &format!(
            "the output {} is {}, which this render reads: writing it would destroy it",
            out.display(),
            input.display()
        ),
        Some("name another output (-o FILE)"),
    ))
}

/// The command line's overrides of the scene's settings.
fn overrides(args: &RenderArgs) -> snell::job::Overrides {
    snell::job::Overrides {
        exposure: args.exposure,
        tonemap: args.tonemap,
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
    if let Some(code) = refuse_outputs_over_inputs(args, &scene, &scene_path, &out_path) {
        return code;
    }
    let mut pending = match PendingOutput::create(&out_path) {
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
        ];
        if let Some((_, flag)) = other.iter().find(|(given, _)| *given) {
            return usage_error(
                &format!("--region cannot be combined with {flag} yet"),
                Some("render the region without it"),
            );
        }
    }
    let random = snell::integrator::chosen(scene.settings.integrator.kind).uses_sampler();
    let mut aovs: Vec<Aov> = vec![];
    for list in &args.aov {
        // `all` is every view the integrator has: Whitted has no variance.
        let all = list.as_slice() == Aov::ALL;
        for a in list {
            let unavailable = all && *a == Aov::Variance && !random;
            if !aovs.contains(a) && !unavailable {
                aovs.push(*a);
            }
        }
    }
    if aovs.contains(&Aov::Variance) && !random {
        return usage_error(
            "the variance view is the path tracer's: Whitted's samples are fixed strata, not random ones whose spread estimates an error",
            Some("render with --integrator path (or [integrator] type = \"path\")"),
        );
    }
    // Separate PNGs are reserved now, like the picture, so a bad path fails before rendering.
    let mut aov_outputs = vec![];
    if pending.format() == OutputFormat::Png {
        for &a in &aovs {
            match PendingOutput::create(&aov_path(&out_path, a)) {
                Ok(p) => aov_outputs.push((a, p)),
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(1);
                }
            }
        }
    }
    if !args.quiet {
        for w in &scene.warnings {
            eprintln!("warning: {w}");
        }
        warn_if_long(&scene, args.threads.map(usize::from), args.time);
    }
    let (w, h, spp) = (
        scene.settings.width,
        scene.settings.height,
        scene.settings.spp,
    );
    let pixels = w as u64 * h as u64;
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
        keep_film: aovs.contains(&Aov::Variance),
        region: args.region,
    };
    // The path tracer renders in passes, unless it resumes a checkpoint of tiles (an
    // earlier snell's).
    let by_passes = integrator.uses_sampler()
        && resumed
            .as_ref()
            .is_none_or(|c| c.film.is_some() || c.tiles.is_empty());
    let outcome = if by_passes {
        passes::render_passes(&run, resumed.and_then(|c| c.film), args.time)
    } else {
        if args.time.is_some() && !args.quiet {
            eprintln!(
                "warning: --time is for the path tracer's passes; this render takes all its samples at once"
            );
        }
        render_tiles(&run, resumed.map(|c| c.tiles).unwrap_or_default())
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
    if !outcome.complete {
        // An unfinished picture never replaces a finished one: it goes beside it.
        pending.make_partial();
        for (_, out) in &mut aov_outputs {
            out.make_partial();
        }
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
    } else if aovs.is_empty() {
        pending
            .commit_toned(&outcome.image, &scene.settings.tone)
            .map_err(|e| e.to_string())
    } else {
        write_aovs(&scene, threads, &outcome, pending, &aovs, aov_outputs)
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
        let _ = std::fs::remove_file(snell::output::partial_path(&aov_path(&out_path, a)));
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
        let (w, h, pixels) = match args.region {
            Some(r) => (r.width(), r.height(), r.pixels()),
            None => (w, h, pixels),
        };
        let samples = pixels * outcome.spp as u64;
        // A resumed render's rate counts only the samples rendered in this run.
        let resumed_part = if outcome.samples < samples {
            format!(" ({} of them in this run)", outcome.samples)
        } else {
            String::new()
        };
        let error = outcome
            .error
            .map(|e| format!("; estimated error {:.2} %", 100.0 * e))
            .unwrap_or_default();
        outln!(
            "wrote {}: {w} x {h}, {} spp{}, {samples} samples{resumed_part} in {elapsed:.2} s ({:.2} M samples/s, {} threads){error}",
            out_path.display(),
            outcome.spp,
            if outcome.spp < spp {
                format!(" (--time stopped it short of {spp})")
            } else {
                String::new()
            },
            outcome.samples as f64 / elapsed.max(1e-9) / 1e6,
            threads.unwrap_or_else(rayon::current_num_threads),
        );
    }
    let bad = &outcome.bad_samples;
    if bad.count > 0 && !args.quiet {
        let places: Vec<String> = bad
            .examples
            .iter()
            .take(3)
            .map(|b| {
                let what = match b.object {
                    Some(i) => format!("object `{}`", scene.objects[i].name),
                    None => "the background".to_string(),
                };
                let kind = if b.nan { "NaN" } else { "infinite" };
                format!("pixel ({}, {}) on {what} ({kind})", b.x, b.y)
            })
            .collect();
        eprintln!(
            "warning: {} samples came out NaN or infinite and were left out of their pixels; {}: {}",
            bad.count,
            if bad.count as usize > places.len() {
                "the first"
            } else {
                "at"
            },
            places.join("; ")
        );
        eprintln!(
            "  help: look for huge or extreme values in those objects' materials and lights, and run `snell explain SCENE --pixel X,Y` on one of them"
        );
    }
    if args.stats {
        print_stats(&scene.stats, load_time, &outcome.rays, elapsed);
    }
    ExitCode::SUCCESS
}

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
            integrator: Some(CheckpointIntegrator::of(&s.integrator)),
            scene: std::fs::canonicalize(self.scene_path)
                .unwrap_or_else(|_| self.scene_path.to_path_buf()),
            output: std::path::absolute(self.out_path)
                .unwrap_or_else(|_| self.out_path.to_path_buf()),
            tiles,
            film,
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

/// Every sample of each pixel at once, tile by tile (Whitted, whose strata are fixed by the
/// sample count, and a resumed checkpoint of tiles), from `earlier` tiles on, with
/// checkpoints saved from a thread of their own.
fn render_tiles(
    run: &Run,
    earlier: std::collections::BTreeMap<u32, Vec<snell::math::Color>>,
) -> Result<Outcome, String> {
    let store = TileStore::new(earlier);
    let finished = AtomicBool::new(false);
    let rendered = std::thread::scope(|scope| {
        if let Some(path) = run.checkpoint {
            let (store, finished) = (&store, &finished);
            let (every, saver) = (run.every, run.saver);
            scope.spawn(move || {
                let mut last = Instant::now();
                while !finished.load(Ordering::SeqCst) {
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    if last.elapsed() >= every {
                        if let Err(e) = saver.checkpoint(store.snapshot(), None).save(path) {
                            eprintln!(
                                "warning: cannot save the checkpoint {}: {e}",
                                path.display()
                            );
                        }
                        last = Instant::now();
                    }
                }
            });
        }
        let options = RenderOptions {
            threads: run.threads,
            progress: &|n| run.bar.set_position(n),
            cancel: Some(&STOP),
            region: run.region,
        };
        let r = snell::render::render_with(run.scene, run.integrator, &options, Some(&store));
        finished.store(true, Ordering::SeqCst);
        r
    })
    .map_err(|e| e.to_string())?;
    let spp = run.scene.settings.spp;
    Ok(Outcome {
        complete: rendered.complete(),
        spp,
        samples: rendered.pixels_rendered * spp as u64,
        done: format!(
            "{} of {} tiles rendered (the rest are black)",
            rendered.tiles_done, rendered.tiles_total
        ),
        checkpoint: Some(run.saver.checkpoint(store.snapshot(), None)),
        image: rendered.image,
        rays: rendered.rays,
        bad_samples: rendered.bad_samples,
        error: None,
        film: None,
    })
}

/// Renders estimated at over an hour are told so before they start, with what would
/// shorten them; `time` (a `--time` cap) bounds the estimate where the path tracer's
/// passes honour it.
fn warn_if_long(scene: &snell::Scene, threads: Option<usize>, time: Option<std::time::Duration>) {
    use snell::render::estimate::{PROBE_FROM_SAMPLES, in_words, render_time};
    let s = &scene.settings;
    if (s.width as u64) * (s.height as u64) * (s.spp as u64) < PROBE_FROM_SAMPLES {
        return;
    }
    let threads = threads.unwrap_or_else(rayon::current_num_threads);
    let integrator = snell::integrator::chosen(scene.settings.integrator.kind);
    if time.is_some_and(|t| t.as_secs_f64() <= 3600.0) && integrator.uses_sampler() {
        return;
    }
    let e = render_time(scene, integrator, threads);
    if e.seconds > 3600.0 {
        eprintln!(
            "warning: this render will take about {} on {threads} threads ({} x {} at {} spp, about {:.2} M samples/s from a probe of {} samples); Ctrl-C stops it and writes what is done",
            in_words(e.seconds),
            s.width,
            s.height,
            s.spp,
            e.samples_per_second / 1e6,
            e.probe_samples
        );
        eprintln!(
            "  help: fewer samples (--spp) or a smaller image (--width, --height) shorten it; --spp 1 at a quarter of the size gives a quick preview"
        );
    }
}

/// Writes the picture and its debug views: one multi-layer EXR, or a PNG per view.
fn write_aovs(
    scene: &snell::Scene,
    threads: Option<usize>,
    outcome: &Outcome,
    pending: PendingOutput,
    aovs: &[Aov],
    pngs: Vec<(Aov, PendingOutput)>,
) -> Result<(), String> {
    let image = &outcome.image;
    let mut buffers = render_aovs(scene, threads).map_err(|e| e.to_string())?;
    if let Some(film) = &outcome.film {
        buffers.set_variance(film);
    }
    if pending.format() == OutputFormat::Exr {
        let layers: Vec<ExrLayer> = aovs
            .iter()
            .map(|&a| (a.name(), buffers.channels(a)))
            .collect();
        let bytes = encode_exr_layers(image, &layers, pending.path()).map_err(|e| e.to_string())?;
        return pending.commit_bytes(&bytes).map_err(|e| e.to_string());
    }
    pending
        .commit_toned(image, &scene.settings.tone)
        .map_err(|e| e.to_string())?;
    for (a, out) in pngs {
        out.commit(&buffers.display(a, scene.settings.max_depth))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// The `--stats` report.
fn print_stats(
    s: &snell::scene::BuildStats,
    load_time: std::time::Duration,
    rays: &snell::integrator::RayStats,
    render_secs: f64,
) {
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    let mib = |b: usize| b as f64 / (1u64 << 20) as f64;
    outln!(
        "scene:     {} objects; {} mesh(es), {} triangles ({} placed); loaded and built in {:.1} ms",
        s.objects,
        s.meshes,
        s.unique_triangles,
        s.instanced_triangles,
        ms(load_time)
    );
    outln!(
        "build:     mesh files read in {:.1} ms, mesh BVHs built in {:.1} ms, object BVH in {:.2} ms",
        ms(s.mesh_load_time),
        ms(s.mesh_bvh_time),
        ms(s.object_bvh_time)
    );
    let per_triangle = if s.unique_triangles > 0 {
        format!(
            " ({:.1} bytes per triangle)",
            s.bvh_bytes as f64 / s.unique_triangles as f64
        )
    } else {
        String::new()
    };
    outln!(
        "memory:    BVHs {:.2} MiB{per_triangle}, mesh data {:.2} MiB",
        mib(s.bvh_bytes),
        mib(s.mesh_bytes)
    );
    let rate = |n: u64| n as f64 / render_secs.max(1e-9) / 1e6;
    outln!(
        "rays:      {:.2} M in {render_secs:.2} s: {:.2} M rays/s",
        rays.total() as f64 / 1e6,
        rate(rays.total())
    );
    for (kind, n) in [
        ("camera", rays.camera),
        ("secondary", rays.secondary),
        ("shadow", rays.shadow),
    ] {
        outln!(
            "  {kind:<10} {:>8.2} M  {:>7.2} M/s of render time",
            n as f64 / 1e6,
            rate(n)
        );
    }
}
