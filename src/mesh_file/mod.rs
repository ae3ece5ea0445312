//! Triangle mesh files: Wavefront OBJ (with MTL materials), Stanford PLY, and glTF 2.0
//! scenes of meshes (`gltf/`).
//!
//! [`load`] picks the loader from the file extension. The loaders never panic on bad
//! input: every problem is either a [`MeshError`] naming the file and a line (text) or
//! byte offset (binary PLY), or a summarised entry in [`MeshData::warnings`].

pub mod gltf;
pub mod obj;
pub mod ply;

use std::fmt;
use std::path::{Path, PathBuf};

/// A triangle mesh as read from a file, before it is placed in a scene.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Per-vertex normals (same length as `positions`), or empty when the file has none.
    /// Vertices that had no normal in a file that has some get `[0, 0, 0]`.
    pub normals: Vec<[f32; 3]>,
    /// Per-vertex texture coordinates (same length as `positions`), or empty.
    pub uvs: Vec<[f32; 2]>,
    /// A second set of them (glTF's `TEXCOORD_1`), or empty.
    pub uvs1: Vec<[f32; 2]>,
    /// Per-vertex tangents (glTF's `TANGENT`: unit `xyz`, the bitangent's sign in `w`),
    /// or empty.
    pub tangents: Vec<[f32; 4]>,
    /// Per-vertex linear RGB colours (glTF's `COLOR_0`), or empty.
    pub colors: Vec<[f32; 3]>,
    /// Triangles as indices into `positions` (and `normals` and `uvs`), in file winding order.
    pub triangles: Vec<[u32; 3]>,
    /// Per-triangle index into `materials`, or empty when no materials are used.
    pub triangle_materials: Vec<u32>,
    /// Materials from the MTL files an OBJ names (always empty for PLY).
    pub materials: Vec<MtlMaterial>,
    /// Problems that did not stop the load, summarised (one entry per kind, not per line).
    pub warnings: Vec<String>,
    /// MTL files that `mtllib` names but that could not be read, each with why (`x.mtl`
    /// not found), so a scene can say why the mesh has no materials.
    pub unread_mtl: Vec<String>,
    /// Every MTL file `mtllib` names, read or not (what a watcher of the mesh's files
    /// watches), sorted.
    pub mtl_files: Vec<std::path::PathBuf>,
}

/// A material from an MTL file (only what was given is `Some`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MtlMaterial {
    /// The name given by `newmtl`.
    pub name: String,
    /// Diffuse colour (`Kd`).
    pub kd: Option<[f32; 3]>,
    /// Specular colour (`Ks`).
    pub ks: Option<[f32; 3]>,
    /// Emitted colour (`Ke`).
    pub ke: Option<[f32; 3]>,
    /// Specular exponent (`Ns`).
    pub ns: Option<f32>,
    /// Index of refraction (`Ni`).
    pub ni: Option<f32>,
    /// Opacity (`d`, or `1 - x` from `Tr x`; `d` wins when both are given).
    pub d: Option<f32>,
    /// Transmission filter colour (`Tf`; a single value means grey).
    pub tf: Option<[f32; 3]>,
    /// Roughness (`Pr`, the PBR extension), as Blender's Principled BSDF reads it.
    pub pr: Option<f32>,
    /// Metallic (`Pm`, the PBR extension).
    pub pm: Option<f32>,
    /// Illumination model (`illum`).
    pub illum: Option<u32>,
    /// Diffuse texture (`map_Kd`), resolved relative to the MTL file's folder.
    pub map_kd: Option<PathBuf>,
}

/// Why file data cannot become a mesh for a scene (see [`MeshData::into_mesh_input`]).
#[derive(Clone, Debug, PartialEq)]
pub enum MeshInputError {
    /// More materials than a triangle's `u16` slot can name.
    TooManyMaterials(usize),
    /// A vertex beyond [`crate::math::MAX_MAGNITUDE`].
    VertexTooFar(crate::math::Vec3),
}

impl MeshData {
    /// The mesh as `Mesh::new` takes it, and the file's materials, as a scene builds it:
    /// vertices beyond the magnitude scenes allow are refused; `smooth` `Some(false)` drops
    /// the file's normals, `Some(true)` computes area-weighted ones where the file has none;
    /// uvs are flipped to snell's convention (OBJ and PLY put v = 0 at the bottom of the
    /// image, snell at the top).
    pub fn into_mesh_input(
        self,
        smooth: Option<bool>,
    ) -> Result<(crate::geometry::mesh::MeshInput, Vec<MtlMaterial>), MeshInputError> {
        use crate::geometry::mesh::{MeshInput, area_weighted_normals};
        use crate::math::{Vec2, Vec3};
        let MeshData {
            positions,
            normals,
            uvs,
            uvs1,
            tangents,
            colors,
            triangles,
            triangle_materials,
            materials,
            warnings: _,
            unread_mtl: _,
            mtl_files: _,
        } = self;
        if materials.len() > u16::MAX as usize {
            return Err(MeshInputError::TooManyMaterials(materials.len()));
        }
        let positions: Vec<Vec3> = positions.into_iter().map(Vec3::from).collect();
        if let Some(p) = positions
            .iter()
            .find(|p| p.abs().max_element() > crate::math::MAX_MAGNITUDE)
        {
            return Err(MeshInputError::VertexTooFar(*p));
        }
        let normals: Vec<Vec3> = match smooth {
            Some(false) => vec![],
            Some(true) if normals.is_empty() => area_weighted_normals(&positions, &triangles),
            _ => normals.into_iter().map(Vec3::from).collect(),
        };
        let input = MeshInput {
            positions,
            normals,
            uvs: uvs
                .into_iter()
                .map(|[u, v]| Vec2::new(u, 1.0 - v))
                .collect(),
            uvs1: uvs1
                .into_iter()
                .map(|[u, v]| Vec2::new(u, 1.0 - v))
                .collect(),
            triangles,
            triangle_slots: triangle_materials.iter().map(|&m| m as u16).collect(),
            tangents,
            colors: colors.into_iter().map(Vec3::from).collect(),
        };
        Ok((input, materials))
    }
}

/// Why a mesh file could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MeshError {
    /// The file at fault (the MTL file for errors inside one).
    pub path: PathBuf,
    /// 1-based line of a text file, when the error is tied to one.
    pub line: Option<usize>,
    /// Byte offset into a binary file, when the error is tied to one.
    pub byte_offset: Option<u64>,
    /// What is wrong, in words.
    pub message: String,
}

impl MeshError {
    pub(crate) fn new(path: &Path, message: impl Into<String>) -> Self {
        MeshError {
            path: path.to_path_buf(),
            line: None,
            byte_offset: None,
            message: message.into(),
        }
    }

    pub(crate) fn at_line(path: &Path, line: usize, message: impl Into<String>) -> Self {
        MeshError {
            line: Some(line),
            ..MeshError::new(path, message)
        }
    }

    pub(crate) fn at_byte(path: &Path, offset: u64, message: impl Into<String>) -> Self {
        MeshError {
            byte_offset: Some(offset),
            ..MeshError::new(path, message)
        }
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let path = self.path.display();
        match (self.line, self.byte_offset) {
            (Some(line), _) => write!(f, "{path}:{line}: {}", self.message),
            (None, Some(offset)) => write!(f, "{path}: byte {offset}: {}", self.message),
            (None, None) => write!(f, "{path}: {}", self.message),
        }
    }
}

impl std::error::Error for MeshError {}

/// Loads a `.obj` or `.ply` mesh (extension compared case-insensitively).
pub fn load(path: &Path) -> Result<MeshData, MeshError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("obj") => obj::load(path),
        Some("ply") => ply::load(path),
        Some(other) => Err(MeshError::new(
            path,
            format!("unsupported mesh file type `.{other}` (expected .obj or .ply)"),
        )),
        None => Err(MeshError::new(
            path,
            "mesh file name has no extension (expected .obj or .ply)",
        )),
    }
}

/// Reads a whole file; mesh files are parsed from memory in one pass.
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, MeshError> {
    crate::read_regular_file(path)
        .map_err(|e| MeshError::new(path, format!("cannot read file: {e}")))
}

/// A capacity for `count` items that a lying header cannot turn into a huge allocation.
pub(crate) fn capped(count: u64) -> usize {
    usize::try_from(count.min(1 << 20)).unwrap_or(1 << 20)
}

/// Removes zero-area triangles (repeated indices, or collinear positions computed in f64
/// so that tiny but valid triangles survive) and adds one summary warning.
pub(crate) fn drop_degenerate(mesh: &mut MeshData) {
    let positions = &mesh.positions;
    let keep: Vec<bool> = mesh
        .triangles
        .iter()
        .map(|t| !is_degenerate(positions, *t))
        .collect();
    let dropped = keep.iter().filter(|k| !**k).count();
    if dropped == 0 {
        return;
    }
    let mut flags = keep.iter();
    mesh.triangles.retain(|_| *flags.next().unwrap_or(&true));
    if !mesh.triangle_materials.is_empty() {
        let mut flags = keep.iter();
        mesh.triangle_materials
            .retain(|_| *flags.next().unwrap_or(&true));
    }
    let s = if dropped == 1 { "" } else { "s" };
    mesh.warnings.push(format!(
        "skipped {dropped} degenerate (zero-area) triangle{s}"
    ));
}

fn is_degenerate(positions: &[[f32; 3]], [a, b, c]: [u32; 3]) -> bool {
    if a == b || b == c || a == c {
        return true;
    }
    let get = |i: u32| positions.get(i as usize).map(|p| p.map(f64::from));
    let (Some(pa), Some(pb), Some(pc)) = (get(a), get(b), get(c)) else {
        return true;
    };
    let u = [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]];
    let v = [pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]];
    let cross = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    cross == [0.0; 3]
}

/// `count` followed by `noun`, with `plural` when count is not 1.
pub(crate) fn count_of(count: usize, noun: &str, plural: &str) -> String {
    if count == 1 {
        format!("1 {noun}")
    } else {
        format!("{count} {plural}")
    }
}

#[cfg(test)]
pub(crate) mod test_util {
    use std::path::PathBuf;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A fresh, empty folder under the system temp dir, unique per process and call.
    pub(crate) fn temp_dir(name: &str) -> PathBuf {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let dir =
            std::env::temp_dir().join(format!("snell-mesh-test-{}-{n}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create temp dir");
        dir
    }

    /// Tiny deterministic generator for fuzz-style tests.
    pub(crate) struct Lcg(pub u64);

    impl Lcg {
        pub(crate) fn next(&mut self) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            self.0 >> 33
        }

        pub(crate) fn below(&mut self, n: usize) -> usize {
            (self.next() % n.max(1) as u64) as usize
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_display_forms() {
        let p = Path::new("a/b.obj");
        assert_eq!(
            MeshError::at_line(p, 7, "`abc` is not a number").to_string(),
            "a/b.obj:7: `abc` is not a number"
        );
        assert_eq!(
            MeshError::at_byte(p, 1234, "bad").to_string(),
            "a/b.obj: byte 1234: bad"
        );
        assert_eq!(MeshError::new(p, "gone").to_string(), "a/b.obj: gone");
        let e: Box<dyn std::error::Error> = Box::new(MeshError::new(p, "x"));
        assert_eq!(e.to_string(), "a/b.obj: x");
    }

    #[test]
    fn load_dispatches_on_extension_case_insensitively() {
        let dir = test_util::temp_dir("dispatch");
        let obj = dir.join("tri.OBJ");
        std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(load(&obj).unwrap().triangles, vec![[0, 1, 2]]);
        let ply = dir.join("tri.Ply");
        std::fs::write(
            &ply,
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
             end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        )
        .unwrap();
        assert_eq!(load(&ply).unwrap().triangles, vec![[0, 1, 2]]);
        let stl = dir.join("tri.stl");
        let e = load(&stl).unwrap_err();
        assert!(
            e.message.contains("unsupported mesh file type `.stl`"),
            "{e}"
        );
        let e = load(&dir.join("noext")).unwrap_err();
        assert!(e.message.contains("no extension"), "{e}");
        let e = load(&dir.join("missing.obj")).unwrap_err();
        assert!(
            e.to_string().contains("missing.obj: cannot read file"),
            "{e}"
        );
        assert_eq!(e.line, None);
    }

    #[test]
    fn degenerate_triangles_are_dropped_with_materials_in_step() {
        let mut m = MeshData {
            positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [2.0, 0.0, 0.0]],
            triangles: vec![[0, 1, 2], [0, 0, 1], [0, 1, 3], [2, 1, 0]],
            triangle_materials: vec![0, 1, 2, 3],
            ..MeshData::default()
        };
        drop_degenerate(&mut m);
        assert_eq!(m.triangles, vec![[0, 1, 2], [2, 1, 0]]);
        assert_eq!(m.triangle_materials, vec![0, 3]);
        assert_eq!(
            m.warnings,
            vec!["skipped 2 degenerate (zero-area) triangles"]
        );
        // Tiny but valid triangles are kept.
        let mut tiny = MeshData {
            positions: vec![[0.0; 3], [1e-20, 0.0, 0.0], [0.0, 1e-20, 0.0]],
            triangles: vec![[0, 1, 2]],
            ..MeshData::default()
        };
        drop_degenerate(&mut tiny);
        assert_eq!(tiny.triangles.len(), 1);
        assert!(tiny.warnings.is_empty());
    }
}
