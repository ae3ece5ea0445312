//! Surface detail that bends the shading normal: a tangent-space normal map, or a bump
//! (height) map. The geometry stays as it is; only the normal that shading reads changes.
//!
//! Both read the surface's tangent frame at the hit: `dpdu` and `dpdv`, how the point moves
//! as the texture's `u` and `v` grow (snell's `v` grows down the image). A normal map's
//! texel `(r, g, b)` is the normal `(2r - 1, 2g - 1, 2b - 1)` in the frame (tangent along
//! `u`, bitangent up the image, the surface normal): glTF's and Blender's (OpenGL's)
//! convention. A bump map's value is a height along the normal, in scene units per unit of
//! the texture.

use crate::math::Vec3A;

/// How a material bends its shading normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SurfaceDetail {
    /// A tangent-space normal map.
    Normal {
        /// Index of the texture (linear data) holding the normals.
        texture: usize,
        /// Factor on the normal's tangent components (glTF's `normalTexture.scale`):
        /// 0 flattens the map, above 1 deepens it.
        scale: f32,
    },
    /// A bump (height) map.
    Bump {
        /// Index of the texture whose value (the mean of r, g and b) is the height.
        texture: usize,
        /// Scene units of height per unit of the texture's value.
        height: f32,
    },
}

impl SurfaceDetail {
    /// The texture it reads.
    pub fn texture(&self) -> usize {
        match *self {
            SurfaceDetail::Normal { texture, .. } | SurfaceDetail::Bump { texture, .. } => texture,
        }
    }
}

/// The normal a normal map's texel `rgb` gives in the frame of unit tangent `t`, unit
/// bitangent `b` (up the image) and unit normal `n`, its tangent components times `scale`.
/// `None` for a texel that gives no direction (black).
pub fn mapped_normal(rgb: [f32; 3], scale: f32, t: Vec3A, b: Vec3A, n: Vec3A) -> Option<Vec3A> {
    let [x, y, z] = rgb.map(|c| 2.0 * c - 1.0);
    let m = (t * (x * scale) + b * (y * scale) + n * z).normalize_or_zero();
    (m != Vec3A::ZERO).then_some(m)
}

/// The normal of the surface displaced along its unit normal `n` by a height whose change
/// with `u` and `v` is `dhdu` and `dhdv`, where the point moves by `dpdu` and `dpdv`
/// (pbrt's bump mapping, without the normal's own change, which matters only where the
/// bumps are as tall as the surface is curved). On the side of `n`.
pub fn bumped_normal(dpdu: Vec3A, dpdv: Vec3A, n: Vec3A, dhdu: f32, dhdv: f32) -> Option<Vec3A> {
    let su = dpdu + n * dhdu;
    let sv = dpdv + n * dhdv;
    let m = su.cross(sv).normalize_or_zero();
    if m == Vec3A::ZERO {
        return None;
    }
    Some(if m.dot(n) < 0.0 { -m } else { m })
}

/// `m` bent toward `ng` until it lies at least a little above the surface on `ng`'s side:
/// a normal map may point a normal below its surface, where shading would find no light
/// and a path could not leave.
pub fn above(m: Vec3A, ng: Vec3A) -> Vec3A {
    const MIN_COS: f32 = 0.01;
    let c = m.dot(ng);
    if c >= MIN_COS {
        return m;
    }
    // The unit vector in the plane of m and ng at cosine MIN_COS from ng.
    let tangent = (m - ng * c).normalize_or_zero();
    if tangent == Vec3A::ZERO {
        return ng;
    }
    (tangent * (1.0 - MIN_COS * MIN_COS).sqrt() + ng * MIN_COS).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: Vec3A = Vec3A::X;
    const B: Vec3A = Vec3A::Y;
    const N: Vec3A = Vec3A::Z;

    fn close(a: Vec3A, b: Vec3A) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn a_flat_normal_map_leaves_the_normal() {
        assert!(close(
            mapped_normal([0.5, 0.5, 1.0], 1.0, T, B, N).unwrap(),
            N
        ));
    }

    #[test]
    fn a_normal_map_reads_x_along_u_and_y_up_the_image() {
        // 45 degrees toward +u: (1, 0, 1) / sqrt 2.
        let h = 0.5 + 0.5 / 2f32.sqrt();
        let m = mapped_normal([h, 0.5, h], 1.0, T, B, N).unwrap();
        assert!(close(m, Vec3A::new(1.0, 0.0, 1.0).normalize()), "{m}");
        // Toward +y of the map: the bitangent.
        let m = mapped_normal([0.5, h, h], 1.0, T, B, N).unwrap();
        assert!(close(m, Vec3A::new(0.0, 1.0, 1.0).normalize()), "{m}");
        // Scale 0 flattens it; scale 2 doubles the tangent part before normalising.
        assert!(close(mapped_normal([h, 0.5, h], 0.0, T, B, N).unwrap(), N));
        let m = mapped_normal([h, 0.5, h], 2.0, T, B, N).unwrap();
        assert!(close(m, Vec3A::new(2.0, 0.0, 1.0).normalize()), "{m}");
        assert!(mapped_normal([0.5, 0.5, 0.5], 1.0, T, B, N).is_none());
    }

    #[test]
    fn a_bump_ramp_tilts_the_normal_by_its_slope() {
        // Height h = 0.5 u on a plane where u is x: the surface z = 0.5 x, whose normal is
        // (-0.5, 0, 1) normalised.
        let m = bumped_normal(Vec3A::X, Vec3A::NEG_Y, N, 0.5, 0.0).unwrap();
        assert!(close(m, Vec3A::new(-0.5, 0.0, 1.0).normalize()), "{m}");
        // A slope along v (down the image, -y): z = 0.25 v = -0.25 y.
        let m = bumped_normal(Vec3A::X, Vec3A::NEG_Y, N, 0.0, 0.25).unwrap();
        assert!(close(m, Vec3A::new(0.0, 0.25, 1.0).normalize()), "{m}");
        // Twice the scale of u: the same height change over half the distance.
        let m = bumped_normal(Vec3A::X * 0.5, Vec3A::NEG_Y, N, 0.5, 0.0).unwrap();
        assert!(close(m, Vec3A::new(-1.0, 0.0, 1.0).normalize()), "{m}");
        // No slope: the normal itself, whichever way the frame turns.
        assert!(close(
            bumped_normal(Vec3A::X, Vec3A::Y, N, 0.0, 0.0).unwrap(),
            N
        ));
    }

    #[test]
    fn normals_below_the_surface_are_bent_back_above_it() {
        let m = above(Vec3A::new(1.0, 0.0, -0.2).normalize(), N);
        assert!((m.dot(N) - 0.01).abs() < 1e-5 && m.x > 0.99, "{m}");
        assert!(close(above(N, N), N));
        assert!(close(above(-N, N), N));
    }
}
