//! A mesh's vertex colours (glTF's `COLOR_0`), which multiply its material's base colour:
//! read at a point of a triangle, between its corners' colours.

use super::Mesh;
use crate::math::{Color, Vec3A};

impl Mesh {
    /// Whether the mesh has vertex colours.
    pub fn has_colors(&self) -> bool {
        !self.colors.is_empty()
    }

    /// The vertex colour at the point `p` (object space) of triangle `prim`: its corners'
    /// colours weighed by the point's barycentrics. White for a mesh without colours.
    pub fn color_at(&self, p: Vec3A, prim: u32) -> Color {
        if self.colors.is_empty() {
            return Color::ONE;
        }
        let b = self.barycentrics(p, prim);
        let f = self.faces[prim as usize];
        let c = |k: usize| Vec3A::from(self.colors[f[k] as usize]);
        c(0) * (1.0 - b.x - b.y) + c(1) * b.x + c(2) * b.y
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Mesh, MeshInput};
    use crate::geometry::Intersect;
    use crate::math::{Ray, Vec3, Vec3A};

    #[test]
    fn colours_blend_between_the_corners() {
        let m = Mesh::new(MeshInput {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2]],
            colors: vec![Vec3::X, Vec3::Y, Vec3::Z],
            ..Default::default()
        })
        .unwrap()
        .0;
        assert!(m.has_colors());
        let hit = m
            .intersect(&Ray::new(Vec3A::new(0.25, 0.5, 1.0), -Vec3A::Z), 10.0)
            .unwrap();
        let c = m.color_at(Vec3A::new(0.25, 0.5, 0.0), hit.prim);
        // Barycentrics 0.25 of the second corner, 0.5 of the third, 0.25 of the first.
        assert!(
            (c - Vec3A::new(0.25, 0.25, 0.5)).abs().max_element() < 1e-6,
            "{c}"
        );
    }
}
