//! A closed mesh as a solid, for constructive solid geometry: whether its surface is
//! closed, and whether a point lies inside it.

use super::Mesh;
use crate::geometry::Intersect;
use crate::math::{Ray, Vec3A};
use std::collections::HashMap;

/// Most crossings counted along one ray from a point (a bound on the walk, far above what
/// any model gives).
const MAX_CROSSINGS: usize = 1 << 16;

impl Mesh {
    /// How many edges border one triangle only, or more than two, corners matched by
    /// position (a file may repeat a vertex for each of its uvs or normals): 0 for a closed
    /// surface, one that bounds a solid.
    pub fn open_edges(&self) -> usize {
        let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        for p in 0..self.faces.len() as u32 {
            if self.own_prim(p) != p {
                continue;
            }
            let c = self.corners(p).map(|v| {
                let next = ids.len() as u32;
                *ids.entry(v.to_array().map(f32::to_bits)).or_insert(next)
            });
            for (a, b) in [(c[0], c[1]), (c[1], c[2]), (c[2], c[0])] {
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        edges.values().filter(|&&n| n != 2).count()
    }

    /// Whether `p` lies inside the (closed) surface: rays from it cross the surface an odd
    /// number of times. The triangle test is watertight, so a ray through an edge between
    /// two faces it crosses counts one crossing there; one that only grazes an edge or a
    /// vertex may count one where there are none or two, so three rays in unrelated
    /// directions vote.
    pub fn encloses(&self, p: Vec3A) -> bool {
        // Along no axis, diagonal or simple ratio, so that a ray seldom meets an edge.
        const DIRECTIONS: [[f32; 3]; 3] = [
            [0.435_6, 0.552_1, 0.711_0],
            [-0.631_3, 0.318_7, 0.707_0],
            [0.241_1, -0.880_3, 0.408_6],
        ];
        let odd = DIRECTIONS
            .iter()
            .filter(|d| self.odd_crossings(p, Vec3A::from_array(**d).normalize()))
            .count();
        odd >= 2
    }

    /// Whether the ray from `p` along `dir` crosses the surface an odd number of times.
    fn odd_crossings(&self, p: Vec3A, dir: Vec3A) -> bool {
        let mut from = p;
        let mut odd = false;
        for _ in 0..MAX_CROSSINGS {
            let Some(h) = self.intersect(&Ray::new(from, dir), f32::INFINITY) else {
                break;
            };
            odd = !odd;
            // Past the crossing by a hair of the point's size, as the CSG walk steps.
            let q = from + dir * h.t;
            from = q + dir * (1e-5 * q.abs().max_element().max(1.0));
        }
        odd
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Mesh, MeshInput};
    use crate::math::{Vec3, Vec3A};

    /// A unit cube's surface, its corners repeated per face (as a file with per-face
    /// normals has them), or with one face left out.
    fn cube(open: bool) -> Mesh {
        let mut positions = vec![];
        let mut triangles = vec![];
        let faces: [[[f32; 3]; 4]; 6] = [
            [[0., 0., 0.], [0., 1., 0.], [1., 1., 0.], [1., 0., 0.]],
            [[0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]],
            [[0., 0., 0.], [1., 0., 0.], [1., 0., 1.], [0., 0., 1.]],
            [[0., 1., 0.], [0., 1., 1.], [1., 1., 1.], [1., 1., 0.]],
            [[0., 0., 0.], [0., 0., 1.], [0., 1., 1.], [0., 1., 0.]],
            [[1., 0., 0.], [1., 1., 0.], [1., 1., 1.], [1., 0., 1.]],
        ];
        for f in &faces[..if open { 5 } else { 6 }] {
            let n = positions.len() as u32;
            positions.extend(f.iter().map(|&p| Vec3::from_array(p)));
            triangles.push([n, n + 1, n + 2]);
            triangles.push([n, n + 2, n + 3]);
        }
        Mesh::new(MeshInput {
            positions,
            triangles,
            ..Default::default()
        })
        .unwrap()
        .0
    }

    #[test]
    fn a_closed_cube_has_no_open_edges_and_one_face_less_has_four() {
        assert_eq!(cube(false).open_edges(), 0);
        assert_eq!(cube(true).open_edges(), 4);
    }

    #[test]
    fn points_inside_and_outside_a_closed_cube() {
        let m = cube(false);
        for (p, inside) in [
            ([0.5, 0.5, 0.5], true),
            ([0.01, 0.99, 0.5], true),
            ([0.25, 0.25, 0.25], true),
            // Rays from here along (1, 2, 3) would only graze the edge at (0, 0.5, 1).
            ([-0.5, -0.5, -0.5], false),
            // Right at an edge's and a corner's level, from outside and inside.
            ([-0.5, 0.0, 0.0], false),
            ([0.5, 0.0, 1e-3], true),
            ([1.5, 0.5, 0.5], false),
            ([-0.5, -0.5, -0.5], false),
            ([0.5, 0.5, 2.0], false),
        ] {
            assert_eq!(m.encloses(Vec3A::from_array(p)), inside, "{p:?}");
        }
    }
}
