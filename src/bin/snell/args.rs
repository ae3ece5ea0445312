//! The command line's arguments, as clap parses them, and the parsers of their values.

use clap::Args;
use snell::integrator::aov::Aov;
use snell::sampler::SamplerKind;
use snell::scene::{IntegratorKind, Limits};
use std::path::PathBuf;
use std::process::ExitCode;

/// The image flags `render` and `explain` share; each overrides the scene's `[image]`.
#[derive(Args, Debug)]
pub(crate) struct ImageArgs {
    /// Image width in pixels (overrides the scene; `explain`'s pixel coordinates depend on
    /// it).
    #[arg(long, allow_negative_numbers = true, value_parser = size, value_name = "W")]
    pub(crate) width: Option<u32>,
    /// Image height in pixels (overrides the scene).
    #[arg(long, allow_negative_numbers = true, value_parser = size, value_name = "H")]
    pub(crate) height: Option<u32>,
    #[command(flatten)]
    pub(crate) sampling: SamplingArgs,
}

/// The sampling flags `render`, `explain` and `serve` share.
#[derive(Args, Debug)]
pub(crate) struct SamplingArgs {
    /// Samples per pixel: for the Whitted integrator a square number, 1, 4, 9, 16 ... (n x n
    /// stratified, jittered), for the path tracer any number; `explain --sample` counts up
    /// to it.
    #[arg(long, allow_negative_numbers = true, value_parser = size, value_name = "N")]
    pub(crate) spp: Option<u32>,
    /// The integrator, `whitted`, `path`, `light` or `bdpt` (overrides the scene's `[integrator] type`).
    #[arg(long, value_name = "NAME", value_parser = parse_integrator)]
    pub(crate) integrator: Option<IntegratorKind>,
    /// The path tracer's sampler, `sobol` or `independent` (overrides the scene).
    #[arg(long, value_name = "NAME", value_parser = parse_sampler)]
    pub(crate) sampler: Option<SamplerKind>,
    /// The path tracer's clamp: the most one sample adds to a pixel, per channel (removes
    /// fireflies, darkens: biased; off unless set here or in the scene).
    #[arg(long, allow_negative_numbers = true, value_name = "X", value_parser = parse_clamp)]
    pub(crate) clamp: Option<f32>,
}

impl ImageArgs {
    /// The overrides these flags give (and the seed, which only `render` takes).
    pub(crate) fn overrides(&self, seed: Option<u64>) -> snell::job::Overrides {
        snell::job::Overrides {
            width: self.width,
            height: self.height,
            seed,
            ..self.sampling.overrides()
        }
    }
}

impl SamplingArgs {
    /// The overrides these flags give.
    pub(crate) fn overrides(&self) -> snell::job::Overrides {
        snell::job::Overrides {
            spp: self.spp,
            integrator: self.integrator,
            sampler: self.sampler,
            clamp: self.clamp,
            ..snell::job::Overrides::default()
        }
    }
}

/// `snell serve`'s arguments.
#[derive(Args, Debug)]
pub(crate) struct ServeArgs {
    /// The scene file (.toml or .json).
    pub(crate) scene: PathBuf,
    /// The port to listen on; 0 takes a free one (the address is printed).
    #[arg(long, allow_negative_numbers = true, value_parser = whole::<u16>, default_value_t = 8570)]
    pub(crate) port: u16,
    /// The address to listen on. The default answers this machine only; another (0.0.0.0
    /// for every interface) lets the network read the picture and the scene's file names.
    #[arg(long, value_name = "ADDRESS", default_value = "127.0.0.1")]
    pub(crate) host: String,
    /// Open the page in the default browser.
    #[arg(long)]
    pub(crate) open: bool,
    /// The preview's longest side in pixels (the scene's shape kept, never enlarged); 0
    /// renders at the scene's own size.
    #[arg(long, allow_negative_numbers = true, value_parser = whole::<u32>, value_name = "PIXELS", default_value_t = 512)]
    pub(crate) size: u32,
    /// The frame of the scene's [animation] to show (a scene without one has frame 0
    /// only); each save shows this frame again.
    #[arg(long, allow_negative_numbers = true, value_parser = whole::<u32>, value_name = "N", default_value_t = 0)]
    pub(crate) frame: u32,
    #[command(flatten)]
    pub(crate) sampling: SamplingArgs,
    /// Adaptive sampling (path tracer), as `render --noise`: after 16 samples a pixel, only
    /// pixels whose estimated relative error, or a neighbour's, is above this take more; the
    /// page's `spp` view shows where the samples went (overrides `[image] noise`).
    #[arg(long, allow_negative_numbers = true, value_parser = parse_noise, value_name = "ERROR")]
    pub(crate) noise: Option<f32>,
    #[command(flatten)]
    pub(crate) limits: LimitArgs,
}

fn parse_integrator(s: &str) -> Result<IntegratorKind, String> {
    match s {
        "whitted" => Ok(IntegratorKind::Whitted),
        "path" => Ok(IntegratorKind::Path),
        "light" => Ok(IntegratorKind::Light),
        "bdpt" => Ok(IntegratorKind::Bdpt),
        _ => Err(format!(
            "`{s}` is not an integrator: use whitted, path, light or bdpt"
        )),
    }
}

fn parse_sampler(s: &str) -> Result<SamplerKind, String> {
    match s {
        "sobol" => Ok(SamplerKind::Sobol),
        "independent" => Ok(SamplerKind::Independent),
        _ => Err(format!("`{s}` is not a sampler: use sobol or independent")),
    }
}

fn parse_clamp(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v > 0.0 && v.is_finite() => Ok(v),
        _ => Err(format!(
            "`{s}` is not a clamp: give a positive number (the most one sample adds to a pixel)"
        )),
    }
}

/// A noise threshold: a relative error above 0 and at most 1, or a percentage (`1%`).
fn parse_noise(s: &str) -> Result<f32, String> {
    let t = s.trim();
    let (number, scale) = match t.strip_suffix('%') {
        Some(n) => (n.trim(), 0.01),
        None => (t, 1.0),
    };
    let bad = || {
        format!(
            "`{s}` is not a noise threshold: give a relative error above 0 and at most 1, as 0.01 or 1%"
        )
    };
    let v = number.parse::<f32>().map_err(|_| bad())? * scale;
    snell::scene::RenderSettings::check_noise(v).map_err(|_| bad())?;
    Ok(v)
}

/// A time: a number with `ms`, `s`, `m` or `h` after it, or seconds without.
pub(crate) fn parse_duration(s: &str) -> Result<std::time::Duration, String> {
    let t = s.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let scale = match unit.trim() {
        "" | "s" => 1.0,
        "ms" => 1e-3,
        "m" | "min" => 60.0,
        "h" => 3600.0,
        _ => f64::NAN,
    };
    match number.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && (v * scale).is_finite() && v * scale < 1e9 => {
            Ok(std::time::Duration::from_secs_f64(v * scale))
        }
        _ => Err(format!(
            "`{s}` is not a time: give a positive number of seconds, or one with ms, s, m or h after it (30s, 2m, 1h)"
        )),
    }
}

#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    /// The scene file (.toml or .json); with --resume, the checkpoint names it.
    #[arg(required_unless_present = "resume")]
    pub(crate) scene: Option<PathBuf>,
    /// Output image; .png or .exr picks the format [default: the scene's name with .png,
    /// in the current folder].
    #[arg(short, long, value_name = "OUT")]
    pub(crate) output: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) image: ImageArgs,
    /// Render threads [default: every core]. The image is the same at any count.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = positive::<u16>)]
    pub(crate) threads: Option<u16>,
    /// Seed of the sample jitter; the same seed gives the same bytes.
    #[arg(long, allow_negative_numbers = true, value_parser = whole::<u64>, value_name = "S")]
    pub(crate) seed: Option<u64>,
    /// Exposure of a PNG, in stops (+1 doubles the light, -1 halves it) before the tone
    /// curve (overrides the scene's `[image] exposure`; an EXR stays linear).
    #[arg(long, allow_negative_numbers = true, value_parser = parse_exposure, value_name = "STOPS")]
    pub(crate) exposure: Option<f32>,
    /// Tone curve of a PNG: clamp (cut at 1), reinhard or aces (overrides the scene's
    /// `[image] tonemap`).
    #[arg(long, value_parser = parse_tonemap, value_name = "CURVE")]
    pub(crate) tonemap: Option<snell::output::tone::ToneCurve>,
    /// The path tracer, light tracing and bdpt render in passes (1, 2, 4 ... samples per
    /// pixel); stop after the pass that spends this time, or at the scene's samples if
    /// sooner: 30s, 2m, 1h, 1.5 (seconds). With --spp 65536 the time alone decides.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_duration, value_name = "TIME")]
    pub(crate) time: Option<std::time::Duration>,
    /// Adaptive sampling (path tracer): after 16 samples a pixel, a pixel takes more only
    /// while its estimated relative error, or a neighbour's, is above this (0.01 or 1 %),
    /// --spp (or the scene's samples) the most it takes (overrides `[image] noise`).
    #[arg(long, allow_negative_numbers = true, value_parser = parse_noise, value_name = "ERROR")]
    pub(crate) noise: Option<f32>,
    /// Also write the picture denoised by Intel Open Image Denoise, guided by albedo and
    /// normal images: beside a PNG as NAME.denoised.png, or as the layer `denoised` of an
    /// EXR. Needs a snell built with the `denoise` feature (docs/denoise.md).
    #[arg(long)]
    pub(crate) denoise: bool,
    /// Render only the pixels of columns X0..X1 and rows Y0..Y1 (ends exclusive, (0, 0) the
    /// top left): the same pixels, bit for bit, as that part of the whole render. A PNG holds
    /// the region alone; an EXR holds it at its place in the whole image (its data window).
    #[arg(long, value_parser = parse_region, value_name = "X0,Y0,X1,Y1")]
    pub(crate) region: Option<snell::render::Region>,
    /// Frames of the scene's [animation] to render: A..B (A to B, both included) or one
    /// frame N. With more than one frame the output names a pattern whose run of # is
    /// the frame number, zero-padded: -o out/frame_####.png.
    #[arg(long, value_parser = parse_frames, value_name = "A..B")]
    pub(crate) frames: Option<FrameRange>,
    /// With --frames: leave a frame whose output file exists as it is (outputs are written
    /// whole or not at all, so an existing one is finished): a stopped job resumes.
    #[arg(long, requires = "frames")]
    pub(crate) skip_existing: bool,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub(crate) quiet: bool,
    /// After rendering, print what the scene cost to load and build (meshes, BVH memory)
    /// and how many rays of each kind were traced, per second.
    #[arg(long)]
    pub(crate) stats: bool,
    /// Debug views to write besides the picture, comma-separated: normal, uv, depth,
    /// albedo, object, material, bounces, variance and spp (the path tracer's), or all; and
    /// strategies (bdpt's: each strategy's light, weighted and not, for paths of up to 4
    /// segments). With a .png output each goes to its own file (seed.normal.png,
    /// seed.s1-t2.png ...); with .exr, all go into the one file as layers.
    #[arg(long, value_name = "NAMES", value_delimiter = ',', value_parser = parse_aov)]
    pub(crate) aov: Vec<AovArg>,
    /// A light path expression to render beside the picture (path tracer; repeatable):
    /// NAME=EXPR, such as direct=C<RD>L, or a preset: emission, direct, indirect, specular,
    /// caustics, per-light. With a .png output each goes to its own file (seed.direct.png);
    /// with .exr, into the one file as layers (direct.R ...). See docs/lpe.md.
    #[arg(long, value_name = "NAME=EXPR", value_parser = snell::lpe::request)]
    pub(crate) lpe: Vec<snell::lpe::Request>,
    /// Save progress to FILE while rendering (and when interrupted), so the render can be
    /// continued with --resume FILE. Removed once the render is complete.
    #[arg(long, value_name = "FILE")]
    pub(crate) checkpoint: Option<PathBuf>,
    /// Continue the render saved in FILE (scene, size, samples, seed, integrator and output
    /// come from it); the result is the same, byte for byte, as a render never stopped.
    #[arg(long, value_name = "FILE")]
    pub(crate) resume: Option<PathBuf>,
    /// Seconds between checkpoints.
    #[arg(
        long,
        allow_negative_numbers = true,
        value_name = "SECS",
        default_value_t = 30.0
    )]
    pub(crate) checkpoint_every: f64,
    #[command(flatten)]
    pub(crate) limits: LimitArgs,
}

fn parse_exposure(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if (-20.0..=20.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "`{s}` is not an exposure: give stops from -20 to 20 (0 leaves the picture as it is)"
        )),
    }
}

fn parse_tonemap(s: &str) -> Result<snell::output::tone::ToneCurve, String> {
    snell::output::tone::ToneCurve::from_name(s)
        .ok_or_else(|| format!("`{s}` is not a tone curve: use clamp, reinhard or aces"))
}

/// One name given to `--aov`: debug views (one, or `all`), or bdpt's strategy images.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum AovArg {
    /// Per-pixel debug views.
    Views(Vec<Aov>),
    /// Bidirectional path tracing's images of each strategy.
    Strategies,
}

impl AovArg {
    /// The debug views it names (none for the strategy images).
    pub(crate) fn views(&self) -> &[Aov] {
        match self {
            AovArg::Views(v) => v,
            AovArg::Strategies => &[],
        }
    }
}

fn parse_aov(s: &str) -> Result<AovArg, String> {
    if s == "all" {
        return Ok(AovArg::Views(Aov::ALL.to_vec()));
    }
    if s == "strategies" {
        return Ok(AovArg::Strategies);
    }
    Aov::from_name(s)
        .map(|a| AovArg::Views(vec![a]))
        .ok_or_else(|| {
            let names: Vec<&str> = Aov::ALL.iter().map(|a| a.name()).collect();
            format!(
                "`{s}` is not a debug view: use {}, all or strategies",
                names.join(", ")
            )
        })
}

#[derive(Args, Debug)]
pub(crate) struct ExplainArgs {
    /// The scene file (.toml or .json).
    pub(crate) scene: PathBuf,
    /// The pixel: column and row from the top-left corner, from 0.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel)]
    pub(crate) pixel: (u32, u32),
    /// Which of the pixel's samples, from 0 (in the order the renderer takes them) [default:
    /// the ray through the pixel's centre; under the path tracer, sample 0].
    #[arg(long, allow_negative_numbers = true, value_parser = whole::<u32>, value_name = "K")]
    pub(crate) sample: Option<u32>,
    #[command(flatten)]
    pub(crate) image: ImageArgs,
    /// Print the tree as JSON, for tools.
    #[arg(long)]
    pub(crate) json: bool,
    /// Most rays shown; the rest of a bigger tree is counted, and the cut is said.
    #[arg(long, allow_negative_numbers = true, value_parser = positive::<usize>, value_name = "N", default_value_t = 200)]
    pub(crate) max_rays: usize,
    #[command(flatten)]
    pub(crate) limits: LimitArgs,
}

/// Raising the limits a scene and a render are checked against.
#[derive(Args, Debug)]
pub(crate) struct LimitArgs {
    /// Most pixels in the image [default: 268435456, 16384 x 16384].
    #[arg(long, allow_negative_numbers = true, value_parser = positive::<u64>, value_name = "N")]
    pub(crate) max_pixels: Option<u64>,
    /// Most samples per pixel [default: 65536].
    #[arg(long, allow_negative_numbers = true, value_parser = positive::<u32>, value_name = "N")]
    pub(crate) max_spp: Option<u32>,
    /// Longest ray chain a scene may ask for with max_depth [default: 64; at most 256].
    #[arg(long, allow_negative_numbers = true, value_parser = positive::<u32>, value_name = "N")]
    pub(crate) max_depth: Option<u32>,
    /// Most texels in one image texture [default: 268435456].
    #[arg(long, allow_negative_numbers = true, value_parser = positive::<u64>, value_name = "N")]
    pub(crate) max_texture_pixels: Option<u64>,
    /// Most triangles in all the scene's meshes [default: 268435456].
    #[arg(long, allow_negative_numbers = true, value_parser = positive::<u64>, value_name = "N")]
    pub(crate) max_triangles: Option<u64>,
}

impl LimitArgs {
    /// The limits, or a usage error when one is raised past what snell can do.
    pub(crate) fn get(&self) -> Result<Limits, ExitCode> {
        let d = Limits::default();
        let l = Limits {
            max_pixels: self.max_pixels.unwrap_or(d.max_pixels),
            max_spp: self.max_spp.unwrap_or(d.max_spp),
            max_depth: self.max_depth.unwrap_or(d.max_depth),
            max_texture_pixels: self.max_texture_pixels.unwrap_or(d.max_texture_pixels),
            max_triangles: self.max_triangles.unwrap_or(d.max_triangles),
        };
        l.check().map_err(|e| crate::usage_error(&e, None))?;
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

/// An image side or a sample count: a whole number, told so when it is negative or not a
/// number; 0 and numbers past the limits get their own message from the render's checks.
fn size(s: &str) -> Result<u32, String> {
    s.trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a positive whole number (1, 2, 3 ...)"))
}

/// A whole number from 0, for `--seed` and `--sample`.
fn whole<T: std::str::FromStr + num::Bounded>(s: &str) -> Result<T, String> {
    let s = s.trim();
    s.parse().map_err(|_| {
        // A whole number past the type's range is told the range, not that it is not one.
        if s.parse::<i128>().is_ok_and(|v| v > 0) {
            format!(
                "`{s}` is too large: give a whole number from 0 to {}",
                T::MAX_TEXT
            )
        } else {
            format!("`{s}` is not a whole number from 0 (0, 1, 2 ...)")
        }
    })
}

/// The largest value of the whole number types flags take, for messages.
mod num {
    pub trait Bounded {
        const MAX_TEXT: &'static str;
    }
    impl Bounded for u16 {
        const MAX_TEXT: &'static str = "65535";
    }
    impl Bounded for u32 {
        const MAX_TEXT: &'static str = "4294967295";
    }
    impl Bounded for u64 {
        const MAX_TEXT: &'static str = "18446744073709551615";
    }
}

/// A whole number from 1, for sizes, counts and limits. Negative numbers reach this parser
/// (`allow_negative_numbers`), so `--width -5` is told what a width is, not to write `-- -5`.
fn positive<T: std::str::FromStr + PartialEq + Default>(s: &str) -> Result<T, String> {
    match s.trim().parse::<T>() {
        Ok(v) if v != T::default() => Ok(v),
        Ok(_) => Err("must be at least 1".to_string()),
        Err(_) => Err(format!(
            "`{s}` is not a positive whole number (1, 2, 3 ...)"
        )),
    }
}

/// `--frames A..B`: frames A to B, both included.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct FrameRange {
    pub(crate) first: u32,
    pub(crate) last: u32,
}

impl FrameRange {
    /// How many frames.
    pub(crate) fn count(&self) -> u64 {
        (self.last - self.first) as u64 + 1
    }
}

fn parse_frames(s: &str) -> Result<FrameRange, String> {
    let number = |t: &str| {
        t.trim().parse::<u32>().map_err(|_| {
            format!("`{s}` is not a frame range: give A..B (frames A to B, both included) or one frame N, whole numbers from 0")
        })
    };
    let (first, last) = match s.split_once("..") {
        Some((a, b)) => (number(a)?, number(b.strip_prefix('=').unwrap_or(b))?),
        None => {
            let n = number(s)?;
            (n, n)
        }
    };
    if last < first {
        return Err(format!(
            "`{s}` runs backwards: the first frame comes first ({last}..{first})"
        ));
    }
    Ok(FrameRange { first, last })
}

/// `--region X0,Y0,X1,Y1`.
fn parse_region(s: &str) -> Result<snell::render::Region, String> {
    snell::render::Region::parse(s)
}
