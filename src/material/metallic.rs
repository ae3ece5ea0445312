//! glTF's metallic-roughness material where its metallic value lies between 0 and 1 (a
//! factor such as 0.3, or a map): at each point, the metal and the coated dielectric of the
//! point's base colour and roughness, blended by the metallic value there (see
//! [`crate::bsdf::MetallicMix`]). glTF's metal reflects its base colour at every angle
//! (snell's conductor of `F = 1` tinted by the colour). Whitted reads the Phong terms of the
//! part the value's mean leans to.

use super::conductor::Conductor;
use super::plastic::Plastic;
use super::{Emission, Material, Scalar, Surface};
use crate::bsdf::{self, Bsdf, ConductorFresnel, MetallicMix};
use crate::math::Color;
use crate::texture::{Texture, TexturePoint};

/// A blend of a metal and a coated diffuse surface of one roughness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metallic {
    /// The dielectric (the base colour under a coat of the material's index), whose
    /// roughness the metal shares.
    pub dielectric: Plastic,
    /// The metal's share, 0 to 1 (kept to that range where read).
    pub metallic: Scalar,
}

impl Metallic {
    /// The material, of base colour texture `texture` and coat index `ior`. Whitted reads
    /// the metal's Phong terms where `mean` (the metallic value on the whole) is 0.5 or
    /// more, else the plastic's; `tint` is the colour and `alpha` the roughness where they
    /// are constant.
    pub fn material(
        self,
        texture: usize,
        tint: Color,
        ior: f32,
        alpha: f32,
        mean: f32,
        emission: Option<Emission>,
    ) -> Material {
        let mut out = if mean >= 0.5 {
            Conductor {
                fresnel: ConductorFresnel::One,
                index: None,
                roughness: self.dielectric.roughness,
            }
            .material(texture, tint, alpha, emission)
        } else {
            self.dielectric.material(texture, ior, alpha, emission)
        };
        out.surface = Surface::Metallic(self);
        out.ior = ior;
        out
    }

    /// The BSDF at a point whose base colour is `base`: the metal or the dielectric alone
    /// where the value is 1 or 0, the blend between.
    pub fn bsdf(&self, m: &Material, base: Color, textures: &[Texture], p: &TexturePoint) -> Bsdf {
        let metallic = self.metallic.at(textures, p);
        let metallic = if metallic.is_finite() {
            metallic.clamp(0.0, 1.0)
        } else {
            0.0
        };
        let dielectric = self.dielectric.plastic(m, base, textures, p);
        let metal = bsdf::Conductor {
            fresnel: ConductorFresnel::One,
            distribution: dielectric.distribution,
            tint: dielectric.r,
        };
        if metallic >= 1.0 {
            Bsdf::Conductor(metal)
        } else if metallic <= 0.0 {
            Bsdf::Plastic(dielectric)
        } else {
            Bsdf::Metallic(MetallicMix {
                metal,
                dielectric,
                metallic,
            })
        }
    }
}
