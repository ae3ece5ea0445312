//! A glTF file placed by a scene: its meshes built once each, its metallic-roughness
//! materials as snell's (material.rs), and one placement per node that shows a mesh.

mod material;
mod placed;

use super::diag::DocPath;
use super::load::Builder;
use super::meshes::{LoadedMesh, Palette};
use crate::math::Transform;
use crate::mesh_file::gltf::{self, PbrMaterial};
use std::path::Path;
use std::sync::Arc;

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
        // Images are held to the limit every texture is (a map may be copied as floats).
        let limit = self.limits.max_texture_pixels;
        if let Some((i, img)) = scene.images.iter().enumerate().find_map(|(i, img)| {
            img.as_ref()
                .filter(|img| img.width() as u64 * img.height() as u64 > limit)
                .map(|img| (i, img))
        }) {
            self.error_help(
                path.clone(),
                format!(
                    "{file}: image {i} is {} x {} texels, more than the {limit} a texture may have",
                    img.width(),
                    img.height()
                ),
                "raise the limit with --max-texture-pixels, or make the image smaller",
            );
            return None;
        }
        let file_images = scene.images.iter().flatten().count();
        let mut images = material::Images::new(scene.images);
        // Scene materials for the file's materials, and for glTF's default one, made when
        // a mesh first uses them.
        let mut made: Vec<Option<usize>> = vec![None; scene.materials.len() + 1];
        let default = PbrMaterial::default();
        let mut meshes = vec![];
        let mesh_names: Vec<String> = scene.meshes.iter().map(|m| m.name.clone()).collect();
        for m in scene.meshes {
            let mut slot_materials = vec![];
            for slot in &m.slots {
                let k = slot.unwrap_or(scene.materials.len());
                let pbr = slot.map_or(&default, |s| &scene.materials[s]);
                let index = match made[k] {
                    Some(i) => i,
                    None => {
                        let warnings = &mut self.warnings;
                        let material =
                            material::pbr_material(pbr, &mut images, palette.textures, &mut |w| {
                                warnings.push(format!("{file}: {w}"))
                            });
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
        // The nodes that place each mesh, for `snell check`.
        let mut nodes_of = vec![vec![]; meshes.len()];
        let mut mesh_of = vec![];
        for inst in scene.instances {
            let Some(node) = Transform::from_matrix(inst.matrix) else {
                self.warnings.push(format!(
                    "{file}: node `{}` has a matrix that cannot be undone (a scale of 0?): skipped",
                    inst.node
                ));
                continue;
            };
            let (mesh, slots) = &meshes[inst.mesh];
            nodes_of[inst.mesh].push(inst.node.clone());
            mesh_of.push(inst.mesh);
            placed.push(LoadedMesh {
                mesh: mesh.clone(),
                node: Some(node),
                part: several.then_some(inst.node),
                file: file.to_string(),
                label: None,
                file_images,
                slot_materials: slots.clone(),
                unread_mtl: vec![],
            });
        }
        for (p, k) in placed.iter_mut().zip(mesh_of) {
            p.label = Some(format!(
                "mesh `{}` ({})",
                mesh_names[k],
                gltf::named("node", &nodes_of[k])
            ));
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
}
