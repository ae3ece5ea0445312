//! UV mappings: what texture coordinates a surface point reads (the shape's own uv, spherical,
//! cylindrical, planar, through an affine map, or the second uv set), and their change over a
//! pixel's footprint.

use crate::geometry::equirectangular_uv;
use crate::math::differential::seamless;
use crate::math::{Frame, Transform, Vec2, Vec3A};

/// What a mapping may need to know about a surface point, all in the object's own space.
#[derive(Clone, Copy, Debug)]
pub struct TexturePoint<'a> {
    /// The point, in object space.
    pub point: Vec3A,
    /// The shape's own uv at the point.
    pub uv: Vec2,
    /// Its second uv (a glTF mesh's `TEXCOORD_1`), `uv` where it has none. (It fills what
    /// was padding before `center`: a hit is no larger for it.)
    pub uv1: Vec2,
    /// Centre of the object's bounds, in object space (the default centre of spherical and
    /// cylindrical mappings).
    pub center: Vec3A,
    /// The patch of surface the pixel sees around the point, if known (`None`: a point,
    /// read unfiltered). Borrowed, so that a hit, which holds a point without one, stays
    /// small.
    pub footprint: Option<&'a Footprint>,
}

/// The patch of surface between a ray and its neighbours one pixel right (`x`) and one pixel
/// down (`y`), as offsets in object space and in the shape's own uv. Zero where the ray
/// carries no differentials (after a diffuse bounce), which reads textures at a point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    /// Offset of the neighbour one pixel right, object space.
    pub dpdx: Vec3A,
    /// Offset of the neighbour one pixel down, object space.
    pub dpdy: Vec3A,
    /// The shape's uv there minus the point's.
    pub duvdx: Vec2,
    /// The same one pixel down.
    pub duvdy: Vec2,
    /// The second uv there minus the point's (`duvdx` where the shape has no second set).
    pub duv1dx: Vec2,
    /// The same one pixel down.
    pub duv1dy: Vec2,
}

impl Footprint {
    /// Whether the footprint is a point (nothing to filter over).
    #[inline]
    pub fn is_point(&self) -> bool {
        self.dpdx == Vec3A::ZERO && self.dpdy == Vec3A::ZERO
    }
}

impl TexturePoint<'_> {
    /// The footprint, if it is more than a point.
    #[inline]
    pub fn area(&self) -> Option<&Footprint> {
        self.footprint.filter(|f| !f.is_point())
    }
}

impl TexturePoint<'static> {
    /// A point with no uv, centred at the origin (for tests and solid textures).
    pub fn at(point: Vec3A) -> Self {
        TexturePoint {
            point,
            uv: Vec2::ZERO,
            uv1: Vec2::ZERO,
            center: Vec3A::ZERO,
            footprint: None,
        }
    }

    /// Only a uv.
    pub fn with_uv(uv: Vec2) -> Self {
        TexturePoint {
            point: Vec3A::ZERO,
            uv,
            uv1: uv,
            center: Vec3A::ZERO,
            footprint: None,
        }
    }
}

/// How a surface point becomes texture coordinates `(u, v)`. For images, `u` runs left to
/// right and `v` top to bottom, both 0 to 1 across the image.
#[derive(Clone, Debug)]
pub enum Mapping {
    /// The shape's own uv (see each shape in docs/scene-format.md).
    Uv,
    /// The shape's own uv through an affine map, `uv' = m[0] u + m[1] v + m[2]` (glTF's
    /// KHR_texture_transform).
    UvTransform {
        /// The map's columns: the images of `u` and `v`, and the offset.
        m: [Vec2; 3],
    },
    /// The shape's second uv (a glTF mesh's `TEXCOORD_1`; the first on shapes without one)
    /// through an affine map as [`Mapping::UvTransform`]'s (the identity where the file
    /// gives none).
    SecondUv {
        /// The map's columns: the images of `u` and `v`, and the offset.
        m: [Vec2; 3],
    },
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
    /// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
    #[inline(always)]
    pub fn uv(&self, p: &TexturePoint) -> Vec2 {
        match self {
            Mapping::Uv => p.uv,
            Mapping::UvTransform { m } => m[0] * p.uv.x + m[1] * p.uv.y + m[2],
            Mapping::SecondUv { m } => m[0] * p.uv1.x + m[1] * p.uv1.y + m[2],
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

    /// Texture coordinates of `p` with how they change to the neighbouring pixels right and
    /// below (zero for a point footprint). The shape's uv carries its own; planar and
    /// spherical mappings differentiate in closed form; the cylindrical one takes its
    /// differences over the footprint, forward and backward, the smaller of each
    /// ([`seamless`]).
    #[inline]
    pub fn uv_footprint(&self, p: &TexturePoint) -> (Vec2, Vec2, Vec2) {
        let uv = self.uv(p);
        let Some(f) = p.area() else {
            return (uv, Vec2::ZERO, Vec2::ZERO);
        };
        match self {
            Mapping::Uv => (uv, f.duvdx, f.duvdy),
            Mapping::UvTransform { m } => {
                let d = |duv: Vec2| m[0] * duv.x + m[1] * duv.y;
                (uv, d(f.duvdx), d(f.duvdy))
            }
            Mapping::SecondUv { m } => {
                let d = |duv: Vec2| m[0] * duv.x + m[1] * duv.y;
                (uv, d(f.duv1dx), d(f.duv1dy))
            }
            Mapping::Planar { u_axis, v_axis, .. } => {
                let d = |dp: Vec3A| Vec2::new(dp.dot(*u_axis), dp.dot(*v_axis));
                (uv, d(f.dpdx), d(f.dpdy))
            }
            Mapping::Spherical { center, rotation } => {
                // The mapping's derivative, in closed form: u = 1/2 + atan2(x, z) / 2 pi and
                // v = 1/2 - asin(y / |d|) / pi for d from the centre. No seam to step over,
                // and no arc tangents at neighbouring points.
                let turn = |v: Vec3A| rotation.as_ref().map_or(v, |r| r.vector_to_object(v));
                let d = turn(p.point - center.unwrap_or(p.center));
                let xz2 = d.x * d.x + d.z * d.z;
                let (len2, xz) = (d.length_squared(), xz2.sqrt());
                let du = |e: Vec3A| (d.z * e.x - d.x * e.z) / (std::f32::consts::TAU * xz2);
                let dv =
                    |e: Vec3A| -(e.y * len2 - d.y * d.dot(e)) / (std::f32::consts::PI * len2 * xz);
                let step = |dp: Vec3A| {
                    let e = turn(dp);
                    Vec2::new(du(e), dv(e))
                };
                (uv, step(f.dpdx), step(f.dpdy))
            }
            _ => {
                let at = |dp: Vec3A| {
                    self.uv(&TexturePoint {
                        point: p.point + dp,
                        ..*p
                    })
                };
                let d = |dp: Vec3A| seamless(at(dp) - uv, uv - at(-dp));
                (uv, d(f.dpdx), d(f.dpdy))
            }
        }
    }

    /// Whether it reads the shape's own uv.
    pub fn reads_shape_uv(&self) -> bool {
        matches!(
            self,
            Mapping::Uv | Mapping::UvTransform { .. } | Mapping::SecondUv { .. }
        )
    }

    /// Whether its `u` and `v` grow the ways the shape's own do (the shape's uv, offset or
    /// scaled by positive factors): a mesh's tangents then serve a normal map read
    /// through it.
    pub fn keeps_uv_axes(&self) -> bool {
        match self {
            Mapping::Uv => true,
            Mapping::UvTransform { m } => {
                m[0].y == 0.0 && m[1].x == 0.0 && m[0].x > 0.0 && m[1].y > 0.0
            }
            _ => false,
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
            uv1: Vec2::ZERO,
            center: Vec3A::new(10.0, 8.0, -80.0),
            footprint: None,
        };
        assert!(m.uv(&p).y.abs() < 1e-6, "north pole");
    }

    /// The second uv set, through its map: its own point and its own footprint.
    #[test]
    fn the_second_uv_set_reads_its_own_uv_and_footprint() {
        let m = Mapping::SecondUv {
            m: [
                Vec2::new(2.0, 0.0),
                Vec2::new(0.0, 1.0),
                Vec2::new(0.5, 0.0),
            ],
        };
        let f = Footprint {
            duvdx: Vec2::new(1.0, 0.0),
            duvdy: Vec2::new(0.0, 1.0),
            duv1dx: Vec2::new(0.01, 0.0),
            duv1dy: Vec2::new(0.0, 0.02),
            dpdx: Vec3A::X,
            dpdy: Vec3A::Y,
        };
        let p = TexturePoint {
            uv1: Vec2::new(0.1, 0.3),
            footprint: Some(&f),
            ..TexturePoint::with_uv(Vec2::new(0.7, 0.7))
        };
        assert_eq!(m.uv(&p), Vec2::new(0.7, 0.3));
        let (uv, dx, dy) = m.uv_footprint(&p);
        assert_eq!(
            (uv, dx, dy),
            (
                Vec2::new(0.7, 0.3),
                Vec2::new(0.02, 0.0),
                Vec2::new(0.0, 0.02)
            )
        );
        assert!(m.reads_shape_uv() && !m.keeps_uv_axes());
    }

    /// The spherical mapping's closed-form derivative is its uv's change over a small step,
    /// at points all over a sphere away from the seam and the poles, turned or not.
    #[test]
    fn the_spherical_derivative_is_the_uvs_change() {
        let mut checked = 0;
        for rotation in [
            None,
            Some(Transform::rotation(Vec3::new(20.0, 75.0, -10.0))),
        ] {
            let m = Mapping::Spherical {
                center: Some(Vec3A::new(1.0, 2.0, 3.0)),
                rotation,
            };
            for (k, step) in [Vec3A::new(1e-3, 0.0, 0.0), Vec3A::new(2e-4, -7e-4, 5e-4)]
                .into_iter()
                .enumerate()
            {
                for i in 0..40 {
                    let a = i as f32 * 0.61 + k as f32;
                    let dir = Vec3A::new(a.sin() * 0.8, (a * 0.37).cos() * 0.6, a.cos() * 0.8);
                    let point = Vec3A::new(1.0, 2.0, 3.0) + dir.normalize() * 2.0;
                    let f = Footprint {
                        dpdx: step,
                        dpdy: step * -0.5,
                        ..Default::default()
                    };
                    let p = TexturePoint {
                        footprint: Some(&f),
                        ..TexturePoint::at(point)
                    };
                    let (uv, dx, dy) = m.uv_footprint(&p);
                    let ahead = m.uv(&TexturePoint::at(point + step));
                    let behind = m.uv(&TexturePoint::at(point - step));
                    if (ahead.x - behind.x).abs() > 0.5 || uv.y < 0.05 || uv.y > 0.95 {
                        continue; // the seam, or too near a pole for differences
                    }
                    let central = (ahead - behind) / 2.0;
                    assert!(
                        (dx - central).abs().max_element() < 2e-5,
                        "{point}: {dx} vs {central}"
                    );
                    assert!((dy + central * 0.5).abs().max_element() < 2e-5, "{dy}");
                    checked += 1;
                }
            }
        }
        assert!(checked >= 140, "{checked} points checked of 160");
    }

    #[test]
    fn footprints_in_uv_across_the_seam_and_on_a_plane() {
        let m = Mapping::Spherical {
            center: Some(Vec3A::ZERO),
            rotation: None,
        };
        // Behind the sphere (-z) u jumps from 1 to 0; a footprint there is as small as
        // anywhere else: 0.01 across a unit sphere's equator is 0.01 / (2 pi) in u.
        for x in [-1e-3f32, 0.0, 1e-3] {
            let f = Footprint {
                dpdx: Vec3A::X * 0.01,
                dpdy: Vec3A::Y * 0.01,
                ..Default::default()
            };
            let p = TexturePoint {
                footprint: Some(&f),
                ..TexturePoint::at(Vec3A::new(x, 0.0, -1.0))
            };
            let (_, dx, dy) = m.uv_footprint(&p);
            let want = 0.01 / std::f32::consts::TAU;
            assert!((dx.x.abs() - want).abs() < 1e-4, "{x}: {dx}");
            assert!(
                (dy.y.abs() - 0.01 / std::f32::consts::PI).abs() < 1e-4,
                "{dy}"
            );
        }
        let planar = Mapping::planar(Vec3A::ZERO, Vec3A::X * 2.0, Vec3A::Z);
        let f = Footprint {
            dpdx: Vec3A::new(0.5, 0.0, 0.25),
            ..Default::default()
        };
        let p = TexturePoint {
            footprint: Some(&f),
            ..TexturePoint::at(Vec3A::new(3.0, 0.0, 1.0))
        };
        let (_, dx, dy) = planar.uv_footprint(&p);
        assert_eq!(dx, Vec2::new(1.0, 0.25));
        assert_eq!(dy, Vec2::ZERO);
        // No footprint, no derivatives.
        let (_, dx, _) = planar.uv_footprint(&TexturePoint::at(Vec3A::ONE));
        assert_eq!(dx, Vec2::ZERO);
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
