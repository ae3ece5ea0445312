//! A directional light: parallel light from infinitely far away, as the sun's.

use super::{Emit, Falloff, LightSample};
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
}
