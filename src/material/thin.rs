//! `type = "thin"`: a thin pane of glass, which reflects (both of its faces, and the light
//! bounced between them) and lets the rest through unbent. Whitted reads it as clear glass
//! of index 1 (no bending and, as Whitted's Fresnel has it then, no reflection) with a white
//! highlight.

use super::{Emission, Material, PhongTerms, Surface};
use crate::bsdf::{Bsdf, ThinDielectric};
use crate::math::Color;

/// The material, a pane of index `ior`.
pub fn material(texture: usize, ior: f32, emission: Option<Emission>) -> Material {
    Material {
        terms: PhongTerms {
            ambient: 0.0,
            diffuse: 0.0,
            specular: Color::ONE,
            shininess: 1000.0,
            transparency: 1.0,
            ..PhongTerms::DEFAULT
        },
        // Whitted bends rays by `ior`; a pane does not bend them. The path tracer reads the
        // pane's index from its `Surface`.
        ior: 1.0,
        ..Material::base(texture, Surface::Thin(ior), emission)
    }
}

/// The BSDF of a pane of index `ior`.
pub fn bsdf(ior: f32) -> Bsdf {
    Bsdf::ThinDielectric(ThinDielectric { eta: ior })
}
