//! `type = "plastic"`: the material's colour as a diffuse base under a clear coat of index
//! `ior`, smooth or rough (GGX). Whitted reads it as Phong: ambient 1, diffuse 1, a white
//! highlight as wide as the roughness, and (smooth only) a mirror of the coat's reflectance
//! at normal incidence.

use super::{Emission, Material, PhongTerms, Scalar, Surface, shininess_of};
use crate::bsdf::coat::CoatSource;
use crate::bsdf::microfacet::Ggx;
use crate::bsdf::plastic::Coat;
use crate::bsdf::{self, Bsdf, internal_diffuse_reflectance};
use crate::math::Color;
use crate::texture::{Texture, TexturePoint};

/// A plastic's own parameters (its index is the material's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plastic {
    /// GGX alpha of the coat.
    pub roughness: Scalar,
    /// The smooth coat's internal diffuse reflectance, worked out once.
    pub fdr_int: f32,
    /// The rough coat's tables; `None` where the coat is smooth everywhere, or passes light
    /// as a smooth one does ([`Plastic::fresnel_coat`]).
    pub coat: Option<CoatSource>,
}

impl Plastic {
    /// A plastic of roughness `roughness` under a coat of index `ior`, as Mitsuba's
    /// `plastic` and `roughplastic`: a rough coat passes light by its tables.
    pub fn new(roughness: Scalar, ior: f32) -> Self {
        let coat = match roughness {
            Scalar::Value(a) if Ggx::isotropic(a.clamp(0.0, 1.0)).is_smooth() => None,
            Scalar::Value(a) => Some(CoatSource::new(ior, Some(a.clamp(0.0, 1.0)))),
            Scalar::Texture(_) => Some(CoatSource::new(ior, None)),
        };
        Plastic {
            roughness,
            fdr_int: internal_diffuse_reflectance(ior),
            coat,
        }
    }

    /// A plastic whose coat lets light in and out as a smooth boundary of index `ior`
    /// does (`1 - F`), whatever its roughness: glTF's dielectric (its BRDF weighs the diffuse
    /// base by `1 - F` and loses no light to the coat's roughness) and OBJ's plastic. A
    /// rough coat of Mitsuba's kind keeps less of the light (a white one at roughness 1
    /// returns about a third of it), which is not how glTF's models are meant to look.
    pub fn fresnel_coat(roughness: Scalar, ior: f32) -> Self {
        Plastic {
            roughness,
            fdr_int: internal_diffuse_reflectance(ior),
            coat: None,
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
        let alpha = self.roughness.at(textures, p).clamp(0.0, 1.0);
        let distribution = Ggx::isotropic(alpha);
        let coat = match self.coat {
            Some(source) if !distribution.is_smooth() => Coat::Rough(source.at(alpha)),
            _ => Coat::Smooth {
                fdr_int: self.fdr_int,
            },
        };
        bsdf::Plastic {
            r: base.clamp(Color::ZERO, Color::ONE),
            eta: m.ior,
            distribution,
            coat,
        }
    }
}
