use super::{ShapeHit, Surface, in_range};
use crate::math::{Aabb, Ray, Vec2, Vec3A};

/// A flat parallelogram: `corner + a * edge_u + b * edge_v` for `a, b` in `[0, 1]`. With
/// perpendicular edges it is a rectangle. Its front side is `edge_u x edge_v`.
#[derive(Clone, Debug, PartialEq)]
pub struct Rect {
    corner: Vec3A,
    edge_u: Vec3A,
    edge_v: Vec3A,
    normal: Vec3A,
    /// `n / (n . n)` with `n = edge_u x edge_v`, to solve for the edge coordinates.
    w: Vec3A,
}

impl Rect {
    /// From a corner and two edges; `None` when the edges are parallel or zero.
    pub fn new(corner: Vec3A, edge_u: Vec3A, edge_v: Vec3A) -> Option<Self> {
        let n = edge_u.cross(edge_v);
        let nn = n.length_squared();
        if nn == 0.0 || !nn.is_finite() {
            return None;
        }
        Some(Rect {
            corner,
            edge_u,
            edge_v,
            normal: n / nn.sqrt(),
            w: n / nn,
        })
    }

    /// Hit in `(0, t_max)` inside the parallelogram (edges included).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let denom = ray.dir.dot(self.normal);
        if denom == 0.0 {
            return None;
        }
        let t = (self.corner - ray.origin).dot(self.normal) / denom;
        let hit = in_range(t, t_max, 0)?;
        let (a, b) = self.coords(ray.at(t));
        ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(hit)
    }

    fn coords(&self, p: Vec3A) -> (f32, f32) {
        let rel = p - self.corner;
        (
            self.w.dot(rel.cross(self.edge_v)),
            self.w.dot(self.edge_u.cross(rel)),
        )
    }

    /// Normal and uv: `u` from 0 to 1 along `edge_u`, `v` from 1 at the corner to 0 at the
    /// far end of `edge_v`. Seen from the front, with `edge_u` to the right and `edge_v` up,
    /// an image appears upright with the corner at its bottom-left.
    pub fn surface(&self, p: Vec3A) -> Surface {
        let (a, b) = self.coords(p);
        Surface {
            point: self.corner + a * self.edge_u + b * self.edge_v,
            normal: self.normal,
            uv: Vec2::new(a, 1.0 - b),
        }
    }

    /// Bounds.
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::new(self.corner, self.corner + self.edge_u);
        b.grow(self.corner + self.edge_v);
        b.grow(self.corner + self.edge_u + self.edge_v);
        b
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    fn floor() -> Shape {
        Shape::Rect(
            Rect::new(
                Vec3A::new(-25.0, -15.0, -40.0),
                Vec3A::new(50.0, 0.0, 0.0),
                Vec3A::new(0.0, 0.0, -160.0),
            )
            .unwrap(),
        )
    }

    #[test]
    fn seed_floor_faces_up_and_maps_uv() {
        let (t, s) = hit(&floor(), [0.0, 0.0, -120.0], [0.0, -1.0, 0.0]).unwrap();
        assert!((t - 15.0).abs() < 1e-5);
        assert_vec_close(s.normal, Vec3A::Y, 1e-6);
        assert!((s.uv - Vec2::new(0.5, 0.5)).length() < 1e-5);
    }

    #[test]
    fn outside_edges_and_parallel_rays_miss() {
        assert!(hit(&floor(), [26.0, 0.0, -120.0], [0.0, -1.0, 0.0]).is_none());
        assert!(hit(&floor(), [0.0, 0.0, -30.0], [0.0, -1.0, 0.0]).is_none());
        assert!(hit(&floor(), [0.0, -15.0, 0.0], [0.0, 0.0, -1.0]).is_none());
        assert!(Rect::new(Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0).is_none());
    }
}
