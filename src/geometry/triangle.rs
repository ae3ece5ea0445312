use super::{ShapeHit, Surface, in_range};
use crate::math::{Aabb, Ray, Vec2, Vec3A};

/// A triangle with corners `a`, `b`, `c`; its front side is `(b - a) x (c - a)`
/// (counter-clockwise seen from the front). Both sides are hit.
#[derive(Clone, Debug, PartialEq)]
pub struct Triangle {
    a: Vec3A,
    e1: Vec3A,
    e2: Vec3A,
    normal: Vec3A,
}

impl Triangle {
    /// A triangle; `None` when its area is zero.
    pub fn new(a: Vec3A, b: Vec3A, c: Vec3A) -> Option<Self> {
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        let len = n.length();
        (len > 0.0 && len.is_finite()).then(|| Triangle {
            a,
            e1,
            e2,
            normal: n / len,
        })
    }

    /// Möller-Trumbore intersection.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let p = ray.dir.cross(self.e2);
        let det = self.e1.dot(p);
        if det == 0.0 {
            return None;
        }
        let inv = 1.0 / det;
        let s = ray.origin - self.a;
        let u = s.dot(p) * inv;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let q = s.cross(self.e1);
        let v = ray.dir.dot(q) * inv;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        in_range(self.e2.dot(q) * inv, t_max, 0)
    }

    fn barycentric(&self, p: Vec3A) -> Vec2 {
        let rel = p - self.a;
        let (d00, d01, d11) = (
            self.e1.dot(self.e1),
            self.e1.dot(self.e2),
            self.e2.dot(self.e2),
        );
        let (d20, d21) = (rel.dot(self.e1), rel.dot(self.e2));
        let denom = d00 * d11 - d01 * d01;
        Vec2::new(
            (d11 * d20 - d01 * d21) / denom,
            (d00 * d21 - d01 * d20) / denom,
        )
    }

    /// Normal and barycentric uv (`u` toward `b`, `v` toward `c`).
    pub fn surface(&self, p: Vec3A) -> Surface {
        let uv = self.barycentric(p);
        Surface {
            point: self.a + self.e1 * uv.x + self.e2 * uv.y,
            normal: self.normal,
            uv,
        }
    }

    /// Bounds.
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::new(self.a, self.a + self.e1);
        b.grow(self.a + self.e2);
        b
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    fn tri() -> Shape {
        Shape::Triangle(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::Y).unwrap())
    }

    #[test]
    fn hit_inside_with_barycentrics() {
        let (t, s) = hit(&tri(), [0.25, 0.5, 2.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 2.0).abs() < 1e-6);
        assert_vec_close(s.normal, Vec3A::Z, 1e-6);
        assert!((s.uv - Vec2::new(0.25, 0.5)).length() < 1e-6);
        // From behind it is hit too.
        assert!(hit(&tri(), [0.25, 0.25, -2.0], [0.0, 0.0, 1.0]).is_some());
    }

    #[test]
    fn misses_outside_parallel_and_degenerate() {
        assert!(hit(&tri(), [0.6, 0.6, 2.0], [0.0, 0.0, -1.0]).is_none());
        assert!(hit(&tri(), [0.2, 0.2, 0.0], [1.0, 0.0, 0.0]).is_none());
        assert!(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0).is_none());
    }
}
