//! Metals: mirror reflection tinted by the conductor's Fresnel reflectance, smooth (a delta
//! lobe) or rough (a GGX microfacet lobe sampled by its visible normals). Reflection only,
//! on the side light arrives from: the surface is taken two-sided by mirroring `z`.

use super::microfacet::Ggx;
use super::{BsdfSample, Lobe, Scatter, fresnel, front, same_hemisphere, to_side_of};
use crate::math::{Color, Vec2, Vec3A};

/// How much a conductor reflects at each angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ConductorFresnel {
    /// A measured complex index of refraction `eta + i k`, per channel.
    Complex {
        /// Real part.
        eta: Color,
        /// Imaginary part (absorption).
        k: Color,
    },
    /// Everything, at every angle: a perfect mirror, and the white furnace's test surface.
    One,
}

impl ConductorFresnel {
    fn at(&self, cos_i: f32) -> Color {
        match *self {
            ConductorFresnel::Complex { eta, k } => fresnel::conductor_rgb(cos_i, eta, k),
            ConductorFresnel::One => Color::ONE,
        }
    }
}

/// A conductor of the given Fresnel reflectance and microfacet roughness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor {
    /// Reflectance by angle.
    pub fresnel: ConductorFresnel,
    /// The microfacet distribution; smooth when [`Ggx::is_smooth`].
    pub distribution: Ggx,
    /// A colour the reflection is multiplied by, each channel in `[0, 1]` (Mitsuba's
    /// `specular_reflectance`).
    pub tint: Color,
}

impl Scatter for Conductor {
    /// The rough lobe's value (0 for a smooth conductor, whose lobe is a delta).
    fn f(&self, wo: Vec3A, wi: Vec3A) -> Color {
        if self.distribution.is_smooth() || !same_hemisphere(wo, wi) {
            return Color::ZERO;
        }
        let (wo, wi) = (front(wo), front(wi));
        match self.distribution.reflection(wo, wi) {
            Some(r) => self.fresnel.at(wo.dot(r.wm).abs()) * self.tint * r.value,
            None => Color::ZERO,
        }
    }

    /// The mirror direction (smooth), or the reflection of `wo` about a visible microfacet
    /// normal (rough).
    fn sample(&self, wo: Vec3A, u: Vec2, _uc: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let fo = front(wo);
        if self.distribution.is_smooth() {
            let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
            return Some(BsdfSample {
                wi,
                f: self.fresnel.at(fo.z) * self.tint / fo.z,
                pdf: 1.0,
                lobe: Lobe::SpecularReflection,
            });
        }
        let wi = to_side_of(wo, self.distribution.sample_reflection(fo, u)?);
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            f: self.f(wo, wi),
            pdf,
            lobe: Lobe::GlossyReflection,
        })
    }

    /// The density of [`Conductor::sample`]'s rough lobe.
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.distribution.is_smooth() || !same_hemisphere(wo, wi) {
            return 0.0;
        }
        self.distribution
            .reflection(front(wo), front(wi))
            .map_or(0.0, |r| r.pdf)
    }

    fn name(&self) -> &'static str {
        if self.distribution.is_smooth() {
            "smooth conductor"
        } else {
            "rough conductor"
        }
    }

    fn has_non_delta(&self) -> bool {
        !self.distribution.is_smooth()
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Bsdf, harness};
    use super::*;

    fn gold(alpha: f32) -> Bsdf {
        Bsdf::Conductor(Conductor {
            fresnel: ConductorFresnel::Complex {
                eta: Color::new(0.143, 0.374, 1.442),
                k: Color::new(3.983, 2.385, 1.603),
            },
            distribution: Ggx::isotropic(alpha),
            tint: Color::ONE,
        })
    }

    #[test]
    fn rough_sampling_matches_the_pdf() {
        for alpha in [0.2f32, 0.5, 1.0] {
            harness::chi2_all_incidences(&format!("gold, alpha {alpha}"), &gold(alpha));
        }
    }

    #[test]
    fn conserves_energy_and_is_reciprocal() {
        for alpha in [0.2f32, 0.5, 1.0] {
            harness::energy_and_reciprocity(&format!("gold, alpha {alpha}"), &gold(alpha), None);
        }
    }

    /// With F = 1, a rough conductor loses only the light that single scattering cannot
    /// follow: what bounces between microfacets (Smith's G), and what a microfacet tilted
    /// past 45 degrees sends below the horizon when lit straight on. The normals within 45
    /// degrees carry `1 / (1 + alpha^2)` of GGX's projected area, an upper bound. The albedo
    /// by integration over the sphere equals the sampling's estimate, `F G2 / G1` a sample,
    /// and falls as the roughness grows.
    #[test]
    fn a_perfect_rough_mirror_loses_only_what_single_scattering_cannot_follow() {
        let mut last = 1.0;
        for alpha in [0.2f32, 0.5, 1.0] {
            let b = Bsdf::Conductor(Conductor {
                fresnel: ConductorFresnel::One,
                distribution: Ggx::isotropic(alpha),
                tint: Color::ONE,
            });
            let a = harness::albedo(&b, Vec3A::Z).x;
            assert!(
                a < 1.0 / (1.0 + alpha * alpha) && a < last,
                "alpha {alpha}: {a}"
            );
            last = a;
            let mut rng = crate::math::Rng::new(5);
            let n = 1 << 18;
            let mut sum = 0.0f64;
            for _ in 0..n {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                if let Some(s) = b.sample(Vec3A::Z, u, 0.5) {
                    sum += (s.f.x * s.wi.z / s.pdf) as f64;
                }
            }
            let sampled = sum / n as f64;
            assert!(
                (sampled - a as f64).abs() < 5e-3,
                "alpha {alpha}: {a} by the grid, {sampled} by sampling"
            );
        }
        assert!(last > 0.25, "{last}");
    }

    #[test]
    fn a_smooth_conductor_is_a_tinted_mirror() {
        let b = gold(0.0);
        let wo = Vec3A::new(0.6, 0.0, 0.8);
        let s = b.sample(wo, Vec2::new(0.3, 0.7), 0.5).unwrap();
        assert_eq!(s.lobe, Lobe::SpecularReflection);
        assert!((s.wi - Vec3A::new(-0.6, 0.0, 0.8)).length() < 1e-6);
        // f cos / pdf is the Fresnel reflectance at the angle.
        let weight = s.f * s.wi.z / s.pdf;
        let expected = fresnel::conductor_rgb(
            0.8,
            Color::new(0.143, 0.374, 1.442),
            Color::new(3.983, 2.385, 1.603),
        );
        assert!((weight - expected).abs().max_element() < 1e-5);
        assert_eq!(b.f(wo, s.wi), Color::ZERO);
        assert_eq!(b.pdf(wo, s.wi), 0.0);
    }
}
