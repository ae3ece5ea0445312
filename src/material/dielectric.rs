//! `type = "dielectric"`: glass, water, diamond; smooth or rough (GGX), with Beer-Lambert
//! absorption inside. Whitted reads it as Phong glass: transparency 1, the same `ior` and
//! absorption, a white highlight as wide as the roughness (a rough surface refracts as a
//! smooth one there: Whitted traces one ray).

use super::{Emission, Material, PhongTerms, Scalar, Surface, shininess_of};
use crate::bsdf::microfacet::Ggx;
use crate::bsdf::{self, Bsdf};
use crate::math::Color;
use crate::texture::{Texture, TexturePoint};

/// A dielectric's own parameter (its index and absorption are the material's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    /// GGX alpha.
    pub roughness: Scalar,
}

impl Dielectric {
    /// The material: index `ior` inside, `absorption` per unit length inside; `alpha` is the
    /// roughness where it is constant (for Whitted).
    pub fn material(
        self,
        texture: usize,
        ior: f32,
        absorption: Color,
        alpha: f32,
        emission: Option<Emission>,
    ) -> Material {
        Material {
            terms: PhongTerms {
                ambient: 0.0,
                diffuse: 0.0,
                specular: Color::ONE,
                shininess: shininess_of(alpha),
                transparency: 1.0,
                ..PhongTerms::DEFAULT
            },
            ior,
            absorption,
            ..Material::base(texture, Surface::Dielectric(self), emission)
        }
    }

    /// The BSDF at a point, of index `ior` inside (the material's, or a dispersive one's at
    /// the path's wavelength).
    pub fn bsdf(&self, textures: &[Texture], p: &TexturePoint, ior: f32) -> Bsdf {
        Bsdf::Dielectric(bsdf::Dielectric {
            eta: ior,
            distribution: Ggx::isotropic(self.roughness.at(textures, p).clamp(0.0, 1.0)),
        })
    }
}
