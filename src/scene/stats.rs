//! What building a scene cost and what it holds (objects, meshes, triangles, bytes), kept
//! with the scene for `snell render --stats` and the summary of `snell check`.

use super::Object;
use crate::geometry::Shape;

/// What building a scene cost, for `snell render --stats`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildStats {
    /// Time reading mesh files.
    pub mesh_load_time: std::time::Duration,
    /// Time building the meshes' BVHs.
    pub mesh_bvh_time: std::time::Duration,
    /// Time building the BVH over the objects.
    pub object_bvh_time: std::time::Duration,
    /// Objects in the scene (each placement of a mesh counts once).
    pub objects: usize,
    /// Distinct meshes (shared by their placements).
    pub meshes: usize,
    /// Triangles in the distinct meshes.
    pub unique_triangles: usize,
    /// Triangles in the scene, every placement counted.
    pub instanced_triangles: usize,
    /// Bytes of all BVHs: the meshes' and the objects'.
    pub bvh_bytes: usize,
    /// Bytes of the distinct meshes' triangles, normals and uvs.
    pub mesh_bytes: usize,
    /// Each distinct mesh, in the order first placed.
    pub per_mesh: Vec<MeshStats>,
}

/// One distinct mesh of a scene: its file, triangles and placements.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshStats {
    /// The file as the scene names it.
    pub file: String,
    /// What the mesh is within its file: a glTF mesh's name and the nodes that place it
    /// (`None` for OBJ and PLY).
    pub label: Option<String>,
    /// The images its file's materials read (a glTF file's; 0 for OBJ and PLY).
    pub file_images: usize,
    /// Triangles loaded from the file (degenerate ones dropped).
    pub triangles: usize,
    /// Objects that place it.
    pub placements: usize,
}

impl BuildStats {
    /// Counts objects, meshes and triangles.
    /// `file_of` names the file a mesh was read from (its `file`, `label` and
    /// `file_images`).
    pub(crate) fn record_objects(
        &mut self,
        objects: &[Object],
        file_of: impl Fn(&std::sync::Arc<crate::geometry::Mesh>) -> MeshStats,
    ) {
        let mut seen = std::collections::HashMap::new();
        self.objects = objects.len();
        for o in objects {
            if let Shape::Mesh(m) = &o.shape {
                self.instanced_triangles += m.triangle_count();
                let i = *seen.entry(std::sync::Arc::as_ptr(m)).or_insert_with(|| {
                    self.meshes += 1;
                    self.unique_triangles += m.triangle_count();
                    self.bvh_bytes += m.bvh_bytes();
                    self.mesh_bytes += m.geometry_bytes();
                    self.per_mesh.push(MeshStats {
                        triangles: m.triangle_count(),
                        placements: 0,
                        ..file_of(m)
                    });
                    self.per_mesh.len() - 1
                });
                self.per_mesh[i].placements += 1;
            }
        }
    }
}
