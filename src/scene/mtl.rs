//! MTL materials as snell materials, as docs/scene-format.md describes: the type from what
//! the file says (`Pm` a metal, `illum` 6 and 7 glass, 4 and 9 a thin pane, `illum 5` or
//! `Pr` a coated plastic, anything else Phong), and the keys read into that type.

use super::diag::DocPath;
use super::load::Builder;
use crate::bsdf::ConductorFresnel;
use crate::material::conductor::Conductor;
use crate::material::dielectric::Dielectric;
use crate::material::plastic::Plastic;
use crate::material::{ColorParam, Emission, Material, Scalar, Surface, thin};
use crate::math::Color;
use crate::mesh_file::MtlMaterial;
use crate::texture::{ColorSpace, Mapping, Pattern, Texture, Wraps};

/// The type an MTL material becomes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum MtlType {
    /// `Pm` 0.5 or more: a metal of the colour, GGX alpha given.
    Metal(f32),
    /// `illum` 6 or 7 with some transparency: glass of alpha given.
    Glass(f32),
    /// `illum` 4 or 9 with some transparency: a thin pane.
    Pane,
    /// `illum 5`, or `Pr` on an opaque material: the colour under a clear coat of alpha given.
    Plastic(f32),
    /// Everything else: the Phong terms.
    Phong,
}

/// How much light `m` lets through: `1 - d`, or for the glass models (`illum` 4, 6, 7, 9)
/// without a `d`, the largest component of `Tf`.
fn transparency(m: &MtlMaterial) -> f32 {
    let t = (1.0 - m.d.unwrap_or(1.0)).clamp(0.0, 1.0);
    if t == 0.0 && matches!(m.illum.unwrap_or(2), 4 | 6 | 7 | 9) {
        return m.tf.map_or(0.0, |t| {
            t.into_iter().fold(0.0f32, f32::max).clamp(0.0, 1.0)
        });
    }
    t
}

/// The roughness of `m`: `Pr`, else from `Ns` (see [`mtl_roughness`]).
fn roughness(m: &MtlMaterial) -> f32 {
    m.pr.filter(|r| r.is_finite())
        .map_or_else(|| mtl_roughness(m.ns), |r| r.clamp(0.0, 1.0))
}

fn mtl_type(m: &MtlMaterial) -> MtlType {
    // Roughness is perceptual, as in Blender's Principled BSDF: GGX alpha is its square.
    let alpha = roughness(m).powi(2);
    let illum = m.illum.unwrap_or(2);
    let see_through = transparency(m) > 0.0;
    if m.pm.is_some_and(|pm| pm >= 0.5) {
        MtlType::Metal(alpha)
    } else if see_through && matches!(illum, 6 | 7) {
        // A glass model with no `Pr` is smooth: `Ns` there is only the highlight's width.
        MtlType::Glass(m.pr.map_or(0.0, |_| alpha))
    } else if see_through && matches!(illum, 4 | 9) {
        MtlType::Pane
    } else if !see_through && (illum == 5 || m.pr.is_some()) {
        MtlType::Plastic(alpha)
    } else {
        MtlType::Phong
    }
}

impl Builder<'_> {
    /// A material from an MTL file (see the module's documentation).
    pub(super) fn mtl_material(
        &mut self,
        m: &MtlMaterial,
        path: &DocPath,
        textures: &mut Vec<Texture>,
    ) -> Material {
        let rgb = |c: [f32; 3]| Color::from(c).clamp(Color::ZERO, Color::splat(1e6));
        let illum = m.illum.unwrap_or(2);
        let transparency = transparency(m);
        let kind = mtl_type(m);
        let kd = m.kd.map_or(Color::splat(0.8), rgb);
        let clear = matches!(kind, MtlType::Glass(_) | MtlType::Pane);
        if let Some(file) = &m.map_kd
            && !clear
        {
            self.files.push(file.clone());
        }
        let pattern = match &m.map_kd {
            // Clear glass: `Tf` colours only Phong's see-through materials.
            _ if clear => Pattern::Solid(Color::ONE),
            Some(file) => match self.image(file, ColorSpace::Srgb, true) {
                Ok(img) => Pattern::Image(img),
                Err(e) => {
                    self.error_help(
                        path.clone(),
                        format!("material `{}`: cannot load map_Kd: {e}", m.name),
                        "map_Kd paths are relative to the MTL file's folder",
                    );
                    Pattern::Solid(kd)
                }
            },
            None if transparency > 0.0 => Pattern::Solid(m.tf.map_or(Color::ONE, rgb)),
            None => Pattern::Solid(kd),
        };
        textures.push(Texture {
            pattern,
            mapping: Mapping::Uv,
            wrap: Wraps::REPEAT,
        });
        let texture = textures.len() - 1;
        let emission =
            m.ke.map(rgb)
                .filter(|e| e.max_element() > 0.0)
                .map(|radiance| Emission {
                    radiance: ColorParam::Value(radiance),
                    two_sided: false,
                });
        let ior = m.ni.filter(|n| *n > 0.0 && n.is_finite()).unwrap_or(1.5);
        match kind {
            MtlType::Metal(alpha) => Conductor {
                fresnel: ConductorFresnel::One,
                index: None,
                roughness: Scalar::Value(alpha),
            }
            .material(texture, kd.min(Color::ONE), alpha, emission),
            MtlType::Glass(alpha) => Dielectric {
                roughness: Scalar::Value(alpha),
            }
            .material(texture, ior, Color::ZERO, alpha, emission),
            MtlType::Pane => thin::material(texture, ior, emission),
            MtlType::Plastic(alpha) => Plastic::fresnel_coat(Scalar::Value(alpha), ior)
                .material(texture, ior, alpha, emission),
            MtlType::Phong => {
                let highlight = !matches!(illum, 0 | 1);
                let ks = m.ks.map_or(Color::ZERO, rgb);
                let (shininess, highlight_weight) = mtl_highlight(m.ns);
                let mut out = Material::base(texture, Surface::Phong, emission);
                out.terms.diffuse = if illum == 0 { 0.0 } else { 1.0 };
                out.terms.specular = if highlight {
                    ks * highlight_weight
                } else {
                    Color::ZERO
                };
                out.terms.shininess = shininess;
                out.terms.reflectivity = if illum == 3 {
                    ks.max_element().clamp(0.0, 1.0)
                } else {
                    0.0
                };
                out.terms.transparency = transparency;
                out.ior = ior;
                out
            }
        }
    }
}

/// The roughness an MTL file's specular exponent `Ns` stands for, as Blender's OBJ importer
/// reads it: `1 - sqrt(Ns / 1000)`, so `Ns 0` (which 3ds Max writes beside `Ks 0.9`) is fully
/// rough and `Ns 1000` a mirror-like polish. A file without `Ns` gets roughness 0.5,
/// Blender's default (`Ns 250`).
pub(super) fn mtl_roughness(ns: Option<f32>) -> f32 {
    let ns = ns.filter(|n| n.is_finite()).unwrap_or(250.0);
    1.0 - (ns.clamp(0.0, 1000.0) / 1000.0).sqrt()
}

/// The Phong highlight of an MTL material: the exponent `Ns` (at least 1), and the weight of
/// `Ks`, `1 - roughness`, so that a rough surface shows no highlight instead of the constant
/// sheen an exponent of 0 gives over the whole lit side.
fn mtl_highlight(ns: Option<f32>) -> (f32, f32) {
    let exponent = ns.filter(|n| n.is_finite()).unwrap_or(250.0);
    (exponent.clamp(1.0, 10_000.0), 1.0 - mtl_roughness(ns))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mtl_shininess_maps_to_roughness_as_blender_reads_it() {
        assert_eq!(mtl_roughness(Some(0.0)), 1.0);
        assert_eq!(mtl_roughness(Some(1000.0)), 0.0);
        assert_eq!(mtl_roughness(Some(5000.0)), 0.0);
        assert!((mtl_roughness(Some(250.0)) - 0.5).abs() < 1e-6);
        assert!((mtl_roughness(None) - 0.5).abs() < 1e-6);
        assert_eq!(mtl_roughness(Some(-3.0)), 1.0);
        // 3ds Max's `Ks 0.9` with `Ns 0`: no highlight at all.
        assert_eq!(mtl_highlight(Some(0.0)), (1.0, 0.0));
        let (n, w) = mtl_highlight(Some(96.0));
        assert_eq!(n, 96.0);
        assert!((w - (0.096f32).sqrt()).abs() < 1e-6);
    }

    fn mtl(f: impl FnOnce(&mut MtlMaterial)) -> MtlMaterial {
        let mut m = MtlMaterial::default();
        f(&mut m);
        m
    }

    /// Each MTL type is chosen by the keys docs/scene-format.md names, `Pm` first.
    #[test]
    fn the_type_follows_what_the_file_says() {
        assert_eq!(mtl_type(&mtl(|_| {})), MtlType::Phong);
        assert_eq!(mtl_type(&mtl(|m| m.illum = Some(3))), MtlType::Phong);
        // Metal: roughness 0.4 is alpha 0.16.
        let metal = mtl_type(&mtl(|m| (m.pm, m.pr) = (Some(1.0), Some(0.4))));
        assert!(matches!(metal, MtlType::Metal(a) if (a - 0.16).abs() < 1e-6));
        assert_eq!(mtl_type(&mtl(|m| m.pm = Some(0.2))), MtlType::Phong);
        // Metal wins over glass.
        let gold_glass = mtl(|m| (m.pm, m.illum, m.d) = (Some(1.0), Some(7), Some(0.0)));
        assert!(matches!(mtl_type(&gold_glass), MtlType::Metal(_)));
        // Glass by `d` or by `Tf`; smooth unless `Pr` says otherwise.
        assert_eq!(
            mtl_type(&mtl(|m| (m.illum, m.d) = (Some(7), Some(0.1)))),
            MtlType::Glass(0.0)
        );
        assert_eq!(
            mtl_type(&mtl(
                |m| (m.illum, m.tf, m.ns) = (Some(6), Some([0.9; 3]), Some(0.0))
            )),
            MtlType::Glass(0.0)
        );
        let rough_glass = mtl(|m| (m.illum, m.d, m.pr) = (Some(7), Some(0.0), Some(0.5)));
        assert_eq!(mtl_type(&rough_glass), MtlType::Glass(0.25));
        // An opaque illum 7 is not glass.
        assert_eq!(mtl_type(&mtl(|m| m.illum = Some(7))), MtlType::Phong);
        assert_eq!(
            mtl_type(&mtl(|m| (m.illum, m.d) = (Some(4), Some(0.5)))),
            MtlType::Pane
        );
        // Plastic: illum 5 takes its roughness from Ns, Pr from Pr.
        assert_eq!(
            mtl_type(&mtl(|m| (m.illum, m.ns) = (Some(5), Some(1000.0)))),
            MtlType::Plastic(0.0)
        );
        assert_eq!(mtl_type(&mtl(|m| m.pr = Some(1.0))), MtlType::Plastic(1.0));
        // A see-through material with `Pr` stays Phong (dissolve is not a coat).
        assert_eq!(
            mtl_type(&mtl(|m| (m.pr, m.d) = (Some(0.5), Some(0.5)))),
            MtlType::Phong
        );
    }
}
