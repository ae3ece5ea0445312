//! Fast approximations of functions where a lookup, not an answer, needs them: an
//! environment map's image coordinates of a direction (a fraction of a texel off at most),
//! found once or twice for every path that leaves the scene, and the direction of a point of
//! the map. The C library's `atanf`, `acosf` and `sincosf` were a large share of an
//! environment-lit render, which needs far less than their precision here.

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

/// `(x.sin(), x.cos())` for `x` in `[-pi, pi]` (clamped), within 2e-7: Taylor polynomials
/// of degree 11 and 12 about 0, on `x` brought into `[-pi/2, pi/2]` (`sin(pi - x) = sin x`,
/// `cos(pi - x) = -cos x`).
#[inline]
pub fn sin_cos(x: f32) -> (f32, f32) {
    let x = x.clamp(-PI, PI);
    let far = x.abs() > FRAC_PI_2;
    let r = if far { PI.copysign(x) - x } else { x };
    let s2 = r * r;
    let sin = (-2.505_210_8e-8_f32)
        .mul_add(s2, 2.755_731_9e-6)
        .mul_add(s2, -1.984_127e-4)
        .mul_add(s2, 8.333_333e-3)
        .mul_add(s2, -0.166_666_67)
        .mul_add(s2, 1.0)
        * r;
    let cos = (2.087_675_7e-9_f32)
        .mul_add(s2, -2.755_732e-7)
        .mul_add(s2, 2.480_158_7e-5)
        .mul_add(s2, -1.388_888_9e-3)
        .mul_add(s2, 4.166_666_8e-2)
        .mul_add(s2, -0.5)
        .mul_add(s2, 1.0);
    (sin, if far { -cos } else { cos })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the standard library over `[-pi, pi]`, its ends, zero and the quarter turns.
    #[test]
    fn sin_cos_matches_the_library() {
        let mut worst = 0.0f32;
        for k in 0..=400_000 {
            let x = (k as f32 / 200_000.0 - 1.0) * PI;
            let (s, c) = sin_cos(x);
            worst = worst.max((s - x.sin()).abs()).max((c - x.cos()).abs());
        }
        assert!(worst < 2e-7, "{worst}");
        for x in [0.0, FRAC_PI_2, -FRAC_PI_2, PI, -PI] {
            let (s, c) = sin_cos(x);
            assert!(
                (s - x.sin()).abs() < 2e-7 && (c - x.cos()).abs() < 2e-7,
                "{x}"
            );
        }
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
    }

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
