//! The `snell` command line: parse arguments, call the library, print, and map errors to
//! exit codes (0 done, 1 render or write failed, 2 bad command line or scene, 130 interrupted).

use clap::{Parser, Subcommand};
use snell::scene::{Limits, RenderSettings, SceneError};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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

/// `n` and the noun, `s` added but for one: "1 frame", "3 frames".
pub(crate) fn count(n: u64, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

mod args;
mod explain;
mod lab;
mod merge;
mod render;
mod serve;

use args::{ExplainArgs, LimitArgs, RenderArgs, ServeArgs};

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
  snell serve scenes/seed.toml --open           a live preview in the browser, redrawn at
                                                every save; click a pixel to explain it

Exit codes: 0 done, 1 rendering or writing failed, 2 bad command line or scene,
130 interrupted (Ctrl-C or SIGTERM; the tiles finished were written to NAME.partial.png
beside the output, which is left as it was).
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
    /// temporary file and renamed into place, so a failed render never leaves a broken image;
    /// an interrupted one writes what it finished to NAME.partial.png (or .exr) beside it.
    #[command(after_help = EXAMPLES)]
    Render(RenderArgs),
    /// Check a scene without rendering: report every problem with its line and column, or
    /// print a summary (objects, lights, textures) and any warnings.
    Check {
        /// The scene file (.toml or .json).
        scene: PathBuf,
        #[command(flatten)]
        limits: LimitArgs,
        /// Print one JSON object instead: the image's size and samples (after the flags
        /// below), the animation's frames and rate, and every file the scene reads, for
        /// tools that plan a render (snell-farm).
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        image: args::ImageArgs,
    },
    /// Explain one pixel: print the tree of rays behind one of its samples, with what each
    /// ray hit, the material's terms, every light and its shadow ray, the Fresnel split and
    /// the colour each ray returns.
    Explain(ExplainArgs),
    /// A live preview in the browser: the picture refines pass after pass and is drawn
    /// again whenever the scene file, or a texture or mesh it reads, is saved; a click on a
    /// pixel shows the rays behind it.
    ///
    /// Listens on 127.0.0.1 (this machine only) unless --host says otherwise, and never
    /// writes the scene file: a camera moved on the page is copied from it as a [camera]
    /// table to paste.
    Serve(ServeArgs),
    /// Put the region files of one render (`snell render --region ... -o PART.exr`) back
    /// into the whole image: the same bytes as one render of it, as PNG or EXR.
    ///
    /// Refuses files of different renders (scene, size, samples, seed or integrator), files
    /// that overlap, and sets that leave pixels uncovered.
    Merge(merge::MergeArgs),
    /// Experiments for learning how sampling works: `snell lab bsdf plastic --roughness 0.3`
    /// tests a material's sampling against its density and draws both.
    #[command(subcommand)]
    Lab(lab::LabCommand),
    /// Print the scene format's JSON Schema, for editors: `snell schema > snell.schema.json`.
    ///
    /// With it, editors complete keys and flag mistakes in scene files as one types;
    /// docs/scene-format.md ("Editor support") shows how to hook it up.
    Schema,
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
        Command::Render(args) => render::render(args),
        Command::Check {
            scene,
            limits,
            json,
            image,
        } => match limits.get() {
            Ok(l) if json => check_json(&scene, &l, &image.overrides(None)),
            Ok(l) => {
                if image.overrides(None) != snell::job::Overrides::default() {
                    return usage_error(
                        "--width, --height and the sampling flags are for `check --json`",
                        Some("add --json, or leave them out"),
                    );
                }
                check(&scene, &l)
            }
            Err(code) => code,
        },
        Command::Explain(args) => explain::explain(args),
        Command::Serve(args) => serve::serve(args),
        Command::Merge(args) => merge::merge_command(args),
        Command::Lab(command) => lab::lab(command),
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

pub(crate) fn print_scene_error(e: &SceneError) {
    eprint!("{}", scene_error_text(e, std::io::stderr().is_terminal()));
}

/// A scene's problems as `snell check` prints them: each with its file, line and column, the
/// line itself and the hint; in colour and wrapped for a terminal, plain otherwise (a log,
/// a tool, the preview's page).
pub(crate) fn scene_error_text(e: &SceneError, terminal: bool) -> String {
    let theme = if terminal {
        miette::GraphicalTheme::unicode()
    } else {
        miette::GraphicalTheme::unicode_nocolor()
    };
    // Lines are wrapped for a person at a terminal only: piped into a log or a tool, a message
    // stays on one line however long its paths are, so that grep finds it whole.
    let handler = miette::GraphicalReportHandler::new_themed(theme).with_wrap_lines(terminal);
    let mut text = String::new();
    for d in &e.diagnostics {
        let mut out = String::new();
        if handler.render_report(&mut out, d).is_err() {
            out = d.message().to_string();
        }
        text.push_str(&out);
    }
    let n = e.diagnostics.len();
    text.push_str(&format!(
        "error: {} has {n} problem{}\n",
        e.file.display(),
        if n == 1 { "" } else { "s" }
    ));
    text
}

pub(crate) fn load(path: &Path, limits: &Limits) -> Result<snell::Scene, ExitCode> {
    snell::scene::load_with(path, limits).map_err(|e| {
        print_scene_error(&e);
        ExitCode::from(2)
    })
}

/// `check --json`: what a tool needs to plan a render of the scene, after the overrides.
fn check_json(path: &Path, limits: &Limits, overrides: &snell::job::Overrides) -> ExitCode {
    let job = match snell::job::RenderJob::prepare(path, overrides, limits, None) {
        Ok(job) => job,
        Err(e) => return job_error(e),
    };
    let s = &job.scene;
    let absolute = |p: &Path| {
        std::fs::canonicalize(p)
            .or_else(|_| std::path::absolute(p))
            .unwrap_or_else(|_| p.to_path_buf())
    };
    let value = serde_json::json!({
        "scene": absolute(path),
        "width": s.settings.width,
        "height": s.settings.height,
        "spp": s.settings.spp,
        "integrator": s.settings.integrator.kind,
        "noise": s.settings.noise,
        "frames": s.animation.map_or(1, |a| a.frames),
        "fps": s.animation.map(|a| a.fps),
        "files": s.files.iter().map(|f| absolute(f)).collect::<Vec<_>>(),
        "warnings": s.warnings,
    });
    outln!("{value}");
    ExitCode::SUCCESS
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

/// Checks the image sides and samples per pixel after the command line's overrides.
pub(crate) fn check_size_and_spp(s: &RenderSettings, limits: &Limits) -> Result<(), ExitCode> {
    snell::job::check_settings(s, limits).map_err(job_error)
}

/// Prints why a job cannot start; exit code 2 (a bad scene or command line).
pub(crate) fn job_error(e: snell::job::JobError) -> ExitCode {
    match e {
        snell::job::JobError::Scene(e) => {
            print_scene_error(&e);
            ExitCode::from(2)
        }
        snell::job::JobError::Settings { message, help } => usage_error(&message, help.as_deref()),
    }
}

pub(crate) fn usage_error(msg: &str, help: Option<&str>) -> ExitCode {
    eprintln!("error: {msg}");
    if let Some(h) = help {
        eprintln!("  help: {h}");
    }
    ExitCode::from(2)
}
