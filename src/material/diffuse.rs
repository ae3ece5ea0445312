//! `type = "diffuse"`: Lambertian reflection of the material's colour. Whitted reads it as
//! Phong with ambient 1, diffuse 1 and no highlight.

use super::{Emission, Material, PhongTerms, Surface};
use crate::bsdf::{Bsdf, Lambert};
use crate::math::Color;

/// The material, its colour from texture `texture`.
pub fn material(texture: usize, emission: Option<Emission>) -> Material {
    Material {
        terms: PhongTerms {
            diffuse: 1.0,
            ..PhongTerms::DEFAULT
        },
        ..Material::base(texture, Surface::Diffuse, emission)
    }
}

/// The BSDF where the colour is `base` (clamped to `[0, 1]`, so it reflects no more light
/// than it receives).
pub fn bsdf(base: Color) -> Bsdf {
    Bsdf::Lambert(Lambert {
        r: base.clamp(Color::ZERO, Color::ONE),
    })
}
