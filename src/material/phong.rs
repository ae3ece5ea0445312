//! `type = "phong"` (the default): the seed report's terms, which the Whitted integrator
//! reads as they are. The path tracer reads them as a mix that conserves energy
//! ([`PhongMix`]): glass of index `ior` with weight `transparency`, a perfect mirror with
//! weight `(1 - transparency) * reflectivity`, and for the rest the colour times `diffuse`
//! (clamped to 1) as Lambertian reflection, under a clear coat of index 1.5 whose roughness
//! matches `shininess` where `specular` is not black. The coat passes light to the base as
//! a smooth boundary would (`Coat::Smooth`), not by a rough coat's tables as `plastic` does:
//! Phong's terms name no physical coat to match, and the tables would cost every scene of
//! Phong materials their making. `ambient` is Whitted's only: the path
//! tracer computes the light that ambient stands in for.

use super::{Material, PhongTerms, alpha_of};
use crate::bsdf::microfacet::Ggx;
use crate::bsdf::{
    Bsdf, Coat, Conductor, ConductorFresnel, Dielectric, Lambert, PhongBase, PhongMix, Plastic,
    internal_diffuse_reflectance,
};
use crate::math::Color;

/// The coat's index of refraction (a typical varnish or plastic).
pub const COAT_IOR: f32 = 1.5;

/// The BSDF at a point whose colour is `base` and Phong terms `terms`.
pub fn bsdf(m: &Material, terms: &PhongTerms, base: Color) -> Bsdf {
    let r = (base * terms.diffuse).clamp(Color::ZERO, Color::ONE);
    let base = if terms.specular.max_element() > 0.0 {
        PhongBase::Plastic(Plastic {
            r,
            eta: COAT_IOR,
            distribution: Ggx::isotropic(alpha_of(terms.shininess)),
            coat: Coat::Smooth {
                fdr_int: coat_fdr(),
            },
        })
    } else {
        PhongBase::Lambert(Lambert { r })
    };
    Bsdf::Phong(PhongMix {
        base,
        mirror: Conductor {
            fresnel: ConductorFresnel::One,
            distribution: Ggx::isotropic(0.0),
            tint: m.mirror_tint.clamp(Color::ZERO, Color::ONE),
        },
        glass: Dielectric {
            eta: m.ior,
            distribution: Ggx::isotropic(0.0),
        },
        weights: PhongMix::weights(terms.reflectivity, terms.transparency),
    })
}

/// [`internal_diffuse_reflectance`] of [`COAT_IOR`], worked out once.
fn coat_fdr() -> f32 {
    static FDR: std::sync::OnceLock<f32> = std::sync::OnceLock::new();
    *FDR.get_or_init(|| internal_diffuse_reflectance(COAT_IOR))
}
