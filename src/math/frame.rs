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
}
