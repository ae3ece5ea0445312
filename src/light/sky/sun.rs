//! The sun: a disk of the sky of uniform radiance (no limb darkening), 0.533° across by
//! default, its colour and brightness those of a 5778 K black body (the sun's effective
//! temperature) dimmed by the atmosphere along its path: Rayleigh scattering by the air
//! (Leckner's optical depth, 0.008735 λ^−4.08 with λ in µm), scattering by aerosols after
//! Ångström (α = 1.3, β = 0.04608 T − 0.04586: Preetham et al.'s turbidity relation), and
//! ozone's Chappuis band (as a Gaussian about 602 nm, 0.045 deep at the zenith: 350 Dobson
//! units), over Kasten and Young's relative air mass. Water vapour's few visible lines are
//! left out.

use crate::math::spectrum::{planck, spectrum_to_xyz};
use crate::math::{Color, Frame, Vec2, Vec3A, luminance};
use std::f32::consts::PI;

/// The sun's mean angular diameter seen from the earth, in degrees.
pub const SUN_DIAMETER_DEG: f64 = 0.533;

/// The sun's surface temperature, kelvin.
const SUN_KELVIN: f64 = 5778.0;

/// A disk of the sky far away: its axis, its size and its radiance.
#[derive(Clone, Debug)]
pub struct Sun {
    /// Unit direction toward its centre.
    axis: Vec3A,
    frame: Frame,
    /// `1 − cos` of its angular radius (its solid angle over 2π), exact enough for a disk
    /// half a degree across.
    h: f32,
    /// Radiance, linear RGB.
    radiance: Color,
}

/// Kasten and Young's (1989) relative air mass at `zenith_deg` degrees from the zenith: 1
/// straight up, about 38 at the horizon.
pub fn air_mass(zenith_deg: f64) -> f64 {
    let z = zenith_deg.clamp(0.0, 90.0);
    1.0 / (z.to_radians().cos() + 0.50572 * (96.07995 - z).powf(-1.6364))
}

/// The fraction of the sun's light at `lambda` nanometres that crosses `mass` air masses of
/// an atmosphere of `turbidity`.
pub fn transmittance(lambda: f64, mass: f64, turbidity: f64) -> f64 {
    let um = lambda / 1000.0;
    let rayleigh = 0.008735 * um.powf(-4.08);
    let beta = 0.04608 * turbidity - 0.04586;
    let aerosol = beta * um.powf(-1.3);
    let t = (lambda - 602.0) / 55.0;
    let ozone = 0.045 * (-0.5 * t * t).exp();
    (-mass * (rayleigh + aerosol + ozone)).exp()
}

/// CIE XYZ of the sun's radiance (Y in cd/m²) seen `zenith_deg` from the zenith through an
/// atmosphere of `turbidity`.
pub fn sun_xyz(zenith_deg: f64, turbidity: f64) -> [f64; 3] {
    let m = air_mass(zenith_deg);
    spectrum_to_xyz(|l| planck(l, SUN_KELVIN) * transmittance(l, m, turbidity))
}

impl Sun {
    /// A disk about unit `axis`, `diameter_deg` across, of `radiance`.
    pub fn new(axis: Vec3A, diameter_deg: f64, radiance: Color) -> Self {
        let half = (0.5 * diameter_deg).to_radians();
        // 1 − cos r = 2 sin²(r/2), without cancellation.
        let h = 2.0 * (0.5 * half).sin().powi(2);
        Sun {
            axis,
            frame: Frame::from_axis(axis),
            h: h as f32,
            radiance,
        }
    }

    /// Its solid angle, steradians.
    pub fn solid_angle(&self) -> f32 {
        2.0 * PI * self.h
    }

    /// Whether unit direction `d` points into the disk (by the chord to its axis, which
    /// keeps its precision where a cosine near 1 would not).
    #[inline]
    pub fn contains(&self, d: Vec3A) -> bool {
        (d - self.axis).length_squared() <= 2.0 * self.h
    }

    /// Radiance along `d`: the disk's inside it, none outside.
    #[inline]
    pub fn radiance(&self, d: Vec3A) -> Color {
        if self.contains(d) {
            self.radiance
        } else {
            Color::ZERO
        }
    }

    /// A direction into the disk, every one equally likely, and its density per unit solid
    /// angle ([`Sun::pdf`]).
    pub fn sample(&self, u: Vec2) -> (Vec3A, f32) {
        let one_minus_cos = u.x * self.h;
        let cos = 1.0 - one_minus_cos;
        let sin = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
        let (sp, cp) = (2.0 * PI * u.y).sin_cos();
        let d = self
            .frame
            .to_world(Vec3A::new(sin * cp, sin * sp, cos))
            .normalize();
        (d, 1.0 / self.solid_angle())
    }

    /// The density of [`Sun::sample`] for direction `d`.
    #[inline]
    pub fn pdf(&self, d: Vec3A) -> f32 {
        if self.contains(d) {
            1.0 / self.solid_angle()
        } else {
            0.0
        }
    }

    /// Its luminance times its solid angle: the illuminance it gives a surface facing it.
    pub fn illuminance(&self) -> f32 {
        luminance(self.radiance) * self.solid_angle()
    }

    /// The radiance inside the disk.
    pub fn disk_radiance(&self) -> Color {
        self.radiance
    }

    /// Unit direction toward its centre.
    pub fn axis(&self) -> Vec3A {
        self.axis
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::chi2::chi2_square;

    /// Kasten and Young's air mass: 1 at the zenith, 2 at 60°, about 38 at the horizon.
    #[test]
    fn air_mass_matches_the_table() {
        assert!((air_mass(0.0) - 1.0).abs() < 1e-3);
        assert!((air_mass(60.0) - 1.995).abs() < 0.01, "{}", air_mass(60.0));
        assert!((air_mass(90.0) - 37.9).abs() < 0.5, "{}", air_mass(90.0));
    }

    /// The noon sun of a clear sky is about 1.5e9 cd/m² and a warm white (about 5000 K); at the horizon it
    /// is thousands of times dimmer and red; haze dims it.
    #[test]
    fn the_sun_dims_and_reddens_toward_the_horizon() {
        let noon = sun_xyz(20.0, 2.5);
        assert!((1.3e9..1.8e9).contains(&noon[1]), "{noon:?}");
        let rgb = crate::math::spectrum::xyz_to_rgb(noon);
        assert!(rgb.min_element() > 0.6 * rgb.max_element(), "{rgb}");
        let low = sun_xyz(88.0, 2.5);
        assert!(low[1] < 0.02 * noon[1], "{low:?}");
        let red = crate::math::spectrum::xyz_to_rgb(low);
        assert!(red.x > 2.0 * red.z && red.x > red.y, "{red}");
        assert!(sun_xyz(20.0, 8.0)[1] < 0.8 * noon[1]);
    }

    /// Directions fill the disk evenly by solid angle: as (1 − cos θ) / h and the angle
    /// about the axis they are uniform over the unit square; a density 10 % off on half the
    /// disk fails. Each lies inside, and the density integrates to 1 over the disk.
    #[test]
    fn directions_fill_the_disk_evenly() {
        let axis = Vec3A::new(0.3, 0.8, -0.52).normalize();
        let sun = Sun::new(axis, SUN_DIAMETER_DEG, Color::ONE);
        let frame = Frame::from_axis(axis);
        let h = 2.0 * (0.25 * SUN_DIAMETER_DEG).to_radians().sin().powi(2);
        let polar = |u: Vec2| {
            let (d, pdf) = sun.sample(u);
            assert!(sun.contains(d) || u.x > 0.999, "{u} falls outside");
            assert_eq!(pdf, sun.pdf(axis));
            let l = frame.to_local(d);
            let one_minus_cos = (l.x * l.x + l.y * l.y) as f64 / (1.0 + l.z as f64);
            let phi = l.y.atan2(l.x).rem_euclid(2.0 * PI);
            Some(Vec2::new(
                ((one_minus_cos / h) as f32).min(1.0),
                phi / (2.0 * PI),
            ))
        };
        chi2_square("sun disk", 16, polar, |_| 1.0).unwrap();
        let broken = |p: Vec2| if p.y < 0.5 { 1.1 } else { 0.9 };
        assert!(chi2_square("sun disk, wrong density", 16, polar, broken).is_err());
        // The density integrated over the disk, on a grid of directions about the axis.
        let r = (0.5 * SUN_DIAMETER_DEG).to_radians() as f32;
        let n = 400;
        let step = 2.4 * r / n as f32;
        let mut sum = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let (x, y) = (
                    -1.2 * r + (i as f32 + 0.5) * step,
                    -1.2 * r + (j as f32 + 0.5) * step,
                );
                let d = frame.to_world(Vec3A::new(x, y, 1.0)).normalize();
                sum += sun.pdf(d) as f64 * (step * step) as f64;
            }
        }
        assert!((sum - 1.0).abs() < 0.01, "{sum}");
        assert_eq!(sun.radiance(-axis), Color::ZERO);
        assert_eq!(sun.radiance(axis), Color::ONE);
    }
}
