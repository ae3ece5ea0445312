//! `type = "phong"` (the default): the seed report's terms, which the Whitted integrator
//! reads as they are. The path tracer reads them as a mix that conserves energy
//! ([`PhongMix`]): glass of index `ior` with weight `transparency`, a perfect mirror with
//! weight `(1 - transparency) * reflectivity`, and for the rest the colour times `diffuse`
//! (clamped to 1) as Lambertian reflection, under a clear coat of index 1.5 (`bsdf::COAT_IOR`) whose roughness
//! matches `shininess` where `specular` is not black. The coat passes light to the base as
//! a smooth boundary would (`Coat::Smooth`), not by a rough coat's tables as `plastic` does:
//! Phong's terms name no physical coat to match, and the tables would cost every scene of
//! Phong materials their making. `ambient` is Whitted's only: the path
//! tracer computes the light that ambient stands in for.

use super::{Material, PhongTerms, alpha_of};
use crate::bsdf::{Bsdf, PhongMix};
use crate::math::Color;

/// The BSDF at a point whose colour is `base` and Phong terms `terms`, its glass of index
/// `ior` (the material's, or a dispersive one's at the path's wavelength).
pub fn bsdf(m: &Material, terms: &PhongTerms, base: Color, ior: f32) -> Bsdf {
    let r = (base * terms.diffuse).clamp(Color::ZERO, Color::ONE);
    let highlight = (terms.specular.max_element() > 0.0).then(|| alpha_of(terms.shininess));
    Bsdf::Phong(PhongMix::new(
        r,
        highlight,
        m.mirror_tint.clamp(Color::ZERO, Color::ONE),
        ior,
        terms.reflectivity,
        terms.transparency,
    ))
}
