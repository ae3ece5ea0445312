//! Affine placements of objects (scale, rotate, translate): points, directions, normals,
//! rays and boxes to world space and back.

use super::{Aabb, Ray, Vec3, Vec3A};
use glam::{Affine3A, EulerRot, Mat3A, Quat};

/// An affine placement of an object: object space to world space and back. Built from a
/// scale, then a rotation (degrees about x, then y, then z), then a translation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    to_world: Affine3A,
    to_object: Affine3A,
    /// Inverse transpose of the linear part: carries normals out to world space.
    normal_to_world: Mat3A,
}

impl Transform {
    /// From scale, rotation in degrees (x then y then z) and translation. Returns `None`
    /// when the scale has a zero component (the placement cannot be undone).
    pub fn from_srt(scale: Vec3, rotate_deg: Vec3, translate: Vec3) -> Option<Self> {
        if scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0 {
            return None;
        }
        let r = Quat::from_euler(
            EulerRot::ZYX,
            rotate_deg.z.to_radians(),
            rotate_deg.y.to_radians(),
            rotate_deg.x.to_radians(),
        );
        Some(Self::from_affine(
            Affine3A::from_scale_rotation_translation(scale, r, translate),
        ))
    }

    /// From a column-major 4 x 4 matrix (glTF's), whose last row must be `0 0 0 1`. `None`
    /// when it is not affine, not finite, or cannot be undone.
    pub fn from_matrix(cols: [[f32; 4]; 4]) -> Option<Self> {
        let m = glam::Mat4::from_cols_array_2d(&cols);
        let det = m.determinant();
        if !m.is_finite() || m.row(3) != glam::Vec4::W || det == 0.0 || !det.is_finite() {
            return None;
        }
        Some(Self::from_affine(Affine3A::from_mat4(m)))
    }

    /// This placement, then `outer`'s: object space through this one to world space
    /// through `outer`.
    pub fn then(&self, outer: &Transform) -> Self {
        Self::from_affine(outer.to_world * self.to_world)
    }

    fn from_affine(to_world: Affine3A) -> Self {
        let to_object = to_world.inverse();
        Transform {
            to_world,
            to_object,
            normal_to_world: to_object.matrix3.transpose(),
        }
    }

    /// Rotation only, for texture mappings.
    pub fn rotation(rotate_deg: Vec3) -> Self {
        Self::from_srt(Vec3::ONE, rotate_deg, Vec3::ZERO).expect("unit scale is invertible")
    }

    /// The ray in object space (same `t` along it; the direction is not renormalised).
    #[inline]
    pub fn ray_to_object(&self, r: &Ray) -> Ray {
        Ray::new(
            self.to_object.transform_point3a(r.origin),
            self.to_object.transform_vector3a(r.dir),
        )
    }

    /// Object-space point to world space.
    #[inline]
    pub fn point_to_world(&self, p: Vec3A) -> Vec3A {
        self.to_world.transform_point3a(p)
    }

    /// World-space point to object space.
    #[inline]
    pub fn point_to_object(&self, p: Vec3A) -> Vec3A {
        self.to_object.transform_point3a(p)
    }

    /// Object-space direction to world space (not renormalised).
    #[inline]
    pub fn vector_to_world(&self, d: Vec3A) -> Vec3A {
        self.to_world.transform_vector3a(d)
    }

    /// World-space direction to object space.
    #[inline]
    pub fn vector_to_object(&self, d: Vec3A) -> Vec3A {
        self.to_object.transform_vector3a(d)
    }

    /// Object-space normal to a unit world-space normal.
    #[inline]
    pub fn normal_to_world(&self, n: Vec3A) -> Vec3A {
        (self.normal_to_world * n).normalize()
    }

    /// World-space bounds of an object-space box (all eight corners transformed).
    pub fn bounds_to_world(&self, b: &Aabb) -> Aabb {
        let mut out = Aabb::EMPTY;
        for i in 0..8 {
            let c = Vec3A::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            out.grow(self.point_to_world(c));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_then_rotate_then_translate() {
        let t = Transform::from_srt(
            Vec3::new(2.0, 1.0, 1.0),
            Vec3::new(0.0, 90.0, 0.0),
            Vec3::new(0.0, 0.0, 5.0),
        )
        .unwrap();
        // x scaled to 2, then rotated +90 about y: +x goes to -z; then moved +5 in z.
        let p = t.point_to_world(Vec3A::X);
        assert!((p - Vec3A::new(0.0, 0.0, 3.0)).length() < 1e-5, "{p}");
        assert!((t.point_to_object(p) - Vec3A::X).length() < 1e-5);
        assert!(Transform::from_srt(Vec3::new(1.0, 0.0, 1.0), Vec3::ZERO, Vec3::ZERO).is_none());
    }

    /// A column-major matrix (a translation after a scale, as glTF writes it) places points
    /// as its parts do; composing applies the inner placement first; matrices that are not
    /// affine or cannot be undone are refused.
    #[test]
    fn matrices_and_composition() {
        let m = Transform::from_matrix([
            [2.0, 0.0, 0.0, 0.0],
            [0.0, 2.0, 0.0, 0.0],
            [0.0, 0.0, 2.0, 0.0],
            [1.0, 2.0, 3.0, 1.0],
        ])
        .unwrap();
        assert!((m.point_to_world(Vec3A::ONE) - Vec3A::new(3.0, 4.0, 5.0)).length() < 1e-6);
        let r = Transform::from_srt(Vec3::ONE, Vec3::new(0.0, 90.0, 0.0), Vec3::ZERO).unwrap();
        // Scale and move, then turn: (3, 4, 5) turned +90 about y is (5, 4, -3).
        let p = m.then(&r).point_to_world(Vec3A::ONE);
        assert!((p - Vec3A::new(5.0, 4.0, -3.0)).length() < 1e-5, "{p}");
        let mut flat = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0; 4],
        ];
        flat[3][3] = 1.0;
        assert!(Transform::from_matrix(flat).is_none());
        let mut projective = [
            [1.0, 0.0, 0.0, 0.5],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0; 4],
        ];
        projective[3][3] = 1.0;
        assert!(Transform::from_matrix(projective).is_none());
    }

    #[test]
    fn normals_stay_perpendicular_under_non_uniform_scale() {
        let t = Transform::from_srt(Vec3::new(4.0, 1.0, 1.0), Vec3::ZERO, Vec3::ZERO).unwrap();
        // Plane x + y = 0 in object space, tangent (1, -1, 0).
        let n = t.normal_to_world(Vec3A::new(1.0, 1.0, 0.0).normalize());
        let tangent = t.to_world.transform_vector3a(Vec3A::new(1.0, -1.0, 0.0));
        assert!(n.dot(tangent).abs() < 1e-5);
    }
}
