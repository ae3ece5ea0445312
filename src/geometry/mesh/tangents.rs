//! A mesh's tangent frames, for normal maps: the file's tangents (glTF's `TANGENT`) or
//! MikkTSpace's, which glTF asks for where a file has none and which Blender bakes normal
//! maps in. Kept per corner of each triangle (MikkTSpace may give one vertex different
//! tangents in different triangles, at a mirrored uv seam), and made only for meshes a
//! normal map is placed on.
//!
//! The convention: the tangent `t` points the way the texture's `u` grows, and the
//! bitangent `w (n x t)` the way up the image (glTF's and OpenGL's +y of a normal map).

use super::{Mesh, ShapeHit};
use crate::math::Vec3A;

/// A corner's tangent: unit `xyz`, and the bitangent's sign in `w`.
pub type Tangent = [f32; 4];

impl Mesh {
    /// Works out the per-corner tangents if the mesh has none yet (MikkTSpace over its
    /// positions, normals and uvs; the face normal where it has no normals). Does nothing for
    /// a mesh without uvs (its texture coordinates are each triangle's barycentrics): a
    /// normal map then reads the tangents its file gave, or else the frame of each triangle.
    pub fn ensure_tangents(&self) {
        if self.uvs.is_empty() {
            return;
        }
        self.tangents.get_or_init(|| self.mikktspace());
    }

    /// Whether the mesh has tangents (from its file or [`Mesh::ensure_tangents`]).
    pub fn has_tangents(&self) -> bool {
        self.tangents.get().is_some()
    }

    /// The tangent and bitangent (object space, unit, the bitangent up the image) at the
    /// point `p` of triangle `prim`, interpolated from its corners and made orthogonal to
    /// the shading normal there; `None` without tangents.
    pub fn tangent_frame(&self, p: Vec3A, prim: u32) -> Option<(Vec3A, Vec3A)> {
        let corners = self.tangents.get()?;
        let prim = self.own_prim(prim);
        let bary = self.barycentrics(p, prim);
        let hit = ShapeHit {
            t: 0.0,
            part: 0,
            prim,
            bary,
        };
        let n = self
            .interpolated_normal(&hit)
            .unwrap_or_else(|| self.hit_surface(&hit).normal);
        let i = 3 * prim as usize;
        let [t0, t1, t2] = [0, 1, 2].map(|k| corners[i + k]);
        let w = 1.0 - bary.x - bary.y;
        let xyz = |t: Tangent| Vec3A::new(t[0], t[1], t[2]);
        let t = xyz(t0) * w + xyz(t1) * bary.x + xyz(t2) * bary.y;
        let t = (t - n * n.dot(t)).normalize_or_zero();
        if t == Vec3A::ZERO {
            return None;
        }
        let sign = if t0[3] < 0.0 { -1.0 } else { 1.0 };
        Some((t, n.cross(t) * sign))
    }

    /// Per-vertex tangents (a file's) spread to every corner.
    pub(super) fn corners_of(faces: &[[u32; 3]], per_vertex: &[Tangent]) -> Vec<Tangent> {
        faces
            .iter()
            .flat_map(|f| f.map(|k| per_vertex[k as usize]))
            .collect()
    }

    fn mikktspace(&self) -> Vec<Tangent> {
        // Only the lanes that hold a triangle of their own: a repeated triangle would count
        // twice in the averages at its vertices.
        let prims: Vec<u32> = (0..self.faces.len() as u32)
            .filter(|&p| self.own_prim(p) == p)
            .collect();
        let mut geometry = Geometry {
            mesh: self,
            prims: &prims,
            out: vec![[1.0, 0.0, 0.0, 1.0]; self.faces.len() * 3],
        };
        // A mesh MikkTSpace cannot work with keeps the default tangents (+x): its normal map
        // is then read in a fixed frame, as a renderer without tangents would.
        let _ = bevy_mikktspace::generate_tangents(&mut geometry);
        let mut out = geometry.out;
        // Unfilled lanes repeat their block's first triangle, and its tangents.
        for p in 0..self.faces.len() {
            let own = self.own_prim(p as u32) as usize;
            if own != p {
                for k in 0..3 {
                    out[3 * p + k] = out[3 * own + k];
                }
            }
        }
        out
    }
}

/// A mesh as MikkTSpace reads it, and where its answers go.
struct Geometry<'a> {
    mesh: &'a Mesh,
    prims: &'a [u32],
    out: Vec<Tangent>,
}

impl bevy_mikktspace::Geometry for Geometry<'_> {
    fn num_faces(&self) -> usize {
        self.prims.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.corners(self.prims[face])[vert].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        let prim = self.prims[face];
        let f = self.mesh.faces[prim as usize];
        match self.mesh.normals.get(f[vert] as usize) {
            Some(n) => n.to_array(),
            None => {
                let [a, b, c] = self.mesh.corners(prim);
                (b - a).cross(c - a).normalize_or_zero().to_array()
            }
        }
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let f = self.mesh.faces[self.prims[face] as usize];
        let uv = self.mesh.uvs[f[vert] as usize];
        // snell's v grows down the image; MikkTSpace's bitangent follows v, which should
        // point up it.
        [uv.x, -uv.y]
    }

    fn set_tangent(
        &mut self,
        tangent_space: Option<bevy_mikktspace::TangentSpace>,
        face: usize,
        vert: usize,
    ) {
        if let Some(t) = tangent_space {
            let i = 3 * self.prims[face] as usize + vert;
            self.out[i] = t.tangent_encoded();
        }
    }
}
