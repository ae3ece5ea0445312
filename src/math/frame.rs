//! Orthonormal frames about a normal or an axis: a direction into the frame and back.

use super::Vec3A;

/// An orthonormal basis `(u, v, w)`, used to express directions relative to a normal or an
/// axis. `w` is the axis the frame was built from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent.
    pub u: Vec3A,
    /// Second tangent, `w x u`.
    pub v: Vec3A,
    /// The axis (unit).
    pub w: Vec3A,
}

impl Frame {
    /// A frame around the unit vector `w`, without branches that flip near poles
    /// (Duff et al., "Building an Orthonormal Basis, Revisited", 2017).
    pub fn from_axis(w: Vec3A) -> Self {
        let sign = 1.0f32.copysign(w.z);
        let a = -1.0 / (sign + w.z);
        let b = w.x * w.y * a;
        let u = Vec3A::new(1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x);
        let v = Vec3A::new(b, sign + w.y * w.y * a, -w.y);
        Frame { u, v, w }
    }

    /// Components of the world vector `d` in this frame.
    #[inline]
    pub fn to_local(&self, d: Vec3A) -> Vec3A {
        Vec3A::new(d.dot(self.u), d.dot(self.v), d.dot(self.w))
    }

    /// The world vector whose components in this frame are `l`.
    #[inline]
    pub fn to_world(&self, l: Vec3A) -> Vec3A {
        self.u * l.x + self.v * l.y + self.w * l.z
    }

    /// [`Frame::to_world`] of a direction, made unit again (zero for zero). A unit `l`
    /// comes out within rounding of unit length, and is then scaled by one Newton step of
    /// `1 / sqrt` about 1, `1.5 - 0.5 |w|^2` (within 4e-9 of the root's answer there), instead
    /// of a square root and a division that each bounce's next ray waited on.
    #[inline]
    pub fn to_world_unit(&self, l: Vec3A) -> Vec3A {
        let w = self.to_world(l);
        let l2 = w.length_squared();
        if (l2 - 1.0).abs() < 1e-4 {
            w * (1.5 - 0.5 * l2)
        } else {
            w.normalize_or_zero()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_for_any_axis() {
        for w in [
            Vec3A::X,
            Vec3A::Y,
            Vec3A::Z,
            -Vec3A::Z,
            Vec3A::new(1.0, 2.0, -3.0).normalize(),
            Vec3A::new(0.0, 1e-8, -1.0).normalize(),
        ] {
            let f = Frame::from_axis(w);
            assert!((f.u.length() - 1.0).abs() < 1e-5);
            assert!((f.v.length() - 1.0).abs() < 1e-5);
            assert!(f.u.dot(f.v).abs() < 1e-5 && f.u.dot(f.w).abs() < 1e-5);
            assert!(f.v.dot(f.w).abs() < 1e-5);
            let d = Vec3A::new(0.3, -0.7, 0.2);
            assert!((f.to_world(f.to_local(d)) - d).length() < 1e-5);
        }
    }

    /// A unit direction comes out unit and where `to_world` puts it, to within rounding; a
    /// longer or shorter one is normalised; zero stays zero.
    #[test]
    fn world_directions_come_out_unit() {
        let f = Frame::from_axis(Vec3A::new(0.2, -0.9, 0.4).normalize());
        let mut checked = 0;
        for i in 0..200 {
            let (a, b) = (i as f32 * 0.731, i as f32 * 0.377);
            let l = Vec3A::new(a.cos() * b.sin(), a.sin() * b.sin(), b.cos());
            for scale in [1.0, 1.00001, 0.5, 3.0] {
                let w = f.to_world_unit(l * scale);
                assert!((w.length() - 1.0).abs() < 2e-7, "{l} x {scale}: {w}");
                assert!(
                    (w - f.to_world(l).normalize()).length() < 3e-7,
                    "{l} x {scale}"
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 800);
        assert_eq!(f.to_world_unit(Vec3A::ZERO), Vec3A::ZERO);
    }
}
