//! `[textures.NAME]`: a solid colour, an image file or a pattern, its colour space, its wrap
//! and the mapping that gives it texture coordinates.

use super::*;

/// `[textures.NAME]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum TextureDef {
    /// One colour.
    Solid {
        /// The colour.
        color: ColorDef,
    },
    /// An image file.
    Image {
        /// Path, relative to the scene file's folder.
        file: String,
        /// How to decode its values (default: `srgb`, or `linear` for a texture a material
        /// uses as a normal or bump map).
        #[serde(default)]
        color_space: Option<ColorSpaceDef>,
        /// What it shows outside `[0, 1]` on both axes: `repeat` (the default), `clamp`
        /// (its edges stretched) or `mirror`.
        #[serde(default)]
        wrap: WrapDef,
        /// How points of the surface get texture coordinates (default: the shape's own uv).
        #[serde(default)]
        mapping: MappingDef,
    },
    /// A checkerboard.
    Checker {
        /// Colour where the cell index sum is even.
        #[serde(default = "white")]
        even: ColorDef,
        /// Colour where it is odd.
        #[serde(default = "black")]
        odd: ColorDef,
        /// Cell side in texture units.
        #[serde(default = "one")]
        size: f32,
        /// How points of the surface get texture coordinates (default: the shape's own uv).
        #[serde(default)]
        mapping: MappingDef,
    },
    /// Stripes across u.
    Stripes {
        /// Colour of even bands.
        #[serde(default = "white")]
        a: ColorDef,
        /// Colour of odd bands.
        #[serde(default = "black")]
        b: ColorDef,
        /// Band width in texture units.
        #[serde(default = "one")]
        width: f32,
        /// How points of the surface get texture coordinates (default: the shape's own uv).
        #[serde(default)]
        mapping: MappingDef,
    },
}

/// Colour space of image files.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ColorSpaceDef {
    /// sRGB-encoded.
    #[default]
    Srgb,
    /// Linear values.
    Linear,
}

/// An image texture's `wrap`.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum WrapDef {
    /// The image again, and again.
    #[default]
    Repeat,
    /// The edge texels, stretched.
    Clamp,
    /// The image mirrored every other time.
    Mirror,
}

/// `mapping = { type = "...", ... }`.
#[derive(Debug, Deserialize, Serialize, JsonSchema)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum MappingDef {
    /// The shape's own uv.
    // `{}`, not a unit variant: serde lets other keys through beside the tag of a unit
    // variant, even with deny_unknown_fields.
    Uv {},
    /// Equirectangular around a centre.
    Spherical {
        /// Centre in object space (default: the object's centre).
        center: Option<V3>,
        /// Rotation of the texture, degrees about x, y, z.
        #[serde(default)]
        rotate: V3,
    },
    /// Around an axis.
    Cylindrical {
        /// A point on the axis (default: the object's centre).
        center: Option<V3>,
        /// Axis direction.
        #[serde(default = "y_axis")]
        axis: V3,
        /// Length along the axis one image spans.
        #[serde(default = "one")]
        height: f32,
    },
    /// Onto a plane.
    Planar {
        /// Where uv is (0, 0).
        #[serde(default)]
        origin: V3,
        /// u axis.
        #[serde(default = "x_axis")]
        u: V3,
        /// v axis.
        #[serde(default = "z_axis")]
        v: V3,
    },
}

impl Default for MappingDef {
    fn default() -> Self {
        MappingDef::Uv {}
    }
}
