//! Phong's highlight for Whitted's direct light: the lobe `max(cos, 0)^shininess`, raised
//! cheaply for the whole exponents scene files give.

/// Phong's highlight, `max(cos, 0)^shininess`. Whole exponents up to 256 (as scene files
/// give them) are raised by repeated squaring, several times cheaper than `powf`'s logarithm
/// and exponential; each squaring doubles the rounding error, which stays under 2e-5 of the
/// value there. From exponent 32 on, a cosine under 1/2 gives under 2^-32 of the light
/// (2.3e-10, nothing a picture can show), taken as 0 without the squarings: most directions
/// are that far from the highlight.
#[inline]
pub(super) fn phong_lobe(cos: f32, shininess: f32) -> f32 {
    let c = cos.max(0.0);
    if shininess == shininess.trunc() && (0.0..=256.0).contains(&shininess) {
        if shininess >= 32.0 && c < 0.5 {
            return 0.0;
        }
        // `powi`'s own squarings, in its order (the same bits), inline: a variable exponent
        // made `powi` a call into the runtime library.
        let (mut base, mut e, mut product) = (c, shininess as u32, 1.0f32);
        loop {
            if e & 1 != 0 {
                product *= base;
            }
            e >>= 1;
            if e == 0 {
                return product;
            }
            base *= base;
        }
    } else {
        c.powf(shininess)
    }
}

#[cfg(test)]
mod tests {
    use super::phong_lobe;

    #[test]
    fn phong_lobe_is_powf_within_rounding() {
        for shininess in [
            0.0f32, 1.0, 2.0, 7.0, 50.0, 100.0, 256.0, 1000.0, 2.5, 49.9, 5000.0,
        ] {
            for k in 0..=1000 {
                let c = k as f32 / 1000.0;
                let (fast, exact) = (phong_lobe(c, shininess), c.powf(shininess));
                // Relative error, or below 2^-32 where the lobe is cut off.
                assert!(
                    (fast - exact).abs() <= 2e-5 * exact.max(1e-30)
                        || (fast == 0.0 && exact < 2.33e-10),
                    "{c}^{shininess}: {fast} against {exact}"
                );
            }
            assert_eq!(phong_lobe(-0.5, shininess), 0.0f32.powf(shininess));
        }
        // The whole exponents' squarings are `powi`'s, to the bit.
        let mut checked = 0;
        for e in 0..=256u32 {
            for k in 500..=1000 {
                let c = k as f32 / 1000.0;
                assert_eq!(
                    phong_lobe(c, e as f32).to_bits(),
                    c.powi(e as i32).to_bits(),
                    "{c}^{e}"
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 257 * 501);
    }
}
