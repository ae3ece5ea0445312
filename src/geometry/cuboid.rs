//! An axis-aligned box in object space (a transform turns it): its hits by the slab test,
//! the face hit, normals and uv.

use super::{Intersect, Leaving, ShapeHit, Surface};
use crate::math::{Aabb, Ray, Vec2, Vec3A};

/// A box between two corners, axis-aligned in object space (rotate it with a transform).
#[derive(Clone, Debug, PartialEq)]
pub struct Cuboid {
    /// Smallest corner.
    pub min: Vec3A,
    /// Largest corner (greater than `min` on every axis).
    pub max: Vec3A,
}

impl Intersect for Cuboid {
    /// Slab test. Parts are faces: `2 * axis` for the `min` face, `2 * axis + 1` for `max`.
    /// A ray from inside hits the face it leaves through.
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let mut near = f32::NEG_INFINITY;
        let mut far = f32::INFINITY;
        let (mut near_part, mut far_part) = (0u8, 0u8);
        for axis in 0..3 {
            let (o, d) = (ray.origin[axis], ray.dir[axis]);
            let (lo, hi) = (self.min[axis], self.max[axis]);
            if d == 0.0 {
                // Parallel to this pair of faces: inside the slab or never.
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let inv = 1.0 / d;
            let (mut t0, mut t1) = ((lo - o) * inv, (hi - o) * inv);
            let (mut p0, mut p1) = (2 * axis as u8, 2 * axis as u8 + 1);
            if t0 > t1 {
                std::mem::swap(&mut t0, &mut t1);
                std::mem::swap(&mut p0, &mut p1);
            }
            if t0 > near {
                near = t0;
                near_part = p0;
            }
            if t1 < far {
                far = t1;
                far_part = p1;
            }
        }
        if near > far {
            return None;
        }
        if near > 0.0 && near < t_max {
            Some(ShapeHit {
                t: near,
                part: near_part,
                prim: 0,
                bary: Vec2::ZERO,
            })
        } else if near <= 0.0 && far > 0.0 && far < t_max {
            Some(ShapeHit {
                t: far,
                part: far_part,
                prim: 0,
                bary: Vec2::ZERO,
            })
        } else {
            None
        }
    }

    /// Face normal and uv across the face, 0 to 1, oriented so an image appears upright on
    /// each side face seen from outside.
    fn surface(&self, p: Vec3A, hit: &ShapeHit, _want_uv: bool) -> Surface {
        let part = hit.part;
        let axis = (part / 2) as usize;
        let positive = part % 2 == 1;
        let mut point = p.clamp(self.min, self.max);
        point[axis] = if positive {
            self.max[axis]
        } else {
            self.min[axis]
        };
        let mut normal = Vec3A::ZERO;
        normal[axis] = if positive { 1.0 } else { -1.0 };
        let r = (point - self.min) / (self.max - self.min);
        // Each face as seen from outside, upright: u to the right, v down (image rows); the
        // top face is seen from above with -z up, the bottom from below with +z up.
        let uv = match part {
            0 => Vec2::new(r.z, 1.0 - r.y),       // -x
            1 => Vec2::new(1.0 - r.z, 1.0 - r.y), // +x
            2 => Vec2::new(r.x, 1.0 - r.z),       // -y
            3 => Vec2::new(r.x, r.z),             // +y
            4 => Vec2::new(1.0 - r.x, 1.0 - r.y), // -z
            _ => Vec2::new(r.x, 1.0 - r.y),       // +z
        };
        Surface { point, normal, uv }
    }

    /// The box itself, object space (it is axis-aligned there).
    fn bounds(&self) -> Option<Aabb> {
        Some(Aabb::new(self.min, self.max))
    }

    fn contains(&self, p: Vec3A) -> bool {
        p.cmpgt(self.min).all() && p.cmplt(self.max).all()
    }

    fn leaving(&self) -> Leaving {
        Leaving::Outside
    }

    fn kind(&self) -> &'static str {
        "box"
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    fn seed_box() -> Shape {
        Shape::Cuboid(Cuboid {
            min: Vec3A::new(-17.0, -15.0, -85.0),
            max: Vec3A::new(-11.0, -8.0, -79.0),
        })
    }

    #[test]
    fn faces_and_normals_from_each_direction() {
        let b = seed_box();
        let (t, s) = hit(&b, [-14.0, -10.0, 0.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 79.0).abs() < 1e-5);
        assert_vec_close(s.normal, Vec3A::Z, 0.0);
        let (t, s) = hit(&b, [-14.0, 0.0, -80.0], [0.0, -1.0, 0.0]).unwrap();
        assert!((t - 8.0).abs() < 1e-5);
        assert_vec_close(s.normal, Vec3A::Y, 0.0);
        let (_, s) = hit(&b, [-30.0, -10.0, -80.0], [1.0, 0.0, 0.0]).unwrap();
        assert_vec_close(s.normal, -Vec3A::X, 0.0);
    }

    #[test]
    fn front_face_uv_is_upright() {
        let b = seed_box();
        // The +z face's top-left corner, seen from +z, is (min x, max y): uv (0, 0).
        let (_, s) = hit(&b, [-16.9, -8.1, 0.0], [0.0, 0.0, -1.0]).unwrap();
        assert!(s.uv.x < 0.05 && s.uv.y < 0.05, "{}", s.uv);
    }

    #[test]
    fn inside_ray_exits_through_the_far_face() {
        let b = seed_box();
        let (t, s) = hit(&b, [-14.0, -10.0, -82.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 3.0).abs() < 1e-5);
        assert_vec_close(s.normal, -Vec3A::Z, 0.0);
    }

    #[test]
    fn parallel_rays_in_and_out_of_the_slab() {
        let b = seed_box();
        // Parallel to x faces, outside the x slab: miss, no NaN.
        assert!(hit(&b, [0.0, -10.0, 0.0], [0.0, 0.0, -1.0]).is_none());
        // Along a face plane exactly (x = -11): counts as touching the slab.
        let r = hit(&b, [-11.0, -10.0, 0.0], [0.0, 0.0, -1.0]);
        assert!(r.is_some_and(|(t, s)| t.is_finite() && s.normal.is_finite()));
        assert!(hit(&b, [-14.0, -10.0, -70.0], [0.0, 0.0, 1.0]).is_none());
    }
}
