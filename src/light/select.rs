//! Choosing a light for next-event estimation: one of all the scene's lights, in proportion
//! to its power, so a bright lamp gets the shadow rays and a faint one few. Point and spot
//! lights and directional lights reach a point from one direction (deltas); area lights are
//! sampled by [`AreaLight::sample`], the environment by [`Environment::sample`].

use super::{AreaLight, Environment, Falloff, Light};
use crate::math::distribution::Distribution1d;
use crate::math::{Color, Vec2, Vec3A, luminance};
use std::f32::consts::PI;

/// The scene's lights, each with its chance of being chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct LightSampler {
    /// Over the point, spot and directional lights, then the area lights, then the
    /// environment, in order.
    choice: Distribution1d,
    /// How many of the first.
    deltas: usize,
    /// How many area lights.
    areas: usize,
}

/// A light chosen for a point, and where its light comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightChoice {
    /// Index among all lights (point, spot and directional first, then area lights, then
    /// the environment).
    pub light: usize,
    /// Unit direction from the point toward the light.
    pub to_light: Vec3A,
    /// Distance to the light (infinite for directional lights and the environment).
    pub distance: f32,
    /// Radiance (area lights) or irradiance over `pdf` (deltas) arriving, unshadowed.
    pub radiance: Color,
    /// The chance of choosing this light times, for an area light, the density per unit
    /// solid angle of the direction; for a delta light the chance alone.
    pub pdf: f32,
    /// Whether the light is a delta (no BSDF sample can reach it; no MIS).
    pub delta: bool,
}

impl LightSampler {
    /// Chances in proportion to power. `radius` is the scene's bounding radius (a
    /// directional light's power is what falls on a disk of that radius; a light that does
    /// not fall off is as bright as one that does at that distance; the environment's is
    /// what falls on such a disk too).
    pub fn new(
        lights: &[Light],
        area: &[AreaLight],
        environment: Option<&Environment>,
        radius: f32,
    ) -> Self {
        let r2 = (radius * radius).max(1e-6);
        let mut weights: Vec<f32> = lights
            .iter()
            .map(|l| match l {
                Light::Point { color, falloff, .. } => {
                    let scale = if *falloff == Some(Falloff::None) {
                        r2
                    } else {
                        1.0
                    };
                    4.0 * PI * luminance(*color) * scale
                }
                Light::Spot {
                    color,
                    cos_outer,
                    cos_inner,
                    falloff,
                    ..
                } => {
                    let scale = if *falloff == Some(Falloff::None) {
                        r2
                    } else {
                        1.0
                    };
                    2.0 * PI * (1.0 - 0.5 * (cos_outer + cos_inner)) * luminance(*color) * scale
                }
                Light::Directional { color, .. } => PI * r2 * luminance(*color),
            })
            .collect();
        weights.extend(area.iter().map(AreaLight::power));
        weights.extend(environment.map(|e| e.power(radius.max(1e-3))));
        LightSampler {
            choice: Distribution1d::new(&weights),
            deltas: lights.len(),
            areas: area.len(),
        }
    }

    /// Whether there is no light at all.
    pub fn is_empty(&self) -> bool {
        self.choice.is_empty()
    }

    /// The chance of choosing area light `i` (for MIS when a BSDF sample hits it).
    pub fn area_probability(&self, i: usize) -> f32 {
        self.choice.probability(self.deltas + i)
    }

    /// The chance of choosing the environment (for MIS when a path leaves the scene).
    pub fn environment_probability(&self) -> f32 {
        self.choice.probability(self.deltas + self.areas)
    }

    /// A light chosen by `uc`, and a point of it by `u` for an area light (a direction for
    /// the environment), seen from `from`; point and spot lights fall off as they say, by
    /// default `default`.
    #[allow(clippy::too_many_arguments)]
    pub fn sample(
        &self,
        lights: &[Light],
        area: &[AreaLight],
        environment: Option<&Environment>,
        from: Vec3A,
        uc: f32,
        u: Vec2,
        default: Falloff,
    ) -> Option<LightChoice> {
        let (i, p, _) = self.choice.sample_discrete(uc)?;
        if p <= 0.0 {
            return None;
        }
        if i < self.deltas {
            let s = lights[i].sample_falling_off(from, default)?;
            return Some(LightChoice {
                light: i,
                to_light: s.to_light,
                distance: s.distance,
                radiance: s.radiance,
                pdf: p,
                delta: true,
            });
        }
        if i >= self.deltas + self.areas {
            let s = environment?.sample(u)?;
            return (s.radiance != Color::ZERO).then_some(LightChoice {
                light: i,
                to_light: s.direction,
                distance: f32::INFINITY,
                radiance: s.radiance,
                pdf: p * s.pdf,
                delta: false,
            });
        }
        let light = &area[i - self.deltas];
        let s = light.sample(from, u)?;
        let d = s.point - from;
        let distance = d.length();
        let to_light = d / distance;
        let radiance = light.emitted(s.normal, -to_light);
        (radiance != Color::ZERO && distance > 0.0).then_some(LightChoice {
            light: i,
            to_light,
            distance,
            radiance,
            pdf: p * s.pdf,
            delta: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Disk;
    use crate::light::Emitter;

    /// A light ten times as powerful is chosen ten times as often.
    #[test]
    fn lights_are_chosen_by_power() {
        let disk = |r: f32| AreaLight {
            emitter: Emitter::Disk(Disk::new(Vec3A::ZERO, Vec3A::Z, 1.0)),
            radiance: Color::splat(r),
            texture: None,
            two_sided: false,
            object: 0,
        };
        let point = Light::Point {
            position: Vec3A::new(0.0, 0.0, 5.0),
            color: Color::splat(PI / 4.0),
            falloff: None,
        };
        let s = LightSampler::new(&[point], &[disk(1.0), disk(10.0)], None, 1.0);
        // Powers: point 4 pi * pi / 4 = pi^2; disks pi^2 and 10 pi^2.
        assert!((s.choice.probability(0) - 1.0 / 12.0).abs() < 1e-6);
        assert!((s.area_probability(0) - 1.0 / 12.0).abs() < 1e-6);
        assert!((s.area_probability(1) - 10.0 / 12.0).abs() < 1e-6);
    }
}
