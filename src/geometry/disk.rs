//! A flat disk: its hits, normal and uv, and its points sampled by area for area lights.

use super::cylinder::disk_bounds;
use super::{Intersect, Leaving, ShapeHit, Surface, in_range};
use crate::math::{Aabb, Frame, Ray, Vec2, Vec3A};

/// A flat disk of radius `radius` around `center`, facing `frame.w`.
#[derive(Clone, Debug, PartialEq)]
pub struct Disk {
    /// Centre, in object space.
    pub center: Vec3A,
    /// Frame whose `w` is the unit normal.
    pub frame: Frame,
    /// Radius, positive.
    pub radius: f32,
}

impl Disk {
    /// A disk; `normal` need not be unit length but must not be zero.
    pub fn new(center: Vec3A, normal: Vec3A, radius: f32) -> Self {
        Disk {
            center,
            frame: Frame::from_axis(normal.normalize()),
            radius,
        }
    }
}

impl Intersect for Disk {
    /// Hit in `(0, t_max)` within the radius; parallel rays miss.
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let n = self.frame.w;
        let denom = ray.dir.dot(n);
        if denom == 0.0 {
            return None;
        }
        let t = (self.center - ray.origin).dot(n) / denom;
        let hit = in_range(t, t_max, 0)?;
        ((ray.at(t) - self.center).length_squared() <= self.radius * self.radius).then_some(hit)
    }

    /// Normal and planar uv centred at (0.5, 0.5), spanning the diameter.
    fn surface(&self, p: Vec3A, _hit: &ShapeHit, _want_uv: bool) -> Surface {
        let l = self.frame.to_local(p - self.center);
        Surface {
            point: self.center + self.frame.to_world(Vec3A::new(l.x, l.y, 0.0)),
            normal: self.frame.w,
            uv: Vec2::new(
                0.5 + l.x / (2.0 * self.radius),
                0.5 - l.y / (2.0 * self.radius),
            ),
        }
    }

    /// The smallest box around the disk, object space: per axis, the radius times the
    /// sine of the angle between that axis and the normal.
    fn bounds(&self) -> Option<Aabb> {
        Some(disk_bounds(self.center, self.frame.w, self.radius))
    }

    fn leaving(&self) -> Leaving {
        Leaving::EitherSide
    }

    fn kind(&self) -> &'static str {
        "disk"
    }
}

impl Disk {
    /// The disk's area.
    pub fn area(&self) -> f32 {
        std::f32::consts::PI * self.radius * self.radius
    }

    /// A point on the disk, every one equally likely (density `1 / area`).
    pub fn sample_area(&self, u: Vec2) -> super::SurfaceSample {
        let d = crate::math::sampling::uniform_disk_concentric(u) * self.radius;
        super::SurfaceSample {
            point: self.center + d.x * self.frame.u + d.y * self.frame.v,
            normal: self.frame.w,
            pdf: 1.0 / self.area(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    #[test]
    fn hits_inside_radius_only() {
        let d = Shape::Disk(Disk::new(Vec3A::new(0.0, 0.0, -5.0), Vec3A::Z, 1.0));
        let (t, s) = hit(&d, [0.5, 0.5, 0.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 5.0).abs() < 1e-6);
        assert_vec_close(s.normal, Vec3A::Z, 1e-6);
        assert!(hit(&d, [0.8, 0.8, 0.0], [0.0, 0.0, -1.0]).is_none());
        assert!(hit(&d, [0.0, 0.0, -5.0], [1.0, 0.0, 0.0]).is_none());
    }

    #[test]
    fn tilted_disk_bounds_are_tight() {
        let d = Disk::new(Vec3A::ZERO, Vec3A::Y, 2.0);
        let b = d.bounds().unwrap();
        assert_vec_close(b.min, Vec3A::new(-2.0, 0.0, -2.0), 1e-6);
        assert_vec_close(b.max, Vec3A::new(2.0, 0.0, 2.0), 1e-6);
    }
}
