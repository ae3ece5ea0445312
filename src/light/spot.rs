//! A spot light: a point light limited to a cone, with a soft edge.

use super::{Emission, Emit, Falloff, LightSample};
use crate::math::{Color, Vec2, Vec3A, luminance};
use std::f32::consts::PI;

/// A point light shining into a cone.
#[derive(Clone, Debug, PartialEq)]
pub struct SpotLight {
    /// Where it is.
    pub position: Vec3A,
    /// Unit direction of the cone's axis.
    pub direction: Vec3A,
    /// Colour times intensity.
    pub color: Color,
    /// Cosine of the cone's half-angle: outside it there is no light.
    pub cos_outer: f32,
    /// Cosine of the half-angle inside which the light is full.
    pub cos_inner: f32,
    /// How it weakens with distance; `None`: the integrator's default.
    pub falloff: Option<Falloff>,
}

impl Emit for SpotLight {
    /// Nothing outside the cone; between the inner and the outer angle, a smooth step.
    #[inline]
    fn sample_li(&self, from: Vec3A, _u: Vec2, default: Falloff) -> Option<LightSample> {
        let d = self.position - from;
        let distance = d.length();
        if distance == 0.0 {
            return None;
        }
        let to_light = d / distance;
        let cos = (-to_light).dot(self.direction);
        let edge = smoothstep(self.cos_outer, self.cos_inner, cos);
        (edge > 0.0).then(|| LightSample {
            to_light,
            distance,
            radiance: super::fall_off(self.color * edge, distance, self.falloff, default),
            pdf: 1.0,
        })
    }

    /// A point light's power over the solid angle of the cone (to the middle of its edge).
    fn power(&self, radius: f32) -> f32 {
        2.0 * PI
            * (1.0 - 0.5 * (self.cos_outer + self.cos_inner))
            * luminance(self.color)
            * super::unfalling_scale(self.falloff, radius)
    }

    fn is_delta(&self) -> bool {
        true
    }

    fn kind_name(&self) -> &'static str {
        "spot"
    }

    /// A direction uniform in the cone: the intensity there (the soft edge's step) over
    /// the cone's density.
    fn sample_le(&self, _u: Vec2, v: Vec2, _world: (Vec3A, f32)) -> Option<Emission> {
        use crate::math::sampling::{uniform_cone, uniform_cone_pdf};
        let local = uniform_cone(v, self.cos_outer);
        let edge = smoothstep(self.cos_outer, self.cos_inner, local.z);
        (edge > 0.0).then(|| Emission {
            origin: self.position,
            dir: crate::math::Frame::from_axis(self.direction).to_world(local),
            normal: None,
            pdf_point: 1.0,
            weight: self.color * (edge / uniform_cone_pdf(self.cos_outer)),
            unfalling: self.falloff == Some(Falloff::None),
        })
    }

    fn pdf_le(&self, _normal: Option<Vec3A>, dir: Vec3A, _radius: f32) -> (f32, f32) {
        let inside = dir.dot(self.direction) >= self.cos_outer;
        let pdf = crate::math::sampling::uniform_cone_pdf(self.cos_outer);
        (1.0, if inside { pdf } else { 0.0 })
    }

    fn position(&self) -> Option<Vec3A> {
        Some(self.position)
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
