//! The environment: light arriving from infinitely far away in every direction, a constant
//! colour, an equirectangular image (env_map.rs, whose convention it gives) sampled in
//! proportion to the image's brightness, or a daylight sky with its sun (sky/).

pub use super::env_map::{EnvironmentMap, EnvironmentSample};
use super::sky::Sky;
use super::{Emission, Emit, Falloff, LightSample};
use crate::math::{Color, Vec2, Vec3A, luminance};
use std::f32::consts::PI;

/// Light from every direction, far away.
#[derive(Clone, Debug)]
pub struct Environment {
    /// What it shows.
    pub source: EnvironmentSource,
    /// Whether camera rays see it (otherwise they see `[image] background`); it lights the
    /// scene either way.
    pub visible: bool,
}

/// A direction toward the environment (unit, world space), with its image coordinates in
/// the environment's map where they were found already.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Toward {
    /// The direction.
    pub dir: Vec3A,
    /// Its image coordinates, if found ([`Environment::prefetch`]).
    pub uv: Option<Vec2>,
}

impl From<Vec3A> for Toward {
    fn from(dir: Vec3A) -> Self {
        Toward { dir, uv: None }
    }
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

    /// Asks for the memory a lookup of direction `dir` will read (a large image's texels
    /// and density), without waiting for it: the direction with the image coordinates
    /// found on the way, or `None` where there was nothing to ask for (a small image, the
    /// sky's among them, stays in the cache).
    #[inline]
    pub fn prefetch(&self, dir: Vec3A) -> Option<Toward> {
        match &self.source {
            EnvironmentSource::Map(m) if m.is_large() => {
                let uv = m.uv(dir);
                m.prefetch_uv(uv);
                Some(Toward { dir, uv: Some(uv) })
            }
            _ => None,
        }
    }

    /// [`Environment::radiance`] toward `t`.
    #[inline]
    pub fn radiance_toward(&self, t: Toward) -> Color {
        match (&self.source, t.uv) {
            (EnvironmentSource::Map(m), Some(uv)) => m.radiance_at(uv),
            _ => self.radiance(t.dir),
        }
    }

    /// [`Environment::radiance_pdf`] toward `t`.
    #[inline]
    pub fn radiance_pdf_toward(&self, t: Toward) -> (Color, f32) {
        match (&self.source, t.uv) {
            (EnvironmentSource::Map(m), Some(uv)) => m.radiance_pdf_uv(uv),
            _ => self.radiance_pdf(t.dir),
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
}

impl Emit for Environment {
    /// A direction by [`Environment::sample`], for a point anywhere.
    fn sample_li(&self, _from: Vec3A, u: Vec2, _default: Falloff) -> Option<LightSample> {
        let s = self.sample(u)?;
        (s.radiance != Color::ZERO).then_some(LightSample {
            to_light: s.direction,
            distance: f32::INFINITY,
            radiance: s.radiance,
            pdf: s.pdf,
        })
    }

    /// What falls on a disk of the scene's radius (at least 0.001): `pi r^2 x pi x` the mean
    /// luminance over all directions.
    fn power(&self, radius: f32) -> f32 {
        let radius = radius.max(1e-3);
        let mean = match &self.source {
            EnvironmentSource::Constant(c) => *c,
            EnvironmentSource::Map(m) => m.mean,
            EnvironmentSource::Sky(s) => s.mean(),
        };
        PI * radius * radius * PI * luminance(mean)
    }

    fn is_delta(&self) -> bool {
        false
    }

    fn kind_name(&self) -> &'static str {
        "environment"
    }

    /// A direction toward the environment by [`Environment::sample`] (from `v`), and a
    /// point uniform on the disk of the scene's radius that faces it, outside the scene
    /// (from `u`): light travels from there into the scene, weighing its radiance over both
    /// densities, `L pi r^2 / pdf` (pbrt's infinite lights).
    fn sample_le(&self, u: Vec2, v: Vec2, (centre, radius): (Vec3A, f32)) -> Option<Emission> {
        let s = self.sample(v)?;
        if s.radiance == Color::ZERO || s.pdf.is_nan() || s.pdf <= 0.0 {
            return None;
        }
        let d = crate::math::sampling::uniform_disk_concentric(u) * radius;
        let frame = crate::math::Frame::from_axis(s.direction);
        Some(Emission {
            origin: centre + s.direction * radius + frame.to_world(Vec3A::new(d.x, d.y, 0.0)),
            dir: -s.direction,
            normal: None,
            pdf_point: 1.0,
            weight: s.radiance * (PI * radius * radius / s.pdf),
            unfalling: false,
        })
    }

    fn pdf_le(&self, _normal: Option<Vec3A>, dir: Vec3A, radius: f32) -> (f32, f32) {
        (1.0 / (PI * radius * radius), self.pdf(-dir))
    }
}

#[cfg(test)]
mod tests {
    use super::super::env_map::{direction_of, uv_of};
    use super::*;
    use crate::math::chi2::{SphereBins, chi2_sphere};
    use crate::texture::ImageData;
    use std::sync::Arc;

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

    /// The radiance read from the half-float texels is the image's bilinear lookup to
    /// within half-float rounding, for a map with a texel far past half-float range too (a
    /// bright sun): nothing is clipped or infinite.
    #[test]
    fn half_float_radiance_is_the_images_lookup() {
        let mut cases = 0;
        for sun in [40.0f32, 2.5e6] {
            let (w, h) = (32u32, 16u32);
            let img = ::image::Rgb32FImage::from_fn(w, h, |x, y| {
                let v = 0.1 + (x * 7 + y * 3) as f32 / 300.0;
                let bright = if (x, y) == (22, 5) { sun } else { 0.0 };
                ::image::Rgb([v + bright, 0.5 * v, 1e-3 * v + bright])
            });
            let data = Arc::new(ImageData::from_dynamic(
                &::image::DynamicImage::ImageRgb32F(img),
                crate::texture::ColorSpace::Linear,
            ));
            let scale = Color::new(1.0, 2.0, 0.5);
            let map = EnvironmentMap::new(data.clone(), Vec3A::ZERO, scale);
            let wraps = crate::texture::Wraps {
                u: crate::texture::Wrap::Repeat,
                v: crate::texture::Wrap::Clamp,
            };
            for (u, v) in [
                (0.1, 0.2),
                (0.7, 0.33),
                (22.5 / 32.0, 5.5 / 16.0),
                (0.999, 0.999),
            ] {
                let uv = Vec2::new(u, v);
                let want = data.sample_bilinear(uv, wraps) * scale;
                let got = map.radiance(direction_of(uv).0);
                assert!(got.is_finite(), "{got}");
                for k in 0..3 {
                    // Values a billion times fainter than the sun are half-float
                    // subnormals, with fewer digits: a millionth absolute there.
                    let tol = 2e-3 * want[k].abs() + 1e-6;
                    assert!(
                        (got[k] - want[k]).abs() <= tol,
                        "{sun} {uv}: {got} vs {want}"
                    );
                }
                cases += 1;
            }
        }
        assert_eq!(cases, 8);
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
