//! `[textures.NAME]` to a [`Texture`]: a solid colour, an image file (loaded in the colour
//! space its use implies), or a pattern, each with the mapping that gives it texture
//! coordinates.

use super::Builder;
use crate::math::{Color, Frame, Transform, Vec3, Vec3A};
use crate::scene::diag::DocPath;
use crate::scene::format::{ColorSpaceDef, MappingDef, TextureDef, WrapDef};
use crate::texture::{ColorSpace, Mapping, Pattern, Texture, Wrap, Wraps};

impl Builder<'_> {
    fn mapping(&mut self, d: &MappingDef, path: &DocPath) -> Mapping {
        match d {
            MappingDef::Uv {} => Mapping::Uv,
            MappingDef::Spherical { center, rotate } => {
                let center = center.map(|c| self.point(c, &path.key("center")));
                let r = self.point(*rotate, &path.key("rotate"));
                let rotation = (r != Vec3A::ZERO).then(|| Transform::rotation(Vec3::from(r)));
                Mapping::Spherical { center, rotation }
            }
            MappingDef::Cylindrical {
                center,
                axis,
                height,
            } => Mapping::Cylindrical {
                center: center.map(|c| self.point(c, &path.key("center"))),
                frame: Frame::from_axis(self.direction(*axis, &path.key("axis"))),
                height: self.positive(*height, &path.key("height")),
            },
            MappingDef::Planar { origin, u, v } => {
                let origin = self.point(*origin, &path.key("origin"));
                let u_axis = self.point(*u, &path.key("u"));
                let v_axis = self.point(*v, &path.key("v"));
                if u_axis.cross(v_axis).length_squared() == 0.0 {
                    self.error(
                        path.key("v"),
                        "the u and v axes must be non-zero and not parallel",
                    );
                }
                Mapping::planar(origin, u_axis, v_axis)
            }
        }
    }

    /// A texture; `data` says a material reads it as a normal or bump map, which an image
    /// without a `color_space` is then read as (linear).
    pub(super) fn texture(&mut self, d: &TextureDef, path: &DocPath, data: bool) -> Texture {
        match d {
            TextureDef::Solid { color } => Texture::solid(self.color(*color, &path.key("color"))),
            TextureDef::Image {
                file,
                color_space,
                wrap,
                mapping,
            } => {
                let mapping = self.mapping(mapping, &path.key("mapping"));
                let full = self.base_dir.join(file);
                self.files.push(full.clone());
                let space = match color_space {
                    Some(ColorSpaceDef::Srgb) => ColorSpace::Srgb,
                    Some(ColorSpaceDef::Linear) => ColorSpace::Linear,
                    None if data => ColorSpace::Linear,
                    None => ColorSpace::Srgb,
                };
                let pattern = match self.image(&full, space, true) {
                    Ok(img) => Pattern::Image(img),
                    Err(e) => {
                        self.error_help(
                            path.key("file"),
                            format!("cannot load texture: {e}"),
                            "paths are relative to the scene file's folder; PNG, JPEG, BMP and OpenEXR are supported",
                        );
                        Pattern::Solid(Color::ONE)
                    }
                };
                let wrap = match wrap {
                    WrapDef::Repeat => Wrap::Repeat,
                    WrapDef::Clamp => Wrap::Clamp,
                    WrapDef::Mirror => Wrap::Mirror,
                };
                Texture {
                    pattern,
                    mapping,
                    wrap: Wraps::both(wrap),
                }
            }
            TextureDef::Checker {
                even,
                odd,
                size,
                mapping,
            } => Texture {
                pattern: Pattern::Checker(crate::texture::Checker {
                    even: self.color(*even, &path.key("even")),
                    odd: self.color(*odd, &path.key("odd")),
                    size: self.positive(*size, &path.key("size")),
                }),
                mapping: self.mapping(mapping, &path.key("mapping")),
                wrap: Wraps::REPEAT,
            },
            TextureDef::Stripes {
                a,
                b,
                width,
                mapping,
            } => Texture {
                pattern: Pattern::Stripes(crate::texture::Stripes {
                    a: self.color(*a, &path.key("a")),
                    b: self.color(*b, &path.key("b")),
                    width: self.positive(*width, &path.key("width")),
                }),
                mapping: self.mapping(mapping, &path.key("mapping")),
                wrap: Wraps::REPEAT,
            },
        }
    }
}
