//! `type = "conductor"`: a metal, from a named metal's measured complex index, or `eta` and
//! `k`, or a perfect mirror; smooth or rough (GGX). The colour tints the reflection.
//! Whitted reads it as a mirror of the metal's reflectance at normal incidence (times the
//! tint), with a highlight as wide as the roughness; from roughness 0.5 up, no mirror and a
//! diffuse term of that colour instead.

use super::{ColorParam, Emission, Material, PhongTerms, Scalar, Surface, shininess_of};
use crate::bsdf::microfacet::Ggx;
use crate::bsdf::{self, Bsdf, ConductorFresnel, fresnel};
use crate::math::Color;
use crate::texture::{Texture, TexturePoint};

/// A conductor's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor {
    /// Reflectance by angle (where `index` is textured, of the textures' means: what
    /// Whitted reads).
    pub fresnel: ConductorFresnel,
    /// The complex index `[eta, k]` where a texture gives either, read point by point.
    pub index: Option<[ColorParam; 2]>,
    /// GGX alpha.
    pub roughness: Scalar,
}

impl Conductor {
    /// Reflectance at normal incidence.
    pub fn normal_reflectance(&self) -> Color {
        match self.fresnel {
            ConductorFresnel::Complex { eta, k } => fresnel::conductor_rgb(1.0, eta, k),
            ConductorFresnel::One => Color::ONE,
        }
    }

    /// The material; `tint` is the colour where it is constant (for Whitted), the texture
    /// `texture`; `alpha` is the roughness where it is constant (for Whitted).
    pub fn material(
        self,
        texture: usize,
        tint: Color,
        alpha: f32,
        emission: Option<Emission>,
    ) -> Material {
        let f0 = self.normal_reflectance() * tint;
        let mirror = (1.0 - alpha / 0.5).clamp(0.0, 1.0);
        Material {
            terms: PhongTerms {
                ambient: 1.0 - mirror,
                diffuse: 1.0 - mirror,
                specular: f0,
                shininess: shininess_of(alpha),
                reflectivity: mirror,
                ..PhongTerms::DEFAULT
            },
            mirror_tint: f0,
            ..Material::base(texture, Surface::Conductor(self), emission)
        }
    }

    /// The BSDF at a point whose tint is `tint`.
    pub fn bsdf(&self, tint: Color, textures: &[Texture], p: &TexturePoint) -> Bsdf {
        let fresnel = match self.index {
            Some([eta, k]) => ConductorFresnel::Complex {
                eta: eta.at(textures, p),
                k: k.at(textures, p),
            },
            None => self.fresnel,
        };
        Bsdf::Conductor(bsdf::Conductor {
            fresnel,
            distribution: Ggx::isotropic(self.roughness.at(textures, p).clamp(0.0, 1.0)),
            tint: tint.clamp(Color::ZERO, Color::ONE),
        })
    }
}
