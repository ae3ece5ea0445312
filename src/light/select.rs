//! Choosing a light for next-event estimation: one of all the scene's lights, in proportion
//! to its power, so a bright lamp gets the shadow rays and a faint one few; the light then
//! gives a direction toward it ([`super::Emit::sample_li`]).

use super::{Falloff, Light};
use crate::math::distribution::Distribution1d;
use crate::math::{Color, Vec2, Vec3A};

/// The scene's lights, each with its chance of being chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct LightSampler {
    /// Over the scene's lights, in their order.
    choice: Distribution1d,
}

/// A light chosen for a point, and where its light comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightChoice {
    /// Index in the scene's list of lights.
    pub light: usize,
    /// Unit direction from the point toward the light.
    pub to_light: Vec3A,
    /// Distance to the light (infinite for directional lights and the environment).
    pub distance: f32,
    /// Radiance (area lights, the environment) or irradiance (deltas) arriving, unshadowed.
    pub radiance: Color,
    /// The chance of choosing this light times the density per unit solid angle of the
    /// direction (for a delta light the chance alone).
    pub pdf: f32,
    /// Whether the light is a delta (no BSDF sample can reach it; no MIS).
    pub delta: bool,
}

impl LightSampler {
    /// Chances in proportion to power ([`super::Emit::power`]) in a scene of radius `radius`.
    pub fn new(lights: &[Light], radius: f32) -> Self {
        let weights: Vec<f32> = lights.iter().map(|l| l.power(radius)).collect();
        LightSampler {
            choice: Distribution1d::new(&weights),
        }
    }

    /// Whether there is no light at all.
    pub fn is_empty(&self) -> bool {
        self.choice.is_empty()
    }

    /// A light chosen by `uc` in proportion to its power, and the chance of that choice.
    pub fn pick(&self, uc: f32) -> Option<(usize, f32)> {
        let (i, p, _) = self.choice.sample_discrete(uc)?;
        (p > 0.0).then_some((i, p))
    }

    /// The chance of choosing light `i` (for MIS when a BSDF sample finds it).
    pub fn probability(&self, i: usize) -> f32 {
        self.choice.probability(i)
    }

    /// A light of `lights` chosen by `uc`, and a point of it by `u` (a direction, for the
    /// environment), seen from `from`; lights that do not say how they fall off fall off as
    /// `default` says.
    pub fn sample(
        &self,
        lights: &[Light],
        from: Vec3A,
        uc: f32,
        u: Vec2,
        default: Falloff,
    ) -> Option<LightChoice> {
        let (i, p, _) = self.choice.sample_discrete(uc)?;
        if p <= 0.0 {
            return None;
        }
        let light = &lights[i];
        let s = light.sample_li(from, u, default)?;
        let delta = light.is_delta();
        Some(LightChoice {
            light: i,
            to_light: s.to_light,
            distance: s.distance,
            radiance: s.radiance,
            pdf: p * s.pdf,
            delta,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Disk;
    use crate::light::{AreaLight, Emitter, PointLight};
    use std::f32::consts::PI;

    /// A light ten times as powerful is chosen ten times as often.
    #[test]
    fn lights_are_chosen_by_power() {
        let disk = |r: f32| {
            Light::Area(AreaLight::new(
                Emitter::Disk(Disk::new(Vec3A::ZERO, Vec3A::Z, 1.0)),
                Color::splat(r),
                None,
                false,
                0,
            ))
        };
        let point = Light::Point(PointLight {
            position: Vec3A::new(0.0, 0.0, 5.0),
            color: Color::splat(PI / 4.0),
            falloff: None,
        });
        let s = LightSampler::new(&[point, disk(1.0), disk(10.0)], 1.0);
        // Powers: point 4 pi * pi / 4 = pi^2; disks pi^2 and 10 pi^2.
        assert!((s.probability(0) - 1.0 / 12.0).abs() < 1e-6);
        assert!((s.probability(1) - 1.0 / 12.0).abs() < 1e-6);
        assert!((s.probability(2) - 10.0 / 12.0).abs() < 1e-6);
    }
}
