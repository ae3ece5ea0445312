//! Files a scene reads, kept from one build of it to the next: the frames of an animation
//! are each built from the file with that frame's values, and read their images and meshes
//! (and build the meshes' BVHs) once. A build that finds nothing here reads the files as
//! a lone build does; what it finds gives the same scene as reading them again would.

use super::load::Builder;
use super::meshes::{LoadedMesh, Palette};
use crate::material::Material;
use crate::texture::{ColorSpace, ImageData, ImageLoadError, Texture};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What earlier builds of a scene loaded: pass the same one to each frame's build.
#[derive(Debug, Default)]
pub struct AssetCache {
    /// Images by file, colour space and whether they carry MIP levels.
    images: HashMap<(PathBuf, ColorSpace, bool), Arc<ImageData>>,
    /// Mesh files by file and normals option, with what loading them added to the scene.
    meshes: HashMap<(PathBuf, Option<bool>), MeshLoad>,
}

/// A mesh file's load and everything it added to the build: its materials and textures
/// (with the sizes of the lists they were added to, since their indices count from
/// there), warnings, files read and triangles.
#[derive(Clone, Debug)]
pub(super) struct MeshLoad {
    pub loaded: Vec<LoadedMesh>,
    /// The palette's materials and textures before the load.
    pub at: (usize, usize),
    pub materials: Vec<Material>,
    pub names: Vec<String>,
    pub textures: Vec<Texture>,
    pub warnings: Vec<String>,
    pub files: Vec<PathBuf>,
    pub triangles: u64,
}

fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

impl Builder<'_> {
    /// An image file, decoded (with MIP levels if `mipmaps`), or the one an earlier build
    /// decoded. Failures are not kept: each build reports them.
    pub(super) fn image(
        &mut self,
        full: &Path,
        space: ColorSpace,
        mipmaps: bool,
    ) -> Result<Arc<ImageData>, ImageLoadError> {
        let key = (canonical(full), space, mipmaps);
        if let Some(img) = self.assets.images.get(&key) {
            return Ok(img.clone());
        }
        let img = ImageData::load_limited(full, space, self.limits.max_texture_pixels)?;
        let img = Arc::new(if mipmaps { img.with_mipmaps() } else { img });
        self.assets.images.insert(key, img.clone());
        Ok(img)
    }

    /// A mesh file an earlier build loaded at the same point of the scene (its palette as
    /// long as then), added to this build as loading it again would add it.
    pub(super) fn replay_mesh(
        &mut self,
        key: &(PathBuf, Option<bool>),
        palette: &mut Palette,
    ) -> Option<Vec<LoadedMesh>> {
        let load = self.assets.meshes.get(key)?;
        if load.at != (palette.materials.len(), palette.textures.len()) {
            return None;
        }
        let load = load.clone();
        palette.materials.extend(load.materials);
        palette.names.extend(load.names);
        palette.textures.extend(load.textures);
        self.warnings.extend(load.warnings);
        self.files.extend(load.files);
        self.triangles_loaded += load.triangles;
        Some(load.loaded)
    }

    /// Loads a mesh file by `load` and keeps what it added for later builds (when it
    /// loaded without problems).
    pub(super) fn record_mesh(
        &mut self,
        key: (PathBuf, Option<bool>),
        palette: &mut Palette,
        load: impl FnOnce(&mut Self, &mut Palette) -> Option<Vec<LoadedMesh>>,
    ) -> Option<Vec<LoadedMesh>> {
        let at = (palette.materials.len(), palette.textures.len());
        let names_at = palette.names.len();
        let (warnings_at, files_at) = (self.warnings.len(), self.files.len());
        let (problems_at, triangles_at) = (self.problem_count(), self.triangles_loaded);
        let loaded = load(self, palette)?;
        if self.problem_count() == problems_at {
            let entry = MeshLoad {
                loaded: loaded.clone(),
                at,
                materials: palette.materials[at.0..].to_vec(),
                names: palette.names[names_at..].to_vec(),
                textures: palette.textures[at.1..].to_vec(),
                warnings: self.warnings[warnings_at..].to_vec(),
                files: self.files[files_at..].to_vec(),
                triangles: self.triangles_loaded - triangles_at,
            };
            self.assets.meshes.insert(key, entry);
        }
        Some(loaded)
    }
}
