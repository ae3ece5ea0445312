//! Scattering at a surface point as pure functions of two directions in the local shading
//! frame (`z` the shading normal; `wo` toward the viewer, `wi` toward the light, both unit):
//! the value `f(wo, wi)`, importance sampling of `wi`, and the density of that sampling. No
//! scene types: a material builds a [`Bsdf`] at a hit from its textured parameters, and each
//! variant is tested on its own (chi-square of its sampling, energy, reciprocity).

pub mod coat;
mod conductor;
mod dielectric;
pub mod fresnel;
mod lambert;
mod metallic;
pub mod metals;
pub mod microfacet;
mod phong;
pub mod plastic;
mod thin_dielectric;

pub use conductor::{Conductor, ConductorFresnel};
pub use dielectric::Dielectric;
pub use lambert::Lambert;
pub use metallic::MetallicMix;
pub use phong::{COAT_IOR, PhongBase, PhongMix};
pub use plastic::{Coat, Plastic, internal_diffuse_reflectance};
pub use thin_dielectric::ThinDielectric;

use crate::math::{Color, Vec2, Vec3A};

/// Which kind of scattering a sample took.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobe {
    /// Diffuse reflection (spread over the hemisphere).
    DiffuseReflection,
    /// Reflection about rough microfacets (a lobe around the mirror direction).
    GlossyReflection,
    /// Mirror reflection (a delta).
    SpecularReflection,
    /// Refraction through rough microfacets.
    GlossyTransmission,
    /// Refraction through a smooth boundary (a delta).
    SpecularTransmission,
}

impl Lobe {
    /// Whether the lobe is a delta (a mirror or a smooth refraction), which light sampling
    /// cannot reach and multiple importance sampling leaves to the BSDF.
    pub fn is_specular(self) -> bool {
        match self {
            Lobe::DiffuseReflection | Lobe::GlossyReflection | Lobe::GlossyTransmission => false,
            Lobe::SpecularReflection | Lobe::SpecularTransmission => true,
        }
    }
}

/// A sampled direction with what the integrator needs of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// The incident direction, unit, in the local frame.
    pub wi: Vec3A,
    /// `f(wo, wi)`.
    pub f: Color,
    /// The density with which `wi` was chosen, per unit solid angle (for a specular lobe,
    /// the probability of choosing that lobe).
    pub pdf: f32,
    /// The lobe taken.
    pub lobe: Lobe,
}

crate::closed_set! {
    /// What every BSDF gives: its value, its sampling and that sampling's density, in the
    /// local frame. Implemented by each variant in its file; [`Bsdf`] forwards to them.
    pub trait Scatter {
        /// `f(wo, wi)`: reflected radiance per unit irradiance, per steradian.
        fn f(&self, wo: Vec3A, wi: Vec3A) -> Color;

        /// Chooses `wi` for `wo` from the uniform point `u` (and `uc`, for choosing a lobe);
        /// `None` when the sample is absorbed or `wo` lies in the surface.
        fn sample(&self, wo: Vec3A, u: Vec2, uc: f32) -> Option<BsdfSample>;

        /// The density with which [`Scatter::sample`] chooses `wi` for `wo`, per unit solid
        /// angle (0 for the directions only a specular lobe reaches).
        fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32;

        /// The part of `f(wo, wi)` that is diffuse (a Lambertian base's), the rest being
        /// glossy: what light path expressions call `D` and `G` for a light sample.
        fn f_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Color {
            Color::ZERO
        }

        /// The variant's name, for `snell explain`.
        fn name(&self) -> &'static str;

        /// Whether some of its scattering is not a delta, so that light sampling can reach it.
        fn has_non_delta(&self) -> bool;

        /// How much a sample from `wo` to `wi` concentrates radiance by refraction, `(eta_i /
        /// eta_o)^2` for a refraction into a denser medium (1 for everything else): Russian
        /// roulette divides the throughput by it, so that light inside glass is not cut short
        /// for being bright.
        fn radiance_scale(&self, wo: Vec3A, wi: Vec3A) -> f32 {
            1.0
        }
    }

    /// A BSDF: one of a closed set, one file per variant.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub enum Bsdf {
        /// Lambertian diffuse reflection.
        Lambert(Lambert),
        /// A metal, smooth or rough.
        Conductor(Conductor),
        /// Glass, smooth or rough.
        Dielectric(Dielectric),
        /// A thin pane of glass.
        ThinDielectric(ThinDielectric),
        /// A diffuse base under a dielectric coat.
        Plastic(Plastic),
        /// A Phong material's mix of base, mirror and glass.
        Phong(PhongMix),
        /// glTF's blend of a metal and a coated diffuse surface.
        Metallic(MetallicMix),
    }
}

/// A sample of one part of a mix, chosen with chance `weight`, as the mix's sample: a delta
/// keeps its part's value and density, each times `weight`; any other direction gets the
/// mix's value `f` and density `pdf` there (the other parts may reach it too). `None` where
/// the mix's density there is 0.
#[inline]
pub(crate) fn as_mix_sample(
    mut s: BsdfSample,
    weight: f32,
    f: impl FnOnce(Vec3A) -> Color,
    pdf: impl FnOnce(Vec3A) -> f32,
) -> Option<BsdfSample> {
    if s.lobe.is_specular() {
        s.f *= weight;
        s.pdf *= weight;
    } else {
        s.f = f(s.wi);
        s.pdf = pdf(s.wi);
        if s.pdf <= 0.0 {
            return None;
        }
    }
    Some(s)
}

/// `w` mirrored onto the front side (`z >= 0`), for lobes that are the same on either side
/// and are written for the front.
#[inline]
pub(crate) fn front(w: Vec3A) -> Vec3A {
    Vec3A::new(w.x, w.y, w.z.abs())
}

/// A front-side direction `w` carried to the side of `wo`.
#[inline]
pub(crate) fn to_side_of(wo: Vec3A, w: Vec3A) -> Vec3A {
    Vec3A::new(w.x, w.y, w.z.copysign(wo.z))
}

/// Whether two local directions lie on the same side of the surface.
#[inline]
pub(crate) fn same_hemisphere(a: Vec3A, b: Vec3A) -> bool {
    a.z * b.z > 0.0
}

#[cfg(test)]
pub(crate) mod harness;
#[cfg(test)]
mod mitsuba_tests;
