//! Lambertian diffuse reflection: light scattered equally in every direction of the side it
//! arrived on, `f = R / pi`.

use super::{BsdfSample, Lobe, Scatter, same_hemisphere, to_side_of};
use crate::math::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::math::{Color, Vec2, Vec3A};
use std::f32::consts::FRAC_1_PI;

/// A diffuse surface of reflectance (albedo) `r`, each channel in `[0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambert {
    /// Fraction of the light reflected, per channel.
    pub r: Color,
}

impl Scatter for Lambert {
    /// `R / pi` for directions on the same side, 0 across the surface.
    fn f_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Color {
        self.f(wo, wi)
    }

    fn f(&self, wo: Vec3A, wi: Vec3A) -> Color {
        if same_hemisphere(wo, wi) {
            self.r * FRAC_1_PI
        } else {
            Color::ZERO
        }
    }

    /// A cosine-weighted direction on `wo`'s side.
    fn sample(&self, wo: Vec3A, u: Vec2, _uc: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let wi = to_side_of(wo, cosine_hemisphere(u));
        let pdf = cosine_hemisphere_pdf(wi.z.abs());
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            f: self.f(wo, wi),
            pdf,
            lobe: Lobe::DiffuseReflection,
        })
    }

    /// `|cos theta_i| / pi` on `wo`'s side.
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if same_hemisphere(wo, wi) {
            cosine_hemisphere_pdf(wi.z.abs())
        } else {
            0.0
        }
    }

    fn name(&self) -> &'static str {
        "lambert"
    }

    fn has_non_delta(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::super::harness;
    use super::*;

    fn grey(r: f32) -> Bsdf {
        Bsdf::Lambert(Lambert { r: Color::splat(r) })
    }

    #[test]
    fn sampling_matches_the_pdf() {
        harness::chi2_all_incidences("lambert", &grey(0.5));
    }

    #[test]
    fn reflects_its_albedo_and_is_reciprocal() {
        for r in [0.0, 0.3, 1.0] {
            harness::energy_and_reciprocity("lambert", &grey(r), Some(r));
        }
    }
}
