//! The environment: light arriving from infinitely far away in every direction, a constant
//! colour, an equirectangular image (latitude-longitude) sampled in proportion to the
//! image's brightness, or a daylight sky with its sun (sky/).
//!
//! The image's convention (docs/scene-format.md, `[environment]`): `+y` is up; the image's
//! top row is straight up and its bottom row straight down; its centre column (`u = 0.5`)
//! lies toward `-z`, and `u` grows toward `+x` (so the picture is seen unmirrored from
//! inside, looking toward `-z`). `rotate` turns the image about the world's axes.

use super::sky::Sky;
use crate::math::approx;
use crate::math::distribution2d::Distribution2d;
use crate::math::{Color, Transform, Vec2, Vec3A, luminance};
use crate::texture::ImageData;
use std::f32::consts::PI;
use std::sync::Arc;

/// Light from every direction, far away.
#[derive(Clone, Debug)]
pub struct Environment {
    /// What it shows.
    pub source: EnvironmentSource,
    /// Whether camera rays see it (otherwise they see `[image] background`); it lights the
    /// scene either way.
    pub visible: bool,
}

/// Where the environment's radiance comes from.
#[derive(Clone, Debug)]
pub enum EnvironmentSource {
    /// The same radiance from every direction.
    Constant(Color),
    /// A latitude-longitude image.
    Map(Box<EnvironmentMap>),
    /// A daylight sky and its sun.
    Sky(Box<Sky>),
}

/// An equirectangular image, its placement, and the density it is sampled with.
#[derive(Clone, Debug)]
pub struct EnvironmentMap {
    image: Arc<ImageData>,
    /// World to the image's frame and back (a rotation).
    rotation: Transform,
    /// Multiplies the image's values.
    scale: Color,
    /// Over the image's texels: the mean luminance the bilinear lookup gives over each
    /// texel's area (positive wherever any light shows there, so light sampling reaches all
    /// of it), times the solid angle of its row.
    density: Distribution2d,
    /// The radiance averaged over all directions.
    mean: Color,
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
fn uv_of(d: Vec3A) -> Vec2 {
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
        let (w, h) = (image.width() as usize, image.height() as usize);
        let lum: Vec<f32> = (0..w * h)
            .map(|i| luminance(image.texel((i % w) as u32, (i / w) as u32) * scale))
            .collect();
        let mut weights = vec![0.0f32; w * h];
        let (mut sum, mut solid) = (Color::ZERO, 0.0f64);
        for y in 0..h {
            let sin = (PI * (y as f32 + 0.5) / h as f32).sin();
            for x in 0..w {
                // The mean luminance of the bilinear lookup over this texel's area: it blends
                // the texel with its eight neighbours, by 6/8 and 1/8 along each axis.
                const K: [f32; 3] = [0.125, 0.75, 0.125];
                let mut m = 0.0f32;
                for (ky, dy) in K.iter().zip([-1i64, 0, 1]) {
                    let yy = (y as i64 + dy).clamp(0, h as i64 - 1) as usize;
                    for (kx, dx) in K.iter().zip([-1i64, 0, 1]) {
                        let xx = (x as i64 + dx).rem_euclid(w as i64) as usize;
                        m += ky * kx * lum[yy * w + xx];
                    }
                }
                weights[y * w + x] = m * sin;
                sum += image.texel(x as u32, y as u32) * (scale * sin);
                solid += sin as f64;
            }
        }
        EnvironmentMap {
            image,
            rotation: Transform::rotation(rotate_deg.into()),
            scale,
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
    fn uv(&self, world: Vec3A) -> Vec2 {
        uv_of(self.rotation.vector_to_object(world).normalize_or_zero())
    }

    #[inline]
    fn radiance_at(&self, uv: Vec2) -> Color {
        self.image.sample_bilinear(
            uv,
            crate::texture::Wraps {
                u: crate::texture::Wrap::Repeat,
                v: crate::texture::Wrap::Clamp,
            },
        ) * self.scale
    }

    /// The density per unit solid angle of image coordinates `uv`: the texel density over
    /// the unit square, over the `2 pi^2 sin(theta)` solid angle per unit of it.
    #[inline]
    fn pdf_at(&self, uv: Vec2) -> f32 {
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
        let uv = self.uv(world);
        (self.radiance_at(uv), self.pdf_at(uv))
    }

    /// The radiance averaged over all directions.
    pub(crate) fn mean(&self) -> Color {
        self.mean
    }

    /// A direction in proportion to the image's brightness.
    pub(crate) fn sample(&self, u: Vec2) -> Option<EnvironmentSample> {
        let (uv, pdf_uv) = self.density.sample(u)?;
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

impl Environment {
    /// The radiance arriving along `-dir` (from direction `dir`, unit, world space).
    #[inline]
    pub fn radiance(&self, dir: Vec3A) -> Color {
        match &self.source {
            EnvironmentSource::Constant(c) => *c,
            EnvironmentSource::Map(m) => m.radiance(dir),
            EnvironmentSource::Sky(s) => s.radiance(dir),
        }
    }

    /// A direction toward the environment, for a point anywhere: uniform over the sphere for
    /// a constant colour, in proportion to the brightness for an image.
    pub fn sample(&self, u: Vec2) -> Option<EnvironmentSample> {
        match &self.source {
            EnvironmentSource::Constant(c) => Some(EnvironmentSample {
                direction: crate::math::sampling::uniform_sphere(u),
                radiance: *c,
                pdf: crate::math::sampling::UNIFORM_SPHERE_PDF,
            }),
            EnvironmentSource::Map(m) => m.sample(u),
            EnvironmentSource::Sky(s) => s.sample(u),
        }
    }

    /// The density of [`Environment::sample`] for direction `dir`.
    pub fn pdf(&self, dir: Vec3A) -> f32 {
        match &self.source {
            EnvironmentSource::Constant(_) => crate::math::sampling::UNIFORM_SPHERE_PDF,
            EnvironmentSource::Map(m) => m.pdf_at(m.uv(dir)),
            EnvironmentSource::Sky(s) => s.radiance_pdf(dir).1,
        }
    }

    /// [`Environment::radiance`] and [`Environment::pdf`] of `dir` at once (the image
    /// coordinates found once): what a path that leaves the scene needs for MIS.
    #[inline]
    pub fn radiance_pdf(&self, dir: Vec3A) -> (Color, f32) {
        match &self.source {
            EnvironmentSource::Constant(c) => (*c, crate::math::sampling::UNIFORM_SPHERE_PDF),
            EnvironmentSource::Map(m) => m.radiance_pdf(dir),
            EnvironmentSource::Sky(s) => s.radiance_pdf(dir),
        }
    }

    /// What it is, for `snell check`: `constant [r, g, b]`, `image FILE, W x H` or `sky, the
    /// sun E° above the horizon`.
    pub fn describe(&self) -> String {
        match &self.source {
            EnvironmentSource::Constant(c) => format!("constant [{}, {}, {}]", c.x, c.y, c.z),
            EnvironmentSource::Map(m) => format!(
                "image {}, {} x {}",
                m.file.as_deref().unwrap_or("(made in memory)"),
                m.image.width(),
                m.image.height()
            ),
            EnvironmentSource::Sky(s) => match s.sun_elevation() {
                Some(e) => format!("sky, the sun {e:.1}° above the horizon"),
                None => "sky, without its sun".into(),
            },
        }
    }

    /// Its power as a light of a scene of radius `radius`: what falls on a disk of that
    /// radius, `pi r^2 x pi x` the mean luminance over all directions.
    pub fn power(&self, radius: f32) -> f32 {
        let mean = match &self.source {
            EnvironmentSource::Constant(c) => *c,
            EnvironmentSource::Map(m) => m.mean,
            EnvironmentSource::Sky(s) => s.mean(),
        };
        PI * radius * radius * PI * luminance(mean)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::chi2::{SphereBins, chi2_sphere};

    /// A small image with a bright spot, a dark band and a colour gradient, as floats.
    fn image() -> Arc<ImageData> {
        let (w, h) = (32u32, 16u32);
        let img = ::image::Rgb32FImage::from_fn(w, h, |x, y| {
            let spot = if (x as i32 - 22).abs() <= 1 && (y as i32 - 5).abs() <= 1 {
                40.0
            } else {
                0.0
            };
            let band = if y == 11 { 0.0 } else { 1.0 };
            ::image::Rgb([
                band * (0.2 + x as f32 / w as f32) + spot,
                band * 0.5 + spot,
                band * (1.0 - y as f32 / h as f32) + spot,
            ])
        });
        Arc::new(ImageData::from_dynamic(
            &::image::DynamicImage::ImageRgb32F(img),
            crate::texture::ColorSpace::Linear,
        ))
    }

    #[test]
    fn directions_and_image_coordinates_are_inverse() {
        for (u, v) in [(0.5, 0.5), (0.75, 0.3), (0.1, 0.9), (0.999, 0.01)] {
            let (d, sin) = direction_of(Vec2::new(u, v));
            assert!((d.length() - 1.0).abs() < 1e-5);
            assert!((sin - (v * PI).sin()).abs() < 1e-5);
            let back = uv_of(d);
            assert!(
                (back - Vec2::new(u, v)).abs().max_element() < 1e-4,
                "{u},{v}: {back}"
            );
        }
        // The convention: the centre lies toward -z, a quarter turn right toward +x, the top
        // row straight up.
        assert!((direction_of(Vec2::new(0.5, 0.5)).0 - -Vec3A::Z).length() < 1e-5);
        assert!((direction_of(Vec2::new(0.75, 0.5)).0 - Vec3A::X).length() < 1e-5);
        assert!((direction_of(Vec2::new(0.3, 0.0)).0 - Vec3A::Y).length() < 1e-5);
    }

    /// Directions follow the density by chi-square, turned or not, and each sample's
    /// density and radiance are what `pdf` and `radiance` give for its direction (but for a
    /// few rounded onto a texel's edge).
    #[test]
    fn sampling_matches_the_density() {
        for rotate in [Vec3A::ZERO, Vec3A::new(30.0, -70.0, 10.0)] {
            let map = EnvironmentMap::new(image(), rotate, Color::new(1.0, 2.0, 0.5));
            let env = Environment {
                source: EnvironmentSource::Map(Box::new(map)),
                visible: true,
            };
            let (mut n, mut off) = (0u32, 0u32);
            chi2_sphere(
                "environment map",
                SphereBins::default(),
                |u| {
                    let s = env.sample(u)?;
                    // A sample on a texel's very edge may round into its neighbour on the
                    // way back: a set of directions of measure zero, which MIS may weigh
                    // inconsistently without bias.
                    let pdf = env.pdf(s.direction);
                    n += 1;
                    off += u32::from((s.pdf - pdf).abs() > 2e-3 * pdf);
                    let l = env.radiance(s.direction);
                    assert!((s.radiance - l).abs().max_element() <= 1e-3 * (1.0 + l.max_element()));
                    Some(s.direction)
                },
                |d| env.pdf(d),
            )
            .unwrap();
            // (The band is a few millionths of a texel wide, the fast arctangent's error
            // and float rounding; a density read wrongly anywhere else is off everywhere.)
            assert!(
                off as f32 <= 3e-4 * n as f32,
                "{off} of {n} samples off their density"
            );
        }
    }

    /// The density is positive wherever the radiance is (the bilinear lookup included), so
    /// light sampling misses no light, and it integrates to 1 over the sphere.
    #[test]
    fn the_density_covers_the_light() {
        let map = EnvironmentMap::new(image(), Vec3A::new(0.0, 45.0, 0.0), Color::ONE);
        let env = Environment {
            source: EnvironmentSource::Map(Box::new(map)),
            visible: true,
        };
        let (nt, np) = (300, 600);
        let mut integral = 0.0f64;
        let mut lit = 0;
        for t in 0..nt {
            let theta = PI * (t as f32 + 0.5) / nt as f32;
            for p in 0..np {
                let phi = 2.0 * PI * (p as f32 + 0.5) / np as f32;
                let d = Vec3A::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                );
                let pdf = env.pdf(d);
                if env.radiance(d).max_element() > 0.0 {
                    assert!(pdf > 0.0, "light at {d} with no density");
                    lit += 1;
                }
                integral += pdf as f64 * theta.sin() as f64;
            }
        }
        integral *= (PI as f64 / nt as f64) * (2.0 * PI as f64 / np as f64);
        assert!((integral - 1.0).abs() < 0.01, "{integral}");
        // Only row 11 of the image's 16 is black, and the bilinear lookup mixes a neighbour
        // row into every band of directions (the nearest, band 215, is 0.7 % row 10): every
        // direction sees light, and each was checked.
        assert_eq!(lit, nt * np, "lit directions");
    }

    /// A wrong density (10 % more in the spot's half) fails the chi-square test.
    #[test]
    fn a_wrong_density_fails() {
        let env = Environment {
            source: EnvironmentSource::Map(Box::new(EnvironmentMap::new(
                image(),
                Vec3A::ZERO,
                Color::ONE,
            ))),
            visible: true,
        };
        let broken = |d: Vec3A| env.pdf(d) * if d.x > 0.0 { 1.1 } else { 1.0 };
        assert!(
            chi2_sphere(
                "broken",
                SphereBins::default(),
                |u| env.sample(u).map(|s| s.direction),
                broken
            )
            .is_err()
        );
    }

    /// A constant environment is sampled uniformly, and its power is that of its colour.
    #[test]
    fn a_constant_environment_is_uniform() {
        let env = Environment {
            source: EnvironmentSource::Constant(Color::splat(2.0)),
            visible: false,
        };
        chi2_sphere(
            "constant environment",
            SphereBins::default(),
            |u| env.sample(u).map(|s| s.direction),
            |d| env.pdf(d),
        )
        .unwrap();
        assert!((env.power(1.0) - PI * PI * 2.0).abs() < 1e-4);
        assert_eq!(env.radiance(Vec3A::Y), Color::splat(2.0));
    }
}
