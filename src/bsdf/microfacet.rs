//! The Trowbridge-Reitz (GGX) distribution of microfacet normals, with Smith's shadowing and
//! Heitz's sampling of the normals visible from a direction (2018), in the local frame.
//! `alpha` is the width of the distribution along x and y, as Mitsuba's `alpha` (Blender's
//! roughness r is alpha = r^2).

use crate::math::sampling::uniform_disk_concentric;
use crate::math::{Vec2, Vec3A};
use std::f32::consts::PI;

/// Below this `alpha` a surface is taken as smooth (a delta lobe), as pbrt-v4 does: the
/// distribution would be too sharp for floats.
pub const SMOOTH_ALPHA: f32 = 1e-3;

/// A GGX distribution of widths `ax` and `ay`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    /// Width along the local x axis.
    pub ax: f32,
    /// Width along the local y axis.
    pub ay: f32,
}

impl Ggx {
    /// An isotropic distribution of width `alpha`.
    pub fn isotropic(alpha: f32) -> Self {
        Ggx {
            ax: alpha.max(SMOOTH_ALPHA),
            ay: alpha.max(SMOOTH_ALPHA),
        }
    }

    /// Whether the distribution is too narrow to sample as a lobe.
    pub fn is_smooth(&self) -> bool {
        self.ax.max(self.ay) <= SMOOTH_ALPHA
    }

    /// The density of microfacet normals `wm` per unit area of the macro surface, per
    /// steradian: `D(wm)` (it integrates to 1 against `cos theta_m`).
    pub fn d(&self, wm: Vec3A) -> f32 {
        // Microfacets face out of the surface.
        if wm.z <= 0.0 {
            return 0.0;
        }
        let cos2 = wm.z * wm.z;
        let sin2 = (1.0 - cos2).max(0.0);
        let tan2 = sin2 / cos2;
        let (c2, s2) = if sin2 > 0.0 {
            (wm.x * wm.x / sin2, wm.y * wm.y / sin2)
        } else {
            (1.0, 0.0)
        };
        let e = tan2 * (c2 / (self.ax * self.ax) + s2 / (self.ay * self.ay));
        1.0 / (PI * self.ax * self.ay * cos2 * cos2 * (1.0 + e) * (1.0 + e))
    }

    /// Smith's `Lambda(w)`: the shadowed area of the microsurface seen from `w`, relative to
    /// its visible projected area.
    pub fn lambda(&self, w: Vec3A) -> f32 {
        let cos2 = w.z * w.z;
        let sin2 = (1.0 - cos2).max(0.0);
        if sin2 == 0.0 || cos2 == 0.0 {
            return if cos2 == 0.0 { f32::INFINITY } else { 0.0 };
        }
        let tan2 = sin2 / cos2;
        let alpha2 = (w.x * w.x * self.ax * self.ax + w.y * w.y * self.ay * self.ay) / sin2;
        ((1.0 + alpha2 * tan2).sqrt() - 1.0) / 2.0
    }

    /// The fraction of microfacets visible from `w`.
    pub fn g1(&self, w: Vec3A) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// The fraction visible from both `wo` and `wi`: Smith's separable form, `G1(wo)
    /// G1(wi)`, as Mitsuba 3's microfacet BSDFs take it (pbrt-v4's height-correlated form
    /// is a little larger at grazing angles), so that snell's rough materials evaluate as
    /// their Mitsuba namesakes (src/bsdf/mitsuba_tests.rs).
    pub fn g(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        self.g1(wo) * self.g1(wi)
    }

    /// The density of the normals visible from `w` (`w.z > 0`): `G1(w) / cos theta * D(wm)
    /// * max(0, w . wm)`, per steradian of `wm`.
    pub fn visible_pdf(&self, w: Vec3A, wm: Vec3A) -> f32 {
        if w.z <= 0.0 {
            return 0.0;
        }
        self.g1(w) / w.z * self.d(wm) * w.dot(wm).max(0.0)
    }

    /// A microfacet normal visible from `w` (`w.z > 0`), drawn with [`Ggx::visible_pdf`]:
    /// the view stretched to a hemisphere of unit roughness, a point on the projected disk of
    /// that hemisphere, and back.
    pub fn sample_visible(&self, w: Vec3A, u: Vec2) -> Vec3A {
        let wh = Vec3A::new(self.ax * w.x, self.ay * w.y, w.z).normalize();
        let t1 = if wh.z < 0.99999 {
            Vec3A::Z.cross(wh).normalize()
        } else {
            Vec3A::X
        };
        let t2 = wh.cross(t1);
        let mut p = uniform_disk_concentric(u);
        // The disk's half behind the stretched view is seen foreshortened.
        let h = (1.0 - p.x * p.x).max(0.0).sqrt();
        let s = (1.0 + wh.z) / 2.0;
        p.y = (1.0 - s) * h + s * p.y;
        let pz = (1.0 - p.length_squared()).max(0.0).sqrt();
        let nh = p.x * t1 + p.y * t2 + pz * wh;
        Vec3A::new(self.ax * nh.x, self.ay * nh.y, nh.z.max(1e-6)).normalize()
    }
}

/// A reflection off the microfacets between two directions on the front side (`z > 0`): the
/// microfacet normal that joins them, the lobe's value `D G / (4 cos_o cos_i)` (the
/// Fresnel factor left to the caller, at `wo . wm`), and the density with which
/// [`Ggx::sample_reflection`] picks `wi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Reflection {
    pub wm: Vec3A,
    pub value: f32,
    pub pdf: f32,
}

impl Ggx {
    /// The reflection lobe between front-side `wo` and `wi`; `None` where they are opposite.
    pub(crate) fn reflection(&self, wo: Vec3A, wi: Vec3A) -> Option<Reflection> {
        let wm = (wo + wi).normalize_or_zero();
        (wm != Vec3A::ZERO).then(|| Reflection {
            wm,
            value: self.d(wm) * self.g(wo, wi) / (4.0 * wo.z * wi.z),
            pdf: self.visible_pdf(wo, wm) / (4.0 * wo.dot(wm).abs()),
        })
    }

    /// Front-side `wo` reflected about a microfacet normal visible from it; `None` when the
    /// reflection goes below the surface.
    pub(crate) fn sample_reflection(&self, wo: Vec3A, u: Vec2) -> Option<Vec3A> {
        let wm = self.sample_visible(wo, u);
        let wi = 2.0 * wo.dot(wm) * wm - wo;
        (wi.z > 0.0).then_some(wi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::chi2::{SphereBins, chi2_sphere};

    /// `D` is a distribution of normals: its projection onto the macro surface covers it
    /// once, `∫ D(wm) cos theta_m dwm = 1`.
    #[test]
    fn the_normals_cover_the_surface_once() {
        for (ax, ay) in [(0.1f32, 0.1f32), (0.5, 0.5), (1.0, 1.0), (0.2, 0.6)] {
            let g = Ggx { ax, ay };
            let (nz, nphi) = (2000, 400);
            let mut sum = 0.0f64;
            for i in 0..nz {
                // Denser near the pole, where narrow distributions live: z = 1 - t^2.
                let t = (i as f64 + 0.5) / nz as f64;
                let z = 1.0 - t * t;
                let dz = 2.0 * t / nz as f64;
                let r = (1.0 - z * z).max(0.0).sqrt();
                for j in 0..nphi {
                    let phi = (j as f64 + 0.5) * 2.0 * std::f64::consts::PI / nphi as f64;
                    let wm = Vec3A::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                    sum += g.d(wm) as f64 * z * dz * 2.0 * std::f64::consts::PI / nphi as f64;
                }
            }
            assert!((sum - 1.0).abs() < 5e-3, "alpha ({ax}, {ay}): {sum}");
        }
    }

    #[test]
    fn visible_normals_follow_their_density() {
        for alpha in [0.15f32, 0.5, 1.0] {
            let g = Ggx::isotropic(alpha);
            for deg in [0.0f32, 45.0, 80.0] {
                let t = deg.to_radians();
                let w = Vec3A::new(t.sin(), 0.0, t.cos());
                chi2_sphere(
                    &format!("GGX visible normals, alpha {alpha}, {deg} degrees"),
                    SphereBins::default(),
                    |u| Some(g.sample_visible(w, u)),
                    |wm| g.visible_pdf(w, wm),
                )
                .unwrap();
            }
        }
    }
}
