//! The path tracer's reading of a Phong material: a mix, by weights that sum to 1, of a base
//! (Lambertian, or plastic where the material has a highlight), a perfect mirror and smooth
//! glass, each of which conserves energy, so the mix does too. The weights follow the
//! Whitted integrator's split: glass `transparency`, mirror `(1 - transparency) *
//! reflectivity`, the base the rest.

use super::microfacet::Ggx;
use super::{
    BsdfSample, Coat, Conductor, ConductorFresnel, Dielectric, Lambert, Plastic, Scatter,
    internal_diffuse_reflectance,
};
use crate::math::{Color, Vec2, Vec3A};

/// The coat's index of refraction where a Phong material has a highlight (a typical varnish
/// or plastic).
pub const COAT_IOR: f32 = 1.5;

/// The base a Phong material's diffuse and highlight become.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PhongBase {
    /// No highlight: Lambertian.
    Lambert(Lambert),
    /// A highlight: diffuse under a clear coat whose roughness comes from the exponent.
    Plastic(Plastic),
}

impl PhongBase {
    fn f_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Color {
        match self {
            PhongBase::Lambert(b) => b.f_diffuse(wo, wi),
            PhongBase::Plastic(b) => b.f_diffuse(wo, wi),
        }
    }

    fn f(&self, wo: Vec3A, wi: Vec3A) -> Color {
        match self {
            PhongBase::Lambert(b) => b.f(wo, wi),
            PhongBase::Plastic(b) => b.f(wo, wi),
        }
    }

    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        match self {
            PhongBase::Lambert(b) => b.pdf(wo, wi),
            PhongBase::Plastic(b) => b.pdf(wo, wi),
        }
    }

    fn sample(&self, wo: Vec3A, u: Vec2, uc: f32) -> Option<BsdfSample> {
        match self {
            PhongBase::Lambert(b) => b.sample(wo, u, uc),
            PhongBase::Plastic(b) => b.sample(wo, u, uc),
        }
    }
}

/// A Phong material as the path tracer reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhongMix {
    /// The diffuse base, with its highlight.
    pub base: PhongBase,
    /// The mirror (a smooth conductor reflecting everything).
    pub mirror: Conductor,
    /// The glass (smooth).
    pub glass: Dielectric,
    /// Weights of base, mirror and glass: each in `[0, 1]`, summing to 1.
    pub weights: [f32; 3],
}

/// One of the mix's parts, for dispatch.
enum Part<'a> {
    Base(&'a PhongBase),
    Mirror(&'a Conductor),
    Glass(&'a Dielectric),
}

impl PhongMix {
    /// The mix for a base of reflectance `r` (each channel in `[0, 1]`), with a highlight
    /// of GGX roughness `highlight` under a coat of index [`COAT_IOR`] (`None`: no highlight,
    /// a Lambertian base), a mirror tinted `mirror_tint` and smooth glass of index `ior`,
    /// weighed by [`PhongMix::weights`]. The coat passes light to the base as a smooth
    /// boundary would (`Coat::Smooth`).
    pub fn new(
        r: Color,
        highlight: Option<f32>,
        mirror_tint: Color,
        ior: f32,
        reflectivity: f32,
        transparency: f32,
    ) -> Self {
        let base = match highlight {
            Some(alpha) => PhongBase::Plastic(Plastic {
                r,
                eta: COAT_IOR,
                distribution: Ggx::isotropic(alpha),
                coat: Coat::Smooth {
                    fdr_int: coat_fdr(),
                },
            }),
            None => PhongBase::Lambert(Lambert { r }),
        };
        PhongMix {
            base,
            mirror: Conductor {
                fresnel: ConductorFresnel::One,
                distribution: Ggx::isotropic(0.0),
                tint: mirror_tint,
            },
            glass: Dielectric {
                eta: ior,
                distribution: Ggx::isotropic(0.0),
            },
            weights: PhongMix::weights(reflectivity, transparency),
        }
    }

    /// The mix's weights from a Phong material's `reflectivity` and `transparency`.
    pub fn weights(reflectivity: f32, transparency: f32) -> [f32; 3] {
        let glass = transparency.clamp(0.0, 1.0);
        let mirror = (1.0 - glass) * reflectivity.clamp(0.0, 1.0);
        [(1.0 - glass - mirror).max(0.0), mirror, glass]
    }

    fn part(&self, i: usize) -> Part<'_> {
        match i {
            0 => Part::Base(&self.base),
            1 => Part::Mirror(&self.mirror),
            _ => Part::Glass(&self.glass),
        }
    }
}

impl Scatter for PhongMix {
    /// The weighted sum of the parts' values (the mirror and smooth glass, deltas, add
    /// nothing).
    fn f(&self, wo: Vec3A, wi: Vec3A) -> Color {
        if self.weights[0] > 0.0 {
            self.base.f(wo, wi) * self.weights[0]
        } else {
            Color::ZERO
        }
    }

    /// The base's diffuse part, in its share.
    fn f_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Color {
        if self.weights[0] > 0.0 {
            self.base.f_diffuse(wo, wi) * self.weights[0]
        } else {
            Color::ZERO
        }
    }

    /// A part chosen by its weight with `uc` (whose remainder then chooses within the
    /// part), then sampled.
    fn sample(&self, wo: Vec3A, u: Vec2, uc: f32) -> Option<BsdfSample> {
        let mut start = 0.0;
        let mut chosen = None;
        for (i, &w) in self.weights.iter().enumerate() {
            if w > 0.0 && (uc < start + w || chosen.is_none() && i == 2) {
                chosen = Some((i, ((uc - start) / w).clamp(0.0, 1.0 - f32::EPSILON / 2.0)));
                break;
            }
            start += w;
        }
        // Rounding can leave `uc` past the last weight: take the last part that has one.
        let (i, uc) = chosen.or_else(|| {
            (0..3)
                .rev()
                .find(|&i| self.weights[i] > 0.0)
                .map(|i| (i, 0.5))
        })?;
        let w = self.weights[i];
        let s = match self.part(i) {
            Part::Base(b) => b.sample(wo, u, uc)?,
            Part::Mirror(m) => m.sample(wo, u, uc)?,
            Part::Glass(g) => g.sample(wo, u, uc)?,
        };
        // Only the base is not a delta: its value and density, weighted.
        super::as_mix_sample(s, w, |wi| self.f(wo, wi), |wi| self.pdf(wo, wi))
    }

    /// The density of [`PhongMix::sample`]: each part's, weighted by its chance.
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.weights[0] > 0.0 {
            self.base.pdf(wo, wi) * self.weights[0]
        } else {
            0.0
        }
    }

    fn name(&self) -> &'static str {
        "phong mix"
    }

    fn has_non_delta(&self) -> bool {
        self.weights[0] > 0.0
    }

    fn radiance_scale(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.weights[2] > 0.0 {
            self.glass.radiance_scale(wo, wi)
        } else {
            1.0
        }
    }
}

/// [`internal_diffuse_reflectance`] of [`COAT_IOR`], worked out once.
fn coat_fdr() -> f32 {
    static FDR: std::sync::OnceLock<f32> = std::sync::OnceLock::new();
    *FDR.get_or_init(|| internal_diffuse_reflectance(COAT_IOR))
}

#[cfg(test)]
mod tests {
    use super::super::{Bsdf, harness};
    use super::*;

    /// The mix a Phong material of colour (0.8, 0.5, 0.2) makes, through the same
    /// constructor the material uses.
    fn mix(highlight: bool, reflectivity: f32, transparency: f32) -> Bsdf {
        let r = Color::new(0.8, 0.5, 0.2);
        let highlight = highlight.then_some(0.2);
        Bsdf::Phong(PhongMix::new(
            r,
            highlight,
            Color::ONE,
            1.5,
            reflectivity,
            transparency,
        ))
    }

    #[test]
    fn weights_split_as_whitted_does_and_sum_to_one() {
        assert_eq!(PhongMix::weights(0.0, 0.0), [1.0, 0.0, 0.0]);
        assert_eq!(PhongMix::weights(0.8, 0.0), [0.19999999, 0.8, 0.0]);
        assert_eq!(PhongMix::weights(0.5, 1.0), [0.0, 0.0, 1.0]);
        let w = PhongMix::weights(0.5, 0.5);
        assert_eq!(w, [0.25, 0.25, 0.5]);
    }

    #[test]
    fn sampling_matches_the_pdf() {
        harness::chi2_all_incidences("phong diffuse", &mix(false, 0.3, 0.0));
        harness::chi2_all_incidences("phong plastic", &mix(true, 0.3, 0.2));
    }

    #[test]
    fn conserves_energy_and_is_reciprocal() {
        for (h, r, t) in [(false, 0.0, 0.0), (true, 0.0, 0.0), (true, 0.5, 0.3)] {
            harness::energy_and_reciprocity("phong", &mix(h, r, t), None);
        }
    }

    /// The deltas carry their weight: a perfect mirror of weight 0.8 returns 0.8 of the
    /// light in its sampled direction, and the glass what Fresnel and its weight leave.
    #[test]
    fn delta_parts_carry_their_weight() {
        let b = mix(false, 0.8, 0.0);
        let wo = Vec3A::new(0.3, 0.0, 0.954).normalize();
        let (mut mirror, mut n) = (0.0, 0);
        for k in 0..1000 {
            let uc = (k as f32 + 0.5) / 1000.0;
            if let Some(s) = b.sample(wo, Vec2::new(0.3, 0.7), uc)
                && s.lobe.is_specular()
            {
                mirror += s.f.x * s.wi.z.abs() / s.pdf;
                n += 1;
            }
        }
        assert!((n as f32 / 1000.0 - 0.8).abs() < 0.01, "{n}");
        assert!(
            (mirror / n as f32 - 1.0).abs() < 1e-5,
            "{}",
            mirror / n as f32
        );
    }
}
