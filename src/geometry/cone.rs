//! A finite cone, capped or open: its hits (a quadratic in the ray's parameter, and the
//! base's disk), normals and uv.

use super::cylinder::{BOTTOM, SIDE, cap_hit, cap_uv, disk_bounds};
use super::{Intersect, Leaving, ShapeHit, Surface, in_range, solve_quadratic};
use crate::math::{Aabb, Frame, Ray, Vec2, Vec3A};

/// A finite cone: a disk of radius `radius` at `base`, narrowing to a point at
/// `base + height * axis`; the base may be capped.
#[derive(Clone, Debug, PartialEq)]
pub struct Cone {
    /// Centre of the base.
    pub base: Vec3A,
    /// Frame whose `w` is the unit axis, pointing to the apex.
    pub frame: Frame,
    /// Base radius, positive.
    pub radius: f32,
    /// Base to apex, positive.
    pub height: f32,
    /// Whether the base is closed by a disk.
    pub capped: bool,
}

impl Cone {
    /// A cone; `axis` need not be unit length but must not be zero.
    pub fn new(base: Vec3A, axis: Vec3A, radius: f32, height: f32, capped: bool) -> Self {
        Cone {
            base,
            frame: Frame::from_axis(axis.normalize()),
            radius,
            height,
            capped,
        }
    }
}

impl Intersect for Cone {
    /// Nearest hit on the side (the nappe between base and apex only) or the base cap.
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let o = self.frame.to_local(ray.origin - self.base);
        let d = self.frame.to_local(ray.dir);
        let k = self.radius / self.height;
        let k2 = k * k;
        // x^2 + y^2 = k^2 (h - z)^2
        let s = self.height - o.z;
        let a = d.x * d.x + d.y * d.y - k2 * d.z * d.z;
        let half_b = o.x * d.x + o.y * d.y + k2 * s * d.z;
        let c = o.x * o.x + o.y * o.y - k2 * s * s;
        let on_nappe = |t: f32| {
            let z = o.z + t * d.z;
            (0.0..=self.height).contains(&z)
        };
        let mut best = None;
        let roots = if a.abs() < 1e-12 * (d.length_squared() * (1.0 + k2)) {
            // Parallel to a generating line: one root.
            (half_b != 0.0).then(|| {
                let t = -c / (2.0 * half_b);
                (t, t)
            })
        } else {
            solve_quadratic(a, half_b, c)
        };
        if let Some((t0, t1)) = roots {
            for t in [t0, t1] {
                if on_nappe(t)
                    && let Some(h) = in_range(t, t_max, SIDE)
                {
                    best = Some(h);
                    break;
                }
            }
        }
        if self.capped {
            best = cap_hit(o, d, 0.0, self.radius, BOTTOM, t_max, best);
        }
        best
    }

    /// Normal and uv (as the cylinder's: angle around the axis, `v` from 0 at the apex to 1
    /// at the base; the cap planar).
    fn surface(&self, p: Vec3A, hit: &ShapeHit, want_uv: bool) -> Surface {
        let part = hit.part;
        let l = self.frame.to_local(p - self.base);
        let k = self.radius / self.height;
        let (local_point, local_normal, uv) = if part == SIDE {
            // Project onto the generating line from (radius, 0) to (0, height) in the
            // (distance from axis, height) plane: the quadratic's root can be off by more than
            // the ray offset, and a point inside the surface would shadow itself.
            let rho = (l.x * l.x + l.y * l.y).sqrt();
            let g = Vec2::new(-self.radius, self.height).normalize();
            let along = ((Vec2::new(rho, l.z) - Vec2::new(self.radius, 0.0)).dot(g))
                .clamp(0.0, self.radius.hypot(self.height));
            let on = Vec2::new(self.radius, 0.0) + g * along;
            let (cx, cy) = if rho > 0.0 {
                (l.x / rho, l.y / rho)
            } else {
                (1.0, 0.0)
            };
            let n = if on.x > 0.0 {
                Vec3A::new(cx, cy, k).normalize()
            } else {
                Vec3A::Z
            };
            let uv = if want_uv {
                Vec2::new(super::cylinder::angle_u(l), 1.0 - on.y / self.height)
            } else {
                Vec2::ZERO
            };
            (Vec3A::new(cx * on.x, cy * on.x, on.y), n, uv)
        } else {
            (
                Vec3A::new(l.x, l.y, 0.0),
                -Vec3A::Z,
                cap_uv(l, self.radius, false),
            )
        };
        Surface {
            point: self.base + self.frame.to_world(local_point),
            normal: self.frame.to_world(local_normal),
            uv,
        }
    }

    /// True when `p` is strictly inside the solid cone.
    fn contains(&self, p: Vec3A) -> bool {
        let l = self.frame.to_local(p - self.base);
        let r = self.radius * (1.0 - l.z / self.height);
        l.z > 0.0 && l.z < self.height && l.x * l.x + l.y * l.y < r * r
    }

    /// Bounds (base disk and apex).
    fn bounds(&self) -> Option<Aabb> {
        let mut b = disk_bounds(self.base, self.frame.w, self.radius);
        b.grow(self.base + self.frame.w * self.height);
        Some(b)
    }

    fn leaving(&self) -> Leaving {
        Leaving::Outside
    }

    fn kind(&self) -> &'static str {
        "cone"
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    fn cone(capped: bool) -> Shape {
        // Base radius 1 at y = 0, apex at y = 2.
        Shape::Cone(Cone::new(Vec3A::ZERO, Vec3A::Y, 1.0, 2.0, capped))
    }

    #[test]
    fn side_hit_and_slanted_normal() {
        // At height 1 the radius is 0.5.
        let (t, s) = hit(&cone(true), [0.0, 1.0, 5.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 4.5).abs() < 1e-5, "{t}");
        // Normal leans up by atan(r / h): (0, 1, 2) normalised.
        assert_vec_close(s.normal, Vec3A::new(0.0, 1.0, 2.0).normalize(), 1e-5);
    }

    #[test]
    fn the_other_nappe_is_not_part_of_the_cone() {
        // Above the apex the double cone would continue; this ray passes there and misses.
        assert!(hit(&cone(true), [0.0, 3.0, 5.0], [0.0, 0.0, -1.0]).is_none());
        // Below the base, likewise.
        assert!(hit(&cone(false), [0.0, -1.0, 5.0], [0.0, 0.0, -1.0]).is_none());
    }

    #[test]
    fn cap_from_below_and_inside_out() {
        let (t, s) = hit(&cone(true), [0.2, -3.0, 0.0], [0.0, 1.0, 0.0]).unwrap();
        assert!((t - 3.0).abs() < 1e-5);
        assert_vec_close(s.normal, -Vec3A::Y, 1e-6);
        let (t, _) = hit(&cone(true), [0.0, 0.5, 0.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((t - 0.75).abs() < 1e-5);
        // Open: from below, the ray goes in through the base and hits the inside.
        let (t, _) = hit(&cone(false), [0.2, -3.0, 0.0], [0.0, 1.0, 0.0]).unwrap();
        assert!((t - 4.6).abs() < 1e-4, "{t}");
    }

    #[test]
    fn shadow_rays_leaving_the_side_never_hit_it_again() {
        use crate::math::offset_ray_origin;
        // The showcase scene's gold cone, seen from its camera, lit from its spot light.
        let c = Shape::Cone(Cone::new(
            Vec3A::new(2.6, 0.0, 0.4),
            Vec3A::Y,
            0.8,
            2.0,
            true,
        ));
        let (eye, light) = (Vec3A::new(0.0, 3.2, 9.0), Vec3A::new(-3.0, 7.0, 4.0));
        let mut lit = 0;
        for i in 0..100 {
            for j in 0..100 {
                let target = Vec3A::new(2.0 + i as f32 * 0.012, 0.05 + j as f32 * 0.02, 0.8);
                let ray = Ray::new(eye, (target - eye).normalize());
                let Some(h) = c.intersect(&ray, f32::INFINITY) else {
                    continue;
                };
                let s = c.surface(ray.at(h.t), &h, false);
                let o = offset_ray_origin(s.point, s.normal);
                let l = (light - o).normalize();
                if s.normal.dot(l) > 0.0 {
                    lit += 1;
                    assert!(
                        c.intersect(&Ray::new(o, l), f32::INFINITY).is_none(),
                        "acne at {}",
                        s.point
                    );
                }
            }
        }
        assert!(lit > 1000);
    }

    #[test]
    fn ray_parallel_to_a_generating_line() {
        // Direction (0.5, -1, 0) up to scale is parallel to the slant from apex to (1, 0, 0).
        let r = hit(&cone(true), [-0.5, 3.0, 0.0], [0.5, -1.0, 0.0]);
        let (t, s) = r.unwrap();
        assert!(t.is_finite() && s.normal.is_finite());
    }
}
