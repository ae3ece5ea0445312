//! A point light: shines equally in every direction from a point, falling off with distance
//! as its `falloff` says.

use super::{Emission, Emit, Falloff, LightSample};
use crate::math::{Color, Vec2, Vec3A, luminance};
use std::f32::consts::PI;

/// Light from a point, the same in every direction.
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    /// Where it is.
    pub position: Vec3A,
    /// Colour times intensity.
    pub color: Color,
    /// How it weakens with distance; `None`: the integrator's default.
    pub falloff: Option<Falloff>,
}

impl Emit for PointLight {
    #[inline]
    fn sample_li(&self, from: Vec3A, _u: Vec2, default: Falloff) -> Option<LightSample> {
        let d = self.position - from;
        let distance = d.length();
        (distance > 0.0).then(|| LightSample {
            to_light: d / distance,
            distance,
            radiance: super::fall_off(self.color, distance, self.falloff, default),
            pdf: 1.0,
        })
    }

    /// `4 pi` times its luminance; one that does not fall off is as bright as one that does
    /// at the scene's radius.
    fn power(&self, radius: f32) -> f32 {
        4.0 * PI * luminance(self.color) * super::unfalling_scale(self.falloff, radius)
    }

    fn is_delta(&self) -> bool {
        true
    }

    fn kind_name(&self) -> &'static str {
        "point"
    }

    /// A direction uniform over the sphere: the intensity over its density `1 / 4 pi`.
    fn sample_le(&self, _u: Vec2, v: Vec2, _world: (Vec3A, f32)) -> Option<Emission> {
        Some(Emission {
            origin: self.position,
            dir: crate::math::sampling::uniform_sphere(v),
            normal: None,
            pdf_point: 1.0,
            weight: self.color * (4.0 * PI),
            unfalling: self.falloff == Some(Falloff::None),
        })
    }

    fn pdf_le(&self, _normal: Option<Vec3A>, _dir: Vec3A, _radius: f32) -> (f32, f32) {
        (1.0, crate::math::sampling::UNIFORM_SPHERE_PDF)
    }

    fn position(&self) -> Option<Vec3A> {
        Some(self.position)
    }
}
