//! Fast approximations of functions where a lookup, not an answer, needs them: an
//! environment map's image coordinates of a direction (a fraction of a texel off at most),
//! found once or twice for every path that leaves the scene. The C library's `atanf` and
//! `acosf` were 6 % of an environment-lit render.

use std::f32::consts::{FRAC_PI_2, PI};

/// `atan(a)` for `a` in `[0, 1]`: an odd polynomial of degree 13 fitted to it (within
/// 3e-7 radians).
#[inline]
fn atan_unit(a: f32) -> f32 {
    let s = a * a;
    let p = 0.006_811_79_f32;
    let p = p.mul_add(s, -0.033_604_21);
    let p = p.mul_add(s, 0.079_623_66);
    let p = p.mul_add(s, -0.132_333_41);
    let p = p.mul_add(s, 0.198_078_16);
    let p = p.mul_add(s, -0.333_173_7);
    let p = p.mul_add(s, 0.999_996_1);
    p * a
}

/// `y.atan2(x)`, within 3e-7 radians; 0 at the origin.
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    if hi == 0.0 {
        return 0.0;
    }
    let mut r = atan_unit(lo / hi);
    if ay > ax {
        r = FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    r.copysign(y)
}

/// `x.acos()` for `x` in `[-1, 1]` (clamped), within 5e-7 radians.
#[inline]
pub fn acos(x: f32) -> f32 {
    let x = x.clamp(-1.0, 1.0);
    atan2(((1.0 - x) * (1.0 + x)).sqrt(), x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the standard library over the whole circle, its axes and diagonals, and
    /// tiny and huge arguments.
    #[test]
    fn atan2_matches_the_library() {
        let mut worst = 0.0f32;
        for k in 0..200_000 {
            let t = k as f32 / 200_000.0 * 2.0 * PI - PI;
            for r in [1e-30f32, 1e-3, 1.0, 7.5, 1e30] {
                let (y, x) = (r * t.sin(), r * t.cos());
                let e = (atan2(y, x) - y.atan2(x)).abs();
                worst = worst.max(e.min(2.0 * PI - e));
            }
        }
        assert!(worst < 5e-7, "{worst}");
        for (y, x) in [
            (0.0, 1.0),
            (1.0, 0.0),
            (0.0, -1.0),
            (-1.0, 0.0),
            (1.0, 1.0),
            (-2.0, -2.0),
        ] {
            let (a, b) = (atan2(y, x), f32::atan2(y, x));
            assert!((a - b).abs() < 5e-7, "({y}, {x}): {a} {b}");
        }
        assert_eq!(atan2(0.0, 0.0), 0.0);
        assert_eq!(atan2(-0.0, 1.0).to_bits(), (-0.0f32).to_bits());
    }

    #[test]
    fn acos_matches_the_library() {
        let mut worst = 0.0f32;
        for k in 0..=200_000 {
            let x = k as f32 / 100_000.0 - 1.0;
            worst = worst.max((acos(x) - x.acos()).abs());
        }
        assert!(worst < 5e-7, "{worst}");
        assert_eq!(acos(1.5), 0.0);
        assert!((acos(-1.5) - PI).abs() < 1e-6);
    }
}
