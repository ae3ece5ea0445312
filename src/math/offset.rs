//! Where a ray leaving a surface starts: off the surface by a few units in the last place of
//! each coordinate, so secondary rays never hit their own surface at any scale.

use super::Vec3A;

/// Moves a hit point off its surface to the side `n` points to, so a ray leaving from it
/// does not hit the same surface again. The step is a fixed number of units in the last
/// place of each coordinate, so it scales with the point's magnitude and works at any scale
/// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
/// Ray Tracing Gems, 2019). Near the origin, where ulps become tiny, a small absolute step is
/// used instead. `n` is the geometric normal, flipped to the side the new ray travels to.
pub fn offset_ray_origin(p: Vec3A, n: Vec3A) -> Vec3A {
    #[cfg(target_arch = "x86_64")]
    {
        offset_sse2(p, n)
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        offset_scalar(p, n)
    }
}

/// Within this distance of 0, a coordinate moves by `FLOAT_SCALE * n` instead of by ulps.
const ORIGIN: f32 = 1.0 / 32.0;
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// 32 ulps (the paper uses 256 for interpolated hit points): snell projects hit points back
/// onto their surfaces, so a smaller step is enough, and it keeps thin solids far from the
/// origin (a 0.05 pane at 1e4) from being stepped over.
const INT_SCALE: f32 = 32.0;

/// [`offset_ray_origin`] one coordinate at a time: the definition, and the code on targets
/// without SSE2.
#[cfg(any(test, not(target_arch = "x86_64")))]
fn offset_scalar(p: Vec3A, n: Vec3A) -> Vec3A {
    let mut out = [0.0f32; 3];
    for i in 0..3 {
        let of_i = (INT_SCALE * n[i]) as i32;
        let bits = p[i].to_bits() as i32;
        let moved = f32::from_bits(bits.wrapping_add(if p[i] < 0.0 { -of_i } else { of_i }) as u32);
        out[i] = if p[i].abs() < ORIGIN {
            p[i] + FLOAT_SCALE * n[i]
        } else {
            moved
        };
    }
    Vec3A::from_array(out)
}

/// [`offset_scalar`] on all three coordinates at once (SSE2, which every x86-64 CPU has):
/// every hit of every sample offsets its point, so the scalar code, one coordinate at a time,
/// was a visible part of each sample's instructions. The same values for every unit `n`:
/// `32 n` lies well inside `i32`, where truncation by `cvttps2dq` and Rust's `as i32` agree.
#[cfg(target_arch = "x86_64")]
#[inline]
fn offset_sse2(p: Vec3A, n: Vec3A) -> Vec3A {
    use safe_arch::{
        add_i32_m128i, bitxor_m128i, cast_to_m128_from_m128i, cast_to_m128i_from_m128, m128,
        sub_i32_m128i, truncate_m128_to_m128i,
    };
    let step = truncate_m128_to_m128i(m128((n * INT_SCALE).into()));
    // Negated where p < 0, as in the scalar code ((s ^ -1) - (-1) = -s: the mask is all
    // ones there): a float's bits grow with its magnitude.
    let negative = cast_to_m128i_from_m128(m128(p.cmplt(Vec3A::ZERO).into()));
    let step = sub_i32_m128i(bitxor_m128i(step, negative), negative);
    let bits = cast_to_m128i_from_m128(m128(p.into()));
    let moved = Vec3A::from(cast_to_m128_from_m128i(add_i32_m128i(bits, step)).0);
    Vec3A::select(
        p.abs().cmplt(Vec3A::splat(ORIGIN)),
        p + FLOAT_SCALE * n,
        moved,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The SSE2 offset is the scalar one, to the bit, for unit normals of every direction
    /// and points of every scale and sign, zero included.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn simd_offset_is_the_scalar_offset() {
        let mut rng = crate::math::Rng::new(5);
        let mut r = || rng.next_f32() * 2.0 - 1.0;
        for k in 0..20_000 {
            let n = Vec3A::new(r(), r(), r()).normalize_or(Vec3A::Y);
            let scale = 10f32.powi(k % 13 - 6);
            let mut p = Vec3A::new(r(), r(), r()) * scale;
            if k % 7 == 0 {
                p.y = 0.0;
            }
            if k % 11 == 0 {
                p.x = -0.0;
            }
            let (a, b) = (offset_sse2(p, n), offset_scalar(p, n));
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits),
                "{p} {n}"
            );
        }
    }

    #[test]
    fn offset_moves_to_the_requested_side_at_every_scale() {
        let n = Vec3A::new(0.3, 0.9, -0.3).normalize();
        for e in -6..=6 {
            let scale = 10f32.powi(e);
            for p in [
                Vec3A::new(1.0, -2.0, 3.0) * scale,
                Vec3A::new(-5.0, 0.5, 0.0) * scale,
            ] {
                let q = offset_ray_origin(p, n);
                assert!((q - p).dot(n) > 0.0, "scale {scale}: not moved along n");
                let q = offset_ray_origin(p, -n);
                assert!((q - p).dot(n) < 0.0, "scale {scale}: not moved against n");
                // Small: well under a thousandth of the point's magnitude.
                assert!((q - p).length() <= 1e-3 * p.length().max(1.0));
            }
        }
    }
}
