//! Debug views (arbitrary output variables): what the ray through each pixel's centre meets
//! first — its normal, uv, distance, surface colour, object and material — and how deep the
//! integrator's rays behind it go (Whitted's tree, or the path tracer's path of sample 0),
//! one ray per pixel, no anti-aliasing, so ids stay exact; and how uncertain the path
//! tracer's pixels are (`variance`, from the render's own samples) and how many samples
//! each took (`spp`, which adaptive sampling varies).
//!
//! [`AovBuffers::channels`] gives the raw values (for a multi-layer EXR);
//! [`AovBuffers::display`] maps them to colours that read well (for PNG), documented in
//! docs/debugging.md.

use super::{Integrator, RayStats, Whitted};
use crate::film::{Film, Image};
use crate::math::{Color, Vec2, Vec3A};
use crate::scene::{Scene, Skip};
use crate::texture::srgb_to_linear;

/// A debug view.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Aov {
    /// The shading normal in world space.
    Normal,
    /// The texture coordinates the surface's texture reads (through its mapping), or the
    /// shape's own where the surface has a plain colour.
    Uv,
    /// Distance along the camera ray to the first hit.
    Depth,
    /// The surface colour (the material's texture at the hit), unlit.
    Albedo,
    /// Which object was hit.
    Object,
    /// Which material is at the hit.
    Material,
    /// How many reflections and refractions the Whitted tree behind the pixel goes down.
    Bounces,
    /// How uncertain the path tracer's pixel is: the variance of its estimate, from the
    /// spread of its samples (the render's own, not a centre ray's).
    Variance,
    /// How many samples the path tracer's pixel took (adaptive sampling's map).
    Spp,
}

impl Aov {
    /// Every view, in the order they are documented.
    pub const ALL: [Aov; 9] = [
        Aov::Normal,
        Aov::Uv,
        Aov::Depth,
        Aov::Albedo,
        Aov::Object,
        Aov::Material,
        Aov::Bounces,
        Aov::Variance,
        Aov::Spp,
    ];

    /// The name used on the command line, in file names and as the EXR layer name.
    pub fn name(self) -> &'static str {
        match self {
            Aov::Normal => "normal",
            Aov::Uv => "uv",
            Aov::Depth => "depth",
            Aov::Albedo => "albedo",
            Aov::Object => "object",
            Aov::Material => "material",
            Aov::Bounces => "bounces",
            Aov::Variance => "variance",
            Aov::Spp => "spp",
        }
    }

    /// Whether the view is read from the path tracer's film of sums (its samples' spread
    /// and count) rather than traced through each pixel's centre.
    pub fn from_film(self) -> bool {
        matches!(self, Aov::Variance | Aov::Spp)
    }

    /// The view with this name.
    pub fn from_name(name: &str) -> Option<Aov> {
        Aov::ALL.into_iter().find(|a| a.name() == name)
    }
}

/// The raw values of every view, per pixel (row by row from the top).
#[derive(Clone, Debug, PartialEq)]
pub struct AovBuffers {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Unit shading normal (zero where the ray hits nothing).
    pub normal: Vec<Vec3A>,
    /// Texture coordinates (zero where nothing is hit).
    pub uv: Vec<Vec2>,
    /// Distance to the first hit (infinite where nothing is hit).
    pub depth: Vec<f32>,
    /// Surface colour, linear RGB (zero where nothing is hit).
    pub albedo: Vec<Color>,
    /// Index of the object in `[[objects]]` (-1 where nothing is hit).
    pub object: Vec<i32>,
    /// Index of the material in the scene's list (-1 where nothing is hit).
    pub material: Vec<i32>,
    /// Reflections and refractions below the camera ray (0: the camera ray alone).
    pub bounces: Vec<u32>,
    /// The variance of each pixel's luminance as the render estimated it, NaN where it is
    /// unknown (fewer than two samples, or a render that kept no sums): empty until
    /// [`AovBuffers::read_film`].
    pub variance: Vec<f32>,
    /// Each pixel's luminance in the render, beside its variance.
    pub luminance: Vec<f32>,
    /// The samples each pixel took (0 where the render kept no sums).
    pub samples: Vec<u32>,
}

/// What one pixel's centre ray finds.
#[derive(Clone, Copy, Debug, bytemuck::Zeroable)]
pub(crate) struct AovSample {
    normal: Vec3A,
    uv: Vec2,
    depth: f32,
    albedo: Color,
    object: i32,
    material: i32,
    bounces: u32,
}

impl AovBuffers {
    /// The buffers of `w` x `h` pixels' samples, row by row.
    pub(crate) fn from_samples(w: u32, h: u32, all: &[AovSample]) -> Self {
        AovBuffers {
            width: w,
            height: h,
            normal: all.iter().map(|s| s.normal).collect(),
            uv: all.iter().map(|s| s.uv).collect(),
            depth: all.iter().map(|s| s.depth).collect(),
            albedo: all.iter().map(|s| s.albedo).collect(),
            object: all.iter().map(|s| s.object).collect(),
            material: all.iter().map(|s| s.material).collect(),
            bounces: all.iter().map(|s| s.bounces).collect(),
            variance: vec![f32::NAN; all.len()],
            luminance: vec![0.0; all.len()],
            samples: vec![0; all.len()],
        }
    }
}

/// What pixel `(x, y)`'s centre ray finds, for every view.
pub(crate) fn sample(scene: &Scene, x: u32, y: u32) -> AovSample {
    let s = &scene.settings;
    let ray = scene
        .camera
        .ray(x as f32 + 0.5, y as f32 + 0.5, s.width, s.height);
    let mut rays = RayStats::default();
    if s.integrator.kind != crate::scene::IntegratorKind::Whitted {
        // The path of the pixel's sample 0, as `snell explain --integrator path` shows it,
        // from the centre: its numbers after the two that place it on the film.
        let mut sampler = crate::sampler::Sampler::new(s.integrator.sampler, s.seed);
        // The two numbers that place sample 0 on the film (`render::start_sample`).
        sampler.start(x, y, 0);
        sampler.next_2d();
        super::Path.radiance_sampled(scene, &ray, &mut sampler, &mut rays);
    } else {
        Whitted.trace(scene, &ray, 1, None, &mut rays);
    }
    let bounces = rays.deepest.saturating_sub(1);
    match scene.closest_hit_with_uv(&ray, f32::INFINITY, Skip::NONE) {
        None => AovSample {
            normal: Vec3A::ZERO,
            uv: Vec2::ZERO,
            depth: f32::INFINITY,
            albedo: Color::ZERO,
            object: -1,
            material: -1,
            bounces,
        },
        Some(mut hit) => {
            let tex = hit.tex;
            scene.with_detail(&mut hit, &tex);
            let uv = scene.texture_uv(&hit);
            AovSample {
                normal: hit.shading_normal,
                uv,
                depth: hit.t,
                albedo: scene.base_color(&hit, &hit.tex),
                object: hit.object as i32,
                material: hit.material as i32,
                bounces,
            }
        }
    }
}

/// A distinct, stable colour for index `i` (the golden-ratio walk around the hue circle, so
/// neighbours in the list differ strongly), black for -1.
pub fn id_color(i: i32) -> Color {
    if i < 0 {
        return Color::ZERO;
    }
    let hue = (i as f32 * 0.618_034 + 0.1).fract();
    hsv(hue, 0.7, 0.95)
}

fn hsv(h: f32, s: f32, v: f32) -> Color {
    let f = |n: f32| {
        let k = (n + h * 6.0) % 6.0;
        v - v * s * k.min(4.0 - k).clamp(0.0, 1.0)
    };
    Color::new(f(5.0), f(3.0), f(1.0))
}

/// Few-stop colour ramp from dark blue (0) through teal and green to yellow (1), readable
/// and monotone in brightness.
fn ramp(t: f32) -> Color {
    const STOPS: [[f32; 3]; 5] = [
        [0.27, 0.0, 0.33],
        [0.23, 0.32, 0.55],
        [0.13, 0.57, 0.55],
        [0.37, 0.79, 0.38],
        [0.99, 0.91, 0.14],
    ];
    let t = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f32;
    let i = (t as usize).min(STOPS.len() - 2);
    let f = t - i as f32;
    Color::from(STOPS[i]).lerp(Color::from(STOPS[i + 1]), f)
}

impl AovBuffers {
    /// The views read from `film` alone (`variance`, `spp`), the centre rays' views empty
    /// (nothing hit): for a picture whose film is at hand but whose centre rays are not
    /// worth tracing (the live preview's).
    pub fn of_film(film: &Film) -> Self {
        let n = film.width() as usize * film.height() as usize;
        let empty = AovSample {
            normal: Vec3A::ZERO,
            uv: Vec2::ZERO,
            depth: f32::INFINITY,
            albedo: Color::ZERO,
            object: -1,
            material: -1,
            bounces: 0,
        };
        let mut b = AovBuffers::from_samples(film.width(), film.height(), &vec![empty; n]);
        b.read_film(film);
        b
    }

    /// Takes each pixel's variance, luminance and sample count from the film of the path
    /// tracer's sums the picture was made from.
    pub fn read_film(&mut self, film: &Film) {
        self.variance = film.rows(|p| p.variance_of_mean().unwrap_or(f32::NAN));
        self.luminance = film.rows(|p| crate::math::luminance(p.value()));
        self.samples = film.rows(|p| p.samples);
    }

    /// The raw values of `aov` as named channels, for an EXR layer: normal `X Y Z`, uv
    /// `U V`, depth `Z`, albedo `R G B`, object and material `id`, bounces `count`, variance
    /// `Y` (of the pixel's luminance).
    pub fn channels(&self, aov: Aov) -> Vec<(&'static str, Vec<f32>)> {
        let per = |f: &dyn Fn(usize) -> f32| (0..self.depth.len()).map(f).collect::<Vec<f32>>();
        match aov {
            Aov::Normal => vec![
                ("X", per(&|i| self.normal[i].x)),
                ("Y", per(&|i| self.normal[i].y)),
                ("Z", per(&|i| self.normal[i].z)),
            ],
            Aov::Uv => vec![("U", per(&|i| self.uv[i].x)), ("V", per(&|i| self.uv[i].y))],
            Aov::Depth => vec![("Z", self.depth.clone())],
            Aov::Albedo => vec![
                ("R", per(&|i| self.albedo[i].x)),
                ("G", per(&|i| self.albedo[i].y)),
                ("B", per(&|i| self.albedo[i].z)),
            ],
            Aov::Object => vec![("id", per(&|i| self.object[i] as f32))],
            Aov::Material => vec![("id", per(&|i| self.material[i] as f32))],
            Aov::Bounces => vec![("count", per(&|i| self.bounces[i] as f32))],
            Aov::Variance => vec![("Y", self.variance.clone())],
            Aov::Spp => vec![("count", per(&|i| self.samples[i] as f32))],
        }
    }

    /// `aov` as a picture for people. The values given here are what the PNG holds (they
    /// are stored so that sRGB encoding gives them back exactly):
    /// - normal: `0.5 + 0.5 n` per channel (x red, y green, z blue); black where nothing is hit;
    /// - uv: red = u, green = v (their fractional parts), with darker grid lines every 0.1
    ///   (every 1 where the uv are not in `[0, 1]`, as with mappings in scene units);
    /// - depth: 1 (white) at the nearest hit down to 0.15 at the farthest, linearly in
    ///   distance; black where nothing is hit;
    /// - albedo: the surface colour, sRGB-encoded like the render;
    /// - object, material: a distinct colour per index (see [`id_color`]);
    /// - bounces: a ramp from dark blue (0) to yellow (`max_depth - 1`);
    /// - variance: the pixel's relative standard error, `sqrt(variance) / (luminance +
    ///   0.01)`, on the same ramp by its logarithm: dark blue at 0.1 % or less, yellow at
    ///   100 % or more (a decade every third of the ramp); black where it is unknown;
    /// - spp: the samples a pixel took on the same ramp by their base-2 logarithm, dark blue
    ///   at 1 and yellow at the most any pixel took; black where it took none.
    pub fn display(&self, aov: Aov, max_depth: u32) -> Image {
        let mut img = Image::new(self.width, self.height);
        let (near, far) = self
            .depth
            .iter()
            .filter(|d| d.is_finite())
            .fold((f32::INFINITY, 0.0f32), |(lo, hi), &d| {
                (lo.min(d), hi.max(d))
            });
        let most = self.samples.iter().copied().max().unwrap_or(0);
        for (i, px) in img.pixels.iter_mut().enumerate() {
            let hit = self.object[i] >= 0;
            // Display values, to be stored as they are.
            let value = match aov {
                Aov::Normal if hit => self.normal[i] * 0.5 + Vec3A::splat(0.5),
                Aov::Uv if hit => {
                    let uv = self.uv[i];
                    let (u, v) = (uv.x.rem_euclid(1.0), uv.y.rem_euclid(1.0));
                    // Grid lines every 0.1 for uv in [0, 1] (shapes, images); every 1 for
                    // mappings in scene units (planar, checkers), where 0.1 would be a blur.
                    let unit = (-0.01..=1.01).contains(&uv.x) && (-0.01..=1.01).contains(&uv.y);
                    let step = if unit { 10.0 } else { 1.0 };
                    let line = |t: f32| (t * step).rem_euclid(1.0) < 0.06;
                    let shade = if line(uv.x) || line(uv.y) { 0.55 } else { 1.0 };
                    Color::new(u, v, 0.0) * shade
                }
                Aov::Depth if hit => {
                    let f = if far > near {
                        (self.depth[i] - near) / (far - near)
                    } else {
                        0.0
                    };
                    Color::splat(1.0 - 0.85 * f)
                }
                Aov::Albedo => {
                    *px = self.albedo[i];
                    continue;
                }
                Aov::Object => id_color(self.object[i]),
                Aov::Material => id_color(self.material[i]),
                Aov::Bounces => ramp(self.bounces[i] as f32 / (max_depth.max(2) - 1) as f32),
                Aov::Variance => {
                    let v = self.variance[i];
                    if v.is_nan() {
                        Color::ZERO
                    } else {
                        let rel = crate::film::relative_error(v, self.luminance[i]);
                        ramp((rel.max(1e-3).log10() + 3.0) / 3.0)
                    }
                }
                Aov::Spp => match self.samples[i] {
                    0 => Color::ZERO,
                    n => ramp((n as f32).log2() / (most as f32).log2().max(1.0)),
                },
                _ => Color::ZERO,
            };
            let v = value.clamp(Color::ZERO, Color::ONE);
            *px = Color::new(
                srgb_to_linear(v.x),
                srgb_to_linear(v.y),
                srgb_to_linear(v.z),
            );
        }
        img
    }
}
