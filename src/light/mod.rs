//! Light sources: point, directional and spot (here), area lights on emitting shapes
//! (area.rs), and the choice among them by power for the path tracer (select.rs). Point and
//! spot lights fall off with distance as their `falloff` says; by default not at all under
//! the Whitted integrator (the seed report's and POV-Ray's default, so a scene's brightness
//! does not depend on its scale), as `1 / d^2` under the path tracer.

pub mod area;
mod env_map;
pub mod environment;
pub mod select;
pub mod sky;

pub use area::{AreaLight, Emitter, ObjectLights};
pub use environment::{Environment, EnvironmentMap, EnvironmentSample, EnvironmentSource};
pub use select::{LightChoice, LightSampler};

use crate::math::{Color, Vec3A};
use schemars::JsonSchema;
use serde::Deserialize;

/// How a point or spot light's light weakens with distance.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Falloff {
    /// Not at all: the same light at any distance (the seed report's and POV-Ray's default).
    None,
    /// As `1 / d^2`, as physics has it: `intensity` is then in watts per steradian.
    InverseSquare,
}

/// A light source. Colours are linear RGB radiance multipliers.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    /// Shines equally in every direction from a point.
    Point {
        /// Where it is.
        position: Vec3A,
        /// Colour times intensity.
        color: Color,
        /// How it weakens with distance; `None`: the integrator's default.
        falloff: Option<Falloff>,
    },
    /// Parallel light from infinitely far away (the sun).
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3A,
        /// Colour times intensity.
        color: Color,
    },
    /// A point light limited to a cone, with a soft edge.
    Spot {
        /// Where it is.
        position: Vec3A,
        /// Unit direction of the cone's axis.
        direction: Vec3A,
        /// Colour times intensity.
        color: Color,
        /// Cosine of the cone's half-angle: outside it there is no light.
        cos_outer: f32,
        /// Cosine of the half-angle inside which the light is full.
        cos_inner: f32,
        /// How it weakens with distance; `None`: the integrator's default.
        falloff: Option<Falloff>,
    },
}

/// Light arriving at a point from one source.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction from the point toward the light.
    pub to_light: Vec3A,
    /// Distance to the light (infinite for directional lights).
    pub distance: f32,
    /// Light arriving, before shadowing.
    pub radiance: Color,
}

impl Light {
    /// The light reaching `p` from this source, or `None` if it cannot (outside a spot's
    /// cone, or `p` at the light's position), falling off as the light says, by default not
    /// at all (the Whitted integrator's reading).
    #[inline]
    pub fn sample(&self, p: Vec3A) -> Option<LightSample> {
        self.sample_falling_off(p, Falloff::None)
    }

    /// [`Light::sample`], lights that do not say how they fall off falling off as `default`
    /// says.
    #[inline]
    pub fn sample_falling_off(&self, p: Vec3A, default: Falloff) -> Option<LightSample> {
        let mut s = self.sample_unattenuated(p)?;
        if let Light::Point { falloff, .. } | Light::Spot { falloff, .. } = self
            && falloff.unwrap_or(default) == Falloff::InverseSquare
        {
            s.radiance /= s.distance * s.distance;
        }
        Some(s)
    }

    fn sample_unattenuated(&self, p: Vec3A) -> Option<LightSample> {
        match self {
            Light::Point {
                position, color, ..
            } => {
                let d = *position - p;
                let distance = d.length();
                (distance > 0.0).then(|| LightSample {
                    to_light: d / distance,
                    distance,
                    radiance: *color,
                })
            }
            Light::Directional { direction, color } => Some(LightSample {
                to_light: -*direction,
                distance: f32::INFINITY,
                radiance: *color,
            }),
            Light::Spot {
                position,
                direction,
                color,
                cos_outer,
                cos_inner,
                ..
            } => {
                let d = *position - p;
                let distance = d.length();
                if distance == 0.0 {
                    return None;
                }
                let to_light = d / distance;
                let cos = (-to_light).dot(*direction);
                let falloff = smoothstep(*cos_outer, *cos_inner, cos);
                (falloff > 0.0).then(|| LightSample {
                    to_light,
                    distance,
                    radiance: *color * falloff,
                })
            }
        }
    }

    /// The light's `type` in the scene file.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Light::Point { .. } => "point",
            Light::Directional { .. } => "directional",
            Light::Spot { .. } => "spot",
        }
    }

    /// Where the light is, for lights that have a position.
    pub fn position(&self) -> Option<Vec3A> {
        match self {
            Light::Point { position, .. } | Light::Spot { position, .. } => Some(*position),
            Light::Directional { .. } => None,
        }
    }
}

/// 0 below `edge0`, 1 above `edge1`, a smooth cubic between (a hard step when they meet).
fn smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    if edge1 <= edge0 {
        return if x >= edge0 { 1.0 } else { 0.0 };
    }
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(angle: f32, soft: f32) -> Light {
        Light::Spot {
            position: Vec3A::new(0.0, 10.0, 0.0),
            direction: -Vec3A::Y,
            color: Color::ONE,
            cos_outer: angle.to_radians().cos(),
            cos_inner: (angle - soft).to_radians().cos(),
            falloff: None,
        }
    }

    fn at_angle(l: &Light, deg: f32) -> f32 {
        let p = Vec3A::new(10.0 * deg.to_radians().tan(), 0.0, 0.0);
        l.sample(p).map_or(0.0, |s| s.radiance.x)
    }

    #[test]
    fn spot_cone_and_soft_edge() {
        let l = spot(30.0, 10.0);
        assert_eq!(at_angle(&l, 0.0), 1.0);
        assert_eq!(at_angle(&l, 19.0), 1.0);
        let mid = at_angle(&l, 25.0);
        assert!(mid > 0.2 && mid < 0.8, "{mid}");
        assert_eq!(at_angle(&l, 31.0), 0.0);
        let hard = spot(30.0, 0.0);
        assert_eq!(at_angle(&hard, 29.9), 1.0);
        assert_eq!(at_angle(&hard, 30.1), 0.0);
    }

    #[test]
    fn point_and_directional() {
        let p = Light::Point {
            position: Vec3A::new(0.0, 4.0, 3.0),
            color: Color::splat(2.0),
            falloff: None,
        };
        let s = p.sample(Vec3A::ZERO).unwrap();
        assert!((s.distance - 5.0).abs() < 1e-6);
        assert!((s.to_light - Vec3A::new(0.0, 0.8, 0.6)).length() < 1e-6);
        assert_eq!(s.radiance, Color::splat(2.0), "no distance falloff");
        let s = p
            .sample_falling_off(Vec3A::ZERO, Falloff::InverseSquare)
            .unwrap();
        assert!((s.radiance.x - 2.0 / 25.0).abs() < 1e-7, "1 / d^2");
        let d = Light::Directional {
            direction: -Vec3A::Y,
            color: Color::ONE,
        };
        let s = d.sample(Vec3A::new(100.0, 0.0, 0.0)).unwrap();
        assert_eq!(s.to_light, Vec3A::Y);
        assert!(s.distance.is_infinite());
    }
}
