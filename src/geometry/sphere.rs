//! A sphere: its hits (the quadratic without the textbook's cancellation), one ray at a time
//! and eight at once, normal and uv, and its points sampled by solid angle for area lights.

use super::{Intersect, Leaving, ShapeHit, Surface, equirectangular_uv, in_range};
use crate::math::{Aabb, LANES, Ray, RayLanes, Vec2, Vec3A};

/// A sphere given by its centre and radius.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    /// Centre, in object space.
    pub center: Vec3A,
    /// Radius, positive.
    pub radius: f32,
}

impl Sphere {
    /// [`Sphere::intersect`] of every ray of a packet at once, each below its own `t_max`:
    /// the distances of the hits, infinite for a miss. The same operations in the same
    /// order, lane by lane, so the same distances to the bit (a test checks it); written
    /// without branches, so that the compiler makes one vector operation of each.
    #[inline]
    pub(crate) fn intersect_lanes(&self, rays: &RayLanes, t_max: &[f32; LANES]) -> [f32; LANES] {
        let (c, r2) = (self.center, self.radius * self.radius);
        let mut out = [f32::INFINITY; LANES];
        for l in 0..LANES {
            let (dx, dy, dz) = (rays.dir[0][l], rays.dir[1][l], rays.dir[2][l]);
            let (fx, fy, fz) = (
                rays.origin[0][l] - c.x,
                rays.origin[1][l] - c.y,
                rays.origin[2][l] - c.z,
            );
            let a = dx * dx + dy * dy + dz * dz;
            let half_b = fx * dx + fy * dy + fz * dz;
            let cc = fx * fx + fy * fy + fz * fz - r2;
            let k = half_b / a;
            let (lx, ly, lz) = (fx - dx * k, fy - dy * k, fz - dz * k);
            let disc = a * (r2 - (lx * lx + ly * ly + lz * lz));
            let q = -(half_b + disc.sqrt().copysign(half_b));
            let (x, y) = (cc / q, q / a);
            let (t0, t1) = if q == 0.0 {
                (0.0, 0.0)
            } else if x < y {
                (x, y)
            } else {
                (y, x)
            };
            let t = if t0 > 0.0 && t0 < t_max[l] {
                t0
            } else if t1 > 0.0 && t1 < t_max[l] {
                t1
            } else {
                f32::INFINITY
            };
            let miss = (cc > 0.0 && half_b > 0.0) || disc < 0.0 || a == 0.0;
            out[l] = if miss { f32::INFINITY } else { t };
        }
        out
    }
}

impl Intersect for Sphere {
    /// Nearest hit in `(0, t_max)`: the near root, or the far root when the ray starts
    /// inside (the near root is then behind it).
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let f = ray.origin - self.center;
        let a = ray.dir.length_squared();
        let half_b = f.dot(ray.dir);
        let c = f.length_squared() - self.radius * self.radius;
        if c > 0.0 && half_b > 0.0 {
            // Starts outside and points away: both roots are behind.
            return None;
        }
        // Discriminant as a * (r^2 - |f - (f.d / d.d) d|^2): the distance from the centre to
        // the line is computed directly, which stays accurate for small or distant spheres
        // (Haines et al., "Precision Improvements for Ray/Sphere Intersection", 2019).
        let l = f - ray.dir * (half_b / a);
        let disc = a * (self.radius * self.radius - l.length_squared());
        if disc < 0.0 || a == 0.0 {
            return None;
        }
        let q = -(half_b + disc.sqrt().copysign(half_b));
        let (t0, t1) = if q == 0.0 {
            (0.0, 0.0)
        } else {
            let (x, y) = (c / q, q / a);
            if x < y { (x, y) } else { (y, x) }
        };
        in_range(t0, t_max, 0).or_else(|| in_range(t1, t_max, 0))
    }

    /// Outward normal and equirectangular uv (longitude 0 toward +z, north pole v = 0). The
    /// normal is the offset from the centre over the radius, unit to within the rounding of
    /// the hit point: no square root and division, which every ray that meets a sphere
    /// waited on before its shading could start.
    fn surface(&self, p: Vec3A, _hit: &ShapeHit, want_uv: bool) -> Surface {
        let n = (p - self.center) * (1.0 / self.radius);
        Surface {
            point: p,
            normal: n,
            uv: if want_uv {
                equirectangular_uv(n)
            } else {
                Vec2::ZERO
            },
        }
    }

    /// The box around the sphere, object space: its centre, less and plus the radius on
    /// every axis.
    fn bounds(&self) -> Option<Aabb> {
        Some(Aabb::new(
            self.center - Vec3A::splat(self.radius),
            self.center + Vec3A::splat(self.radius),
        ))
    }

    fn contains(&self, p: Vec3A) -> bool {
        (p - self.center).length_squared() < self.radius * self.radius
    }

    /// The unit normal changes by the step over the radius (to first order, for a step in
    /// the tangent plane): no square root for a mirror ball's reflected differentials.
    fn differential(&self, p: Vec3A, hit: &ShapeHit, dp: Vec3A, want_uv: bool) -> (Vec2, Vec3A) {
        if want_uv {
            return super::differenced(self, p, hit, dp, true);
        }
        (Vec2::ZERO, (p + dp - self.center) / self.radius)
    }

    fn leaving(&self) -> Leaving {
        Leaving::Outside
    }

    fn kind(&self) -> &'static str {
        "sphere"
    }
}

impl Sphere {
    /// The sphere's area.
    pub fn area(&self) -> f32 {
        4.0 * std::f32::consts::PI * self.radius * self.radius
    }

    /// A point on the sphere, every one equally likely (density `1 / area`).
    pub fn sample_area(&self, u: Vec2) -> super::SurfaceSample {
        let n = crate::math::sampling::uniform_sphere(u);
        super::SurfaceSample {
            point: self.center + self.radius * n,
            normal: n,
            pdf: 1.0 / self.area(),
        }
    }

    /// The cosine of the half-angle of the cone the sphere fills seen from `from`, or
    /// `None` when `from` is inside it (it then fills every direction).
    fn cone_cos(&self, from: Vec3A) -> Option<f32> {
        let d2 = (self.center - from).length_squared();
        let r2 = self.radius * self.radius;
        (d2 > r2 * 1.0001).then(|| (1.0 - r2 / d2).max(0.0).sqrt())
    }

    /// A point of the sphere seen from `from`, chosen uniformly within the cone of
    /// directions it fills (from outside; inside, by area), with its density per unit solid
    /// angle at `from`. Only the visible cap is reached, so no sample is wasted on the back.
    pub fn sample_solid_angle(&self, from: Vec3A, u: Vec2) -> Option<super::SurfaceSample> {
        let Some(cos_max) = self.cone_cos(from) else {
            let mut s = self.sample_area(u);
            s.pdf = super::area_to_solid_angle(s.pdf, from, s.point, s.normal)?;
            return Some(s);
        };
        let axis = self.center - from;
        let dist = axis.length();
        let frame = crate::math::Frame::from_axis(axis / dist);
        let dir = frame.to_world(crate::math::sampling::uniform_cone(u, cos_max));
        // The nearer crossing of the ray `from + t dir` with the sphere; a direction that
        // rounding put just outside the cone takes the tangent point.
        let b = dir.dot(axis);
        let disc = b * b - (dist * dist - self.radius * self.radius);
        let t = b - disc.max(0.0).sqrt();
        let point = from + t * dir;
        Some(super::SurfaceSample {
            point,
            normal: (point - self.center).normalize_or(dir),
            pdf: crate::math::sampling::uniform_cone_pdf(cos_max),
        })
    }

    /// The density per unit solid angle with which [`Sphere::sample_solid_angle`] from
    /// `from` picks `point`, a point of the sphere that `from` sees.
    pub fn solid_angle_pdf(&self, from: Vec3A, point: Vec3A) -> f32 {
        match self.cone_cos(from) {
            Some(cos_max) => crate::math::sampling::uniform_cone_pdf(cos_max),
            None => {
                let n = (point - self.center).normalize_or(Vec3A::Z);
                super::area_to_solid_angle(1.0 / self.area(), from, point, n).unwrap_or(0.0)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    fn unit_at(c: [f32; 3], r: f32) -> Shape {
        Shape::Sphere(Sphere {
            center: Vec3A::from_array(c),
            radius: r,
        })
    }

    /// The packet test gives what the test of one ray gives, to the bit: from outside and
    /// inside, grazing, and with degenerate directions.
    #[test]
    fn packets_match_single_rays() {
        use crate::math::Rng;
        for (c, r) in [
            ([0.0, 0.0, -10.0], 2.0),
            ([3.5, -1.0, 7.0], 0.25),
            ([1e3, 2e3, -5e3], 40.0),
        ] {
            let s = Sphere {
                center: Vec3A::from_array(c),
                radius: r,
            };
            let c = s.center;
            let on_sphere = |rng: &mut Rng| {
                let d = in_unit_cube(rng);
                c + d.normalize() * r * (0.9 + rng.next_f32() * 0.2)
            };
            let origin = |rng: &mut Rng| {
                if rng.next_f32() < 0.2 {
                    on_sphere(rng) - (on_sphere(rng) - c) * 0.5
                } else {
                    c + in_unit_cube(rng) * (r * 20.0)
                }
            };
            let hits = assert_lanes_match(
                |ray, t_max| s.intersect(ray, t_max),
                |rays, t_max| s.intersect_lanes(rays, t_max),
                origin,
                on_sphere,
            );
            assert!(hits > 10_000, "{hits} hits");
        }
    }

    #[test]
    fn hit_from_outside_gives_near_side_and_normal() {
        let s = unit_at([0.0, 0.0, -10.0], 2.0);
        let (t, surf) = hit(&s, [0.0; 3], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 8.0).abs() < 1e-5);
        assert_vec_close(surf.normal, Vec3A::Z, 1e-6);
    }

    #[test]
    fn hit_from_inside_finds_the_far_side() {
        let s = unit_at([0.0, 0.0, 0.0], 3.0);
        let (t, surf) = hit(&s, [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((t - 2.0).abs() < 1e-6);
        assert_vec_close(surf.normal, Vec3A::X, 1e-6);
    }

    #[test]
    fn behind_and_missing_rays_miss() {
        let s = unit_at([0.0, 0.0, -10.0], 2.0);
        assert!(hit(&s, [0.0; 3], [0.0, 0.0, 1.0]).is_none());
        assert!(hit(&s, [0.0, 2.001, 0.0], [0.0, 0.0, -1.0]).is_none());
    }

    #[test]
    fn grazing_ray_touches_without_nan() {
        let s = unit_at([0.0, 0.0, -10.0], 2.0);
        let (t, surf) = hit(&s, [0.0, 1.9999, 0.0], [0.0, 0.0, -1.0]).unwrap();
        assert!(t.is_finite() && surf.normal.is_finite());
        assert!((t - 10.0).abs() < 0.05);
    }

    #[test]
    fn unnormalised_direction_gives_the_same_point() {
        let s = unit_at([1.0, 2.0, -7.0], 1.5);
        let (t1, s1) = hit(&s, [0.0; 3], [1.0, 2.0, -7.0]).unwrap();
        let (t2, s2) = hit(&s, [0.0; 3], [0.1, 0.2, -0.7]).unwrap();
        assert!((t1 * 10.0 - t2).abs() < 1e-3);
        assert_vec_close(s1.point, s2.point, 1e-5);
    }

    #[test]
    fn small_far_sphere_is_hit_precisely() {
        let s = unit_at([0.0, 0.0, -1.0e4], 0.01);
        let (t, surf) = hit(&s, [0.0, 0.005, 0.0], [0.0, 0.0, -1.0]).unwrap();
        let expected = 1.0e4 - (0.01f32 * 0.01 - 0.005 * 0.005).sqrt();
        // t to within a few ulps of 1e4 (the textbook discriminant loses it entirely).
        assert!((t - expected).abs() < 2e-3, "{t}");
        // The point itself is only as precise as f32 at 1e4 (about 1e-3, a tenth of the
        // radius), so the normal is only roughly right.
        assert!((surf.normal.y - 0.5).abs() < 0.1, "{}", surf.normal);
    }
}
