//! A glTF file's metallic-roughness materials as far as snell reads them: factors, the maps
//! (base colour, metallic-roughness, normal, emissive) with their uv sets and
//! KHR_texture_transform, alpha modes, and the KHR_materials extensions snell knows.

/// A texture a material reads: its image, its uv set, and KHR_texture_transform's.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureRef {
    /// Index into [`super::GltfScene::images`].
    pub image: usize,
    /// Which texture coordinates it reads (0 or 1).
    pub texcoord: u32,
    /// KHR_texture_transform as `uv' = m[0] u + m[1] v + m[2]` (glTF's uv, `v` down the
    /// image, as snell's), or `None`.
    pub transform: Option<[[f32; 2]; 3]>,
    /// The sampler's wrap modes (glTF's default: repeat).
    pub wrap: crate::texture::Wraps,
}

/// A glTF sampler's wrap modes.
fn wraps(t: &gltf::Texture) -> crate::texture::Wraps {
    use crate::texture::Wrap;
    use gltf::texture::WrappingMode as W;
    let mode = |m: W| match m {
        W::ClampToEdge => Wrap::Clamp,
        W::MirroredRepeat => Wrap::Mirror,
        W::Repeat => Wrap::Repeat,
    };
    let s = t.sampler();
    crate::texture::Wraps {
        u: mode(s.wrap_s()),
        v: mode(s.wrap_t()),
    }
}

/// How a material's alpha is read (glTF's `alphaMode`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Alpha {
    /// Alpha is ignored.
    Opaque,
    /// Alpha below the cutoff is a hole.
    Mask(f32),
    /// Alpha blends the surface with what lies behind it.
    Blend,
}

/// A metallic-roughness material, as far as snell reads it.
#[derive(Clone, Debug, PartialEq)]
pub struct PbrMaterial {
    /// Its name, or `material N`.
    pub name: String,
    /// Linear RGBA.
    pub base_color: [f32; 4],
    /// The base colour's image (sRGB), if any.
    pub base_color_texture: Option<TextureRef>,
    /// 0 dielectric, 1 metal.
    pub metallic: f32,
    /// Perceptual roughness (GGX alpha is its square).
    pub roughness: f32,
    /// The metallic (blue) and roughness (green) image (linear), if any: factors on
    /// `metallic` and `roughness`.
    pub metallic_roughness_texture: Option<TextureRef>,
    /// The tangent-space normal map (linear), if any.
    pub normal_texture: Option<TextureRef>,
    /// Factor on the normal map's x and y.
    pub normal_scale: f32,
    /// Emitted radiance, linear RGB (the factor times KHR_materials_emissive_strength).
    pub emissive: [f32; 3],
    /// The emissive image (sRGB), if any, times `emissive`.
    pub emissive_texture: Option<TextureRef>,
    /// KHR_materials_transmission's factor.
    pub transmission: f32,
    /// KHR_materials_ior's, 1.5 by default.
    pub ior: f32,
    /// Whether the back side is shaded too.
    pub double_sided: bool,
    /// `alphaMode` (with `alphaCutoff`).
    pub alpha: Alpha,
}

impl Default for PbrMaterial {
    /// glTF's default material: white, fully metallic and fully rough.
    fn default() -> Self {
        PbrMaterial {
            name: "default".into(),
            base_color: [1.0; 4],
            base_color_texture: None,
            metallic: 1.0,
            roughness: 1.0,
            metallic_roughness_texture: None,
            normal_texture: None,
            normal_scale: 1.0,
            emissive: [0.0; 3],
            emissive_texture: None,
            transmission: 0.0,
            ior: 1.5,
            double_sided: false,
            alpha: Alpha::Opaque,
        }
    }
}

impl PbrMaterial {
    /// The textures it reads.
    pub fn textures(&self) -> impl Iterator<Item = &TextureRef> {
        [
            &self.base_color_texture,
            &self.metallic_roughness_texture,
            &self.normal_texture,
            &self.emissive_texture,
        ]
        .into_iter()
        .flatten()
    }
}

/// What snell reads of material `m`.
pub(super) fn read(m: &gltf::Material) -> PbrMaterial {
    let pbr = m.pbr_metallic_roughness();
    let strength = m.emissive_strength().unwrap_or(1.0);
    let info = |i: gltf::texture::Info| {
        let t = i.texture_transform();
        TextureRef {
            image: i.texture().source().index(),
            texcoord: t
                .as_ref()
                .and_then(|t| t.tex_coord())
                .unwrap_or(i.tex_coord()),
            transform: t.map(|t| uv_transform(t.offset(), t.rotation(), t.scale())),
            wrap: wraps(&i.texture()),
        }
    };
    let normal = m.normal_texture();
    PbrMaterial {
        name: m.name().map_or_else(
            || format!("material {}", m.index().unwrap_or(0)),
            str::to_string,
        ),
        base_color: pbr.base_color_factor(),
        base_color_texture: pbr.base_color_texture().map(info),
        metallic: pbr.metallic_factor(),
        roughness: pbr.roughness_factor(),
        metallic_roughness_texture: pbr.metallic_roughness_texture().map(info),
        normal_scale: normal.as_ref().map_or(1.0, |n| n.scale()),
        normal_texture: normal.map(|n| {
            let transform = n.extension_value("KHR_texture_transform");
            TextureRef {
                image: n.texture().source().index(),
                // The extension's texCoord, where given, overrides the texture's own.
                texcoord: transform
                    .and_then(|v| v.get("texCoord")?.as_u64())
                    .map_or(n.tex_coord(), |t| t.min(u32::MAX as u64) as u32),
                transform: json_transform(transform),
                wrap: wraps(&n.texture()),
            }
        }),
        emissive: m.emissive_factor().map(|e| e * strength),
        emissive_texture: m.emissive_texture().map(info),
        transmission: m.transmission().map_or(0.0, |t| t.transmission_factor()),
        ior: m.ior().unwrap_or(1.5),
        double_sided: m.double_sided(),
        alpha: match m.alpha_mode() {
            gltf::material::AlphaMode::Opaque => Alpha::Opaque,
            gltf::material::AlphaMode::Mask => Alpha::Mask(m.alpha_cutoff().unwrap_or(0.5)),
            gltf::material::AlphaMode::Blend => Alpha::Blend,
        },
    }
}

/// KHR_texture_transform's offset, rotation (radians, counter-clockwise) and scale as a
/// matrix on uv: scale, then rotate, then offset, as the extension composes them.
pub fn uv_transform(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> [[f32; 2]; 3] {
    let (s, c) = rotation.sin_cos();
    // u' = c su u + s sv v + ou;  v' = -s su u + c sv v + ov.
    [
        [c * scale[0], -s * scale[0]],
        [s * scale[1], c * scale[1]],
        offset,
    ]
}

/// KHR_texture_transform read from a texture's extension JSON (the `gltf` crate reads it
/// only for plain texture references, not a normal map's).
fn json_transform(v: Option<&gltf::json::Value>) -> Option<[[f32; 2]; 3]> {
    let v = v?;
    let pair = |key: &str, default: [f32; 2]| {
        v.get(key)
            .and_then(|a| a.as_array())
            .filter(|a| a.len() == 2)
            .and_then(|a| Some([a[0].as_f64()? as f32, a[1].as_f64()? as f32]))
            .unwrap_or(default)
    };
    let rotation = v.get("rotation").and_then(|r| r.as_f64()).unwrap_or(0.0) as f32;
    Some(uv_transform(
        pair("offset", [0.0, 0.0]),
        rotation,
        pair("scale", [1.0, 1.0]),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// KHR_texture_transform scales, then rotates counter-clockwise, then offsets.
    #[test]
    fn texture_transforms_scale_then_rotate_then_offset() {
        let apply = |m: [[f32; 2]; 3], u: f32, v: f32| {
            [
                m[0][0] * u + m[1][0] * v + m[2][0],
                m[0][1] * u + m[1][1] * v + m[2][1],
            ]
        };
        let close =
            |a: [f32; 2], b: [f32; 2]| (a[0] - b[0]).abs() < 1e-6 && (a[1] - b[1]).abs() < 1e-6;
        let m = uv_transform([0.0, 0.0], std::f32::consts::FRAC_PI_2, [2.0, 3.0]);
        assert!(
            close(apply(m, 1.0, 0.0), [0.0, -2.0]),
            "{:?}",
            apply(m, 1.0, 0.0)
        );
        assert!(
            close(apply(m, 0.0, 1.0), [3.0, 0.0]),
            "{:?}",
            apply(m, 0.0, 1.0)
        );
        // The extension's own example: the lower left quadrant, turned a quarter.
        let m = uv_transform([0.0, 1.0], std::f32::consts::FRAC_PI_2, [0.5, 0.5]);
        assert!(close(apply(m, 0.0, 0.0), [0.0, 1.0]));
        assert!(close(apply(m, 1.0, 0.0), [0.0, 0.5]));
        assert!(close(apply(m, 0.0, 1.0), [0.5, 1.0]));
        assert!(close(apply(m, 1.0, 1.0), [0.5, 0.5]));
        // A normal map's transform read from its JSON.
        let json: gltf::json::Value =
            serde_json::from_str(r#"{"offset": [0.25, 0], "scale": [2, 2]}"#).unwrap();
        let m = json_transform(Some(&json)).unwrap();
        assert!(close(apply(m, 0.5, 0.5), [1.25, 1.0]));
        assert_eq!(json_transform(None), None);
    }
}
