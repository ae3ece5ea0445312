//! Surface materials: Phong shading terms plus mirror reflection and refraction, shared by
//! every integrator.

use crate::math::Color;

/// How a surface responds to light. Every coefficient is dimensionless.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Index of the texture that gives the surface colour.
    pub texture: usize,
    /// Multiplies the global ambient light (times the surface colour).
    pub ambient: f32,
    /// Lambertian term: light times surface colour times `cos` at the surface.
    pub diffuse: f32,
    /// Phong highlight colour.
    pub specular: Color,
    /// Phong exponent: larger is a smaller, sharper highlight.
    pub shininess: f32,
    /// Mirror reflection weight, in `[0, 1]`.
    pub reflectivity: f32,
    /// Fraction of light that passes into the surface, in `[0, 1]`; Fresnel splits it
    /// between reflection and refraction.
    pub transparency: f32,
    /// Index of refraction of the inside of the solid.
    pub ior: f32,
    /// Beer-Lambert absorption coefficient per scene unit travelled inside, per channel.
    pub absorption: Color,
}

impl Material {
    /// True when the surface lets light through (refraction and lighter shadows).
    #[inline]
    pub fn is_transparent(&self) -> bool {
        self.transparency > 0.0
    }
}
