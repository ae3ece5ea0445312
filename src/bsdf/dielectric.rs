//! Glass and other dielectrics: Fresnel-weighted reflection and refraction, smooth (two
//! delta lobes) or rough (GGX microfacets, Walter et al. 2007, sampled by visible normals).
//! `eta` is the index inside over the index outside (the side `+z` faces is outside).
//! Values are for radiance carried from the light to the camera: refraction into a denser
//! medium concentrates radiance by `eta^2`.

use super::microfacet::Ggx;
use super::{BsdfSample, Lobe, Scatter};
use crate::math::{Color, Vec2, Vec3A, fresnel_dielectric};

/// A dielectric boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    /// Index of refraction inside over outside; 1 lets light through unbent.
    pub eta: f32,
    /// The microfacet distribution; smooth when [`Ggx::is_smooth`].
    pub distribution: Ggx,
}

/// Fresnel reflectance for `cos_i` measured on the side of `+z` (negative: arriving from
/// inside), with `eta` inside over outside.
pub(crate) fn fresnel(cos_i: f32, eta: f32) -> f32 {
    if cos_i >= 0.0 {
        fresnel_dielectric(cos_i, 1.0 / eta)
    } else {
        fresnel_dielectric(-cos_i, eta)
    }
}

/// `wo` refracted through a boundary of normal `n` (on either side), with `eta` inside
/// over outside: the direction and the ratio of indices across it (`eta` when entering,
/// `1 / eta` when leaving); `None` at total internal reflection.
pub(crate) fn refract(wo: Vec3A, n: Vec3A, eta: f32) -> Option<(Vec3A, f32)> {
    let (mut cos_i, mut eta, mut n) = (n.dot(wo), eta, n);
    if cos_i < 0.0 {
        (eta, cos_i, n) = (1.0 / eta, -cos_i, -n);
    }
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-wo / eta + (cos_i / eta - cos_t) * n, eta))
}

impl Dielectric {
    fn smooth(&self) -> bool {
        self.distribution.is_smooth() || self.eta == 1.0
    }

    /// The microfacet normal that takes `wo` to `wi`, faced to `+z`, and the ratio of
    /// indices across the boundary (1 for a reflection); `None` for a pair no microfacet
    /// joins.
    fn half_vector(&self, wo: Vec3A, wi: Vec3A) -> Option<(Vec3A, f32)> {
        let (co, ci) = (wo.z, wi.z);
        if co == 0.0 || ci == 0.0 {
            return None;
        }
        let etap = if co * ci > 0.0 {
            1.0
        } else if co > 0.0 {
            self.eta
        } else {
            1.0 / self.eta
        };
        let wm = (wi * etap + wo).normalize_or_zero();
        if wm == Vec3A::ZERO {
            return None;
        }
        let wm = if wm.z < 0.0 { -wm } else { wm };
        // Microfacets seen from behind scatter nothing.
        if wm.dot(wi) * ci < 0.0 || wm.dot(wo) * co < 0.0 {
            return None;
        }
        Some((wm, etap))
    }

    /// The density of the normals visible from `wo`, on whichever side it is.
    fn visible_pdf(&self, wo: Vec3A, wm: Vec3A) -> f32 {
        let w = if wo.z < 0.0 { -wo } else { wo };
        self.distribution.visible_pdf(w, wm)
    }
}

impl Scatter for Dielectric {
    /// The rough lobes' value (0 for a smooth boundary).
    fn f(&self, wo: Vec3A, wi: Vec3A) -> Color {
        if self.smooth() {
            return Color::ZERO;
        }
        let Some((wm, etap)) = self.half_vector(wo, wi) else {
            return Color::ZERO;
        };
        let g = &self.distribution;
        let f = fresnel(wo.dot(wm), self.eta);
        let v = if etap == 1.0 {
            g.d(wm) * g.g(wo, wi) * f / (4.0 * wi.z * wo.z).abs()
        } else {
            let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2) * wi.z * wo.z;
            g.d(wm) * (1.0 - f) * g.g(wo, wi) * (wi.dot(wm) * wo.dot(wm) / denom).abs()
                / (etap * etap)
        };
        Color::splat(v)
    }

    /// Reflection or refraction, chosen in proportion to the Fresnel reflectance by `uc`.
    fn sample(&self, wo: Vec3A, u: Vec2, uc: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        if self.smooth() {
            let r = fresnel(wo.z, self.eta);
            if uc < r {
                let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
                return Some(BsdfSample {
                    wi,
                    f: Color::splat(r / wi.z.abs()),
                    pdf: r,
                    lobe: Lobe::SpecularReflection,
                });
            }
            let (wi, etap) = refract(wo, Vec3A::Z, self.eta)?;
            let t = 1.0 - r;
            return Some(BsdfSample {
                wi,
                f: Color::splat(t / wi.z.abs() / (etap * etap)),
                pdf: t,
                lobe: Lobe::SpecularTransmission,
            });
        }
        let w = if wo.z < 0.0 { -wo } else { wo };
        let wm = self.distribution.sample_visible(w, u);
        let r = fresnel(wo.dot(wm), self.eta);
        let (wi, lobe) = if uc < r {
            let wi = 2.0 * wo.dot(wm) * wm - wo;
            if wi.z * wo.z <= 0.0 {
                return None;
            }
            (wi, Lobe::GlossyReflection)
        } else {
            let (wi, _) = refract(wo, wm, self.eta)?;
            if wi.z * wo.z >= 0.0 {
                return None;
            }
            (wi, Lobe::GlossyTransmission)
        };
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            f: self.f(wo, wi),
            pdf,
            lobe,
        })
    }

    /// The density of [`Dielectric::sample`]'s rough lobes.
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.smooth() {
            return 0.0;
        }
        let Some((wm, etap)) = self.half_vector(wo, wi) else {
            return 0.0;
        };
        let r = fresnel(wo.dot(wm), self.eta);
        if etap == 1.0 {
            self.visible_pdf(wo, wm) / (4.0 * wo.dot(wm).abs()) * r
        } else {
            let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2);
            self.visible_pdf(wo, wm) * wi.dot(wm).abs() / denom * (1.0 - r)
        }
    }

    /// `(eta_i / eta_o)^2`: how much `f` of a refraction from `wi`'s side to `wo`'s is
    /// divided by for radiance (1 for a reflection). Weighted by it, the light scattered
    /// from `wo` adds up to at most 1.
    fn radiance_scale(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z > 0.0 {
            1.0
        } else if wo.z > 0.0 {
            self.eta * self.eta
        } else {
            1.0 / (self.eta * self.eta)
        }
    }

    fn name(&self) -> &'static str {
        if self.distribution.is_smooth() {
            "smooth dielectric"
        } else {
            "rough dielectric"
        }
    }

    fn has_non_delta(&self) -> bool {
        !self.distribution.is_smooth() && self.eta != 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Bsdf, harness};
    use super::*;
    use crate::math::Rng;

    fn glass(alpha: f32) -> Dielectric {
        Dielectric {
            eta: 1.5,
            distribution: Ggx::isotropic(alpha),
        }
    }

    #[test]
    fn rough_sampling_matches_the_pdf() {
        for alpha in [0.2f32, 0.6] {
            harness::chi2_all_incidences(
                &format!("glass, alpha {alpha}"),
                &Bsdf::Dielectric(glass(alpha)),
            );
        }
    }

    /// A rough dielectric scatters at most what it receives (refraction's concentration of
    /// radiance undone) and obeys the reciprocity of refraction (Veach):
    /// `f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2`, `eta_o` the index on `wo`'s side.
    #[test]
    fn conserves_energy_and_is_reciprocal_in_symmetric_form() {
        for alpha in [0.2f32, 0.6] {
            let d = glass(alpha);
            let b = Bsdf::Dielectric(d);
            for wo in harness::incidences() {
                let a = harness::albedo_weighted(&b, wo, |wi| d.radiance_scale(wo, wi));
                assert!(
                    a.x <= 1.0 + 3e-3 && a.x > 0.5,
                    "alpha {alpha}, wo {wo}: {a}"
                );
            }
            let mut rng = Rng::new(3);
            for _ in 0..2000 {
                let a = crate::math::sampling::uniform_sphere(Vec2::new(
                    rng.next_f32(),
                    rng.next_f32(),
                ));
                let c = crate::math::sampling::uniform_sphere(Vec2::new(
                    rng.next_f32(),
                    rng.next_f32(),
                ));
                let index2 = |w: Vec3A| if w.z > 0.0 { 1.0 } else { 1.5f32 * 1.5 };
                let ac = d.f(a, c).x / index2(a);
                let ca = d.f(c, a).x / index2(c);
                assert!(
                    (ac - ca).abs() <= 1e-3 * ac.max(ca).max(1.0),
                    "{a} {c}: {ac} against {ca}"
                );
            }
        }
    }

    /// A smooth boundary reflects with the Fresnel probability and otherwise refracts by
    /// Snell's law; the weights `f cos / pdf` are 1 for reflection and `1 / eta'^2` for
    /// refraction, from either side; past the critical angle everything reflects.
    #[test]
    fn smooth_glass_splits_by_fresnel_and_bends_by_snell() {
        let b = Bsdf::Dielectric(glass(0.0));
        for wo in harness::incidences() {
            let r = fresnel(wo.z, 1.5);
            let mut reflected = 0;
            let n = 20_000;
            let mut rng = Rng::new(9);
            for _ in 0..n {
                let s = b.sample(wo, Vec2::new(0.5, 0.5), rng.next_f32()).unwrap();
                let weight = s.f.x * s.wi.z.abs() / s.pdf;
                if s.lobe == Lobe::SpecularReflection {
                    reflected += 1;
                    assert!((weight - 1.0).abs() < 1e-5);
                    assert!((s.wi - Vec3A::new(-wo.x, -wo.y, wo.z)).length() < 1e-6);
                } else {
                    assert_eq!(s.lobe, Lobe::SpecularTransmission);
                    let (n_o, n_i): (f32, f32) = if wo.z > 0.0 { (1.0, 1.5) } else { (1.5, 1.0) };
                    let sin_o = (1.0 - wo.z * wo.z).sqrt();
                    let sin_i = (1.0 - s.wi.z * s.wi.z).sqrt();
                    assert!(
                        (n_o * sin_o - n_i * sin_i).abs() < 1e-5,
                        "Snell's law at {wo}"
                    );
                    assert!(s.wi.z * wo.z < 0.0);
                    assert!((weight - (n_o / n_i).powi(2)).abs() < 1e-4);
                }
            }
            let fraction = reflected as f32 / n as f32;
            let sigma = (r * (1.0 - r) / n as f32).sqrt().max(1e-4);
            assert!(
                (fraction - r).abs() < 5.0 * sigma,
                "wo {wo}: {fraction} reflected, R = {r}"
            );
        }
        // From inside, 60 degrees is past the critical angle of 41.8.
        let t = 60f32.to_radians();
        let wo = Vec3A::new(t.sin(), 0.0, -t.cos());
        assert_eq!(fresnel(wo.z, 1.5), 1.0);
        let s = b.sample(wo, Vec2::ZERO, 0.999).unwrap();
        assert_eq!(s.lobe, Lobe::SpecularReflection);
    }
}
