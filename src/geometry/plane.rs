//! An infinite plane: unbounded, so the BVH keeps it apart and tests it on every ray.

use super::{Intersect, Leaving, ShapeHit, Surface, in_range};
use crate::math::{Aabb, Frame, Ray, Vec2, Vec3A};

/// An infinite plane through `point` with unit normal `normal`. Unbounded, so it stays out
/// of the acceleration structure.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// A point on the plane.
    pub point: Vec3A,
    /// Unit normal (the front side).
    pub normal: Vec3A,
    /// Texture axes: `u` along `axes.u`, `v` along `axes.v`.
    pub axes: Frame,
}

impl Plane {
    /// A plane with texture axes chosen so that for an upward normal `u` runs along +x and
    /// `v` along +z.
    pub fn new(point: Vec3A, normal: Vec3A) -> Self {
        let n = normal.normalize();
        let reference = if n.x.abs() < 0.9 { Vec3A::X } else { Vec3A::Z };
        let u = (reference - n * n.dot(reference)).normalize();
        let v = u.cross(n);
        Plane {
            point,
            normal: n,
            axes: Frame { u, v, w: n },
        }
    }
}

impl Intersect for Plane {
    /// Hit in `(0, t_max)`; a ray parallel to the plane misses it.
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let denom = ray.dir.dot(self.normal);
        if denom == 0.0 {
            return None;
        }
        let t = (self.point - ray.origin).dot(self.normal) / denom;
        in_range(t, t_max, 0)
    }

    /// Normal and planar uv in scene units from `point`.
    fn surface(&self, p: Vec3A, _hit: &ShapeHit, _want_uv: bool) -> Surface {
        let rel = p - self.point;
        let in_plane = rel - self.normal * rel.dot(self.normal);
        Surface {
            point: self.point + in_plane,
            normal: self.normal,
            uv: Vec2::new(in_plane.dot(self.axes.u), in_plane.dot(self.axes.v)),
        }
    }

    fn bounds(&self) -> Option<Aabb> {
        None
    }

    fn leaving(&self) -> Leaving {
        Leaving::EitherSide
    }

    fn kind(&self) -> &'static str {
        "plane"
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    #[test]
    fn floor_hit_and_uv_axes() {
        let p = Shape::Plane(Plane::new(Vec3A::new(0.0, -1.0, 0.0), Vec3A::Y));
        let (t, s) = hit(&p, [2.0, 1.0, 3.0], [0.0, -1.0, 0.0]).unwrap();
        assert!((t - 2.0).abs() < 1e-6);
        assert_vec_close(s.normal, Vec3A::Y, 0.0);
        assert!((s.uv - Vec2::new(2.0, 3.0)).length() < 1e-6, "{}", s.uv);
    }

    #[test]
    fn parallel_and_behind_rays_miss() {
        let p = Shape::Plane(Plane::new(Vec3A::ZERO, Vec3A::Y));
        assert!(hit(&p, [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]).is_none());
        assert!(hit(&p, [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]).is_none());
        assert!(hit(&p, [0.0, 1.0, 0.0], [0.0, 1.0, 0.0]).is_none());
        // From below, the plane is still hit.
        assert!(hit(&p, [0.0, -1.0, 0.0], [0.0, 1.0, 0.0]).is_some());
    }
}
