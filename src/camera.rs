//! The perspective camera: turns film positions into world-space rays.

use crate::math::{Ray, Vec3A};

/// A pinhole camera with a vertical field of view.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: Vec3A,
    /// Unit view direction.
    forward: Vec3A,
    /// Unit right vector.
    right: Vec3A,
    /// Unit up vector (perpendicular to `forward`).
    up: Vec3A,
    /// tan(fov / 2).
    tan_half_fov: f32,
}

impl Camera {
    /// A camera at `position` looking at `look_at`, with `up` giving the roll and `fov_deg`
    /// the vertical field of view in degrees. The caller checks that the vectors are not
    /// degenerate (the scene builder does).
    pub fn new(position: Vec3A, look_at: Vec3A, up: Vec3A, fov_deg: f32) -> Self {
        let forward = (look_at - position).normalize();
        let right = forward.cross(up).normalize();
        let up = right.cross(forward);
        Camera {
            position,
            forward,
            right,
            up,
            tan_half_fov: (fov_deg.to_radians() * 0.5).tan(),
        }
    }

    /// The ray through film position `(x, y)` in pixels (x to the right, y down, (0, 0) the
    /// top-left corner of the image) for an image of `width` by `height` pixels.
    #[inline]
    pub fn ray(&self, x: f32, y: f32, width: u32, height: u32) -> Ray {
        self.raster(width, height).ray(x, y)
    }

    /// The camera set up for an image of `width` by `height` pixels, for many rays.
    #[inline]
    pub fn raster(&self, width: u32, height: u32) -> RasterCamera {
        let aspect = width as f32 / height as f32;
        let (half_w, half_h) = (self.tan_half_fov * aspect, self.tan_half_fov);
        RasterCamera {
            origin: self.position,
            corner: self.forward - half_w * self.right + half_h * self.up,
            per_x: self.right * (2.0 * half_w / width as f32),
            per_y: self.up * (-2.0 * half_h / height as f32),
        }
    }
}

/// A camera for one image size: a film position's ray is two multiply-adds and a
/// normalisation, with the divisions by the image's size done once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterCamera {
    origin: Vec3A,
    /// Direction (not unit) through the film's top-left corner.
    corner: Vec3A,
    /// Change of that direction per pixel to the right.
    per_x: Vec3A,
    /// Change per pixel down.
    per_y: Vec3A,
}

impl RasterCamera {
    /// The ray through film position `(x, y)` in pixels, as [`Camera::ray`].
    #[inline]
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let dir = self.corner + self.per_x * x + self.per_y * y;
        Ray::new(self.origin, dir.normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_view_plane_is_20_by_20_at_distance_40() {
        let c = Camera::new(Vec3A::ZERO, -Vec3A::Z, Vec3A::Y, 28.07);
        let centre = c.ray(512.0, 512.0, 1024, 1024);
        assert!((centre.dir - (-Vec3A::Z)).length() < 1e-6);
        // The top-right corner of the film goes through (10, 10, -40), to 0.1 %.
        let corner = c.ray(1024.0, 0.0, 1024, 1024).dir;
        let p = corner * (40.0 / -corner.z);
        assert!(
            (p.x - 10.0).abs() < 0.01 && (p.y - 10.0).abs() < 0.01,
            "{p}"
        );
    }
}
