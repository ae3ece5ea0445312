//! The `snell` command line: parse arguments, call the library, print, and map errors to
//! exit codes (0 done, 1 render or write failed, 2 bad command line or scene).

use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use snell::integrator::Whitted;
use snell::output::{OutputError, PendingOutput};
use snell::scene::{RenderSettings, SceneError};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

const EXAMPLES: &str = "\
Examples:
  snell render scenes/seed.toml                 writes seed.png at the scene's size
  snell render scenes/seed.toml -o seed.exr     linear floating-point EXR instead of PNG
  snell render scenes/seed.toml --width 256 --height 256 --spp 1
                                                a quick low-resolution preview
  snell render scenes/seed.toml --spp 16 --threads 1 --seed 7
                                                4 x 4 anti-aliasing on one core, another jitter
  snell check scenes/seed.toml                  validate a scene and print a summary

Exit codes: 0 done, 1 rendering or writing failed, 2 bad command line or scene.
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
    },
    /// Print the scene format's JSON Schema, for editors: `snell schema > snell.schema.json`.
    ///
    /// With it, editors complete keys and flag mistakes in scene files as one types;
    /// docs/scene-format.md ("Editor support") shows how to hook it up.
    Schema,
}

#[derive(Args, Debug)]
struct RenderArgs {
    /// The scene file (.toml or .json).
    scene: PathBuf,
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
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Render(args) => render(args),
        Command::Check { scene } => check(&scene),
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
    let theme = if std::io::stderr().is_terminal() {
        miette::GraphicalTheme::unicode()
    } else {
        miette::GraphicalTheme::unicode_nocolor()
    };
    let handler = miette::GraphicalReportHandler::new_themed(theme);
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

fn load(path: &Path) -> Result<snell::Scene, ExitCode> {
    snell::scene::load(path).map_err(|e| {
        print_scene_error(&e);
        ExitCode::from(2)
    })
}

fn check(path: &Path) -> ExitCode {
    let scene = match load(path) {
        Ok(s) => s,
        Err(code) => return code,
    };
    println!("{}", scene.summary());
    for w in &scene.warnings {
        println!("warning: {w}");
    }
    println!("ok: {} is a valid scene", path.display());
    ExitCode::SUCCESS
}

fn usage_error(msg: &str, help: Option<&str>) -> ExitCode {
    eprintln!("error: {msg}");
    if let Some(h) = help {
        eprintln!("  help: {h}");
    }
    ExitCode::from(2)
}

fn render(args: RenderArgs) -> ExitCode {
    let load_start = Instant::now();
    let mut scene = match load(&args.scene) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let load_time = load_start.elapsed();
    let s = &mut scene.settings;
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
    for (what, v) in [("--width", s.width), ("--height", s.height)] {
        if let Err(e) = RenderSettings::check_side(what, v) {
            return usage_error(&e, None);
        }
    }
    if let Err(e) = RenderSettings::check_pixels(s.width, s.height) {
        return usage_error(&e, None);
    }
    if let Err((e, help)) = RenderSettings::check_spp(s.spp) {
        return usage_error(&e, help.as_deref());
    }
    let out_path = args.output.clone().unwrap_or_else(|| {
        // `cap.day.toml` gives `cap.day.png` (with_extension would cut it to `cap.png`).
        let mut name = args.scene.file_stem().unwrap_or_default().to_os_string();
        name.push(".png");
        PathBuf::from(name)
    });
    let pending = match PendingOutput::create(&out_path) {
        Ok(p) => p,
        Err(e @ OutputError::UnknownFormat(_)) => return usage_error(&e.to_string(), None),
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
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
    let rendered = match snell::render::render(&scene, &Whitted, threads, &|n| bar.set_position(n))
    {
        Ok(r) => r,
        Err(e) => {
            bar.abandon();
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    bar.finish_and_clear();
    let elapsed = start.elapsed().as_secs_f64();
    if let Err(e) = pending.commit(&rendered.image) {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    if !args.quiet {
        let samples = pixels * spp as u64;
        println!(
            "wrote {}: {w} x {h}, {spp} spp, {samples} samples in {elapsed:.2} s ({:.2} M samples/s, {} threads)",
            out_path.display(),
            samples as f64 / elapsed.max(1e-9) / 1e6,
            threads.unwrap_or_else(rayon::current_num_threads),
        );
    }
    if args.stats {
        print_stats(&scene.stats, load_time, &rendered.rays, elapsed);
    }
    ExitCode::SUCCESS
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
    println!(
        "scene:     {} objects; {} mesh(es), {} triangles ({} placed); loaded and built in {:.1} ms",
        s.objects,
        s.meshes,
        s.unique_triangles,
        s.instanced_triangles,
        ms(load_time)
    );
    println!(
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
    println!(
        "memory:    BVHs {:.2} MiB{per_triangle}, mesh data {:.2} MiB",
        mib(s.bvh_bytes),
        mib(s.mesh_bytes)
    );
    let rate = |n: u64| n as f64 / render_secs.max(1e-9) / 1e6;
    println!(
        "rays:      {:.2} M in {render_secs:.2} s: {:.2} M rays/s",
        rays.total() as f64 / 1e6,
        rate(rays.total())
    );
    for (kind, n) in [
        ("camera", rays.camera),
        ("secondary", rays.secondary),
        ("shadow", rays.shadow),
    ] {
        println!(
            "  {kind:<10} {:>8.2} M  {:>7.2} M/s of render time",
            n as f64 / 1e6,
            rate(n)
        );
    }
}
