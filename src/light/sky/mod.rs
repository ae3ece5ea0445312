//! A physical daylight sky with its sun, so outdoor scenes need no downloaded image: the
//! clear sky after Preetham et al. (preetham.rs), baked into an equirectangular map that is
//! sampled as any environment image is, and the sun's disk (sun.rs) of the radiance that
//! crosses the atmosphere, sampled by itself. Next-event estimation picks the sun or the
//! sky in proportion to the light each gives; both can reach any direction of the disk, so
//! the density of a direction is the mixture of both.
//!
//! Units: a value of 1 is [`SKY_UNIT_CD_M2`] cd/m² of luminance, which exposes a sunlit
//! scene about as the photographer's "sunny 16" rule does (an 18 % grey card in the noon
//! sun comes out near 0.3).

pub mod preetham;
pub mod solar_position;
pub mod sun;

use super::env_map::{EnvironmentMap, EnvironmentSample, direction_of};
use crate::math::spectrum::xyz_to_rgb;
use crate::math::{Color, Vec2, Vec3A, luminance};
use crate::texture::{ColorSpace, ImageData};
use preetham::Preetham;
use std::f32::consts::PI;
use std::sync::Arc;
pub use sun::{SUN_DIAMETER_DEG, Sun};

/// Luminance, in cd/m², of a value of 1.
pub const SKY_UNIT_CD_M2: f64 = 20_000.0;

/// Turbidity the Preetham fits hold for.
pub const TURBIDITY_RANGE: (f64, f64) = (2.0, 10.0);

/// The map's size: a texel is 0.7° across, finer than anything the clear sky does.
const MAP_SIZE: (u32, u32) = (512, 256);

/// What a sky is made from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkySettings {
    /// Unit direction toward the sun, at or above the horizon (`y ≥ 0`).
    pub sun_direction: Vec3A,
    /// Haze: 2 (very clear) to 10 (hazy).
    pub turbidity: f64,
    /// Multiplies the sky and the sun.
    pub scale: f32,
    /// Multiplies the sun alone (0: no sun disk).
    pub sun_scale: f32,
    /// The sun's angular diameter, degrees; a larger sun keeps the light it gives (its
    /// radiance falls), so only its shadows soften.
    pub sun_diameter_deg: f64,
}

/// The sky and its sun, ready to render.
#[derive(Clone, Debug)]
pub struct Sky {
    map: EnvironmentMap,
    sun: Option<Sun>,
    /// The chance that a light sample goes to the sun.
    sun_probability: f32,
    /// Radiance averaged over all directions.
    mean: Color,
}

impl Sky {
    /// The sky of `s`.
    pub fn new(s: &SkySettings) -> Self {
        let d = s.sun_direction.normalize();
        let sun_dir = [d.x as f64, d.y.max(0.0) as f64, d.z as f64];
        let model = Preetham::new(s.turbidity, sun_dir);
        let unit = s.scale as f64 / SKY_UNIT_CD_M2;
        let (w, h) = MAP_SIZE;
        let img = ::image::Rgb32FImage::from_fn(w, h, |x, y| {
            let uv = Vec2::new((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
            let (dir, _) = direction_of(uv);
            let xyz = model.xyz([dir.x as f64, dir.y as f64, dir.z as f64]);
            let rgb = xyz_to_rgb(xyz.map(|v| v * unit)).max(Color::ZERO);
            ::image::Rgb(rgb.to_array())
        });
        let image =
            ImageData::from_owned(::image::DynamicImage::ImageRgb32F(img), ColorSpace::Linear);
        let map = EnvironmentMap::new(Arc::new(image), Vec3A::ZERO, Color::ONE);
        let zenith_deg = (sun_dir[1].clamp(-1.0, 1.0)).acos().to_degrees();
        let sun = (s.sun_scale > 0.0 && s.scale > 0.0).then(|| {
            let diameter = s.sun_diameter_deg;
            // A larger disk keeps the sun's light: its radiance falls with its solid angle.
            let keep = (SUN_DIAMETER_DEG / diameter).powi(2) as f32;
            let xyz = sun::sun_xyz(zenith_deg, s.turbidity).map(|v| v * unit);
            let radiance = xyz_to_rgb(xyz).max(Color::ZERO) * (s.sun_scale * keep);
            Sun::new(d, diameter, radiance)
        });
        let sun_light = sun.as_ref().map_or(0.0, Sun::illuminance);
        let sky_light = luminance(map.mean()) * 4.0 * PI;
        let sun_probability = if sun_light + sky_light > 0.0 {
            sun_light / (sun_light + sky_light)
        } else {
            0.0
        };
        let mean = map.mean()
            + sun.as_ref().map_or(Color::ZERO, |s| {
                s.disk_radiance() * (s.solid_angle() / (4.0 * PI))
            });
        Sky {
            map,
            sun,
            sun_probability,
            mean,
        }
    }

    /// The sun's height above the horizon in degrees, where the sky has a sun.
    pub fn sun_elevation(&self) -> Option<f32> {
        self.sun
            .as_ref()
            .map(|s| s.axis().y.clamp(-1.0, 1.0).asin().to_degrees())
    }

    /// Radiance arriving from direction `dir` (unit, world space).
    #[inline]
    pub fn radiance(&self, dir: Vec3A) -> Color {
        let sun = self.sun.as_ref().map_or(Color::ZERO, |s| s.radiance(dir));
        self.map.radiance(dir) + sun
    }

    /// Radiance from `dir` and the density of [`Sky::sample`] for it.
    #[inline]
    pub fn radiance_pdf(&self, dir: Vec3A) -> (Color, f32) {
        let (sky, sky_pdf) = self.map.radiance_pdf(dir);
        match &self.sun {
            Some(sun) if sun.contains(dir) => (
                sky + sun.disk_radiance(),
                self.sun_probability * sun.pdf(dir) + (1.0 - self.sun_probability) * sky_pdf,
            ),
            _ => (sky, (1.0 - self.sun_probability) * sky_pdf),
        }
    }

    /// A direction toward the sun or the sky, by the light each gives.
    pub fn sample(&self, u: Vec2) -> Option<EnvironmentSample> {
        let p = self.sun_probability;
        let direction = match &self.sun {
            Some(sun) if u.x < p => sun.sample(Vec2::new(u.x / p, u.y)).0,
            _ => {
                let ux = if p > 0.0 {
                    ((u.x - p) / (1.0 - p)).clamp(0.0, 1.0 - f32::EPSILON)
                } else {
                    u.x
                };
                self.map.sample(Vec2::new(ux, u.y))?.direction
            }
        };
        let (radiance, pdf) = self.radiance_pdf(direction);
        (pdf > 0.0).then_some(EnvironmentSample {
            direction,
            radiance,
            pdf,
        })
    }

    /// Radiance averaged over all directions.
    pub fn mean(&self) -> Color {
        self.mean
    }

    /// The sun, if it shows.
    pub fn sun(&self) -> Option<&Sun> {
        self.sun.as_ref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::chi2::{SphereBins, chi2_sphere};

    fn settings(elevation: f64) -> SkySettings {
        SkySettings {
            sun_direction: solar_position::from_elevation_azimuth(elevation, 120.0),
            turbidity: 3.0,
            scale: 1.0,
            sun_scale: 1.0,
            sun_diameter_deg: SUN_DIAMETER_DEG,
        }
    }

    /// Sky directions follow the mixture's density by chi-square (the sun's share is a
    /// single bin, so it is tested apart, in sun.rs); every sample's density and radiance
    /// are what `radiance_pdf` gives for its direction; the density integrates to 1.
    #[test]
    fn sampling_matches_the_density() {
        for elevation in [50.0, 4.0] {
            let sky = Sky::new(&settings(elevation));
            let p = sky.sun_probability;
            assert!(p > 0.05 && p < 0.95, "{p}");
            // The sky's part alone, with u.x above the sun's share. The test's pole is the
            // sky's zenith (a turn of the axes), so the horizon, where the density stops,
            // is an edge between bands.
            let to_test = |d: Vec3A| Vec3A::new(d.z, d.x, d.y);
            let from_test = |d: Vec3A| Vec3A::new(d.y, d.z, d.x);
            chi2_sphere(
                "sky",
                SphereBins::default(),
                |u| {
                    let s = sky.sample(Vec2::new(p + u.x * (1.0 - p), u.y))?;
                    let (l, pdf) = sky.radiance_pdf(s.direction);
                    assert_eq!((l, pdf), (s.radiance, s.pdf));
                    Some(to_test(s.direction))
                },
                |d| sky.map.radiance_pdf(from_test(d)).1,
            )
            .unwrap();
            let sun = sky.sun().unwrap();
            let s = sky.sample(Vec2::new(0.3 * p, 0.7)).unwrap();
            assert!(sun.contains(s.direction));
            let expected =
                p * sun.pdf(s.direction) + (1.0 - p) * sky.map.radiance_pdf(s.direction).1;
            assert!((s.pdf - expected).abs() < 1e-4 * expected);
            assert!(s.radiance.max_element() > 100.0, "the disk: {}", s.radiance);
        }
    }

    /// The map holds the model's radiance, in the documented unit, and the sun's beam and
    /// the sky's light on the ground are daylight's: with the sun 50° up on a clear day, some
    /// 80 000 lux of direct sun on a surface facing it; the model's skylight on the ground
    /// is 30 000 lux (measured clear skies give less, 15 000 to 25 000: the model is bright
    /// near the sun).
    #[test]
    fn daylight_has_its_known_illuminance() {
        let s = settings(50.0);
        let sky = Sky::new(&s);
        let d = s.sun_direction;
        let model = Preetham::new(3.0, [d.x as f64, d.y as f64, d.z as f64]);
        for (e, a) in [(20.0, 0.0), (60.0, 250.0), (85.0, 10.0), (10.0, 180.0)] {
            let dir = solar_position::from_elevation_azimuth(e, a);
            let want = model.luminance([dir.x as f64, dir.y as f64, dir.z as f64]);
            let got = luminance(sky.radiance(dir)) as f64 * SKY_UNIT_CD_M2;
            assert!((got - want).abs() < 0.01 * want, "{e} {a}: {got} {want}");
        }
        let sun = sky.sun().unwrap();
        let direct = sun.illuminance() as f64 * SKY_UNIT_CD_M2;
        assert!((60_000.0..110_000.0).contains(&direct), "{direct} lux");
        let (nt, np) = (200, 400);
        let mut e = 0.0f64;
        for t in 0..nt {
            let theta = 0.5 * PI * (t as f32 + 0.5) / nt as f32;
            for k in 0..np {
                let phi = 2.0 * PI * (k as f32 + 0.5) / np as f32;
                let d = Vec3A::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                );
                e += (luminance(sky.map.radiance_pdf(d).0) * theta.cos() * theta.sin()) as f64;
            }
        }
        e *= (0.5 * PI as f64 / nt as f64) * (2.0 * PI as f64 / np as f64) * SKY_UNIT_CD_M2;
        assert!((27_000.0..33_000.0).contains(&e), "{e} lux of skylight");
    }

    /// Below the horizon there is no light, and a larger sun gives the same light.
    #[test]
    fn no_light_below_the_horizon_and_a_larger_sun_keeps_its_light() {
        let sky = Sky::new(&settings(30.0));
        assert_eq!(
            sky.radiance(Vec3A::new(0.3, -0.5, 0.2).normalize()),
            Color::ZERO
        );
        let big = Sky::new(&SkySettings {
            sun_diameter_deg: 5.0,
            ..settings(30.0)
        });
        let (a, b) = (
            sky.sun().unwrap().illuminance(),
            big.sun().unwrap().illuminance(),
        );
        assert!((a - b).abs() < 1e-3 * a, "{a} {b}");
        let none = Sky::new(&SkySettings {
            sun_scale: 0.0,
            ..settings(30.0)
        });
        assert!(none.sun().is_none() && none.sun_probability == 0.0);
    }
}
