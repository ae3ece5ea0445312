//! The `snell` command line: parse arguments, call the library, print, and map errors to
//! exit codes (0 done, 1 render or write failed, 2 bad command line or scene).

use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use snell::checkpoint::Checkpoint;
use snell::integrator::Whitted;
use snell::integrator::aov::{Aov, render_aovs};
use snell::integrator::explain::TreeRecorder;
use snell::output::{ExrLayer, OutputError, OutputFormat, PendingOutput, encode_exr_layers};
use snell::render::{RenderOptions, TileStore};
use snell::scene::{Limits, RenderSettings, SceneError};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::time::Instant;

/// `print!` that never panics: output cut short (a closed pipe, as with `| head`) is not
/// an error worth a crash, so write failures are ignored.
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stdout().lock(), $($arg)*);
    }};
}

/// `println!` that never panics (see `out!`).
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout().lock(), $($arg)*);
    }};
}

const EXAMPLES: &str = "\
Examples:
  snell render scenes/seed.toml                 writes seed.png at the scene's size
  snell render scenes/seed.toml -o seed.exr     linear floating-point EXR instead of PNG
  snell render scenes/seed.toml --width 256 --height 256 --spp 1
                                                a quick low-resolution preview
  snell render scenes/seed.toml --spp 16 --threads 1 --seed 7
                                                4 x 4 anti-aliasing on one core, another jitter
  snell check scenes/seed.toml                  validate a scene and print a summary
  snell explain scenes/seed.toml --pixel 512,760
                                                the tree of rays behind one pixel

Exit codes: 0 done, 1 rendering or writing failed, 2 bad command line or scene,
130 interrupted (Ctrl-C or SIGTERM; the tiles finished were written).
The scene format is documented key by key in docs/scene-format.md.";

/// snell renders images from scene files (TOML or JSON) by ray tracing.
#[derive(Parser, Debug)]
#[command(name = "snell", version, after_help = EXAMPLES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render a scene to a PNG (sRGB, 8-bit) or EXR (linear, float) image.
    ///
    /// Command-line values override the scene's [image] table. The picture is written to a
    /// temporary file and renamed into place, so a failed render never leaves a broken image.
    #[command(after_help = EXAMPLES)]
    Render(RenderArgs),
    /// Check a scene without rendering: report every problem with its line and column, or
    /// print a summary (objects, lights, textures) and any warnings.
    Check {
        /// The scene file (.toml or .json).
        scene: PathBuf,
        #[command(flatten)]
        limits: LimitArgs,
    },
    /// Explain one pixel: print the tree of rays behind one of its samples, with what each
    /// ray hit, the material's terms, every light and its shadow ray, the Fresnel split and
    /// the colour each ray returns.
    Explain(ExplainArgs),
    /// Print the scene format's JSON Schema, for editors: `snell schema > snell.schema.json`.
    ///
    /// With it, editors complete keys and flag mistakes in scene files as one types;
    /// docs/scene-format.md ("Editor support") shows how to hook it up.
    Schema,
}

#[derive(Args, Debug)]
struct RenderArgs {
    /// The scene file (.toml or .json); with --resume, the checkpoint names it.
    #[arg(required_unless_present = "resume")]
    scene: Option<PathBuf>,
    /// Output image; .png or .exr picks the format [default: the scene's name with .png,
    /// in the current folder].
    #[arg(short, long, value_name = "OUT")]
    output: Option<PathBuf>,
    /// Image width in pixels (overrides the scene).
    #[arg(long, value_name = "W")]
    width: Option<u32>,
    /// Image height in pixels (overrides the scene).
    #[arg(long, value_name = "H")]
    height: Option<u32>,
    /// Samples per pixel, a square number: 1, 4, 9, 16 ... (n x n stratified, jittered).
    #[arg(long, value_name = "N")]
    spp: Option<u32>,
    /// Render threads [default: every core]. The image is the same at any count.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    threads: Option<u16>,
    /// Seed of the sample jitter; the same seed gives the same bytes.
    #[arg(long, value_name = "S")]
    seed: Option<u64>,
    /// Print nothing but errors.
    #[arg(short, long)]
    quiet: bool,
    /// After rendering, print what the scene cost to load and build (meshes, BVH memory)
    /// and how many rays of each kind were traced, per second.
    #[arg(long)]
    stats: bool,
    /// Debug views to write besides the picture, comma-separated: normal, uv, depth,
    /// albedo, object, material, bounces, or all. With a .png output each goes to its own
    /// file (seed.normal.png ...); with .exr, all go into the one file as layers.
    #[arg(long, value_name = "NAMES", value_delimiter = ',', value_parser = parse_aov)]
    aov: Vec<Vec<Aov>>,
    /// Save progress to FILE while rendering (and when interrupted), so the render can be
    /// continued with --resume FILE. Removed once the render is complete.
    #[arg(long, value_name = "FILE")]
    checkpoint: Option<PathBuf>,
    /// Continue the render saved in FILE (scene, size, samples, seed and output come from
    /// it); the result is the same, byte for byte, as a render never stopped.
    #[arg(long, value_name = "FILE")]
    resume: Option<PathBuf>,
    /// Seconds between checkpoints.
    #[arg(long, value_name = "SECS", default_value_t = 30.0)]
    checkpoint_every: f64,
    #[command(flatten)]
    limits: LimitArgs,
}

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
            eprintln!("\ninterrupted again: stopping now, without writing the image");
            std::process::exit(EXIT_INTERRUPTED as i32);
        }
        STOP.store(true, Ordering::SeqCst);
        eprintln!(
            "\ninterrupted: finishing the tiles under way, then writing what is done (Ctrl-C again stops at once)"
        );
    });
}

fn parse_aov(s: &str) -> Result<Vec<Aov>, String> {
    if s == "all" {
        return Ok(Aov::ALL.to_vec());
    }
    Aov::from_name(s).map(|a| vec![a]).ok_or_else(|| {
        let names: Vec<&str> = Aov::ALL.iter().map(|a| a.name()).collect();
        format!("`{s}` is not a debug view: use {} or all", names.join(", "))
    })
}

/// `out.png` with a view's name before the extension: `out.normal.png`.
fn aov_path(out: &Path, aov: Aov) -> PathBuf {
    let mut name = out.file_stem().unwrap_or_default().to_os_string();
    name.push(format!(".{}.", aov.name()));
    name.push(out.extension().unwrap_or_default());
    out.with_file_name(name)
}

#[derive(Args, Debug)]
struct ExplainArgs {
    /// The scene file (.toml or .json).
    scene: PathBuf,
    /// The pixel: column and row from the top-left corner, from 0.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel)]
    pixel: (u32, u32),
    /// Which of the pixel's samples, from 0 (in the order the renderer takes them) [default:
    /// the ray through the pixel's centre].
    #[arg(long, value_name = "K")]
    sample: Option<u32>,
    /// Image width in pixels (overrides the scene; pixel coordinates depend on it).
    #[arg(long, value_name = "W")]
    width: Option<u32>,
    /// Image height in pixels (overrides the scene).
    #[arg(long, value_name = "H")]
    height: Option<u32>,
    /// Samples per pixel (overrides the scene; `--sample` counts up to it).
    #[arg(long, value_name = "N")]
    spp: Option<u32>,
    /// Print the tree as JSON, for tools.
    #[arg(long)]
    json: bool,
    /// Most rays shown; the rest of a bigger tree is counted, and the cut is said.
    #[arg(long, value_name = "N", default_value_t = 200)]
    max_rays: usize,
    #[command(flatten)]
    limits: LimitArgs,
}

/// Raising the limits a scene and a render are checked against.
#[derive(Args, Debug)]
struct LimitArgs {
    /// Most pixels in the image [default: 268435456, 16384 x 16384].
    #[arg(long, value_name = "N")]
    max_pixels: Option<u64>,
    /// Most samples per pixel [default: 65536].
    #[arg(long, value_name = "N")]
    max_spp: Option<u32>,
    /// Longest ray chain a scene may ask for with max_depth [default: 64; at most 256].
    #[arg(long, value_name = "N")]
    max_depth: Option<u32>,
    /// Most texels in one image texture [default: 268435456].
    #[arg(long, value_name = "N")]
    max_texture_pixels: Option<u64>,
    /// Most triangles in all the scene's meshes [default: 268435456].
    #[arg(long, value_name = "N")]
    max_triangles: Option<u64>,
}

impl LimitArgs {
    /// The limits, or a usage error when one is raised past what snell can do.
    fn get(&self) -> Result<Limits, ExitCode> {
        let d = Limits::default();
        let l = Limits {
            max_pixels: self.max_pixels.unwrap_or(d.max_pixels),
            max_spp: self.max_spp.unwrap_or(d.max_spp),
            max_depth: self.max_depth.unwrap_or(d.max_depth),
            max_texture_pixels: self.max_texture_pixels.unwrap_or(d.max_texture_pixels),
            max_triangles: self.max_triangles.unwrap_or(d.max_triangles),
        };
        l.check().map_err(|e| usage_error(&e, None))?;
        Ok(l)
    }
}

fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let (x, y) = s
        .split_once(',')
        .ok_or_else(|| format!("`{s}` is not X,Y (for example 512,300)"))?;
    let n = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("`{v}` is not a pixel coordinate (a whole number from 0)"))
    };
    Ok((n(x)?, n(y)?))
}

fn main() -> ExitCode {
    // A decoder panic on a corrupt texture is caught and reported as a scene error; the
    // default hook would print it as if snell had crashed.
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if !snell::texture::in_guarded_decoder() {
            default_hook(info)
        }
    }));
    let cli = Cli::parse();
    match cli.command {
        Command::Render(args) => render(args),
        Command::Check { scene, limits } => match limits.get() {
            Ok(l) => check(&scene, &l),
            Err(code) => code,
        },
        Command::Explain(args) => explain(args),
        Command::Schema => schema(),
    }
}

fn schema() -> ExitCode {
    use std::io::Write;
    let text = serde_json::to_string_pretty(&snell::scene::schema())
        .expect("a JSON value always serializes");
    // writeln, not println: `snell schema | head` must not panic on the closed pipe.
    match writeln!(std::io::stdout(), "{text}") {
        Ok(()) => ExitCode::SUCCESS,
        Err(_) => ExitCode::from(1),
    }
}

fn print_scene_error(e: &SceneError) {
    let terminal = std::io::stderr().is_terminal();
    let theme = if terminal {
        miette::GraphicalTheme::unicode()
    } else {
        miette::GraphicalTheme::unicode_nocolor()
    };
    // Lines are wrapped for a person at a terminal only: piped into a log or a tool, a message
    // stays on one line however long its paths are, so that grep finds it whole.
    let handler = miette::GraphicalReportHandler::new_themed(theme).with_wrap_lines(terminal);
    for d in &e.diagnostics {
        let mut out = String::new();
        if handler.render_report(&mut out, d).is_err() {
            out = d.message().to_string();
        }
        eprint!("{out}");
    }
    let n = e.diagnostics.len();
    eprintln!(
        "error: {} has {n} problem{}",
        e.file.display(),
        if n == 1 { "" } else { "s" }
    );
}

fn load(path: &Path, limits: &Limits) -> Result<snell::Scene, ExitCode> {
    snell::scene::load_with(path, limits).map_err(|e| {
        print_scene_error(&e);
        ExitCode::from(2)
    })
}

fn check(path: &Path, limits: &Limits) -> ExitCode {
    let scene = match load(path, limits) {
        Ok(s) => s,
        Err(code) => return code,
    };
    outln!("{}", scene.summary());
    for w in &scene.warnings {
        outln!("warning: {w}");
    }
    outln!("ok: {} is a valid scene", path.display());
    ExitCode::SUCCESS
}

fn explain(args: ExplainArgs) -> ExitCode {
    let limits = match args.limits.get() {
        Ok(l) => l,
        Err(code) => return code,
    };
    let mut scene = match load(&args.scene, &limits) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let s = &mut scene.settings;
    s.width = args.width.unwrap_or(s.width);
    s.height = args.height.unwrap_or(s.height);
    s.spp = args.spp.unwrap_or(s.spp);
    if let Err(code) = check_size_and_spp(s, &limits) {
        return code;
    }
    let (x, y) = args.pixel;
    if x >= s.width || y >= s.height {
        return usage_error(
            &format!(
                "pixel {x},{y} is outside the {} x {} image",
                s.width, s.height
            ),
            Some(&format!(
                "columns go from 0 to {}, rows from 0 to {}",
                s.width - 1,
                s.height - 1
            )),
        );
    }
    let film = match args.sample {
        None => (x as f32 + 0.5, y as f32 + 0.5),
        Some(k) if k >= s.spp => {
            return usage_error(
                &format!("sample {k} does not exist: the pixel has {} samples", s.spp),
                Some(&format!("use --sample 0 to {}, or --spp", s.spp - 1)),
            );
        }
        Some(k) => {
            let mut at = (0.0, 0.0);
            let mut i = 0;
            snell::render::for_each_sample(s, x, y, |px, py, _| {
                if i == k {
                    at = (px, py);
                }
                i += 1;
            });
            at
        }
    };
    let ray = scene.camera.ray(film.0, film.1, s.width, s.height);
    let mut rec = TreeRecorder::new(args.max_rays);
    let mut rays = snell::integrator::RayStats::default();
    let color = Whitted.explain(&scene, &ray, &mut rays, &mut rec);
    let Some(tree) = rec.finish() else {
        eprintln!("error: no ray was recorded");
        return ExitCode::from(1);
    };
    let which = match args.sample {
        None => "the ray through its centre".to_string(),
        Some(k) => format!("sample {k} of {}", scene.settings.spp),
    };
    if args.json {
        let doc = serde_json::json!({
            "scene": args.scene.display().to_string(),
            "image": [scene.settings.width, scene.settings.height],
            "pixel": [x, y],
            "sample": args.sample,
            "film_position": [film.0, film.1],
            "color": color.to_array(),
            "rays_traced": { "camera": rays.camera, "secondary": rays.secondary, "shadow": rays.shadow },
            "tree": tree,
        });
        match serde_json::to_string_pretty(&doc) {
            Ok(text) => outln!("{text}"),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
    } else {
        outln!(
            "pixel {x},{y} of {} ({} x {}), {which}, film position ({}, {}):",
            args.scene.display(),
            scene.settings.width,
            scene.settings.height,
            film.0,
            film.1
        );
        out!("{}", tree.to_text());
        outln!(
            "{} rays traced ({} camera, {} reflected or refracted, {} shadow); the sample's colour is ({}, {}, {}) in linear RGB",
            rays.camera + rays.secondary + rays.shadow,
            rays.camera,
            rays.secondary,
            rays.shadow,
            color.x,
            color.y,
            color.z
        );
    }
    ExitCode::SUCCESS
}

/// Checks the image sides and samples per pixel after the command line's overrides.
fn check_size_and_spp(s: &RenderSettings, limits: &Limits) -> Result<(), ExitCode> {
    for (what, v) in [("--width", s.width), ("--height", s.height)] {
        RenderSettings::check_side(what, v).map_err(|e| usage_error(&e, None))?;
    }
    limits
        .check_spp(s.spp)
        .map_err(|(e, help)| usage_error(&e, help.as_deref()))
}

fn usage_error(msg: &str, help: Option<&str>) -> ExitCode {
    eprintln!("error: {msg}");
    if let Some(h) = help {
        eprintln!("  help: {h}");
    }
    ExitCode::from(2)
}

fn render(args: RenderArgs) -> ExitCode {
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
    let load_start = Instant::now();
    let mut scene = match load(&scene_path, &limits) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let load_time = load_start.elapsed();
    let s = &mut scene.settings;
    if let Some(c) = &resumed {
        s.width = c.width;
        s.height = c.height;
        s.spp = c.spp;
        s.seed = c.seed;
    }
    if let Some(w) = args.width {
        s.width = w;
    }
    if let Some(h) = args.height {
        s.height = h;
    }
    if let Some(n) = args.spp {
        s.spp = n;
    }
    if let Some(seed) = args.seed {
        s.seed = seed;
    }
    if let Err(code) = check_size_and_spp(s, &limits) {
        return code;
    }
    if let Err((e, help)) = limits.check_pixels(s.width, s.height) {
        return usage_error(&e, help.as_deref());
    }
    // Refuse a render the machine cannot hold before spending time on it.
    let estimate = snell::scene::memory_estimate(&scene);
    if let Some(available) = snell::scene::available_memory()
        && let Err(e) = estimate.check(available)
    {
        return usage_error(&e, Some("render a smaller image (--width, --height)"));
    }
    let scene_bytes = std::fs::read(&scene_path).unwrap_or_default();
    let fingerprint = snell::checkpoint::fingerprint(
        &scene_bytes,
        scene.settings.width,
        scene.settings.height,
        scene.settings.spp,
        scene.settings.seed,
    );
    if let Some(c) = &resumed
        && c.fingerprint != fingerprint
    {
        return usage_error(
            "the scene file or the settings changed since the checkpoint was saved, so resuming would not give the same picture",
            Some("render again without --resume, or restore the scene as it was"),
        );
    }
    let out_path = args
        .output
        .clone()
        .or_else(|| resumed.as_ref().map(|c| c.output.clone()))
        .unwrap_or_else(|| {
            // `cap.day.toml` gives `cap.day.png` (with_extension would cut it to `cap.png`).
            let mut name = scene_path.file_stem().unwrap_or_default().to_os_string();
            name.push(".png");
            PathBuf::from(name)
        });
    let checkpoint_path = args.checkpoint.clone().or_else(|| args.resume.clone());
    if !(args.checkpoint_every > 0.0 && args.checkpoint_every.is_finite()) {
        return usage_error(
            "--checkpoint-every must be a positive number of seconds",
            None,
        );
    }
    let pending = match PendingOutput::create(&out_path) {
        Ok(p) => p,
        Err(e @ OutputError::UnknownFormat(_)) => return usage_error(&e.to_string(), None),
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    let mut aovs: Vec<Aov> = vec![];
    for a in args.aov.iter().flatten() {
        if !aovs.contains(a) {
            aovs.push(*a);
        }
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
    }
    let (w, h, spp) = (
        scene.settings.width,
        scene.settings.height,
        scene.settings.spp,
    );
    let pixels = w as u64 * h as u64;
    let bar = if !args.quiet && std::io::stderr().is_terminal() {
        let bar = ProgressBar::with_draw_target(Some(pixels), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} rendering [{elapsed_precise}] {wide_bar} {percent:>3}%  ETA {eta}",
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
    let store = TileStore::new(resumed.map(|c| c.tiles).unwrap_or_default());
    let snapshot = |tiles| Checkpoint {
        fingerprint,
        width: scene.settings.width,
        height: scene.settings.height,
        spp: scene.settings.spp,
        seed: scene.settings.seed,
        scene: std::fs::canonicalize(&scene_path).unwrap_or_else(|_| scene_path.clone()),
        output: std::path::absolute(&out_path).unwrap_or_else(|_| out_path.clone()),
        tiles,
    };
    let finished = AtomicBool::new(false);
    let rendered = std::thread::scope(|scope| {
        // Checkpoints are written from their own thread, every few seconds.
        if let Some(path) = &checkpoint_path {
            let (store, finished, snapshot) = (&store, &finished, &snapshot);
            let every = std::time::Duration::from_secs_f64(args.checkpoint_every);
            scope.spawn(move || {
                let mut last = Instant::now();
                while !finished.load(Ordering::SeqCst) {
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    if last.elapsed() >= every {
                        if let Err(e) = snapshot(store.snapshot()).save(path) {
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
            threads,
            progress: &|n| bar.set_position(n),
            cancel: Some(&STOP),
            store: Some(&store),
        };
        let r = snell::render::render_with(&scene, &Whitted, &options);
        finished.store(true, Ordering::SeqCst);
        r
    });
    let rendered = match rendered {
        Ok(r) => r,
        Err(e) => {
            bar.abandon();
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    bar.finish_and_clear();
    let elapsed = start.elapsed().as_secs_f64();
    let written = if aovs.is_empty() {
        pending.commit(&rendered.image).map_err(|e| e.to_string())
    } else {
        write_aovs(
            &scene,
            threads,
            &rendered.image,
            pending,
            &aovs,
            aov_outputs,
        )
    };
    if let Err(e) = written {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    if !rendered.complete() {
        let resume = match &checkpoint_path {
            Some(path) => match snapshot(store.snapshot()).save(path) {
                Ok(()) => format!("; continue with: snell render --resume {}", path.display()),
                Err(e) => format!("; the checkpoint could not be saved: {e}"),
            },
            None => String::new(),
        };
        eprintln!(
            "interrupted: wrote {} with {} of {} tiles rendered (the rest are black){resume}",
            out_path.display(),
            rendered.tiles_done,
            rendered.tiles_total
        );
        return ExitCode::from(EXIT_INTERRUPTED);
    }
    if let Some(path) = &checkpoint_path {
        // The render is whole: its checkpoint has nothing left to continue.
        let _ = std::fs::remove_file(path);
    }
    if !args.quiet {
        let samples = pixels * spp as u64;
        outln!(
            "wrote {}: {w} x {h}, {spp} spp, {samples} samples in {elapsed:.2} s ({:.2} M samples/s, {} threads)",
            out_path.display(),
            samples as f64 / elapsed.max(1e-9) / 1e6,
            threads.unwrap_or_else(rayon::current_num_threads),
        );
    }
    let bad = &rendered.bad_samples;
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
        print_stats(&scene.stats, load_time, &rendered.rays, elapsed);
    }
    ExitCode::SUCCESS
}

/// Writes the picture and its debug views: one multi-layer EXR, or a PNG per view.
fn write_aovs(
    scene: &snell::Scene,
    threads: Option<usize>,
    image: &snell::film::Image,
    pending: PendingOutput,
    aovs: &[Aov],
    pngs: Vec<(Aov, PendingOutput)>,
) -> Result<(), String> {
    let buffers = render_aovs(scene, threads).map_err(|e| e.to_string())?;
    if pending.format() == OutputFormat::Exr {
        let layers: Vec<ExrLayer> = aovs
            .iter()
            .map(|&a| (a.name(), buffers.channels(a)))
            .collect();
        let bytes = encode_exr_layers(image, &layers, pending.path()).map_err(|e| e.to_string())?;
        return pending.commit_bytes(&bytes).map_err(|e| e.to_string());
    }
    pending.commit(image).map_err(|e| e.to_string())?;
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
