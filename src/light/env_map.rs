//! An equirectangular image as light from far away: its radiance by direction, and
//! directions sampled in proportion to its brightness with their density. The environment
//! (an image) and the daylight sky (an image made from the model) both use it, so it sits
//! below both.
//!
//! The image's convention (docs/scene-format.md, `[environment]`): `+y` is up; the image's
//! top row is straight up and its bottom row straight down; its centre column (`u = 0.5`)
//! lies toward `-z`, and `u` grows toward `+x` (so the picture is seen unmirrored from
//! inside, looking toward `-z`). `rotate` turns the image about the world's axes.

use crate::math::approx;
use crate::math::distribution2d::Distribution2d;
use crate::math::{Color, Transform, Vec2, Vec3A, luminance};
use crate::texture::ImageData;
use std::f32::consts::PI;
use std::sync::Arc;

/// How many texels a map has at most for its lookups to stay in a core's cache (its
/// tables take about 10 bytes a texel: 2.5 MiB here, past a 2 MiB L2). A lookup in a
/// larger map waits on memory; one in a smaller map has nothing to gain from asking for
/// its memory ahead (docs/perf-log.md).
const CACHED_TEXELS: usize = 1 << 18;

/// An equirectangular image, its placement, and the density it is sampled with.
#[derive(Clone, Debug)]
pub struct EnvironmentMap {
    pub(super) image: Arc<ImageData>,
    /// The image's texels (times the scale it was made with) as half floats, row by row, which the radiance
    /// lookups read: half the bytes of single floats, so more of a large map stays in the
    /// cache between lookups (docs/perf-log.md).
    texels: Box<[[half::f16; 3]]>,
    /// What the half floats are multiplied by: a power of two that keeps the brightest texel
    /// within half-float range (1 for most maps; a sun of radiance past 32,768 raises it).
    unit: f32,
    /// World to the image's frame and back (a rotation).
    rotation: Transform,
    /// Over the image's texels: the mean luminance the bilinear lookup gives over each
    /// texel's area (positive wherever any light shows there, so light sampling reaches all
    /// of it), times the solid angle of its row.
    density: Distribution2d,
    /// The radiance averaged over all directions.
    pub(super) mean: Color,
    /// The image's file as the scene names it, where it came from one.
    pub file: Option<String>,
}

/// A direction toward the environment chosen for a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvironmentSample {
    /// Unit direction toward it, in world space.
    pub direction: Vec3A,
    /// Radiance arriving from there.
    pub radiance: Color,
    /// Density per unit solid angle.
    pub pdf: f32,
}

/// The image coordinates `(u, v)` of a unit direction in the image's frame.
pub(crate) fn uv_of(d: Vec3A) -> Vec2 {
    // Fast approximations: a lookup a millionth of a radian off is the same lookup.
    let phi = approx::atan2(d.x, -d.z);
    let theta = approx::acos(d.y);
    Vec2::new(0.5 + phi / (2.0 * PI), theta / PI)
}

/// The unit direction (in the image's frame) of image coordinates `(u, v)`, and the sine of
/// its angle from straight up.
pub(crate) fn direction_of(uv: Vec2) -> (Vec3A, f32) {
    let (phi, theta) = ((uv.x - 0.5) * 2.0 * PI, uv.y * PI);
    let (st, ct) = approx::sin_cos(theta);
    let (sp, cp) = approx::sin_cos(phi);
    (Vec3A::new(st * sp, ct, -st * cp), st)
}

impl EnvironmentMap {
    /// The map of `image`, turned by `rotate_deg` (degrees about x, then y, then z), its
    /// values multiplied by `scale`.
    pub fn new(image: Arc<ImageData>, rotate_deg: Vec3A, scale: Color) -> Self {
        use rayon::prelude::*;
        let (w, h) = (image.width() as usize, image.height() as usize);
        // Row by row on every core: each texel's value depends on its own row and the rows
        // beside it only, so the tables are the same whatever the threads.
        // The luminances, and with them the brightest channel that the half floats must hold.
        let mut lum = vec![0.0f32; w * h];
        let brightest = lum
            .par_chunks_mut(w.max(1))
            .enumerate()
            .map(|(y, row)| {
                let mut most = 0.0f32;
                for (x, l) in row.iter_mut().enumerate() {
                    let c = image.texel(x as u32, y as u32) * scale;
                    *l = luminance(c);
                    if c.max_element().is_finite() {
                        most = most.max(c.max_element());
                    }
                }
                most
            })
            .reduce(|| 0.0f32, f32::max);
        let sines: Vec<f32> = (0..h)
            .map(|y| (PI * (y as f32 + 0.5) / h as f32).sin())
            .collect();
        let mut weights = vec![0.0f32; w * h];
        weights
            .par_chunks_mut(w.max(1))
            .enumerate()
            .for_each(|(y, row)| {
                for (x, weight) in row.iter_mut().enumerate() {
                    // The mean luminance of the bilinear lookup over this texel's area: it
                    // blends the texel with its eight neighbours, by 6/8 and 1/8 along each
                    // axis.
                    const K: [f32; 3] = [0.125, 0.75, 0.125];
                    let mut m = 0.0f32;
                    for (ky, dy) in K.iter().zip([-1i64, 0, 1]) {
                        let yy = (y as i64 + dy).clamp(0, h as i64 - 1) as usize;
                        for (kx, dx) in K.iter().zip([-1i64, 0, 1]) {
                            let xx = (x as i64 + dx).rem_euclid(w as i64) as usize;
                            m += ky * kx * lum[yy * w + xx];
                        }
                    }
                    *weight = m * sines[y];
                }
            });
        // The mean in one order, texel after texel, as it always was summed.
        let (mut sum, mut solid) = (Color::ZERO, 0.0f64);
        for (y, &sin) in sines.iter().enumerate() {
            for x in 0..w {
                sum += image.texel(x as u32, y as u32) * (scale * sin);
                solid += sin as f64;
            }
        }
        let unit = (brightest / 32768.0).max(1.0).log2().ceil().exp2();
        let texels = (0..w * h)
            .into_par_iter()
            .map(|i| {
                let c = image.texel((i % w) as u32, (i / w) as u32) * scale / unit;
                c.to_array().map(half::f16::from_f32)
            })
            .collect();
        EnvironmentMap {
            texels,
            unit,
            image,
            rotation: Transform::rotation(rotate_deg.into()),
            density: Distribution2d::new(&weights, w, h),
            mean: if solid > 0.0 {
                sum / solid as f32
            } else {
                Color::ZERO
            },
            file: None,
        }
    }

    /// The image coordinates of world direction `world`.
    #[inline]
    pub(super) fn uv(&self, world: Vec3A) -> Vec2 {
        uv_of(self.rotation.vector_to_object(world).normalize_or_zero())
    }

    /// The four texels the bilinear lookup at `uv` blends (columns `xs`, rows `ys`) and
    /// its weights along each axis; `None` off the image.
    #[inline]
    fn footprint(&self, uv: Vec2) -> Option<([i64; 2], [i64; 2], f32, f32)> {
        use crate::texture::Wrap;
        let (w, h) = (self.image.width() as i64, self.image.height() as i64);
        let x = uv.x * w as f32 - 0.5;
        let y = uv.y * h as f32 - 0.5;
        if !(x.is_finite() && y.is_finite()) || w == 0 || h == 0 {
            return None;
        }
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        // Round the sphere in u, clamped at the poles in v.
        let xs = [
            Wrap::Repeat.index(x0, w),
            Wrap::Repeat.index(x0.saturating_add(1), w),
        ];
        let ys = [
            Wrap::Clamp.index(y0, h),
            Wrap::Clamp.index(y0.saturating_add(1), h),
        ];
        Some((xs, ys, fx, fy))
    }

    /// Asks for the cache lines of the texels a lookup at `uv` would read, without waiting.
    #[inline]
    fn prefetch(&self, uv: Vec2) {
        if let Some((xs, ys, _, _)) = self.footprint(uv) {
            let w = self.image.width() as i64;
            for y in ys {
                crate::math::prefetch(&self.texels[(y * w + xs[0]) as usize]);
                crate::math::prefetch(&self.texels[(y * w + xs[1]) as usize]);
            }
        }
    }

    /// Whether the map is too large for its lookups to stay in the cache.
    #[inline]
    pub(crate) fn is_large(&self) -> bool {
        self.texels.len() > CACHED_TEXELS
    }

    /// Asks for the memory a lookup at image coordinates `uv` reads (its texels, and its
    /// density's entry), without waiting.
    #[inline]
    pub(crate) fn prefetch_uv(&self, uv: Vec2) {
        self.prefetch(uv);
        self.density.prefetch(uv);
    }

    /// Radiance from image coordinates `uv`.
    #[inline]
    pub(crate) fn radiance_at(&self, uv: Vec2) -> Color {
        let w = self.image.width() as i64;
        let Some((xs, ys, fx, fy)) = self.footprint(uv) else {
            return Color::ZERO;
        };
        let texel = |x: i64, y: i64| {
            let t = self.texels[(y * w + x) as usize];
            Color::new(t[0].to_f32(), t[1].to_f32(), t[2].to_f32())
        };
        let top = texel(xs[0], ys[0]).lerp(texel(xs[1], ys[0]), fx);
        let bottom = texel(xs[0], ys[1]).lerp(texel(xs[1], ys[1]), fx);
        top.lerp(bottom, fy) * self.unit
    }

    /// The density per unit solid angle of image coordinates `uv`: the texel density over
    /// the unit square, over the `2 pi^2 sin(theta)` solid angle per unit of it.
    #[inline]
    pub(super) fn pdf_at(&self, uv: Vec2) -> f32 {
        let sin = approx::sin_cos(uv.y * PI).0;
        if sin <= 0.0 {
            return 0.0;
        }
        self.density.pdf(uv) / (2.0 * PI * PI * sin)
    }

    /// Radiance from world direction `world`.
    #[inline]
    pub(crate) fn radiance(&self, world: Vec3A) -> Color {
        self.radiance_at(self.uv(world))
    }

    /// Radiance from world direction `world` and the density of [`EnvironmentMap::sample`]
    /// for it.
    #[inline]
    pub(crate) fn radiance_pdf(&self, world: Vec3A) -> (Color, f32) {
        self.radiance_pdf_uv(self.uv(world))
    }

    /// [`EnvironmentMap::radiance_pdf`] at image coordinates `uv`.
    #[inline]
    pub(crate) fn radiance_pdf_uv(&self, uv: Vec2) -> (Color, f32) {
        (self.radiance_at(uv), self.pdf_at(uv))
    }

    /// The radiance averaged over all directions.
    pub(crate) fn mean(&self) -> Color {
        self.mean
    }

    /// A direction in proportion to the image's brightness.
    pub(crate) fn sample(&self, u: Vec2) -> Option<EnvironmentSample> {
        // The texels the sample will read are asked for while its column is searched for.
        let (uv, pdf_uv) = self
            .density
            .sample_hinting(u, |guess| self.prefetch(guess))?;
        let (local, sin) = direction_of(uv);
        if sin <= 0.0 {
            return None;
        }
        Some(EnvironmentSample {
            direction: self.rotation.vector_to_world(local).normalize_or_zero(),
            radiance: self.radiance_at(uv),
            pdf: pdf_uv / (2.0 * PI * PI * sin),
        })
    }
}
