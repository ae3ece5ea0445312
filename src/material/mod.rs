//! Materials: what a scene file says of a surface, textured, and how each integrator reads
//! it. The Whitted integrator reads the Phong terms every material carries (each type sets
//! them in its own file, as docs/scene-format.md documents); the path tracer builds a
//! [`Bsdf`] at each hit from the material's [`Surface`] and its textures. One file per type.

pub mod conductor;
pub mod dielectric;
pub mod diffuse;
pub mod phong;
pub mod plastic;
pub mod thin;

use crate::bsdf::Bsdf;
use crate::math::Color;
use crate::texture::{Texture, TexturePoint};

/// How a surface responds to light. Every coefficient is dimensionless.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Index of the texture that gives the surface colour.
    pub texture: usize,
    /// Whitted: multiplies the global ambient light (times the surface colour).
    pub ambient: f32,
    /// Whitted: Lambertian term, light times surface colour times `cos` at the surface.
    pub diffuse: f32,
    /// Whitted: Phong highlight colour.
    pub specular: Color,
    /// Whitted: Phong exponent, larger is a smaller, sharper highlight.
    pub shininess: f32,
    /// Whitted: mirror reflection weight, in `[0, 1]`.
    pub reflectivity: f32,
    /// Whitted: the colour of the mirror reflection (white but for metals).
    pub mirror_tint: Color,
    /// Fraction of light that passes into the surface, in `[0, 1]`; Fresnel splits it
    /// between reflection and refraction (Whitted; the path tracer's Phong mix).
    pub transparency: f32,
    /// Index of refraction of the inside of the solid.
    pub ior: f32,
    /// Beer-Lambert absorption coefficient per scene unit travelled inside, per channel.
    pub absorption: Color,
    /// What the path tracer scatters by.
    pub surface: Surface,
    /// Light the surface gives off, if any.
    pub emission: Option<Emission>,
}

/// Light given off by a surface: constant radiance on its front side, or on both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// Radiance, linear RGB (per unit area and solid angle).
    pub radiance: Color,
    /// Whether the back side emits too.
    pub two_sided: bool,
}

impl Emission {
    /// The radiance leaving the side of the surface that `front` says.
    #[inline]
    pub fn emitted(&self, front: bool) -> Color {
        if front || self.two_sided {
            self.radiance
        } else {
            Color::ZERO
        }
    }
}

/// A scalar parameter: a constant or the mean of a texture's channels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scalar {
    /// The same everywhere.
    Value(f32),
    /// Index of a texture in the scene's list.
    Texture(usize),
}

impl Scalar {
    /// The value at a surface point.
    #[inline]
    pub fn at(&self, textures: &[Texture], p: &TexturePoint) -> f32 {
        match *self {
            Scalar::Value(v) => v,
            Scalar::Texture(t) => textures[t].eval(p).element_sum() / 3.0,
        }
    }
}

/// The scattering of each type of material, for the path tracer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Surface {
    /// The Phong terms, read as a mix (see [`phong`]).
    Phong,
    /// Lambertian, of the material's colour.
    Diffuse,
    /// A metal (see [`conductor`]).
    Conductor(conductor::Conductor),
    /// Glass (see [`dielectric`]).
    Dielectric(dielectric::Dielectric),
    /// A thin pane of this index of refraction.
    Thin(f32),
    /// Coated diffuse (see [`plastic`]).
    Plastic(plastic::Plastic),
}

impl Material {
    /// The BSDF at a surface point, whose textured colour is `base`.
    pub fn bsdf(&self, textures: &[Texture], p: &TexturePoint, base: Color) -> Bsdf {
        match &self.surface {
            Surface::Phong => phong::bsdf(self, base),
            Surface::Diffuse => diffuse::bsdf(base),
            Surface::Conductor(c) => c.bsdf(base, textures, p),
            Surface::Dielectric(d) => d.bsdf(self, textures, p),
            Surface::Thin(ior) => thin::bsdf(*ior),
            Surface::Plastic(c) => c.bsdf(self, base, textures, p),
        }
    }

    /// The absorption inside the solid, for a path that has crossed into it, or `None`
    /// where the material lets no light in or absorbs nothing.
    pub fn absorption_inside(&self) -> Option<Color> {
        (self.absorption != Color::ZERO).then_some(self.absorption)
    }

    /// True when the surface lets light through (refraction and lighter shadows).
    #[inline]
    pub fn is_transparent(&self) -> bool {
        self.transparency > 0.0
    }

    /// A material with Whitted's defaults (white, ambient 1, diffuse 0.8, nothing else),
    /// for each type's constructor to change.
    pub(crate) fn base(texture: usize, surface: Surface, emission: Option<Emission>) -> Self {
        Material {
            texture,
            ambient: 1.0,
            diffuse: 0.8,
            specular: Color::ZERO,
            shininess: 50.0,
            reflectivity: 0.0,
            mirror_tint: Color::ONE,
            transparency: 0.0,
            ior: 1.5,
            absorption: Color::ZERO,
            surface,
            emission,
        }
    }
}

/// The Phong exponent that gives a highlight about as wide as GGX of roughness `alpha`:
/// Blinn-Phong's `2 / alpha^2 - 2` (Walter et al. 2007), over 4 for Phong's mirror-vector
/// form; smooth surfaces get 1000.
pub fn shininess_of(alpha: f32) -> f32 {
    if alpha <= 0.0 {
        return 1000.0;
    }
    ((2.0 / (alpha * alpha) - 2.0) / 4.0).clamp(1.0, 1000.0)
}

/// The inverse of [`shininess_of`]: the GGX roughness a Phong exponent stands for.
pub fn alpha_of(shininess: f32) -> f32 {
    (2.0 / (4.0 * shininess.max(0.0) + 2.0)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shininess_and_roughness_are_inverse() {
        for n in [1.0f32, 10.0, 50.0, 200.0] {
            assert!((shininess_of(alpha_of(n)) - n).abs() < 1e-2 * n, "{n}");
        }
        // The seed's exponent 50 is a fairly sharp coat.
        assert!((alpha_of(50.0) - 0.0995).abs() < 1e-3);
        assert_eq!(shininess_of(0.0), 1000.0);
    }
}
