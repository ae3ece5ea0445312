//! Plastic: a diffuse base under a dielectric coat, smooth (a delta reflection on top) or
//! rough (GGX reflection on top), as Mitsuba 3's `plastic` and `roughplastic` in their
//! default, linear form. Light the coat lets in scatters diffusely in the base and leaves
//! through the coat, refraction spreading it by `1 / eta^2`; the light the coat's inside
//! bounces back is accounted for by `1 / (1 - R_int)`. A smooth coat lets in `1 - F(cos)`
//! and bounces back the smooth boundary's share of diffuse light; a rough one lets in its
//! tabulated transmittance and bounces back its own share ([`super::coat`]), so that the
//! whole conserves energy at every roughness. src/bsdf/mitsuba_tests.rs checks both against
//! Mitsuba's own values.

use super::coat::RoughCoat;
use super::dielectric::fresnel;
use super::microfacet::Ggx;
use super::{BsdfSample, Lobe, Scatter, front, same_hemisphere, to_side_of};
use crate::math::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::math::{Color, Vec2, Vec3A};

/// The fraction of diffuse light from inside a boundary of index `eta` (inside over
/// outside) that the boundary reflects back in: `2 ∫ F(mu) mu dmu` over the inside
/// hemisphere, total internal reflection included. By quadrature; once per material.
pub fn internal_diffuse_reflectance(eta: f32) -> f32 {
    let n = 1024;
    let mut sum = 0.0f64;
    for i in 0..n {
        let mu = (i as f64 + 0.5) / n as f64;
        sum += fresnel(-(mu as f32), eta) as f64 * mu;
    }
    (2.0 * sum / n as f64) as f32
}

/// How the coat passes light to and from the base.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Coat {
    /// As a smooth boundary: it lets in `1 - F(cos)`, and reflects `fdr_int` of the
    /// diffuse light under it ([`internal_diffuse_reflectance`]). A smooth coat's, and the
    /// cheaper reading of a rough coat that a Phong material's path-traced base takes
    /// (`material::phong`).
    Smooth {
        /// The boundary's internal diffuse reflectance.
        fdr_int: f32,
    },
    /// A rough boundary, by its tables.
    Rough(RoughCoat),
}

/// A coated diffuse surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plastic {
    /// The base's diffuse reflectance.
    pub r: Color,
    /// The coat's index over the outside's.
    pub eta: f32,
    /// The coat's roughness; smooth when [`Ggx::is_smooth`].
    pub distribution: Ggx,
    /// What the coat lets through (for `plastic` materials, [`Coat::Rough`] exactly when
    /// the distribution is rough).
    pub coat: Coat,
}

impl Plastic {
    /// A base of reflectance `r` under a coat of index `eta` and roughness `distribution`,
    /// its tables looked up for this one roughness (materials keep theirs: see
    /// `material::plastic`).
    pub fn new(r: Color, eta: f32, distribution: Ggx) -> Self {
        let coat = if distribution.is_smooth() {
            Coat::Smooth {
                fdr_int: internal_diffuse_reflectance(eta),
            }
        } else {
            let alpha = distribution.ax;
            Coat::Rough(super::coat::CoatSource::new(eta, Some(alpha)).at(alpha))
        };
        Plastic {
            r,
            eta,
            distribution,
            coat,
        }
    }

    /// The fraction of light arriving at `|cos| = cos` that the coat lets in.
    #[inline]
    fn transmittance(&self, cos: f32) -> f32 {
        match &self.coat {
            Coat::Smooth { .. } => 1.0 - fresnel(cos.abs(), self.eta),
            Coat::Rough(c) => c.transmittance(cos),
        }
    }

    fn internal_reflectance(&self) -> f32 {
        match &self.coat {
            Coat::Smooth { fdr_int } => *fdr_int,
            Coat::Rough(c) => c.internal_reflectance(),
        }
    }

    /// The probability of sampling the coat's reflection at `cos_o` (the rest goes to the
    /// base): what the coat reflects and what it lets in, weighted by `1` and the base's
    /// mean reflectance.
    fn coat_probability(&self, cos_o: f32) -> f32 {
        let t = self.transmittance(cos_o);
        let w_coat = 1.0 / (1.0 + self.r.element_sum() / 3.0);
        let p = (1.0 - t) * w_coat;
        p / (p + t * (1.0 - w_coat))
    }

    fn diffuse(&self, wo: Vec3A, wi: Vec3A) -> Color {
        let (to, ti) = (self.transmittance(wo.z), self.transmittance(wi.z));
        self.r
            * (to * ti
                / (std::f32::consts::PI
                    * self.eta
                    * self.eta
                    * (1.0 - self.internal_reflectance())))
    }

    /// The rough coat's value and density.
    fn coat(&self, wo: Vec3A, wi: Vec3A) -> (Color, f32) {
        let (wo, wi) = (front(wo), front(wi));
        match self.distribution.reflection(wo, wi) {
            Some(r) => (
                Color::splat(fresnel(wo.dot(r.wm), self.eta) * r.value),
                r.pdf,
            ),
            None => (Color::ZERO, 0.0),
        }
    }
}

impl Scatter for Plastic {
    /// The base's lobe, and the rough coat's (a smooth coat's reflection is a delta).
    fn f(&self, wo: Vec3A, wi: Vec3A) -> Color {
        if !same_hemisphere(wo, wi) {
            return Color::ZERO;
        }
        let d = self.diffuse(wo, wi);
        if self.distribution.is_smooth() {
            d
        } else {
            d + self.coat(wo, wi).0
        }
    }

    /// The base's lobe.
    fn f_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Color {
        if same_hemisphere(wo, wi) {
            self.diffuse(wo, wi)
        } else {
            Color::ZERO
        }
    }

    /// The coat's reflection or the base's, chosen by `uc`.
    fn sample(&self, wo: Vec3A, u: Vec2, uc: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let p_coat = self.coat_probability(wo.z);
        if uc < p_coat {
            if self.distribution.is_smooth() {
                let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
                return Some(BsdfSample {
                    wi,
                    f: Color::splat(fresnel(wo.z.abs(), self.eta) / wi.z.abs()),
                    pdf: p_coat,
                    lobe: Lobe::SpecularReflection,
                });
            }
            let wi = to_side_of(wo, self.distribution.sample_reflection(front(wo), u)?);
            let pdf = self.pdf(wo, wi);
            return (pdf > 0.0).then(|| BsdfSample {
                wi,
                f: self.f(wo, wi),
                pdf,
                lobe: Lobe::GlossyReflection,
            });
        }
        let wi = to_side_of(wo, cosine_hemisphere(u));
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            f: self.f(wo, wi),
            pdf,
            lobe: Lobe::DiffuseReflection,
        })
    }

    /// The mixture of the base's cosine density and the rough coat's.
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if !same_hemisphere(wo, wi) {
            return 0.0;
        }
        let p_coat = self.coat_probability(wo.z);
        let base = (1.0 - p_coat) * cosine_hemisphere_pdf(wi.z.abs());
        if self.distribution.is_smooth() {
            base
        } else {
            base + p_coat * self.coat(wo, wi).1
        }
    }

    fn name(&self) -> &'static str {
        "plastic"
    }

    fn has_non_delta(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Bsdf, harness};
    use super::*;

    fn plastic(r: f32, alpha: f32) -> Plastic {
        Plastic::new(Color::splat(r), 1.5, Ggx::isotropic(alpha))
    }

    /// From inside glass of 1.5 the boundary returns 59.6 % of diffuse light (the known
    /// value: 1 - (1 - F_dr,ext) / eta^2 with F_dr,ext = 0.0918).
    #[test]
    fn the_coat_returns_the_known_share_of_diffuse_light() {
        let fdr = internal_diffuse_reflectance(1.5);
        assert!((fdr - (1.0 - (1.0 - 0.0918) / 2.25)).abs() < 1e-3, "{fdr}");
    }

    #[test]
    fn sampling_matches_the_pdf() {
        for alpha in [0.0f32, 0.3] {
            harness::chi2_all_incidences(
                &format!("plastic, alpha {alpha}"),
                &Bsdf::Plastic(plastic(0.5, alpha)),
            );
        }
    }

    /// Under a smooth coat the whole reflects `F(cos_o) + (1 - F(cos_o)) R`: the coat's
    /// delta lobe carries `F(cos_o)` and the integral of the base's lobe the rest.
    #[test]
    fn a_smooth_coat_reflects_its_fresnel_share_and_the_base_the_rest() {
        for r in [0.0f32, 0.5, 1.0] {
            let b = Bsdf::Plastic(plastic(r, 0.0));
            for wo in harness::incidences() {
                let f = fresnel(wo.z.abs(), 1.5);
                let base = harness::albedo(&b, wo).x;
                assert!(
                    (base - (1.0 - f) * r).abs() < 2e-3,
                    "R {r}, wo {wo}: base {base}"
                );
            }
        }
    }

    /// A white plastic, rough or smooth, never reflects more than it receives (a furnace
    /// for one bounce), and is reciprocal.
    #[test]
    fn a_rough_coat_conserves_energy_and_is_reciprocal() {
        for alpha in [0.05f32, 0.1, 0.5, 1.0] {
            harness::energy_and_reciprocity(
                &format!("plastic, alpha {alpha}"),
                &Bsdf::Plastic(plastic(1.0, alpha)),
                None,
            );
        }
    }
}
