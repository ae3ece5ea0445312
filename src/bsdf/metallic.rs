//! glTF's metallic-roughness surface where it is partly metal: the metal and the dielectric
//! it blends, `f = m f_metal + (1 - m) f_dielectric` for the metallic value `m` at the point
//! (glTF 2.0, appendix B: `mix(dielectric_brdf, metal_brdf, metallic)`). Both parts are
//! made of the point's base colour and roughness: the metal tinted by the colour, the
//! dielectric the colour under a clear coat (snell's plastic).

use super::{BsdfSample, Conductor, Plastic, Scatter};
use crate::math::{Color, Vec2, Vec3A};

/// A blend of a metal and a coated diffuse surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetallicMix {
    /// The metal.
    pub metal: Conductor,
    /// The dielectric: the base colour under a coat.
    pub dielectric: Plastic,
    /// The metal's share, strictly between 0 and 1 (a surface all of one part is that
    /// part's own BSDF).
    pub metallic: f32,
}

impl Scatter for MetallicMix {
    /// The blend of the parts' values (a smooth metal, a delta, adds nothing).
    fn f(&self, wo: Vec3A, wi: Vec3A) -> Color {
        self.metal.f(wo, wi) * self.metallic + self.dielectric.f(wo, wi) * (1.0 - self.metallic)
    }

    /// The dielectric's base, in its share.
    fn f_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Color {
        self.dielectric.f_diffuse(wo, wi) * (1.0 - self.metallic)
    }

    /// The metal with chance `metallic`, else the dielectric, chosen by `uc` (whose
    /// remainder then chooses within the dielectric); then that part sampled. A delta
    /// (the smooth metal's mirror, the smooth coat's) carries its part's weight; any other
    /// direction the blend's value and density, which both parts may reach.
    fn sample(&self, wo: Vec3A, u: Vec2, uc: f32) -> Option<BsdfSample> {
        let m = self.metallic;
        let (s, weight) = if uc < m {
            (self.metal.sample(wo, u, uc)?, m)
        } else {
            let uc = ((uc - m) / (1.0 - m)).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
            (self.dielectric.sample(wo, u, uc)?, 1.0 - m)
        };
        super::as_mix_sample(s, weight, |wi| self.f(wo, wi), |wi| self.pdf(wo, wi))
    }

    /// The density of [`MetallicMix::sample`]: each part's, weighted by its chance.
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        self.metal.pdf(wo, wi) * self.metallic + self.dielectric.pdf(wo, wi) * (1.0 - self.metallic)
    }

    /// Whether some of its scattering is not a delta: always, as the dielectric's diffuse
    /// base is not.
    fn has_non_delta(&self) -> bool {
        true
    }

    fn name(&self) -> &'static str {
        "metallic mix"
    }
}

#[cfg(test)]
mod tests {
    use super::super::microfacet::Ggx;
    use super::super::{Bsdf, ConductorFresnel, harness};
    use super::*;

    fn mix(metallic: f32, alpha: f32) -> Bsdf {
        let base = Color::new(0.9, 0.4, 0.1);
        Bsdf::Metallic(MetallicMix {
            metal: Conductor {
                fresnel: ConductorFresnel::One,
                distribution: Ggx::isotropic(alpha),
                tint: base,
            },
            dielectric: Plastic::new(base, 1.5, Ggx::isotropic(alpha)),
            metallic,
        })
    }

    #[test]
    fn sampling_matches_the_pdf() {
        harness::chi2_all_incidences("metallic 0.3, rough", &mix(0.3, 0.3));
        harness::chi2_all_incidences("metallic 0.8, rough", &mix(0.8, 0.15));
        harness::chi2_all_incidences("metallic 0.5, smooth", &mix(0.5, 0.0));
    }

    #[test]
    fn conserves_energy_and_is_reciprocal() {
        for (m, a) in [(0.3, 0.3), (0.7, 0.5), (0.5, 0.0)] {
            harness::energy_and_reciprocity("metallic", &mix(m, a), None);
        }
    }

    /// The blend is the parts weighted: at a direction both reach, `f` and the density are
    /// `m` of the metal's and `1 - m` of the dielectric's.
    #[test]
    fn the_blend_weighs_its_parts() {
        let Bsdf::Metallic(b) = mix(0.25, 0.4) else {
            unreachable!()
        };
        let wo = Vec3A::new(0.3, 0.1, 0.9).normalize();
        let wi = Vec3A::new(-0.2, 0.3, 0.8).normalize();
        let f = b.f(wo, wi);
        let want = b.metal.f(wo, wi) * 0.25 + b.dielectric.f(wo, wi) * 0.75;
        assert!((f - want).abs().max_element() < 1e-6, "{f} {want}");
        let pdf = b.pdf(wo, wi);
        let want = b.metal.pdf(wo, wi) * 0.25 + b.dielectric.pdf(wo, wi) * 0.75;
        assert!((pdf - want).abs() < 1e-6 * want, "{pdf} {want}");
    }

    /// A smooth metal's mirror is taken with the metal's chance and carries its weight: a
    /// quarter of the samples, each returning the tint.
    #[test]
    fn a_smooth_metals_mirror_carries_its_weight() {
        let b = mix(0.25, 0.0);
        let wo = Vec3A::new(0.3, 0.0, 0.954).normalize();
        let (mut mirror, mut n) = (Color::ZERO, 0);
        for k in 0..4000 {
            let uc = (k as f32 + 0.5) / 4000.0;
            if let Some(s) = b.sample(wo, Vec2::new(0.3, 0.7), uc)
                && s.lobe == super::super::Lobe::SpecularReflection
                && uc < 0.25
            {
                mirror += s.f * s.wi.z.abs() / s.pdf;
                n += 1;
            }
        }
        assert_eq!(n, 1000);
        let each = mirror / n as f32;
        assert!(
            (each - Color::new(0.9, 0.4, 0.1)).abs().max_element() < 1e-5,
            "{each}"
        );
    }
}
