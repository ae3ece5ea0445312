//! A glTF file placed by a scene: its meshes built once each, its metallic-roughness
//! materials as snell's, and one placement per node that shows a mesh.
//!
//! The materials, as docs/scene-format.md sets out: KHR_materials_transmission of 0.5 or
//! more makes glass (of KHR_materials_ior, 1.5 by default); metallic 0.5 or more a metal of
//! the base colour; anything else the base colour under a clear coat (snell's `plastic`, as
//! glTF's dielectric is a diffuse base under a GGX specular layer of IOR 1.5). Roughness is
//! perceptual (GGX alpha is its square). The emissive factor (times
//! KHR_materials_emissive_strength) makes an emitter.

use super::build::Builder;
use super::diag::DocPath;
use super::meshes::{LoadedMesh, Palette};
use crate::bsdf::ConductorFresnel;
use crate::material::conductor::Conductor;
use crate::material::dielectric::Dielectric;
use crate::material::plastic::Plastic;
use crate::material::{ColorParam, Emission, Material, Scalar};
use crate::math::{Color, Transform};
use crate::mesh_file::gltf::{self, PbrMaterial};
use crate::texture::{ColorSpace, ImageData, Mapping, Pattern, Texture};
use std::path::Path;
use std::sync::Arc;

/// The snell material type a glTF material becomes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum PbrType {
    /// See-through: glass.
    Glass,
    /// Metallic: a metal of the base colour.
    Metal,
    /// Otherwise: the base colour under a clear coat.
    Plastic,
}

/// Which type `m` becomes.
pub(super) fn pbr_type(m: &PbrMaterial) -> PbrType {
    if m.transmission >= 0.5 {
        PbrType::Glass
    } else if m.metallic >= 0.5 {
        PbrType::Metal
    } else {
        PbrType::Plastic
    }
}

impl Builder<'_> {
    /// Reads a glTF file: its meshes (each built once), its materials (added to the
    /// palette, named `FILE:MATERIAL`) and the placements of its nodes.
    pub(super) fn read_gltf(
        &mut self,
        file: &str,
        full: &Path,
        smooth: Option<bool>,
        path: &DocPath,
        palette: &mut Palette,
    ) -> Option<Vec<LoadedMesh>> {
        let start = std::time::Instant::now();
        let scene = match gltf::load(full) {
            Ok(s) => s,
            Err(e) => {
                self.error_help(
                    path.clone(),
                    format!("cannot load glTF file: {e}"),
                    "paths are relative to the scene file's folder; .gltf (with its buffers and images) and .glb are read",
                );
                return None;
            }
        };
        self.stats.mesh_load_time += start.elapsed();
        self.files.extend(scene.files.iter().cloned());
        for w in &scene.warnings {
            self.warnings.push(format!("{file}: {w}"));
        }
        let stem = Path::new(file)
            .file_name()
            .map_or(file.into(), |n| n.to_string_lossy());
        let images: Vec<Option<Arc<ImageData>>> = scene
            .images
            .into_iter()
            .map(|i| {
                i.map(|img| Arc::new(ImageData::from_owned(img, ColorSpace::Srgb).with_mipmaps()))
            })
            .collect();
        // Scene materials for the file's materials, and for glTF's default one, made when
        // a mesh first uses them.
        let mut made: Vec<Option<usize>> = vec![None; scene.materials.len() + 1];
        let default = PbrMaterial::default();
        let mut meshes = vec![];
        for m in scene.meshes {
            let mut slot_materials = vec![];
            for slot in &m.slots {
                let k = slot.unwrap_or(scene.materials.len());
                let pbr = slot.map_or(&default, |s| &scene.materials[s]);
                let index = match made[k] {
                    Some(i) => i,
                    None => {
                        if pbr.base_color_texcoord != 0 {
                            self.warnings.push(format!(
                                "{file}: material `{}` reads TEXCOORD_{}, which snell does not read: it uses TEXCOORD_0",
                                pbr.name, pbr.base_color_texcoord
                            ));
                        }
                        let material = self.pbr_material(pbr, &images, palette.textures);
                        palette.materials.push(material);
                        palette.names.push(format!("{stem}:{}", pbr.name));
                        made[k] = Some(palette.materials.len() - 1);
                        palette.materials.len() - 1
                    }
                };
                slot_materials.push(index);
            }
            let name = format!("{file} ({})", m.name);
            let (mesh, _) = self.build_mesh(&name, m.data, smooth, "", path)?;
            meshes.push((Arc::new(mesh), slot_materials));
        }
        let several = scene.instances.len() > 1;
        let mut placed = vec![];
        for inst in scene.instances {
            let Some(node) = Transform::from_matrix(inst.matrix) else {
                self.warnings.push(format!(
                    "{file}: node `{}` has a matrix that cannot be undone (a scale of 0?): skipped",
                    inst.node
                ));
                continue;
            };
            let (mesh, slots) = &meshes[inst.mesh];
            placed.push(LoadedMesh {
                mesh: mesh.clone(),
                node: Some(node),
                part: several.then_some(inst.node),
                file: file.to_string(),
                slot_materials: slots.clone(),
                unread_mtl: vec![],
            });
        }
        if placed.is_empty() {
            self.error_help(
                path.clone(),
                format!("{file} places no mesh: its scene has no node with a mesh"),
                "export the scene with its meshes (in Blender, File > Export > glTF 2.0 with the objects included)",
            );
            return None;
        }
        Some(placed)
    }

    /// A glTF material as a snell material (see the module's documentation).
    fn pbr_material(
        &mut self,
        m: &PbrMaterial,
        images: &[Option<Arc<ImageData>>],
        textures: &mut Vec<Texture>,
    ) -> Material {
        let clamp01 = |x: f32| {
            if x.is_finite() {
                x.clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        let base = Color::new(
            clamp01(m.base_color[0]),
            clamp01(m.base_color[1]),
            clamp01(m.base_color[2]),
        );
        let image = m
            .base_color_image
            .and_then(|i| images.get(i).cloned().flatten())
            .map(|img| tinted(img, m.base_color));
        textures.push(Texture {
            pattern: match image {
                Some(img) => Pattern::Image(img),
                None => Pattern::Solid(base),
            },
            mapping: Mapping::Uv,
        });
        let texture = textures.len() - 1;
        let alpha = clamp01(m.roughness).powi(2);
        let ior = if m.ior.is_finite() && m.ior >= 1.0 {
            m.ior
        } else {
            1.5
        };
        let emissive = Color::from(m.emissive.map(|e| {
            if e.is_finite() {
                e.clamp(0.0, 1e6)
            } else {
                0.0
            }
        }));
        let emission = (emissive.max_element() > 0.0).then_some(Emission {
            radiance: ColorParam::Value(emissive),
            two_sided: m.double_sided,
        });
        match pbr_type(m) {
            PbrType::Glass => Dielectric {
                roughness: Scalar::Value(alpha),
            }
            .material(texture, ior, Color::ZERO, alpha, emission),
            PbrType::Metal => Conductor {
                fresnel: ConductorFresnel::One,
                index: None,
                roughness: Scalar::Value(alpha),
            }
            .material(texture, base, alpha, emission),
            PbrType::Plastic => {
                Plastic::new(Scalar::Value(alpha), ior).material(texture, ior, alpha, emission)
            }
        }
    }
}

/// The base-colour image times the base-colour factor (glTF multiplies them): the image
/// itself where the factor is white, else a copy in linear floats with the factor applied.
fn tinted(img: Arc<ImageData>, factor: [f32; 4]) -> Arc<ImageData> {
    let f = Color::new(factor[0], factor[1], factor[2]);
    if f == Color::ONE || !f.is_finite() {
        return img;
    }
    let f = f.clamp(Color::ZERO, Color::ONE);
    let (w, h) = (img.width(), img.height());
    let tinted =
        ::image::Rgb32FImage::from_fn(w, h, |x, y| ::image::Rgb((img.texel(x, y) * f).to_array()));
    Arc::new(
        ImageData::from_owned(
            ::image::DynamicImage::ImageRgb32F(tinted),
            ColorSpace::Linear,
        )
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
        assert_eq!(pbr_type(&m(0.0, 0.0)), PbrType::Plastic);
        assert_eq!(pbr_type(&m(0.4, 0.0)), PbrType::Plastic);
        assert_eq!(pbr_type(&m(0.5, 0.0)), PbrType::Metal);
        assert_eq!(pbr_type(&m(1.0, 1.0)), PbrType::Glass);
        assert_eq!(pbr_type(&PbrMaterial::default()), PbrType::Metal);
    }
}
