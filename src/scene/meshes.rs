//! Meshes in a scene: `[meshes.NAME]` and objects of type `mesh`. Each file is read and its
//! BVH built once, however many objects place it (instancing); its MTL materials become scene
//! materials. A glTF file is a scene of its own: each of its meshes is built once, and an
//! object placing the file becomes one object per node that places a mesh (gltf.rs here).

use super::diag::{DocPath, name_help};
use super::format::{MeshDef, MeshObjectDef};
use super::load::Builder;
use crate::geometry::Mesh;
use crate::material::Material;
use crate::mesh_file::{self, MeshInputError};
use crate::texture::Texture;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// A mesh ready to be placed: its shared geometry and the scene materials of its slots
/// (and, from a glTF file, where its node puts it).
#[derive(Clone, Debug)]
pub(super) struct LoadedMesh {
    pub mesh: Arc<Mesh>,
    /// The node's placement within the file (glTF), applied before the object's.
    pub node: Option<crate::math::Transform>,
    /// The node's name, where a file places several meshes.
    pub part: Option<String>,
    /// The file as the scene first names it.
    pub file: String,
    /// What the mesh is within its file, for `snell check`: a glTF mesh's name and the
    /// nodes that place it (`None` for OBJ and PLY).
    pub label: Option<String>,
    /// The images its file's materials read (a glTF file's; 0 for OBJ and PLY).
    pub file_images: usize,
    /// Scene material of each of the file's materials (empty when it has none).
    pub slot_materials: Vec<usize>,
    /// The MTL files the mesh file names that could not be read, each with why.
    pub unread_mtl: Vec<String>,
}

/// Loaded meshes by (file, normals option): one placement for OBJ and PLY, one per node for
/// glTF; `None` where loading failed (reported once).
pub(super) type MeshCache = HashMap<(PathBuf, Option<bool>), Option<Vec<LoadedMesh>>>;

/// The scene's materials and textures while they are being built, so meshes can add theirs.
pub(super) struct Palette<'a> {
    pub materials: &'a mut Vec<Material>,
    pub names: &'a mut Vec<String>,
    pub textures: &'a mut Vec<Texture>,
}

impl Builder<'_> {
    /// Loads every `[meshes.NAME]`.
    pub(super) fn named_meshes(
        &mut self,
        defs: &BTreeMap<String, MeshDef>,
        path: &DocPath,
        palette: &mut Palette,
    ) -> Vec<(String, Option<Vec<LoadedMesh>>)> {
        defs.iter()
            .map(|(name, d)| {
                let m = self.load_mesh(&d.file, d.smooth, &path.key(name).key("file"), palette);
                (name.clone(), m)
            })
            .collect()
    }

    /// The mesh an object of type `mesh` places: from its `file`, or a `[meshes]` name.
    pub(super) fn mesh_object(
        &mut self,
        d: &MeshObjectDef,
        path: &DocPath,
        named: &[(String, Option<Vec<LoadedMesh>>)],
        used: &mut [bool],
        palette: &mut Palette,
    ) -> Option<Vec<LoadedMesh>> {
        match (&d.file, &d.mesh) {
            (Some(_), Some(_)) => {
                self.error_help(
                    path.key("mesh"),
                    "a mesh object takes `file` or `mesh`, not both",
                    "use `mesh` to place a mesh defined under [meshes], `file` to read one directly",
                );
                None
            }
            (None, None) => {
                self.error_help(
                    path.clone(),
                    "a mesh object needs `file` (an OBJ or PLY file) or `mesh` (a name from [meshes])",
                    "add file = \"model.obj\"",
                );
                None
            }
            (Some(file), None) => self.load_mesh(file, d.smooth, &path.key("file"), palette),
            (None, Some(name)) => {
                if d.smooth.is_some() {
                    self.error_help(
                        path.key("smooth"),
                        "`smooth` belongs to the mesh's definition when it is placed by name",
                        format!("set it under [meshes.{name}]"),
                    );
                }
                match named.iter().position(|(n, _)| n == name) {
                    Some(i) => {
                        used[i] = true;
                        named[i].1.clone()
                    }
                    None => {
                        let help = name_help(
                            name,
                            named.iter().map(|(n, _)| n.as_str()),
                            "defined meshes",
                            "define it under [meshes.NAME] with a `file`",
                        );
                        self.error_help(path.key("mesh"), format!("no mesh named `{name}`"), help);
                        None
                    }
                }
            }
        }
    }

    /// Reads a mesh file (or finds it in the cache) and builds its BVH. Problems are reported
    /// at `path` (the `file` key).
    fn load_mesh(
        &mut self,
        file: &str,
        smooth: Option<bool>,
        path: &DocPath,
        palette: &mut Palette,
    ) -> Option<Vec<LoadedMesh>> {
        let full = self.base_dir.join(file);
        self.files.push(full.clone());
        let key = (
            std::fs::canonicalize(&full).unwrap_or_else(|_| full.clone()),
            smooth,
        );
        if let Some(cached) = self.mesh_cache.get(&key) {
            return cached.clone();
        }
        // An earlier build of this scene (an animation's frame before) may have read it.
        if let Some(loaded) = self.replay_mesh(&key, palette) {
            self.mesh_cache.insert(key, Some(loaded.clone()));
            return Some(loaded);
        }
        let gltf = full
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"));
        let loaded = self.record_mesh(key.clone(), palette, |b, palette| {
            if gltf {
                b.read_gltf(file, &full, smooth, path, palette)
            } else {
                b.read_mesh(file, &full, smooth, path, palette)
                    .map(|m| vec![m])
            }
        });
        self.mesh_cache.insert(key, loaded.clone());
        loaded
    }

    fn read_mesh(
        &mut self,
        file: &str,
        full: &Path,
        smooth: Option<bool>,
        path: &DocPath,
        palette: &mut Palette,
    ) -> Option<LoadedMesh> {
        let start = Instant::now();
        let mut data = match mesh_file::load(full) {
            Ok(d) => d,
            Err(e) => {
                self.error_help(
                    path.clone(),
                    format!("cannot load mesh: {e}"),
                    "paths are relative to the scene file's folder; OBJ (with MTL), PLY and glTF (.gltf, .glb) are supported",
                );
                return None;
            }
        };
        self.stats.mesh_load_time += start.elapsed();
        for w in &data.warnings {
            self.warnings.push(format!("{file}: {w}"));
        }
        let loader_notes = data.warnings.join("; ");
        let unread_mtl = std::mem::take(&mut data.unread_mtl);
        self.files.append(&mut data.mtl_files);
        let (mesh, materials) = self.build_mesh(file, data, smooth, &loader_notes, path)?;
        let stem = Path::new(file)
            .file_name()
            .map_or(file.into(), |n| n.to_string_lossy());
        let mut slot_materials = vec![];
        for m in &materials {
            let material = self.mtl_material(m, path, palette.textures);
            slot_materials.push(palette.materials.len());
            palette.materials.push(material);
            palette.names.push(format!("{stem}:{}", m.name));
        }
        Some(LoadedMesh {
            mesh: Arc::new(mesh),
            node: None,
            part: None,
            file: file.to_string(),
            label: None,
            file_images: 0,
            slot_materials,
            unread_mtl,
        })
    }

    /// A mesh file's data as a mesh with its BVH, within the scene's limits, and the file's
    /// MTL materials (problems reported at `path`).
    pub(super) fn build_mesh(
        &mut self,
        file: &str,
        data: mesh_file::MeshData,
        smooth: Option<bool>,
        loader_notes: &str,
        path: &DocPath,
    ) -> Option<(Mesh, Vec<mesh_file::MtlMaterial>)> {
        let (input, materials) = match data.into_mesh_input(smooth) {
            Ok(converted) => converted,
            Err(MeshInputError::TooManyMaterials(n)) => {
                self.error(
                    path.clone(),
                    format!(
                        "{file} uses {n} materials; at most {} are supported",
                        u16::MAX
                    ),
                );
                return None;
            }
            Err(MeshInputError::VertexTooFar(p)) => {
                self.error_help(
                    path.clone(),
                    format!("{file} has a vertex at {p}, beyond the 1e15 snell accepts"),
                    "scale the model down in the file, or use a transform",
                );
                return None;
            }
        };
        let (mesh, dropped) = match Mesh::new(input) {
            Ok(m) => m,
            Err(e) if loader_notes.is_empty() => {
                self.error(path.clone(), format!("{file}: {e}"));
                return None;
            }
            Err(e) => {
                self.error(path.clone(), format!("{file}: {e} ({loader_notes})"));
                return None;
            }
        };
        if dropped > 0 {
            self.warnings.push(format!(
                "{file}: skipped {dropped} triangles with zero area"
            ));
        }
        self.stats.mesh_bvh_time += mesh.build_time;
        self.triangles_loaded += mesh.triangle_count() as u64;
        if self.triangles_loaded > self.limits.max_triangles {
            self.error_help(
                path.clone(),
                format!(
                    "with {file} the scene's meshes hold {} triangles, more than the {} allowed",
                    self.triangles_loaded, self.limits.max_triangles
                ),
                "raise the limit with --max-triangles",
            );
            return None;
        }
        Some((mesh, materials))
    }
}
