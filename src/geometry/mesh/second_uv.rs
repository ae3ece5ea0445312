//! A mesh's second set of texture coordinates (glTF's `TEXCOORD_1`, where a material's map
//! reads it: often an occlusion or light map laid out apart from the colour's): read at a
//! point of a triangle, between its corners'.

use super::Mesh;
use crate::geometry::ShapeHit;
use crate::math::{Vec2, Vec3A};

impl Mesh {
    /// Whether the mesh has a second set of uvs.
    pub fn has_second_uv(&self) -> bool {
        !self.uvs1.is_empty()
    }

    /// The second uv at a hit (its barycentrics), if the mesh has them.
    #[inline]
    pub fn second_uv(&self, hit: &ShapeHit) -> Option<Vec2> {
        if self.uvs1.is_empty() {
            return None;
        }
        let f = self.faces[hit.prim as usize];
        let (u, v) = (hit.bary.x, hit.bary.y);
        let t = |k: usize| self.uvs1[f[k] as usize];
        Some(t(0) * (1.0 - u - v) + t(1) * u + t(2) * v)
    }

    /// How the second uv changes over an offset `dp` in the plane of triangle `prim`, if
    /// the mesh has them (zero where the triangle has no area).
    pub fn second_uv_change(&self, prim: u32, dp: Vec3A) -> Option<Vec2> {
        if self.uvs1.is_empty() {
            return None;
        }
        let db = self.barycentric_change(prim, dp);
        let f = self.faces[prim as usize];
        let t = |k: usize| self.uvs1[f[k] as usize];
        Some((t(1) - t(0)) * db.x + (t(2) - t(0)) * db.y)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Mesh, MeshInput};
    use crate::geometry::Intersect;
    use crate::math::{Ray, Vec2, Vec3, Vec3A};

    /// The second set blends between its corners like the first, and changes across the
    /// triangle as its corners say; a mesh without one has none.
    #[test]
    fn the_second_uv_blends_between_the_corners() {
        let input = MeshInput {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2]],
            uvs: vec![Vec2::ZERO, Vec2::X, Vec2::Y],
            uvs1: vec![
                Vec2::new(0.5, 0.5),
                Vec2::new(0.7, 0.5),
                Vec2::new(0.5, 0.9),
            ],
            ..Default::default()
        };
        let m = Mesh::new(input.clone()).unwrap().0;
        assert!(m.has_second_uv());
        let hit = m
            .intersect(&Ray::new(Vec3A::new(0.25, 0.5, 1.0), -Vec3A::Z), 10.0)
            .unwrap();
        let uv = m.second_uv(&hit).unwrap();
        assert!((uv - Vec2::new(0.55, 0.7)).length() < 1e-6, "{uv}");
        // Along x the second u grows by 0.2 per unit, along y the second v by 0.4.
        let d = m
            .second_uv_change(hit.prim, Vec3A::new(0.1, 0.2, 0.0))
            .unwrap();
        assert!((d - Vec2::new(0.02, 0.08)).length() < 1e-6, "{d}");
        let plain = Mesh::new(MeshInput {
            uvs1: vec![],
            ..input
        })
        .unwrap()
        .0;
        assert_eq!(plain.second_uv(&hit), None);
        assert!(!plain.has_second_uv());
    }
}
