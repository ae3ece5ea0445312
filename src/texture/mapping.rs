use crate::geometry::equirectangular_uv;
use crate::math::{Frame, Transform, Vec2, Vec3A};

/// What a mapping may need to know about a surface point, all in the object's own space.
#[derive(Clone, Copy, Debug)]
pub struct TexturePoint {
    /// The point, in object space.
    pub point: Vec3A,
    /// The shape's own uv at the point.
    pub uv: Vec2,
    /// Centre of the object's bounds, in object space (the default centre of spherical and
    /// cylindrical mappings).
    pub center: Vec3A,
}

impl TexturePoint {
    /// A point with no uv, centred at the origin (for tests and solid textures).
    pub fn at(point: Vec3A) -> Self {
        TexturePoint {
            point,
            uv: Vec2::ZERO,
            center: Vec3A::ZERO,
        }
    }

    /// Only a uv.
    pub fn with_uv(uv: Vec2) -> Self {
        TexturePoint {
            point: Vec3A::ZERO,
            uv,
            center: Vec3A::ZERO,
        }
    }
}

/// How a surface point becomes texture coordinates `(u, v)`. For images, `u` runs left to
/// right and `v` top to bottom, both 0 to 1 across the image.
#[derive(Clone, Debug)]
pub enum Mapping {
    /// The shape's own uv (see each shape in docs/scene-format.md).
    Uv,
    /// Equirectangular, around `center`: longitude 0 faces +z, east (+x) is to the right,
    /// the north pole (+y) is `v = 0`. `rotation` turns the texture on the sphere.
    Spherical {
        /// Centre in object space; `None` means the object's centre.
        center: Option<Vec3A>,
        /// Rotation of the texture (object to texture space is its inverse).
        rotation: Option<Transform>,
    },
    /// Around an axis: `u` is the angle (0 to 1; for the +y axis 0.5 faces +z and `u` grows
    /// toward +x, as the sphere's longitude), `v` is the distance along the axis divided by
    /// `height`, 0.5 at the centre and growing downward.
    Cylindrical {
        /// A point on the axis; `None` means the object's centre.
        center: Option<Vec3A>,
        /// Frame whose `w` is the axis.
        frame: Frame,
        /// Length along the axis that one image spans.
        height: f32,
    },
    /// Projection onto a plane: `u = (p - origin) . u_axis`, `v = (p - origin) . v_axis`.
    Planar {
        /// Where `(u, v) = (0, 0)`.
        origin: Vec3A,
        /// Direction (and scale) of `u`.
        u_axis: Vec3A,
        /// Direction (and scale) of `v`.
        v_axis: Vec3A,
    },
}

impl Mapping {
    /// A planar mapping.
    pub fn planar(origin: Vec3A, u_axis: Vec3A, v_axis: Vec3A) -> Self {
        Mapping::Planar {
            origin,
            u_axis,
            v_axis,
        }
    }

    /// Texture coordinates of `p`.
    #[inline]
    pub fn uv(&self, p: &TexturePoint) -> Vec2 {
        match self {
            Mapping::Uv => p.uv,
            Mapping::Spherical { center, rotation } => {
                let mut d = p.point - center.unwrap_or(p.center);
                if let Some(r) = rotation {
                    d = r.vector_to_object(d);
                }
                equirectangular_uv(d.normalize_or(Vec3A::Z))
            }
            Mapping::Cylindrical {
                center,
                frame,
                height,
            } => {
                let l = frame.to_local(p.point - center.unwrap_or(p.center));
                Vec2::new(crate::geometry::angle_u(l), 0.5 - l.z / height)
            }
            Mapping::Planar {
                origin,
                u_axis,
                v_axis,
            } => {
                let rel = p.point - *origin;
                Vec2::new(rel.dot(*u_axis), rel.dot(*v_axis))
            }
        }
    }

    /// Whether images should clamp rather than repeat vertically (the poles of a sphere).
    pub fn clamps_v(&self) -> bool {
        matches!(self, Mapping::Spherical { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec3;

    #[test]
    fn spherical_rotation_turns_the_texture() {
        let plain = Mapping::Spherical {
            center: None,
            rotation: None,
        };
        let turned = Mapping::Spherical {
            center: None,
            rotation: Some(Transform::rotation(Vec3::new(0.0, 90.0, 0.0))),
        };
        let front = TexturePoint::at(Vec3A::new(0.0, 0.0, 4.0));
        assert!((plain.uv(&front).x - 0.5).abs() < 1e-6);
        // Turning the texture +90 degrees about y carries longitude 0 from +z to +x, so the
        // point facing +z now shows longitude -90 (u = 0.25).
        assert!(
            (turned.uv(&front).x - 0.25).abs() < 1e-5,
            "{}",
            turned.uv(&front)
        );
        let right = TexturePoint::at(Vec3A::new(4.0, 0.0, 0.0));
        assert!((turned.uv(&right).x - 0.5).abs() < 1e-5);
    }

    #[test]
    fn spherical_centre_defaults_to_the_object() {
        let m = Mapping::Spherical {
            center: None,
            rotation: None,
        };
        let p = TexturePoint {
            point: Vec3A::new(10.0, 12.0, -80.0),
            uv: Vec2::ZERO,
            center: Vec3A::new(10.0, 8.0, -80.0),
        };
        assert!(m.uv(&p).y.abs() < 1e-6, "north pole");
    }

    #[test]
    fn cylindrical_and_planar() {
        let m = Mapping::Cylindrical {
            center: Some(Vec3A::ZERO),
            frame: Frame::from_axis(Vec3A::Y),
            height: 2.0,
        };
        let a = m.uv(&TexturePoint::at(Vec3A::new(1.0, 0.5, 0.0)));
        let b = m.uv(&TexturePoint::at(Vec3A::new(-1.0, 0.5, 0.0)));
        assert!(((a.x - b.x).abs() - 0.5).abs() < 1e-5);
        assert!((a.y - 0.25).abs() < 1e-6);
        let p = Mapping::planar(Vec3A::new(1.0, 0.0, 0.0), Vec3A::X * 2.0, Vec3A::Z);
        let uv = p.uv(&TexturePoint::at(Vec3A::new(2.0, 5.0, 3.0)));
        assert!((uv - Vec2::new(2.0, 3.0)).length() < 1e-6);
    }
}
