//! A finite cylinder about any axis, capped or open: its hits (a quadratic, and the caps'
//! disks), normals and uv; the cap helpers the cone and disk share.

use super::{Intersect, Leaving, ShapeHit, Surface, in_range, nearer, solve_quadratic};
use crate::math::{Aabb, Frame, Ray, Vec2, Vec3A};
use std::f32::consts::TAU;

/// A finite cylinder around any axis: radius `radius`, from `base` to
/// `base + height * axis`, with or without end caps.
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    /// Centre of the bottom end.
    pub base: Vec3A,
    /// Frame whose `w` is the unit axis.
    pub frame: Frame,
    /// Radius, positive.
    pub radius: f32,
    /// Length along the axis, positive.
    pub height: f32,
    /// Whether the ends are closed by disks.
    pub capped: bool,
}

/// Part indices of cylinders and cones.
pub(crate) const SIDE: u8 = 0;
pub(crate) const BOTTOM: u8 = 1;
pub(crate) const TOP: u8 = 2;

impl Cylinder {
    /// A cylinder; `axis` need not be unit length but must not be zero.
    pub fn new(base: Vec3A, axis: Vec3A, radius: f32, height: f32, capped: bool) -> Self {
        Cylinder {
            base,
            frame: Frame::from_axis(axis.normalize()),
            radius,
            height,
            capped,
        }
    }
}

impl Intersect for Cylinder {
    /// Nearest hit among the side (both roots tried against the height) and the caps.
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let o = self.frame.to_local(ray.origin - self.base);
        let d = self.frame.to_local(ray.dir);
        let r2 = self.radius * self.radius;
        // (o + t d) projected off the axis has length r: the quadratic in t, with the
        // middle term's factor 2 kept in the half-b form (the report's bug).
        let a = d.x * d.x + d.y * d.y;
        let half_b = o.x * d.x + o.y * d.y;
        let c = o.x * o.x + o.y * o.y - r2;
        let mut best = None;
        if let Some((t0, t1)) = solve_quadratic(a, half_b, c) {
            for t in [t0, t1] {
                let z = o.z + t * d.z;
                if (0.0..=self.height).contains(&z)
                    && let Some(h) = in_range(t, t_max, SIDE)
                {
                    best = Some(h);
                    break;
                }
            }
        }
        if self.capped {
            best = cap_hit(o, d, 0.0, self.radius, BOTTOM, t_max, best);
            best = cap_hit(o, d, self.height, self.radius, TOP, t_max, best);
        }
        best
    }

    /// Normal (radial on the side, along the axis on the caps) and uv: on the side `u` is the
    /// angle around the axis from 0 to 1 and `v` runs from 0 at the top to 1 at the base; on
    /// the caps uv are planar, centred at (0.5, 0.5), spanning the diameter.
    fn surface(&self, p: Vec3A, hit: &ShapeHit, want_uv: bool) -> Surface {
        let part = hit.part;
        let l = self.frame.to_local(p - self.base);
        let (local_point, local_normal, uv) = match part {
            SIDE => {
                let radial = Vec3A::new(l.x, l.y, 0.0).normalize_or(Vec3A::X);
                (
                    radial * self.radius + Vec3A::Z * l.z,
                    radial,
                    if want_uv {
                        Vec2::new(angle_u(l), 1.0 - l.z / self.height)
                    } else {
                        Vec2::ZERO
                    },
                )
            }
            _ => {
                let top = part == TOP;
                let z = if top { self.height } else { 0.0 };
                (
                    Vec3A::new(l.x, l.y, z),
                    if top { Vec3A::Z } else { -Vec3A::Z },
                    cap_uv(l, self.radius, top),
                )
            }
        };
        Surface {
            point: self.base + self.frame.to_world(local_point),
            normal: self.frame.to_world(local_normal),
            uv,
        }
    }

    /// True when `p` is strictly inside (capped or not, the solid is the same).
    fn contains(&self, p: Vec3A) -> bool {
        let l = self.frame.to_local(p - self.base);
        l.z > 0.0 && l.z < self.height && l.x * l.x + l.y * l.y < self.radius * self.radius
    }

    /// Bounds (of the two end disks).
    fn bounds(&self) -> Option<Aabb> {
        Some(
            disk_bounds(self.base, self.frame.w, self.radius).union(&disk_bounds(
                self.base + self.frame.w * self.height,
                self.frame.w,
                self.radius,
            )),
        )
    }

    fn leaving(&self) -> Leaving {
        Leaving::Outside
    }

    fn kind(&self) -> &'static str {
        "cylinder"
    }
}

/// The nearer of `best` and a hit on the end disk of radius `r` at height `z` (local
/// coordinates: the axis is z), within `t_max`.
#[inline]
pub(crate) fn cap_hit(
    o: Vec3A,
    d: Vec3A,
    z: f32,
    r: f32,
    part: u8,
    t_max: f32,
    best: Option<ShapeHit>,
) -> Option<ShapeHit> {
    if d.z == 0.0 {
        return best;
    }
    let t = (z - o.z) / d.z;
    let (x, y) = (o.x + t * d.x, o.y + t * d.y);
    if x * x + y * y > r * r {
        return best;
    }
    nearer(best, in_range(t, best.map_or(t_max, |h| h.t), part))
}

/// Planar uv of an end disk, centred at (0.5, 0.5) and spanning the diameter, seen from
/// outside: the top from above, the bottom from below (mirrored), so images never read
/// backwards.
pub(crate) fn cap_uv(l: Vec3A, r: f32, top: bool) -> Vec2 {
    let x = if top { l.x } else { -l.x };
    Vec2::new(0.5 + x / (2.0 * r), 0.5 - l.y / (2.0 * r))
}

/// The angle around the axis as `u` in `[0, 1]`, for a point in a frame built from the axis.
/// For the default axis (+y) this is the sphere's longitude: `u = 0.5` faces +z, and `u`
/// grows toward +x, with the seam at -z.
pub(crate) fn angle_u(l: Vec3A) -> f32 {
    // Frame::from_axis(+y) has u = +x and v = -z, so world z is -l.y.
    0.5 + l.x.atan2(-l.y) / TAU
}

/// Bounds of a disk with unit normal `n`: per axis, the half-extent is `r * sqrt(1 - n_i^2)`.
pub(crate) fn disk_bounds(center: Vec3A, n: Vec3A, r: f32) -> Aabb {
    let e = r * Vec3A::from_array(
        (Vec3A::ONE - n * n)
            .max(Vec3A::ZERO)
            .to_array()
            .map(f32::sqrt),
    );
    Aabb::new(center - e, center + e)
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    fn seed_cylinder(capped: bool) -> Shape {
        Shape::Cylinder(Cylinder::new(
            Vec3A::new(15.0, -15.0, -92.0),
            Vec3A::Y,
            2.0,
            8.0,
            capped,
        ))
    }

    #[test]
    fn side_hit_matches_closed_form() {
        // The report's bug (b without its factor 2) made this miss entirely.
        let (t, s) = hit(&seed_cylinder(true), [15.0, -10.0, 0.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 90.0).abs() < 1e-4, "{t}");
        assert_vec_close(s.normal, Vec3A::Z, 1e-5);
        // Off-centre: x offset 1 hits where z = -92 + sqrt(4 - 1).
        let (t, s) = hit(&seed_cylinder(true), [16.0, -10.0, 0.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - (92.0 - 3f32.sqrt())).abs() < 1e-4);
        assert_vec_close(s.normal, Vec3A::new(0.5, 0.0, 3f32.sqrt() / 2.0), 1e-5);
        assert_eq!(s.normal.y, 0.0, "side normals are horizontal");
    }

    #[test]
    fn caps_are_disks_and_normals_vertical() {
        let (t, s) = hit(&seed_cylinder(true), [15.5, 0.0, -92.0], [0.0, -1.0, 0.0]).unwrap();
        assert!((t - 7.0).abs() < 1e-5);
        assert_vec_close(s.normal, Vec3A::Y, 1e-6);
        let (t, s) = hit(&seed_cylinder(true), [15.5, -20.0, -92.0], [0.0, 1.0, 0.0]).unwrap();
        assert!((t - 5.0).abs() < 1e-5);
        assert_vec_close(s.normal, -Vec3A::Y, 1e-6);
    }

    #[test]
    fn open_cylinder_shows_its_inside_through_the_top() {
        let (t, s) = hit(&seed_cylinder(false), [15.0, -6.0, -92.0], [0.6, -0.8, 0.0]).unwrap();
        // Passes the open top at y = -7 (x = 15.75) and meets the inner wall at x = 17.
        assert!((t - 2.0 / 0.6).abs() < 1e-4, "{t}");
        // The same ray against the capped cylinder stops at the top.
        let (t, _) = hit(&seed_cylinder(true), [15.0, -6.0, -92.0], [0.6, -0.8, 0.0]).unwrap();
        assert!((t - 1.25).abs() < 1e-5, "{t}");
        assert_vec_close(s.normal, Vec3A::X, 1e-5);
    }

    #[test]
    fn height_bounds_reject_the_near_root_and_keep_the_far_one() {
        // A steep ray enters through the top cap region of an open cylinder: the near root of
        // the side is above the top, the far one is on the side.
        let (t, _) = hit(&seed_cylinder(false), [13.5, -6.0, -92.0], [1.0, -1.0, 0.0]).unwrap();
        assert!((t - 3.5).abs() < 1e-4, "{t}");
    }

    #[test]
    fn from_inside_and_parallel_to_axis() {
        let (t, s) = hit(&seed_cylinder(true), [15.0, -11.0, -92.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((t - 2.0).abs() < 1e-5);
        assert_vec_close(s.normal, Vec3A::X, 1e-5);
        // Parallel to the axis: the side quadratic degenerates; the caps still answer.
        let (t, _) = hit(&seed_cylinder(true), [16.0, 0.0, -92.0], [0.0, -1.0, 0.0]).unwrap();
        assert!((t - 7.0).abs() < 1e-5);
        assert!(hit(&seed_cylinder(false), [16.0, 0.0, -92.0], [0.0, -1.0, 0.0]).is_none());
        assert!(hit(&seed_cylinder(true), [18.0, 0.0, -92.0], [0.0, -1.0, 0.0]).is_none());
    }

    #[test]
    fn side_uv_matches_the_sphere_longitude() {
        let c = Cylinder::new(Vec3A::ZERO, Vec3A::Y, 1.0, 2.0, true);
        let u = |p: Vec3A| c.surface(p, &on_part(SIDE), true).uv;
        assert!(
            (u(Vec3A::new(0.0, 1.0, 1.0)).x - 0.5).abs() < 1e-6,
            "+z is the centre"
        );
        assert!(
            (u(Vec3A::new(1.0, 1.0, 0.0)).x - 0.75).abs() < 1e-6,
            "+x is to the right"
        );
        assert!(
            (u(Vec3A::new(0.0, 2.0, 1.0)).y).abs() < 1e-6,
            "v = 0 at the top"
        );
    }

    #[test]
    fn any_axis() {
        let c = Shape::Cylinder(Cylinder::new(
            Vec3A::ZERO,
            Vec3A::new(1.0, 1.0, 0.0),
            1.0,
            10.0,
            true,
        ));
        let (t, s) = hit(&c, [5.0, 5.0, 10.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 9.0).abs() < 1e-4);
        assert_vec_close(s.normal, Vec3A::Z, 1e-5);
    }
}
