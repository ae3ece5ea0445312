//! The perspective camera: turns film positions into world-space rays.

use crate::math::{Ray, Vec3A};

/// How a camera was placed: the scene file's `[camera]` keys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraView {
    /// Eye position.
    pub position: Vec3A,
    /// The point looked at.
    pub look_at: Vec3A,
    /// Which way is up (as given; the camera makes it perpendicular to the view).
    pub up: Vec3A,
    /// Vertical field of view, in degrees.
    pub fov: f32,
}

impl CameraView {
    /// Whether a camera can be made from it: finite values, a field of view strictly
    /// between 0 and 180 degrees, `look_at` away from `position` and `up` not along the
    /// view (what the scene builder checks in a file).
    pub fn is_valid(&self) -> bool {
        let finite = [self.position, self.look_at, self.up]
            .iter()
            .all(|v| v.is_finite());
        let forward = self.look_at - self.position;
        finite
            && self.fov > 0.0
            && self.fov < 180.0
            && forward.length_squared() > 0.0
            && self.up.length_squared() > 0.0
            && forward.normalize().cross(self.up.normalize()).length() >= 1e-6
    }
}

/// A pinhole camera with a vertical field of view.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: Vec3A,
    /// The placement it was made from.
    view: CameraView,
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
        let view = CameraView {
            position,
            look_at,
            up,
            fov: fov_deg,
        };
        let forward = (look_at - position).normalize();
        let right = forward.cross(up).normalize();
        let up = right.cross(forward);
        Camera {
            position,
            view,
            forward,
            right,
            up,
            tan_half_fov: (fov_deg.to_radians() * 0.5).tan(),
        }
    }

    /// A camera placed as `view` says, if [`CameraView::is_valid`].
    pub fn from_view(view: CameraView) -> Option<Self> {
        view.is_valid()
            .then(|| Camera::new(view.position, view.look_at, view.up, view.fov))
    }

    /// The placement it was made from.
    pub fn view(&self) -> CameraView {
        self.view
    }

    /// Where world point `p` appears on the film of a `width` by `height` image, in pixels
    /// (as [`Camera::ray`] takes them), or `None` when it is behind the camera.
    pub fn project(&self, p: Vec3A, width: u32, height: u32) -> Option<(f32, f32)> {
        let d = p - self.position;
        let z = d.dot(self.forward);
        if z <= 0.0 {
            return None;
        }
        let aspect = width as f32 / height as f32;
        let x = d.dot(self.right) / (z * self.tan_half_fov * aspect);
        let y = d.dot(self.up) / (z * self.tan_half_fov);
        Some((
            (x + 1.0) * 0.5 * width as f32,
            (1.0 - y) * 0.5 * height as f32,
        ))
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

    /// A point on the ray through a film position projects back to that position.
    #[test]
    fn projection_inverts_the_ray() {
        let c = Camera::new(
            Vec3A::new(1.0, 2.0, 3.0),
            Vec3A::new(-1.0, 0.5, -4.0),
            Vec3A::Y,
            40.0,
        );
        for (x, y) in [(0.0, 0.0), (320.0, 100.0), (639.5, 479.5), (17.25, 300.0)] {
            let r = c.ray(x, y, 640, 480);
            let (px, py) = c.project(r.origin + r.dir * 7.5, 640, 480).unwrap();
            assert!(
                (px - x).abs() < 1e-2 && (py - y).abs() < 1e-2,
                "{x},{y}: {px},{py}"
            );
        }
        assert_eq!(c.project(c.position - c.forward, 640, 480), None);
        assert_eq!(Camera::from_view(c.view()), Some(c.clone()));
        let bad = CameraView {
            look_at: c.position,
            ..c.view()
        };
        assert_eq!(Camera::from_view(bad), None);
        let along = CameraView {
            up: c.view().look_at - c.position,
            ..c.view()
        };
        assert!(Camera::from_view(along).is_none());
        assert!(
            Camera::from_view(CameraView {
                fov: 180.0,
                ..c.view()
            })
            .is_none()
        );
    }
}
