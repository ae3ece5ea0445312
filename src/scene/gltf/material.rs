//! glTF's metallic-roughness materials as snell's, as docs/scene-format.md sets out:
//! KHR_materials_transmission of 0.5 or more makes glass (of KHR_materials_ior, 1.5 by
//! default); metallic 1 (the factor times the metallic map's blue channel, the same
//! everywhere) a metal of the base colour; metallic 0 the base colour under a clear coat
//! (snell's `plastic`, as glTF's dielectric is a diffuse base under a GGX specular layer of
//! IOR 1.5); anything between (a factor such as 0.3, a map of metal and dielectric areas)
//! their blend by the metallic value point by point ([`Metallic`]). Roughness is
//! perceptual (GGX alpha is its square), from the factor times the map's green channel
//! point by point. The normal map bends the shading normal; the emissive factor (times
//! KHR_materials_emissive_strength, times the emissive map) makes an emitter. Each map is
//! read through its own uv transform (KHR_texture_transform). `alphaMode` `MASK` and
//! `BLEND` cut holes where the base colour's alpha (factor times image) says (see
//! [`Cutout`]).

use crate::bsdf::ConductorFresnel;
use crate::material::conductor::Conductor;
use crate::material::cutout::Cutout;
use crate::material::detail::SurfaceDetail;
use crate::material::dielectric::Dielectric;
use crate::material::metallic::Metallic;
use crate::material::plastic::Plastic;
use crate::material::{ColorParam, Emission, Material, Scalar};
use crate::math::{Color, Vec2};
use crate::mesh_file::gltf::{Alpha, PbrMaterial, TextureRef};
use crate::texture::{ColorSpace, ImageData, Mapping, Pattern, Texture, Wraps};
use std::collections::HashMap;
use std::sync::Arc;

/// The snell material type a glTF material becomes, or, where it is partly metal, whose
/// Phong terms Whitted reads (the path tracer blends the two point by point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::scene) enum PbrType {
    /// See-through: glass.
    Glass,
    /// Metallic (on the whole): a metal of the base colour.
    Metal,
    /// Otherwise: the base colour under a clear coat.
    Plastic,
}

/// Which type `m` becomes, its metallic factor times `metallic_mean` (the metallic map's
/// mean, 1 without one).
pub(in crate::scene) fn pbr_type(m: &PbrMaterial, metallic_mean: f32) -> PbrType {
    if m.transmission >= 0.5 {
        PbrType::Glass
    } else if m.metallic * metallic_mean >= 0.5 {
        PbrType::Metal
    } else {
        PbrType::Plastic
    }
}

/// A glTF file's decoded images, made into snell's images as each use reads them: colour
/// (sRGB) or data (linear), each made once.
pub(in crate::scene) struct Images {
    raw: Vec<Option<::image::DynamicImage>>,
    made: HashMap<(usize, bool), Arc<ImageData>>,
}

impl Images {
    /// The file's images, by glTF index (`None` for those no used material reads).
    pub fn new(raw: Vec<Option<::image::DynamicImage>>) -> Self {
        Images {
            raw,
            made: HashMap::new(),
        }
    }

    /// The alpha channel of image `i` times `factor`, as data in every channel; `None` for
    /// an image without alpha.
    fn alpha(&mut self, i: usize, factor: f32) -> Option<Arc<ImageData>> {
        let raw = self.raw.get(i)?.as_ref()?;
        if !raw.color().has_alpha() {
            return None;
        }
        let rgba = raw.to_rgba32f();
        let out = ::image::Rgb32FImage::from_fn(rgba.width(), rgba.height(), |x, y| {
            ::image::Rgb([rgba.get_pixel(x, y)[3] * factor; 3])
        });
        Some(Arc::new(
            ImageData::from_owned(::image::DynamicImage::ImageRgb32F(out), ColorSpace::Linear)
                .with_mipmaps(),
        ))
    }

    /// Image `i` read as colour or as data.
    fn get(&mut self, i: usize, space: ColorSpace) -> Option<Arc<ImageData>> {
        let linear = space == ColorSpace::Linear;
        if let Some(img) = self.made.get(&(i, linear)) {
            return Some(img.clone());
        }
        let raw = self.raw.get(i)?.as_ref()?;
        let img = Arc::new(ImageData::from_owned(raw.clone(), space).with_mipmaps());
        self.made.insert((i, linear), img.clone());
        Some(img)
    }
}

/// A glTF material as a snell material, its textures added to `textures`; `warn` hears
/// what it cannot read.
pub(in crate::scene) fn pbr_material(
    m: &PbrMaterial,
    images: &mut Images,
    textures: &mut Vec<Texture>,
    warn: &mut dyn FnMut(String),
) -> Material {
    for t in m.textures().filter(|t| t.texcoord > 1) {
        warn(format!(
            "material `{}` reads TEXCOORD_{}, which snell does not read: it uses TEXCOORD_0",
            m.name, t.texcoord
        ));
    }
    let mut add = |pattern: Pattern, t: Option<&TextureRef>| {
        textures.push(Texture {
            pattern,
            mapping: mapping(t),
            wrap: t.map_or(Wraps::REPEAT, |t| t.wrap),
        });
        textures.len() - 1
    };
    let base = Color::from_slice(&m.base_color[..3]).map(unit);
    let base_image = m.base_color_texture.as_ref().and_then(|t| {
        let img = images.get(t.image, ColorSpace::Srgb)?;
        Some((scaled(img, base, Color::ONE), t))
    });
    let texture = match base_image {
        Some((img, t)) => add(Pattern::Image(img), Some(t)),
        None => add(Pattern::Solid(base), None),
    };
    // Roughness point by point from the map's green channel; the metallic map's mean picks
    // the type of the whole (below: the blend point by point, where it is partly metal).
    let roughness = unit(m.roughness);
    let mr = m
        .metallic_roughness_texture
        .as_ref()
        .and_then(|t| Some((images.get(t.image, ColorSpace::Linear)?, t)));
    let (alpha, metallic_mean) = match &mr {
        Some((img, _)) => {
            let mean = img.mean();
            ((roughness * mean.y).powi(2), mean.z)
        }
        None => (roughness * roughness, 1.0),
    };
    // Metallic point by point from the map's blue channel: a constant where the factor
    // times the map is one value all over.
    let factor = unit(m.metallic);
    let metallic = match &mr {
        Some((img, t)) => match blue_range(img) {
            (lo, hi) if factor * lo == factor * hi => Scalar::Value(factor * lo),
            _ => Scalar::Texture(add(
                Pattern::Image(from_texels(img, |c| Color::splat(factor * c.z))),
                Some(t),
            )),
        },
        None => Scalar::Value(factor),
    };
    let alpha_param = match mr {
        Some((img, t)) => {
            Scalar::Texture(add(Pattern::Image(squared_green(&img, roughness)), Some(t)))
        }
        None => Scalar::Value(alpha),
    };
    let ior = if m.ior.is_finite() && m.ior >= 1.0 {
        m.ior
    } else {
        1.5
    };
    let emissive = Color::from(m.emissive).map(|e| {
        if e.is_finite() {
            e.clamp(0.0, 1e6)
        } else {
            0.0
        }
    });
    let radiance = match &m.emissive_texture {
        _ if emissive.max_element() <= 0.0 => None,
        Some(t) => match images.get(t.image, ColorSpace::Srgb) {
            Some(img) => Some(ColorParam::Texture(add(
                Pattern::Image(scaled(img, emissive, Color::splat(1e6))),
                Some(t),
            ))),
            None => Some(ColorParam::Value(emissive)),
        },
        None => Some(ColorParam::Value(emissive)),
    };
    let emission = radiance.map(|radiance| Emission {
        radiance,
        two_sided: m.double_sided,
    });
    let detail = m.normal_texture.as_ref().and_then(|t| {
        let img = images.get(t.image, ColorSpace::Linear)?;
        Some(SurfaceDetail::Normal {
            texture: add(Pattern::Image(img), Some(t)),
            scale: if m.normal_scale.is_finite() {
                m.normal_scale
            } else {
                1.0
            },
        })
    });
    // Alpha: the factor times the base-colour image's alpha channel, through its mapping.
    let cutout = match m.alpha {
        Alpha::Opaque => None,
        mode => {
            let factor = unit(m.base_color[3]);
            let image = m
                .base_color_texture
                .as_ref()
                .and_then(|t| Some((images.alpha(t.image, factor)?, t)));
            let texture = match image {
                Some((img, t)) => Some(add(Pattern::Image(img), Some(t))),
                None if factor < 1.0 => Some(add(Pattern::Solid(Color::splat(factor)), None)),
                // Alpha 1 everywhere: nothing to cut.
                None => None,
            };
            texture.map(|texture| match mode {
                Alpha::Mask(cutoff) => Cutout::Mask {
                    texture,
                    cutoff: if cutoff.is_finite() { cutoff } else { 0.5 },
                },
                _ => Cutout::Blend { texture },
            })
        }
    };
    // Partly metal: the blend, under the Phong terms of the part its mean leans to.
    let partly = !matches!(metallic, Scalar::Value(v) if v <= 0.0 || v >= 1.0);
    let mut out = match pbr_type(m, metallic_mean) {
        PbrType::Glass => Dielectric {
            roughness: alpha_param,
        }
        .material(texture, ior, Color::ZERO, alpha, emission),
        _ if partly => Metallic {
            dielectric: Plastic::fresnel_coat(alpha_param, ior),
            metallic,
        }
        .material(
            texture,
            base,
            ior,
            alpha,
            m.metallic * metallic_mean,
            emission,
        ),
        PbrType::Metal => Conductor {
            fresnel: ConductorFresnel::One,
            index: None,
            roughness: alpha_param,
        }
        .material(texture, base, alpha, emission),
        PbrType::Plastic => {
            Plastic::fresnel_coat(alpha_param, ior).material(texture, ior, alpha, emission)
        }
    };
    out.detail = detail;
    out.cutout = cutout;
    out
}

/// `x` kept to 0..1 (0 where it is not a number).
fn unit(x: f32) -> f32 {
    if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The mapping a texture reference reads through: the shape's uv (its second set for
/// `TEXCOORD_1`), transformed where it says so.
fn mapping(t: Option<&TextureRef>) -> Mapping {
    let transform = t
        .and_then(|t| t.transform)
        .filter(|m| m.iter().flatten().all(|x| x.is_finite()))
        .map(|m| m.map(Vec2::from));
    match (transform, t.is_some_and(|t| t.texcoord == 1)) {
        (m, true) => Mapping::SecondUv {
            m: m.unwrap_or([Vec2::X, Vec2::Y, Vec2::ZERO]),
        },
        (Some(m), false) => Mapping::UvTransform { m },
        (None, false) => Mapping::Uv,
    }
}

/// An image times a factor (glTF multiplies a map by its factor): the image itself where
/// the factor is white, else a copy in linear floats with the factor (kept to `0..=max`)
/// applied.
fn scaled(img: Arc<ImageData>, factor: Color, max: Color) -> Arc<ImageData> {
    if factor == Color::ONE || !factor.is_finite() {
        return img;
    }
    let f = factor.clamp(Color::ZERO, max);
    from_texels(&img, |c| c * f)
}

/// The least and the greatest of an image's blue channel.
fn blue_range(img: &ImageData) -> (f32, f32) {
    let mut range = (f32::INFINITY, f32::NEG_INFINITY);
    for y in 0..img.height() {
        for x in 0..img.width() {
            let b = img.texel(x, y).z;
            range = (range.0.min(b), range.1.max(b));
        }
    }
    range
}

/// GGX alpha from a metallic-roughness map: `(factor x green)^2` in every channel.
fn squared_green(img: &ImageData, factor: f32) -> Arc<ImageData> {
    from_texels(img, |c| Color::splat((factor * c.y).powi(2)))
}

/// A linear float image of `f` of each of `img`'s texels.
fn from_texels(img: &ImageData, f: impl Fn(Color) -> Color) -> Arc<ImageData> {
    let (w, h) = (img.width(), img.height());
    let out =
        ::image::Rgb32FImage::from_fn(w, h, |x, y| ::image::Rgb(f(img.texel(x, y)).to_array()));
    Arc::new(
        ImageData::from_owned(::image::DynamicImage::ImageRgb32F(out), ColorSpace::Linear)
            .with_mipmaps(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_type_follows_transmission_then_metallic() {
        let m = |metallic: f32, transmission: f32| PbrMaterial {
            metallic,
            transmission,
            ..PbrMaterial::default()
        };
        assert_eq!(pbr_type(&m(0.0, 0.0), 1.0), PbrType::Plastic);
        assert_eq!(pbr_type(&m(0.4, 0.0), 1.0), PbrType::Plastic);
        assert_eq!(pbr_type(&m(0.5, 0.0), 1.0), PbrType::Metal);
        assert_eq!(pbr_type(&m(1.0, 1.0), 1.0), PbrType::Glass);
        assert_eq!(pbr_type(&PbrMaterial::default(), 1.0), PbrType::Metal);
        // A metallic map mostly dielectric.
        assert_eq!(pbr_type(&PbrMaterial::default(), 0.2), PbrType::Plastic);
    }
}
