use super::Vec3A;

/// Moves a hit point off its surface to the side `n` points to, so a ray leaving from it
/// does not hit the same surface again. The step is a fixed number of units in the last
/// place of each coordinate, so it scales with the point's magnitude and works at any scale
/// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
/// Ray Tracing Gems, 2019). Near the origin, where ulps become tiny, a small absolute step is
/// used instead. `n` is the geometric normal, flipped to the side the new ray travels to.
pub fn offset_ray_origin(p: Vec3A, n: Vec3A) -> Vec3A {
    const ORIGIN: f32 = 1.0 / 32.0;
    const FLOAT_SCALE: f32 = 1.0 / 65536.0;
    // 32 ulps (the paper uses 256 for interpolated hit points): snell projects hit points
    // back onto their surfaces, so a smaller step is enough, and it keeps thin solids far
    // from the origin (a 0.05 pane at 1e4) from being stepped over.
    const INT_SCALE: f32 = 32.0;
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

#[cfg(test)]
mod tests {
    use super::*;

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
