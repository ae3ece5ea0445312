//! A directional light: parallel light from infinitely far away, as the sun's.

use super::{Emission, Emit, Falloff, LightSample};
use crate::math::{Color, Vec2, Vec3A, luminance};
use std::f32::consts::PI;

/// Parallel light from infinitely far away (the sun).
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub direction: Vec3A,
    /// Colour times intensity.
    pub color: Color,
}

impl Emit for DirectionalLight {
    #[inline]
    fn sample_li(&self, _from: Vec3A, _u: Vec2, _default: Falloff) -> Option<LightSample> {
        Some(LightSample {
            to_light: -self.direction,
            distance: f32::INFINITY,
            radiance: self.color,
            pdf: 1.0,
        })
    }

    /// What falls on a disk of the scene's radius.
    fn power(&self, radius: f32) -> f32 {
        PI * (radius * radius).max(1e-6) * luminance(self.color)
    }

    fn is_delta(&self) -> bool {
        true
    }

    fn kind_name(&self) -> &'static str {
        "directional"
    }

    /// A point uniform on the disk of the scene's radius that faces the light, on the
    /// light's side of the scene: the irradiance over the disk's density `1 / (pi r^2)`.
    fn sample_le(&self, u: Vec2, _v: Vec2, (centre, radius): (Vec3A, f32)) -> Option<Emission> {
        let d = crate::math::sampling::uniform_disk_concentric(u) * radius;
        let frame = crate::math::Frame::from_axis(self.direction);
        Some(Emission {
            origin: centre - self.direction * radius + frame.to_world(Vec3A::new(d.x, d.y, 0.0)),
            dir: self.direction,
            normal: None,
            pdf_point: 1.0,
            weight: self.color * (PI * radius * radius),
            unfalling: false,
        })
    }

    fn pdf_le(&self, _normal: Option<Vec3A>, _dir: Vec3A, radius: f32) -> (f32, f32) {
        (1.0 / (PI * radius * radius), 0.0)
    }
}
