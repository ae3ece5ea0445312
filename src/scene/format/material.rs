//! `[materials.NAME]`: one table for every type of material, its `type` saying how the
//! keys are read. Which keys each type takes is checked when the scene is built (a key
//! another type reads is an error at its line), so the file stays one plain table that
//! TOML, JSON and the schema all read alike.

use super::{ColorDef, ColorParamDef, ScalarDef};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The types of material. docs/scene-format.md says how each is read by each integrator.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum MaterialKind {
    /// The seed report's Phong terms (the default): ambient, diffuse, a highlight, mirror
    /// reflection and refraction by weight. The path tracer reads it as a documented mix of
    /// diffuse, plastic, mirror and glass.
    #[default]
    Phong,
    /// Lambertian: the same radiance seen from every direction.
    Diffuse,
    /// A metal, smooth or rough (GGX), from a named metal's measured index or `eta` and `k`.
    Conductor,
    /// Glass or water, smooth or rough, with Beer-Lambert absorption inside.
    Dielectric,
    /// A thin pane of glass: reflects and lets light through without bending it.
    Thin,
    /// A diffuse base under a clear dielectric coat, smooth or rough.
    Plastic,
    /// glTF's metallic-roughness material: a metal and a plastic of one colour and one
    /// roughness, blended by `metallic` (a number or a texture, point by point).
    Metallic,
}

impl MaterialKind {
    /// The name the file gives the type.
    pub fn name(self) -> &'static str {
        match self {
            MaterialKind::Phong => "phong",
            MaterialKind::Diffuse => "diffuse",
            MaterialKind::Conductor => "conductor",
            MaterialKind::Dielectric => "dielectric",
            MaterialKind::Thin => "thin",
            MaterialKind::Plastic => "plastic",
            MaterialKind::Metallic => "metallic",
        }
    }

    /// All types, in the order the documentation gives them.
    pub const ALL: [MaterialKind; 7] = [
        MaterialKind::Phong,
        MaterialKind::Diffuse,
        MaterialKind::Conductor,
        MaterialKind::Dielectric,
        MaterialKind::Thin,
        MaterialKind::Plastic,
        MaterialKind::Metallic,
    ];
}

/// `[materials.NAME]`.
#[derive(Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialDef {
    /// How the other keys are read: `phong` (default), `diffuse`, `conductor`,
    /// `dielectric`, `thin`, `plastic` or `metallic`.
    #[serde(rename = "type", default)]
    pub kind: MaterialKind,
    /// Surface colour, linear RGB (or use `texture`): the Phong colour, the diffuse
    /// reflectance of `diffuse` and `plastic`, a tint on a `conductor`'s reflection, the
    /// base colour of `metallic`. Default 1.
    pub color: Option<ColorDef>,
    /// Name of a texture giving `color`.
    pub texture: Option<String>,
    /// Phong: ambient coefficient (default 1), a number or a texture's name.
    pub ambient: Option<ScalarDef>,
    /// Phong: diffuse coefficient (default 0.8), a number or a texture's name.
    pub diffuse: Option<ScalarDef>,
    /// Phong: highlight colour (default 0, none), a colour or a texture's name.
    pub specular: Option<ColorParamDef>,
    /// Phong: highlight exponent, larger is sharper (default 50), a number or a texture's
    /// name.
    pub shininess: Option<ScalarDef>,
    /// Phong: mirror weight in [0, 1] (default 0), a number or a texture's name.
    pub reflectivity: Option<ScalarDef>,
    /// Phong: transmitted fraction in [0, 1] (default 0), a number or a texture's name.
    pub transparency: Option<ScalarDef>,
    /// Index of refraction of the inside (phong, dielectric, thin) or of the coat
    /// (plastic, metallic); default 1.5. A number, a named glass (`"BK7"`, `"fused silica"`,
    /// `"SF11"`, `"diamond"`, `"water"`) or a formula in wavelength (`{ cauchy = [a, b] }`,
    /// `{ sellmeier = [B1, B2, B3, C1, C2, C3] }`, b and C in µm²): a phong or dielectric
    /// material with a glass or a formula disperses light; the others take its index at
    /// 587.6 nm. Not textured: it belongs to the solid, not to a point of its surface.
    pub ior: Option<super::IorDef>,
    /// Beer-Lambert absorption per scene unit travelled inside, per channel (phong,
    /// dielectric); default 0. A colour: it belongs to the solid's inside.
    pub absorption: Option<ColorDef>,
    /// GGX roughness alpha (Mitsuba's `alpha`; Blender's roughness r is alpha = r^2), a
    /// number or the name of a texture (its mean of r, g, b): 0 is smooth (conductor,
    /// dielectric, plastic, metallic; default 0).
    pub roughness: Option<ScalarDef>,
    /// Metallic: the metal's share, 0 (plastic) to 1 (metal), a number or the name of a
    /// texture (its mean of r, g, b, kept to 0..1); default 1, as glTF's.
    pub metallic: Option<ScalarDef>,
    /// Conductor: a named metal, `Au`, `Ag`, `Cu` or `Al` (or give `eta` and `k`; with
    /// neither the conductor is a perfect mirror).
    pub metal: Option<String>,
    /// Conductor: real part of the complex index of refraction, per channel, a colour or
    /// a texture's name.
    pub eta: Option<ColorParamDef>,
    /// Conductor: imaginary part (extinction) of the index, per channel, a colour or a
    /// texture's name.
    pub k: Option<ColorParamDef>,
    /// Light the surface gives off, linear RGB radiance (any type; default none), a colour
    /// or a texture's name. An emitting shape is an area light to the path tracer.
    pub emission: Option<ColorParamDef>,
    /// Whether `emission` leaves both sides (default: the front side only).
    pub two_sided: Option<bool>,
    /// Name of a texture holding a tangent-space normal map (any type; read as linear data
    /// unless the texture says `color_space`).
    pub normal_map: Option<String>,
    /// Factor on the normal map's tangent components (default 1; 0 flattens it).
    pub normal_scale: Option<f32>,
    /// Name of a texture holding a bump (height) map (any type; the mean of r, g, b is the
    /// height; read as linear data unless the texture says `color_space`).
    pub bump: Option<String>,
    /// Scene units of height per unit of the bump map's value (default 1).
    pub bump_height: Option<f32>,
}

/// A key of [`MaterialDef`], for checking which type reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaterialKey {
    /// `color` or `texture`.
    Color,
    /// Phong's own terms.
    Phong,
    /// `ior`.
    Ior,
    /// `absorption`.
    Absorption,
    /// `roughness`.
    Roughness,
    /// `metal`, `eta`, `k`.
    Metal,
    /// `metallic`.
    Metallic,
}

impl MaterialKind {
    /// Whether this type reads keys of the kind `key`.
    pub fn reads(self, key: MaterialKey) -> bool {
        use MaterialKey as K;
        use MaterialKind as M;
        match key {
            K::Color => matches!(
                self,
                M::Phong | M::Diffuse | M::Conductor | M::Plastic | M::Metallic
            ),
            K::Phong => self == M::Phong,
            K::Ior => matches!(
                self,
                M::Phong | M::Dielectric | M::Thin | M::Plastic | M::Metallic
            ),
            K::Absorption => matches!(self, M::Phong | M::Dielectric),
            K::Roughness => matches!(
                self,
                M::Conductor | M::Dielectric | M::Plastic | M::Metallic
            ),
            K::Metal => self == M::Conductor,
            K::Metallic => self == M::Metallic,
        }
    }
}

impl MaterialDef {
    /// The keys given, each with its kind, as the file spells them.
    pub fn given(&self) -> Vec<(&'static str, MaterialKey)> {
        use MaterialKey as K;
        let mut out = vec![];
        let mut add = |given: bool, name, key| {
            if given {
                out.push((name, key));
            }
        };
        add(self.color.is_some(), "color", K::Color);
        add(self.texture.is_some(), "texture", K::Color);
        add(self.ambient.is_some(), "ambient", K::Phong);
        add(self.diffuse.is_some(), "diffuse", K::Phong);
        add(self.specular.is_some(), "specular", K::Phong);
        add(self.shininess.is_some(), "shininess", K::Phong);
        add(self.reflectivity.is_some(), "reflectivity", K::Phong);
        add(self.transparency.is_some(), "transparency", K::Phong);
        add(self.ior.is_some(), "ior", K::Ior);
        add(self.absorption.is_some(), "absorption", K::Absorption);
        add(self.roughness.is_some(), "roughness", K::Roughness);
        add(self.metal.is_some(), "metal", K::Metal);
        add(self.eta.is_some(), "eta", K::Metal);
        add(self.k.is_some(), "k", K::Metal);
        add(self.metallic.is_some(), "metallic", K::Metallic);
        out
    }
}
