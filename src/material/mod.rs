//! Materials: what a scene file says of a surface, textured, and how each integrator reads
//! it. The Whitted integrator reads the Phong terms every material carries (each type sets
//! them in its own file, as docs/scene-format.md documents); the path tracer builds a
//! [`Bsdf`] at each hit from the material's [`Surface`] and its textures. One file per type.

pub mod conductor;
pub mod cutout;
pub mod detail;
pub mod dielectric;
pub mod diffuse;
pub mod dispersion;
pub mod metallic;
pub mod param;
pub mod phong;
pub mod plastic;
pub mod thin;

use crate::bsdf::Bsdf;
use crate::math::Color;
use crate::texture::{Texture, TexturePoint};
use std::borrow::Cow;

pub use param::{ColorParam, Scalar};

/// How a surface responds to light. Every coefficient is dimensionless.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Index of the texture that gives the surface colour.
    pub texture: usize,
    /// The Phong terms Whitted reads (and the path tracer's reading of a Phong material),
    /// where no texture gives them: see [`Material::terms_at`].
    pub terms: PhongTerms,
    /// Whitted: the colour of the mirror reflection (white but for metals).
    pub mirror_tint: Color,
    /// Index of refraction of the inside of the solid (a dispersive one's at
    /// [`dispersion::D_LINE_NM`], for whatever follows no wavelength).
    pub ior: f32,
    /// How the index changes with wavelength, for a dielectric or Phong glass that
    /// disperses light (`None`: the same index at every wavelength).
    pub dispersion: Option<dispersion::Dispersion>,
    /// Beer-Lambert absorption coefficient per scene unit travelled inside, per channel.
    pub absorption: Color,
    /// What the path tracer scatters by.
    pub surface: Surface,
    /// Light the surface gives off, if any.
    pub emission: Option<Emission>,
    /// The Phong terms read from textures, where the file names textures for them (the
    /// constants above are used elsewhere).
    pub textured: Option<Box<TexturedTerms>>,
    /// A normal or bump map bending the shading normal, if any.
    pub detail: Option<detail::SurfaceDetail>,
    /// Holes cut by alpha, if any.
    pub cutout: Option<cutout::Cutout>,
}

/// The Phong terms at a surface point: the material's constants, or its textures read
/// there (see [`Material::terms_at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhongTerms {
    /// Multiplies the global ambient light (times the surface colour).
    pub ambient: f32,
    /// Lambertian term.
    pub diffuse: f32,
    /// Highlight colour.
    pub specular: Color,
    /// Highlight exponent.
    pub shininess: f32,
    /// Mirror reflection weight, in `[0, 1]`.
    pub reflectivity: f32,
    /// Fraction of light that passes into the surface, in `[0, 1]`; Fresnel splits it
    /// between reflection and refraction.
    pub transparency: f32,
}

impl PhongTerms {
    /// Whitted's defaults: ambient 1, diffuse 0.8, no highlight (exponent 50), no mirror,
    /// opaque.
    pub const DEFAULT: PhongTerms = PhongTerms {
        ambient: 1.0,
        diffuse: 0.8,
        specular: Color::ZERO,
        shininess: 50.0,
        reflectivity: 0.0,
        transparency: 0.0,
    };
}

/// Textures (indices into the scene's list) that give Phong terms point by point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TexturedTerms {
    /// `ambient`.
    pub ambient: Option<usize>,
    /// `diffuse`.
    pub diffuse: Option<usize>,
    /// `specular`.
    pub specular: Option<usize>,
    /// `shininess`.
    pub shininess: Option<usize>,
    /// `reflectivity`.
    pub reflectivity: Option<usize>,
    /// `transparency`.
    pub transparency: Option<usize>,
}

impl TexturedTerms {
    /// `terms` with what the textures give at `p` in place of the terms they stand for.
    /// Out of line: most materials have no textured terms, and Whitted's shading, which
    /// asks at every hit, stays short.
    #[cold]
    #[inline(never)]
    fn read(&self, mut terms: PhongTerms, textures: &[Texture], p: &TexturePoint) -> PhongTerms {
        let scalar = |slot: &mut f32, tex: Option<usize>, hi: f32| {
            if let Some(i) = tex {
                *slot = Scalar::Texture(i).at(textures, p).clamp(0.0, hi);
            }
        };
        scalar(&mut terms.ambient, self.ambient, f32::MAX);
        scalar(&mut terms.diffuse, self.diffuse, f32::MAX);
        scalar(&mut terms.shininess, self.shininess, f32::MAX);
        scalar(&mut terms.reflectivity, self.reflectivity, 1.0);
        scalar(&mut terms.transparency, self.transparency, 1.0);
        if let Some(i) = self.specular {
            terms.specular = textures[i].eval(p).max(Color::ZERO);
        }
        terms
    }
}

/// Light given off by a surface, on its front side or on both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// Radiance, linear RGB (per unit area and solid angle), constant or textured.
    pub radiance: ColorParam,
    /// Whether the back side emits too.
    pub two_sided: bool,
}

impl Emission {
    /// The radiance leaving the side of the surface that `front` says, at point `p`.
    #[inline]
    pub fn emitted(&self, front: bool, textures: &[Texture], p: &TexturePoint) -> Color {
        if front || self.two_sided {
            self.radiance.at(textures, p)
        } else {
            Color::ZERO
        }
    }
}

/// The scattering of each type of material, for the path tracer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Surface {
    /// The Phong terms, read as a mix (see [`phong`]).
    Phong,
    /// Lambertian, of the material's colour.
    Diffuse,
    /// A metal (see [`conductor`]).
    Conductor(conductor::Conductor),
    /// Glass (see [`dielectric`]).
    Dielectric(dielectric::Dielectric),
    /// A thin pane of this index of refraction.
    Thin(f32),
    /// Coated diffuse (see [`plastic`]).
    Plastic(plastic::Plastic),
    /// glTF's blend of metal and coated diffuse (see [`metallic`]).
    Metallic(metallic::Metallic),
}

impl Material {
    /// The Phong terms at a surface point: the constants, with what textures give in
    /// place of those the file names textures for. Borrowed where no texture gives any
    /// (most materials): Whitted asks at every hit, so a copy there is paid on every ray,
    /// and measurably (docs/perf-log.md).
    #[inline(always)]
    pub fn terms_at(&self, textures: &[Texture], p: &TexturePoint) -> Cow<'_, PhongTerms> {
        match &self.textured {
            None => Cow::Borrowed(&self.terms),
            Some(t) => Cow::Owned(t.read(self.terms, textures, p)),
        }
    }

    /// The BSDF at a surface point, whose textured colour is `base`.
    #[inline]
    pub fn bsdf(&self, textures: &[Texture], p: &TexturePoint, base: Color) -> Bsdf {
        self.bsdf_at(textures, p, base, None)
    }

    /// [`Material::bsdf`] for light of wavelength `nm` nanometres, where the path follows
    /// one: a dispersive material's index is then its index there.
    pub fn bsdf_at(
        &self,
        textures: &[Texture],
        p: &TexturePoint,
        base: Color,
        nm: Option<f32>,
    ) -> Bsdf {
        let ior = match (&self.dispersion, nm) {
            (Some(d), Some(nm)) => d.ior(nm),
            _ => self.ior,
        };
        match &self.surface {
            Surface::Phong => phong::bsdf(self, &self.terms_at(textures, p), base, ior),
            Surface::Diffuse => diffuse::bsdf(base),
            Surface::Conductor(c) => c.bsdf(base, textures, p),
            Surface::Dielectric(d) => d.bsdf(textures, p, ior),
            Surface::Thin(ior) => thin::bsdf(*ior),
            Surface::Plastic(c) => c.bsdf(self, base, textures, p),
            Surface::Metallic(c) => c.bsdf(self, base, textures, p),
        }
    }

    /// Every texture the material reads (its colour's, and those of textured parameters),
    /// as indices into the scene's list.
    pub fn textures(&self) -> Vec<usize> {
        let mut out = vec![self.texture];
        let mut scalar = |s: &Scalar| {
            if let Scalar::Texture(t) = s {
                out.push(*t);
            }
        };
        match &self.surface {
            Surface::Conductor(c) => scalar(&c.roughness),
            Surface::Dielectric(d) => scalar(&d.roughness),
            Surface::Plastic(p) => scalar(&p.roughness),
            Surface::Metallic(m) => {
                scalar(&m.dielectric.roughness);
                scalar(&m.metallic);
            }
            Surface::Phong | Surface::Diffuse | Surface::Thin(_) => {}
        }
        let mut color = |c: &ColorParam| {
            if let ColorParam::Texture(t) = c {
                out.push(*t);
            }
        };
        if let Surface::Conductor(c) = &self.surface {
            c.index.iter().flatten().for_each(&mut color);
        }
        if let Some(e) = &self.emission {
            color(&e.radiance);
        }
        out.extend(self.detail.map(|d| d.texture()));
        out.extend(self.cutout.map(|c| c.texture()));
        if let Some(t) = &self.textured {
            out.extend(
                [
                    t.ambient,
                    t.diffuse,
                    t.specular,
                    t.shininess,
                    t.reflectivity,
                    t.transparency,
                ]
                .into_iter()
                .flatten(),
            );
        }
        out
    }

    /// The absorption inside the solid, for a path that has crossed into it, or `None`
    /// where the material lets no light in or absorbs nothing.
    pub fn absorption_inside(&self) -> Option<Color> {
        (self.absorption != Color::ZERO).then_some(self.absorption)
    }

    /// True when the surface may let light through somewhere (refraction and lighter
    /// shadows).
    #[inline]
    pub fn is_transparent(&self) -> bool {
        self.terms.transparency > 0.0
            || self
                .textured
                .as_ref()
                .is_some_and(|t| t.transparency.is_some())
    }

    /// A material with Whitted's defaults (white, ambient 1, diffuse 0.8, nothing else),
    /// for each type's constructor to change.
    pub(crate) fn base(texture: usize, surface: Surface, emission: Option<Emission>) -> Self {
        Material {
            texture,
            terms: PhongTerms::DEFAULT,
            mirror_tint: Color::ONE,
            ior: 1.5,
            dispersion: None,
            absorption: Color::ZERO,
            surface,
            emission,
            textured: None,
            detail: None,
            cutout: None,
        }
    }
}

/// The Phong exponent that gives a highlight about as wide as GGX of roughness `alpha`:
/// Blinn-Phong's `2 / alpha^2 - 2` (Walter et al. 2007), over 4 for Phong's mirror-vector
/// form; smooth surfaces get 1000.
pub fn shininess_of(alpha: f32) -> f32 {
    if alpha <= 0.0 {
        return 1000.0;
    }
    ((2.0 / (alpha * alpha) - 2.0) / 4.0).clamp(1.0, 1000.0)
}

/// The inverse of [`shininess_of`]: the GGX roughness a Phong exponent stands for.
pub fn alpha_of(shininess: f32) -> f32 {
    (2.0 / (4.0 * shininess.max(0.0) + 2.0)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shininess_and_roughness_are_inverse() {
        for n in [1.0f32, 10.0, 50.0, 200.0] {
            assert!((shininess_of(alpha_of(n)) - n).abs() < 1e-2 * n, "{n}");
        }
        // The seed's exponent 50 is a fairly sharp coat.
        assert!((alpha_of(50.0) - 0.0995).abs() < 1e-3);
        assert_eq!(shininess_of(0.0), 1000.0);
    }
}
