//! `type = "plastic"`: the material's colour as a diffuse base under a clear coat of index
//! `ior`, smooth or rough (GGX). Whitted reads it as Phong: ambient 1, diffuse 1, a white
//! highlight as wide as the roughness, and (smooth only) a mirror of the coat's reflectance
//! at normal incidence.

use super::{Emission, Material, PhongTerms, Scalar, Surface, shininess_of};
use crate::bsdf::microfacet::Ggx;
use crate::bsdf::{self, Bsdf, internal_diffuse_reflectance};
use crate::math::Color;
use crate::texture::{Texture, TexturePoint};

/// A plastic's own parameters (its index is the material's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plastic {
    /// GGX alpha of the coat.
    pub roughness: Scalar,
    /// The coat's internal diffuse reflectance, worked out once.
    pub fdr_int: f32,
}

impl Plastic {
    /// A plastic of roughness `roughness` under a coat of index `ior`.
    pub fn new(roughness: Scalar, ior: f32) -> Self {
        Plastic {
            roughness,
            fdr_int: internal_diffuse_reflectance(ior),
        }
    }

    /// The material; `alpha` is the roughness where it is constant (for Whitted).
    pub fn material(
        self,
        texture: usize,
        ior: f32,
        alpha: f32,
        emission: Option<Emission>,
    ) -> Material {
        let f0 = ((ior - 1.0) / (ior + 1.0)).powi(2);
        let mirror = if alpha == 0.0 { f0 } else { 0.0 };
        Material {
            terms: PhongTerms {
                diffuse: 1.0 - mirror,
                ambient: 1.0 - mirror,
                specular: Color::ONE,
                shininess: shininess_of(alpha),
                reflectivity: mirror,
                ..PhongTerms::DEFAULT
            },
            ior,
            ..Material::base(texture, Surface::Plastic(self), emission)
        }
    }

    /// The BSDF at a point whose colour is `base`.
    pub fn bsdf(&self, m: &Material, base: Color, textures: &[Texture], p: &TexturePoint) -> Bsdf {
        Bsdf::Plastic(self.plastic(m, base, textures, p))
    }

    /// [`Plastic::bsdf`]'s plastic.
    pub fn plastic(
        &self,
        m: &Material,
        base: Color,
        textures: &[Texture],
        p: &TexturePoint,
    ) -> bsdf::Plastic {
        bsdf::Plastic {
            r: base.clamp(Color::ZERO, Color::ONE),
            eta: m.ior,
            fdr_int: self.fdr_int,
            distribution: Ggx::isotropic(self.roughness.at(textures, p).clamp(0.0, 1.0)),
        }
    }
}
