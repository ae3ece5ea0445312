//! `[camera]` to a [`Camera`]: its placement checked, perspective or orthographic, and its
//! lens.

use super::Builder;
use crate::camera::{Camera, CameraView, Lens, Projection};
use crate::math::Vec3A;
use crate::scene::diag::DocPath;
use crate::scene::format::{CameraDef, CameraKind};

impl Builder<'_> {
    pub(super) fn camera(&mut self, d: &CameraDef, path: &DocPath) -> Camera {
        let fallback = || Camera::new(Vec3A::ZERO, -Vec3A::Z, Vec3A::Y, 45.0);
        if d.gltf_camera.is_some() && d.gltf.is_none() {
            self.error_help(
                path.key("gltf_camera"),
                "`gltf_camera` names a camera of the file `gltf` gives, and there is no `gltf`",
                "add gltf = \"FILE\", or remove `gltf_camera`",
            );
        }
        let placed = match &d.gltf {
            Some(file) => self.gltf_camera(d, file, path),
            None => self.placement(d, path),
        };
        let Some(Placement {
            position,
            look_at,
            up,
            fov,
            projection,
        }) = placed
        else {
            return fallback();
        };
        let forward = look_at - position;
        let aperture = self.finite(d.aperture, &path.key("aperture"));
        if aperture < 0.0 {
            self.error(
                path.key("aperture"),
                format!("the lens's radius must be 0 (a pinhole) or more, not {aperture}"),
            );
        }
        let focus = match d.focus_distance {
            None => forward.length(),
            Some(f) => {
                let f = self.finite(f, &path.key("focus_distance"));
                if f > 0.0 {
                    f
                } else {
                    self.error(
                        path.key("focus_distance"),
                        format!("the distance in focus must be greater than 0, not {f}"),
                    );
                    1.0
                }
            }
        };
        if d.gltf.is_some() && aperture > 0.0 && d.focus_distance.is_none() {
            self.warnings.push(
                "camera.aperture with a glTF file's camera and no focus_distance: the focus is 1 scene unit away".into(),
            );
        }
        if d.focus_distance.is_some() && aperture == 0.0 {
            self.warnings.push(
                "camera.focus_distance does nothing without an aperture: a pinhole keeps everything sharp".into(),
            );
        }
        let view = CameraView {
            position,
            look_at,
            up,
            fov,
            projection,
            lens: (aperture > 0.0).then_some(Lens {
                radius: aperture,
                focus,
            }),
        };
        Camera::from_view(view).unwrap_or_else(fallback)
    }

    /// Where the camera is and how it projects, from `[camera]`'s own keys.
    fn placement(&mut self, d: &CameraDef, path: &DocPath) -> Option<Placement> {
        let position = self.point(d.position, &path.key("position"));
        let Some(look_at) = d.look_at else {
            self.error_help(
                path.clone(),
                "missing key `look_at`",
                "add look_at = [x, y, z], the point at the centre of the picture (or gltf = \"FILE\" for a glTF file's camera)",
            );
            return None;
        };
        let look_at = self.point(look_at, &path.key("look_at"));
        let up = self.direction(d.up, &path.key("up"));
        let mut fov = 45.0;
        if let Some(f) = d.fov {
            let f = self.finite(f, &path.key("fov"));
            if d.kind == CameraKind::Orthographic {
                self.error_help(
                    path.key("fov"),
                    "an orthographic camera has no field of view",
                    "give the view's size with height = SCENE_UNITS",
                );
            } else if !(f > 0.0 && f < 180.0) {
                self.error_help(
                    path.key("fov"),
                    format!("field of view must be between 0 and 180 degrees (exclusive), not {f}"),
                    "the seed scene uses 28.07",
                );
            } else {
                fov = f;
            }
        }
        let projection = match (d.kind, d.height) {
            (CameraKind::Perspective, None) => Projection::Perspective,
            (CameraKind::Perspective, Some(_)) => {
                self.error_help(
                    path.key("height"),
                    "height is the size of an orthographic camera's view",
                    "add type = \"orthographic\", or give a perspective camera's fov",
                );
                Projection::Perspective
            }
            (CameraKind::Orthographic, None) => {
                self.error_help(
                    path.key("type"),
                    "an orthographic camera needs the height of its view",
                    "add height = SCENE_UNITS (what the picture spans from top to bottom)",
                );
                Projection::Orthographic { height: 1.0 }
            }
            (CameraKind::Orthographic, Some(h)) => {
                let h = self.finite(h, &path.key("height"));
                if h > 0.0 {
                    Projection::Orthographic { height: h }
                } else {
                    self.error(
                        path.key("height"),
                        format!("the view's height must be greater than 0, not {h}"),
                    );
                    Projection::Orthographic { height: 1.0 }
                }
            }
        };
        let forward = look_at - position;
        if forward.length_squared() == 0.0 {
            self.error(
                path.key("look_at"),
                "the camera looks at its own position: look_at must differ from position",
            );
            return None;
        }
        if forward.normalize().cross(up).length() < 1e-6 {
            self.error_help(
                path.key("up"),
                "up is parallel to the viewing direction, so the camera's roll is undefined",
                "choose an up vector not along look_at - position",
            );
            return None;
        }
        Some(Placement {
            position,
            look_at,
            up,
            fov,
            projection,
        })
    }
}

/// A camera's placement and projection, before its lens.
pub(in crate::scene) struct Placement {
    /// The eye.
    pub position: Vec3A,
    /// A point at the centre of the picture.
    pub look_at: Vec3A,
    /// Up in the picture.
    pub up: Vec3A,
    /// Vertical field of view, degrees (perspective).
    pub fov: f32,
    /// Perspective or orthographic.
    pub projection: Projection,
}
