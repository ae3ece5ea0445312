//! glTF's metallic-roughness material where its metallic value lies between 0 and 1 (a
//! factor such as 0.3, or a map): at each point, the metal and the coated dielectric of the
//! point's base colour and roughness, blended by the metallic value there (see
//! [`crate::bsdf::MetallicMix`]). Whitted reads the Phong terms of the part the value's mean
//! leans to.

use super::conductor::Conductor;
use super::plastic::Plastic;
use super::{Material, Scalar};
use crate::bsdf::{Bsdf, MetallicMix};
use crate::math::Color;
use crate::texture::{Texture, TexturePoint};

/// A blend of a metal and a coated diffuse surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metallic {
    /// The metal (tinted by the base colour).
    pub metal: Conductor,
    /// The dielectric (the base colour under a coat of the material's index).
    pub dielectric: Plastic,
    /// The metal's share, 0 to 1 (kept to that range where read).
    pub metallic: Scalar,
}

impl Metallic {
    /// The BSDF at a point whose base colour is `base`: the metal or the dielectric alone
    /// where the value is 1 or 0, the blend between.
    pub fn bsdf(&self, m: &Material, base: Color, textures: &[Texture], p: &TexturePoint) -> Bsdf {
        let metallic = self.metallic.at(textures, p);
        let metallic = if metallic.is_finite() {
            metallic.clamp(0.0, 1.0)
        } else {
            0.0
        };
        if metallic >= 1.0 {
            return self.metal.bsdf(base, textures, p);
        }
        let dielectric = self.dielectric.plastic(m, base, textures, p);
        if metallic <= 0.0 {
            return Bsdf::Plastic(dielectric);
        }
        Bsdf::Metallic(MetallicMix {
            metal: self.metal.conductor(base, textures, p),
            dielectric,
            metallic,
        })
    }
}
