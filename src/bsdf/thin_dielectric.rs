//! A thin slab of glass (a window pane): light is reflected or passes straight through,
//! unbent, the slab's internal reflections summed into the split (`R + T^2 R / (1 - R^2)`).

use super::dielectric::fresnel;
use super::{BsdfSample, Lobe, Scatter};
use crate::math::{Color, Vec2, Vec3A};

/// A thin dielectric slab of index `eta` (relative to the air on both sides).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinDielectric {
    /// Index of refraction of the slab.
    pub eta: f32,
}

impl ThinDielectric {
    /// The slab's reflectance at `|cos theta| = cos`, internal bounces included.
    pub fn reflectance(&self, cos: f32) -> f32 {
        let r = fresnel(cos.abs(), self.eta);
        if r < 1.0 {
            let t = 1.0 - r;
            r + t * t * r / (1.0 - r * r)
        } else {
            r
        }
    }
}

impl Scatter for ThinDielectric {
    /// Only delta lobes: 0 for every pair of directions.
    fn f(&self, _wo: Vec3A, _wi: Vec3A) -> Color {
        Color::ZERO
    }

    /// The mirror direction or straight through, chosen in proportion by `uc`.
    fn sample(&self, wo: Vec3A, _u: Vec2, uc: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let r = self.reflectance(wo.z);
        let (wi, lobe, p) = if uc < r {
            (Vec3A::new(-wo.x, -wo.y, wo.z), Lobe::SpecularReflection, r)
        } else {
            (-wo, Lobe::SpecularTransmission, 1.0 - r)
        };
        Some(BsdfSample {
            wi,
            f: Color::splat(p / wi.z.abs()),
            pdf: p,
            lobe,
        })
    }

    /// 0: no direction is reached except by a delta lobe.
    fn pdf(&self, _wo: Vec3A, _wi: Vec3A) -> f32 {
        0.0
    }

    fn name(&self) -> &'static str {
        "thin dielectric"
    }

    fn has_non_delta(&self) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Straight on, glass of index 1.5 reflects 4 % at each face and, with the bounces
    /// between them, 2 R / (1 + R) = 7.7 % in all; every sample's weight is 1 and a
    /// transmitted ray goes on unbent.
    #[test]
    fn a_pane_reflects_both_faces_and_lets_the_rest_through_unbent() {
        let pane = ThinDielectric { eta: 1.5 };
        let r1 = 0.04f32;
        assert!((pane.reflectance(1.0) - 2.0 * r1 / (1.0 + r1)).abs() < 1e-5);
        assert!((pane.reflectance(-1.0) - pane.reflectance(1.0)).abs() < 1e-7);
        assert!(
            (pane.reflectance(1e-4) - 1.0).abs() < 1e-2,
            "grazing light is reflected"
        );
        let wo = Vec3A::new(0.6, 0.0, 0.8);
        let r = pane.reflectance(0.8);
        let through = pane.sample(wo, Vec2::ZERO, r + 0.01).unwrap();
        assert_eq!(through.lobe, Lobe::SpecularTransmission);
        assert_eq!(through.wi, -wo);
        let back = pane.sample(wo, Vec2::ZERO, r - 0.01).unwrap();
        assert_eq!(back.lobe, Lobe::SpecularReflection);
        for s in [through, back] {
            assert!((s.f.x * s.wi.z.abs() / s.pdf - 1.0).abs() < 1e-5);
        }
    }
}
