//! The camera: turns film positions into world-space rays. Perspective (a pinhole, or a thin
//! lens that focuses at one distance and blurs the rest) or orthographic (parallel rays, for
//! diagrams and plans).

use crate::math::differential::Differentials;
use crate::math::sampling::uniform_disk_concentric;
use crate::math::{FilmPlanes, Frustum, Ray, Vec2, Vec3A};

/// How the film maps onto rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Rays from the eye, `fov` degrees from top to bottom.
    Perspective,
    /// Parallel rays along the view, from a film `height` scene units tall.
    Orthographic {
        /// The film's height in scene units (its width follows from the aspect ratio).
        height: f32,
    },
}

/// A thin lens: rays leave a disk of radius `radius` about the eye, perpendicular to the
/// view, and meet again on the plane `focus` away along the view, which is sharp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    /// The aperture's radius, scene units.
    pub radius: f32,
    /// Distance along the view to the plane in focus.
    pub focus: f32,
}

/// How a camera was placed: the scene file's `[camera]` keys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraView {
    /// Eye position.
    pub position: Vec3A,
    /// The point looked at.
    pub look_at: Vec3A,
    /// Which way is up (as given; the camera makes it perpendicular to the view).
    pub up: Vec3A,
    /// Vertical field of view, in degrees (perspective).
    pub fov: f32,
    /// Perspective or orthographic.
    pub projection: Projection,
    /// The lens, if not a pinhole.
    pub lens: Option<Lens>,
}

impl CameraView {
    /// A pinhole perspective camera's placement.
    pub fn perspective(position: Vec3A, look_at: Vec3A, up: Vec3A, fov: f32) -> Self {
        CameraView {
            position,
            look_at,
            up,
            fov,
            projection: Projection::Perspective,
            lens: None,
        }
    }

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
            && match self.projection {
                Projection::Perspective => true,
                Projection::Orthographic { height } => height > 0.0 && height.is_finite(),
            }
            && self.lens.is_none_or(|l| {
                l.radius >= 0.0 && l.radius.is_finite() && l.focus > 0.0 && l.focus.is_finite()
            })
    }
}

/// A point seen by the eye, for light tracing ([`Camera::connect`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EyeConnection {
    /// Where it lands on the film, in pixels.
    pub film: (f32, f32),
    /// The point of the eye it connects to (on the lens, for a camera with one).
    pub eye: Vec3A,
    /// The unit direction from the point to the eye.
    pub to_eye: Vec3A,
    /// The distance to the eye.
    pub distance: f32,
    /// The eye's importance over the connection's density.
    pub importance: f32,
}

/// A camera placed by a [`CameraView`].
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
    /// Half the film's height (see [`Camera::half_height`]), worked out once: it is read
    /// for every textured hit's footprint.
    half_height: f32,
}

impl Camera {
    /// A pinhole perspective camera at `position` looking at `look_at`, with `up` giving
    /// the roll and `fov_deg` the vertical field of view in degrees. The caller checks that
    /// the vectors are not degenerate (the scene builder does).
    pub fn new(position: Vec3A, look_at: Vec3A, up: Vec3A, fov_deg: f32) -> Self {
        Camera::placed(CameraView::perspective(position, look_at, up, fov_deg))
    }

    /// The camera `view` places (the caller has checked it).
    fn placed(view: CameraView) -> Self {
        let forward = (view.look_at - view.position).normalize();
        let right = forward.cross(view.up).normalize();
        let up = right.cross(forward);
        Camera {
            position: view.position,
            view,
            forward,
            right,
            up,
            half_height: match view.projection {
                Projection::Perspective => (view.fov.to_radians() * 0.5).tan(),
                Projection::Orthographic { height } => height * 0.5,
            },
        }
    }

    /// A camera placed as `view` says, if [`CameraView::is_valid`].
    pub fn from_view(view: CameraView) -> Option<Self> {
        view.is_valid().then(|| Camera::placed(view))
    }

    /// Half the film's height: at distance 1 for a perspective camera (the tangent of half
    /// the field of view), in scene units for an orthographic one.
    #[inline]
    fn half_height(&self) -> f32 {
        self.half_height
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
        // Orthographic: no division by the distance.
        let z = match self.view.projection {
            Projection::Perspective => z,
            Projection::Orthographic { .. } => 1.0,
        };
        let aspect = width as f32 / height as f32;
        let x = d.dot(self.right) / (z * self.half_height() * aspect);
        let y = d.dot(self.up) / (z * self.half_height());
        Some((
            (x + 1.0) * 0.5 * width as f32,
            (1.0 - y) * 0.5 * height as f32,
        ))
    }

    /// How the eye of a perspective camera sees world point `p`, for paths that start at a
    /// light and end at the eye (light tracing): the point of the eye (the pinhole, or the
    /// point of the lens `u` picks, uniformly over its disk, as [`RasterCamera::ray_lens`]
    /// does), where `p` lands on the film of a `width` x `height` image (through the plane
    /// in focus, for a lens), and the eye's importance over the density of the connection,
    /// `We / pdf = 1 / (A cos^3 theta d^2)` (pbrt's, `A` the film's area at distance 1,
    /// `theta` the angle to the view, `d` the distance; the lens's area cancels). `None`
    /// where `p` is behind the eye or off the film, and for an orthographic camera (no such
    /// paths yet).
    pub fn connect(&self, p: Vec3A, u: Vec2, width: u32, height: u32) -> Option<EyeConnection> {
        if self.view.projection != Projection::Perspective {
            return None;
        }
        let (eye, seen) = match self.view.lens.filter(|l| l.radius > 0.0) {
            None => (self.position, p),
            Some(lens) => {
                let d = uniform_disk_concentric(u) * lens.radius;
                let eye = self.position + self.right * d.x + self.up * d.y;
                let z = (p - eye).dot(self.forward);
                if z <= 0.0 {
                    return None;
                }
                // Where the line from the lens point through `p` meets the plane in focus:
                // the film position whose rays all pass there.
                (eye, eye + (p - eye) * (lens.focus / z))
            }
        };
        let (x, y) = self.project(seen, width, height)?;
        if !(x >= 0.0 && y >= 0.0 && x < width as f32 && y < height as f32) {
            return None;
        }
        let d = eye - p;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        let to_eye = d / dist;
        let cos = (-to_eye).dot(self.forward);
        let aspect = width as f32 / height as f32;
        let area = 4.0 * self.half_height * self.half_height * aspect;
        Some(EyeConnection {
            film: (x, y),
            eye,
            to_eye,
            distance: dist,
            importance: 1.0 / (area * cos * cos * cos * dist2),
        })
    }

    /// The density per unit solid angle with which a perspective camera's rays of a `width`
    /// x `height` film take direction `dir` (unit), film positions being uniform:
    /// `1 / (A cos^3 theta)`, `A` the film's area at distance 1 and `theta` the angle to the
    /// view (pbrt's; the same from any point of a lens). 0 off the film, behind the eye and
    /// for an orthographic camera. Bidirectional path tracing weighs its strategies by it.
    pub fn direction_pdf(&self, dir: Vec3A, width: u32, height: u32) -> f32 {
        let cos = dir.dot(self.forward);
        if self.view.projection != Projection::Perspective || cos <= 0.0 {
            return 0.0;
        }
        let aspect = width as f32 / height as f32;
        let x = dir.dot(self.right) / (cos * self.half_height * aspect);
        let y = dir.dot(self.up) / (cos * self.half_height);
        if x.abs() > 1.0 || y.abs() > 1.0 {
            return 0.0;
        }
        let area = 4.0 * self.half_height * self.half_height * aspect;
        1.0 / (area * cos * cos * cos)
    }

    /// The ray through film position `(x, y)` in pixels (x to the right, y down, (0, 0) the
    /// top-left corner of the image) for an image of `width` by `height` pixels.
    #[inline]
    pub fn ray(&self, x: f32, y: f32, width: u32, height: u32) -> Ray {
        self.raster(width, height).ray(x, y)
    }

    /// How `ray`, a ray of this camera (from any point of the lens), changes from one pixel
    /// of an image `height` pixels tall to the next: the rays from the same point of the lens
    /// through the film one pixel right and one pixel down, to first order (a perspective
    /// ray's direction turns by the pixel's step less its part along the ray, times the
    /// cosine to the view; with a lens too, as the step and the distance to the film both
    /// scale by the focus distance).
    #[inline]
    pub fn differentials(&self, ray: &Ray, height: u32) -> Differentials {
        // Pixels are square: one is 2 half-heights over the height across either way.
        let k = 2.0 * self.half_height() / height as f32;
        let (step_x, step_y) = (self.right * k, self.up * -k);
        if let Projection::Orthographic { .. } = self.view.projection {
            return Differentials {
                dx_origin: step_x,
                dy_origin: step_y,
                ..Default::default()
            };
        }
        let d = ray.dir;
        let cos = d.dot(self.forward).max(0.0);
        let turn = |step: Vec3A| (step - d * d.dot(step)) * cos;
        Differentials {
            dx_dir: turn(step_x),
            dy_dir: turn(step_y),
            ..Default::default()
        }
    }

    /// The most a perspective camera ray's direction changes to the next pixel's of an image
    /// `height` pixels tall ([`Camera::differentials`]' `dx_dir` and `dy_dir` are never
    /// longer); `None` for parallel rays, whose neighbours are offset instead.
    pub fn pixel_spread(&self, height: u32) -> Option<f32> {
        match self.view.projection {
            Projection::Orthographic { .. } => None,
            _ => Some(2.0 * self.half_height() / height as f32),
        }
    }

    /// The camera set up for an image of `width` by `height` pixels, for many rays.
    #[inline]
    pub fn raster(&self, width: u32, height: u32) -> RasterCamera {
        let aspect = width as f32 / height as f32;
        let half_h = self.half_height();
        let half_w = half_h * aspect;
        let lens = self.view.lens.filter(|l| l.radius > 0.0);
        let (per_x, per_y) = (
            self.right * (2.0 * half_w / width as f32),
            self.up * (-2.0 * half_h / height as f32),
        );
        let across = -half_w * self.right + half_h * self.up;
        match self.view.projection {
            Projection::Perspective => RasterCamera {
                origin: self.position,
                corner: self.forward + across,
                per_x,
                per_y,
                ortho: false,
                forward: self.forward,
                lens: lens.map(|l| (self.right * l.radius, self.up * l.radius, l.focus)),
                planes: FilmPlanes::new(self.forward + across, per_x, per_y),
            },
            Projection::Orthographic { .. } => RasterCamera {
                origin: self.position + across,
                corner: self.forward,
                per_x,
                per_y,
                ortho: true,
                forward: self.forward,
                lens: lens.map(|l| (self.right * l.radius, self.up * l.radius, l.focus)),
                // Unread: an orthographic film has no pyramid.
                planes: FilmPlanes::new(self.forward, per_x, per_y),
            },
        }
    }
}

/// A camera for one image size: a film position's ray is two multiply-adds and a
/// normalisation, with the divisions by the image's size done once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterCamera {
    /// Perspective: the eye. Orthographic: the film's top-left corner.
    origin: Vec3A,
    /// Perspective: the direction (not unit, 1 along the view) through the film's top-left
    /// corner. Orthographic: the view direction.
    corner: Vec3A,
    /// Change of that direction (perspective) or origin (orthographic) per pixel right.
    per_x: Vec3A,
    /// The same per pixel down.
    per_y: Vec3A,
    /// Whether the rays are parallel.
    ortho: bool,
    /// The unit view direction.
    forward: Vec3A,
    /// The lens: its two radii (along the film's right and up) and the focus distance.
    lens: Option<(Vec3A, Vec3A, f32)>,
    /// What every pixel's pyramid of rays shares ([`RasterCamera::film_frustum`]).
    planes: FilmPlanes,
}

impl RasterCamera {
    /// The ray through film position `(x, y)` in pixels, as [`Camera::ray`], from the lens's
    /// centre.
    #[inline]
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        if self.ortho {
            Ray::new(self.origin + self.per_x * x + self.per_y * y, self.forward)
        } else {
            let dir = self.corner + self.per_x * x + self.per_y * y;
            Ray::new(self.origin, dir.normalize())
        }
    }

    /// The pyramid holding every ray through the film rectangle `[x0, x1] x [y0, y1]` (in
    /// pixels), for a pinhole camera (`None` for a lens or parallel rays); `scale` is the
    /// largest coordinate of what it will be tested against (see [`Frustum::through_film`]).
    pub fn film_frustum(&self, rect: [f32; 4], scale: f32) -> Option<Frustum> {
        if self.ortho || self.lens.is_some() {
            return None;
        }
        let scale = scale.max(self.origin.abs().max_element());
        Some(self.planes.frustum(self.origin, rect, scale))
    }

    /// Whether rays leave a lens (so each needs a point of it, [`RasterCamera::ray_lens`]).
    #[inline]
    pub fn has_lens(&self) -> bool {
        self.lens.is_some()
    }

    /// The ray through film position `(x, y)` from the point of the lens that `u` (in the
    /// unit square) picks, uniformly over its disk: aimed at where the centre's ray meets the
    /// plane in focus. Without a lens, [`RasterCamera::ray`].
    #[inline]
    pub fn ray_lens(&self, x: f32, y: f32, u: Vec2) -> Ray {
        let centre = self.ray(x, y);
        let Some((ru, rv, focus)) = self.lens else {
            return centre;
        };
        // The centre ray's distance to the focus plane: focus over its cosine to the view.
        let t = focus / centre.dir.dot(self.forward);
        let target = centre.origin + centre.dir * t;
        let d = uniform_disk_concentric(u);
        let origin = centre.origin + ru * d.x + rv * d.y;
        Ray::new(origin, (target - origin).normalize())
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

    /// The differentials are the rays through the next pixels, for every kind of camera.
    #[test]
    fn differentials_reach_the_next_pixels() {
        let base = CameraView::perspective(
            Vec3A::new(1.0, 2.0, 3.0),
            Vec3A::new(-1.0, 0.5, -4.0),
            Vec3A::Y,
            40.0,
        );
        let lens = CameraView {
            lens: Some(Lens {
                radius: 0.3,
                focus: 6.0,
            }),
            ..base
        };
        let ortho = CameraView {
            projection: Projection::Orthographic { height: 5.0 },
            ..base
        };
        let u = Vec2::new(0.8, 0.3);
        for view in [base, lens, ortho] {
            let camera = Camera::from_view(view).unwrap();
            let cam = camera.raster(640, 480);
            for (x, y) in [(0.5, 0.5), (320.0, 240.0), (600.25, 17.5)] {
                let r = cam.ray_lens(x, y, u);
                let d = camera.differentials(&r, 480);
                for (n, o, dd) in [
                    (cam.ray_lens(x + 1.0, y, u), d.dx_origin, d.dx_dir),
                    (cam.ray_lens(x, y + 1.0, u), d.dy_origin, d.dy_dir),
                ] {
                    assert!(((r.origin + o) - n.origin).length() < 1e-5, "{view:?}");
                    assert!(((r.dir + dd) - n.dir).length() < 1e-5, "{view:?}");
                }
            }
        }
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
    fn lens_camera(radius: f32, focus: f32, projection: Projection) -> Camera {
        Camera::from_view(CameraView {
            lens: Some(Lens { radius, focus }),
            projection,
            ..CameraView::perspective(
                Vec3A::new(1.0, 2.0, 3.0),
                Vec3A::new(-1.0, 0.5, -4.0),
                Vec3A::Y,
                40.0,
            )
        })
        .unwrap()
    }

    /// Rays through the lens leave points spread evenly over its disk, in the plane
    /// perpendicular to the view (as (radius squared, angle) they are uniform over the unit
    /// square); a density 10 % off on half the disk fails the same test.
    #[test]
    fn lens_points_are_uniform_over_the_aperture() {
        use crate::math::chi2::chi2_square;
        let c = lens_camera(0.5, 6.0, Projection::Perspective);
        let r = c.raster(64, 48);
        let polar = |u: Vec2| {
            let o = r.ray_lens(20.0, 30.0, u).origin - c.position;
            assert!(o.dot(c.forward).abs() < 1e-5, "off the lens plane: {o}");
            let (x, y) = (o.dot(c.right) / 0.5, o.dot(c.up) / 0.5);
            let phi = y.atan2(x).rem_euclid(2.0 * std::f32::consts::PI);
            Some(Vec2::new(
                (x * x + y * y).min(1.0),
                phi / (2.0 * std::f32::consts::PI),
            ))
        };
        chi2_square("thin lens", 24, polar, |_| 1.0).unwrap();
        let broken = |p: Vec2| if p.y < 0.5 { 1.1 } else { 0.9 };
        assert!(chi2_square("thin lens, wrong density", 24, polar, broken).is_err());
    }

    /// Rays through film positions uniform over a wide film take their directions with the
    /// density `direction_pdf` gives (chi-square), and the eye's importance over a
    /// connection's density is that density over the distance squared.
    #[test]
    fn ray_directions_have_the_density_bidirectional_paths_weigh_by() {
        use crate::math::chi2::{SphereBins, chi2_sphere};
        let c = Camera::new(Vec3A::ZERO, Vec3A::Z, Vec3A::Y, 100.0);
        let (w, h) = (64, 40);
        let r = c.raster(w, h);
        chi2_sphere(
            "camera rays",
            // Coarse bins: fewer of them straddle the film's edge, where the expected
            // counts' integration is least exact.
            SphereBins { theta: 10, phi: 16 },
            |u| Some(r.ray(u.x * w as f32, u.y * h as f32).dir),
            |d| c.direction_pdf(d, w, h),
        )
        .unwrap();
        let p = Vec3A::new(0.7, -0.4, 3.0);
        let e = c.connect(p, Vec2::ZERO, w, h).unwrap();
        let want = c.direction_pdf(-e.to_eye, w, h) / (e.distance * e.distance);
        assert!((e.importance - want).abs() < 1e-6 * want);
        assert_eq!(c.direction_pdf(-Vec3A::Z, w, h), 0.0);
    }

    /// Every lens ray through a film position meets the pinhole ray through it on the plane
    /// in focus; nearer and farther they part.
    #[test]
    fn lens_rays_meet_on_the_plane_in_focus() {
        for projection in [
            Projection::Perspective,
            Projection::Orthographic { height: 3.0 },
        ] {
            let c = lens_camera(0.3, 6.0, projection);
            let r = c.raster(64, 48);
            for (x, y) in [(32.0, 24.0), (0.0, 0.0), (63.5, 10.25)] {
                let centre = r.ray(x, y);
                let on_plane = |ray: &Ray, d: f32| {
                    let t = (d - (ray.origin - c.position).dot(c.forward)) / ray.dir.dot(c.forward);
                    ray.origin + ray.dir * t
                };
                let sharp = on_plane(&centre, 6.0);
                for u in [Vec2::new(0.1, 0.9), Vec2::new(0.7, 0.3), Vec2::splat(0.5)] {
                    let ray = r.ray_lens(x, y, u);
                    assert!((ray.dir.length() - 1.0).abs() < 1e-5);
                    let p = on_plane(&ray, 6.0);
                    assert!(
                        (p - sharp).length() < 1e-4,
                        "{projection:?} {x},{y} {u}: {p} vs {sharp}"
                    );
                    if u != Vec2::splat(0.5) {
                        assert!((on_plane(&ray, 12.0) - on_plane(&centre, 12.0)).length() > 1e-2);
                    }
                }
            }
        }
    }

    /// An orthographic camera's rays are parallel to the view, from a film `height` tall
    /// and as wide as the aspect ratio makes it; points project back onto their pixels.
    #[test]
    fn orthographic_rays_are_parallel_and_span_the_height() {
        let c = Camera::from_view(CameraView {
            projection: Projection::Orthographic { height: 4.0 },
            ..CameraView::perspective(Vec3A::new(0.0, 0.0, 10.0), Vec3A::ZERO, Vec3A::Y, 45.0)
        })
        .unwrap();
        let (top_left, bottom_right) = (c.ray(0.0, 0.0, 200, 100), c.ray(200.0, 100.0, 200, 100));
        assert_eq!(top_left.dir, -Vec3A::Z);
        assert_eq!(bottom_right.dir, -Vec3A::Z);
        assert!((top_left.origin - Vec3A::new(-4.0, 2.0, 10.0)).length() < 1e-5);
        assert!((bottom_right.origin - Vec3A::new(4.0, -2.0, 10.0)).length() < 1e-5);
        for (x, y) in [(0.5, 0.5), (100.0, 50.0), (150.25, 99.5)] {
            let r = c.ray(x, y, 200, 100);
            let (px, py) = c.project(r.origin + r.dir * 3.0, 200, 100).unwrap();
            assert!(
                (px - x).abs() < 1e-3 && (py - y).abs() < 1e-3,
                "{x},{y}: {px},{py}"
            );
        }
        assert!(
            Camera::from_view(CameraView {
                projection: Projection::Orthographic { height: 0.0 },
                ..c.view()
            })
            .is_none()
        );
    }
}
