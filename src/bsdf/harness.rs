//! The checks every BSDF passes (test code only): its sampling follows its pdf (chi-square,
//! for light arriving from several angles on either side), the `f` and pdf a sample reports
//! are those `f` and `pdf` give for its direction, it reflects no more light than it
//! receives, and it is reciprocal.

use super::Bsdf;
use crate::math::chi2::{SAMPLES, SphereBins};
use crate::math::{Rng, Vec3A};
use std::f32::consts::PI;

/// Directions of the light's viewer `wo` the checks run at: from straight above to grazing,
/// on the front side and on the back.
pub(crate) fn incidences() -> Vec<Vec3A> {
    let mut v = vec![];
    for deg in [0.0f32, 30.0, 60.0, 85.0] {
        let t = deg.to_radians();
        let w = Vec3A::new(t.sin() * 0.8, t.sin() * 0.6, t.cos());
        v.push(w);
        v.push(Vec3A::new(w.x, -w.y, -w.z));
    }
    v
}

/// Chi-square of the sampling at every incidence, and the consistency of each sample (the
/// lab's test, `snell lab bsdf`, at the tests' default bins).
pub(crate) fn chi2_all_incidences(name: &str, bsdf: &Bsdf) {
    for wo in incidences() {
        let t = crate::lab::warp_test(bsdf, wo, SAMPLES, SphereBins::default())
            .unwrap_or_else(|e| panic!("{name} at wo = {wo}: {e}"));
        let c = &t.chi2;
        if c.stray > 10.0 {
            panic!(
                "{name} at wo = {wo}: {} samples fell where the density is 0",
                c.stray
            );
        }
        if !c.passed() {
            let (bin, o, e) = c.worst.unwrap_or((0, 0.0, 0.0));
            panic!(
                "{name} at wo = {wo}: the samples do not follow the density: chi^2 = {:.1} with {} degrees of freedom, p = {:.3e}; bin {bin} has {o} samples where {e:.1} are expected",
                c.chi2, c.dof, c.p
            );
        }
        if let Some(e) = t.inconsistent {
            panic!("{name} at wo = {wo}: {e}");
        }
    }
}

/// The light a BSDF reflects and transmits from `wo`, `∫ f(wo, wi) |cos theta_i| dwi`, by a
/// midpoint rule on a grid of the sphere, fine near both poles where narrow lobes of light
/// arriving straight on lie (`z = ±(1 - t^2)`).
pub(crate) fn albedo(bsdf: &Bsdf, wo: Vec3A) -> Vec3A {
    albedo_weighted(bsdf, wo, |_| 1.0)
}

/// [`albedo`] with each direction's `f` weighted by `weight(wi)`.
pub(crate) fn albedo_weighted(bsdf: &Bsdf, wo: Vec3A, weight: impl Fn(Vec3A) -> f32) -> Vec3A {
    let (nt, nphi) = (1000, 400);
    let dphi = 2.0 * PI as f64 / nphi as f64;
    let mut sum = Vec3A::ZERO;
    for side in [1.0f64, -1.0] {
        for i in 0..nt {
            let t = (i as f64 + 0.5) / nt as f64;
            let z = 1.0 - t * t;
            let dz = 2.0 * t / nt as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let mut ring = Vec3A::ZERO;
            for j in 0..nphi {
                let phi = (j as f64 + 0.5) * dphi;
                let wi = Vec3A::new(
                    (r * phi.cos()) as f32,
                    (r * phi.sin()) as f32,
                    (side * z) as f32,
                );
                ring += bsdf.f(wo, wi) * weight(wi);
            }
            sum += ring * (z * dz * dphi) as f32;
        }
    }
    sum
}

/// Energy: at every incidence the albedo is at most 1 (and `expected` where it is known in
/// closed form). Reciprocity: `f(wo, wi) = f(wi, wo)` for random pairs on either side.
pub(crate) fn energy_and_reciprocity(name: &str, bsdf: &Bsdf, expected: Option<f32>) {
    for wo in incidences() {
        let a = albedo(bsdf, wo);
        assert!(
            a.max_element() <= 1.0 + 2e-3,
            "{name} at wo = {wo} reflects {a}, more than it receives"
        );
        if let Some(e) = expected {
            assert!(
                (a - Vec3A::splat(e)).abs().max_element() < 2e-3,
                "{name} at wo = {wo}: albedo {a}, not {e}"
            );
        }
    }
    let mut rng = Rng::new(11);
    let mut direction = || {
        let u = crate::math::Vec2::new(rng.next_f32(), rng.next_f32());
        crate::math::sampling::uniform_sphere(u)
    };
    for _ in 0..1000 {
        let (a, b) = (direction(), direction());
        let (ab, ba) = (bsdf.f(a, b), bsdf.f(b, a));
        assert!(
            (ab - ba).abs().max_element() <= 1e-4 * ab.max_element().max(1.0),
            "{name}: f({a}, {b}) = {ab} but f({b}, {a}) = {ba}"
        );
    }
}
