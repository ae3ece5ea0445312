//! Just enough colour science to turn a spectrum into the renderer's linear RGB: the CIE
//! 1931 colour-matching functions (as Wyman, Sloan and Shirley's multi-lobe Gaussian fit,
//! JCGT 2013, within about 1 % of the tables), Planck's law, and CIE XYZ to linear sRGB
//! (Rec. 709 primaries, D65 white, as the rest of the renderer reads colours).

use super::Color;

/// One lobe of the fit: a Gaussian with a different width on each side of its peak.
fn lobe(lambda: f64, mu: f64, sigma_below: f64, sigma_above: f64) -> f64 {
    let s = if lambda < mu {
        sigma_below
    } else {
        sigma_above
    };
    let t = (lambda - mu) / s;
    (-0.5 * t * t).exp()
}

/// The CIE 1931 2° colour-matching functions `(x̄, ȳ, z̄)` at `lambda` nanometres.
pub fn cie_xyz(lambda: f64) -> [f64; 3] {
    let x = 1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7)
        - 0.065 * lobe(lambda, 501.1, 20.4, 26.2);
    let y = 0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1);
    let z = 1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8);
    [x, y, z]
}

/// Lumens per watt at the peak of the eye's response (555 nm): what turns `∫ L ȳ dλ`
/// (radiance in W/(m² sr nm)) into luminance in cd/m².
pub const LUMINOUS_EFFICACY: f64 = 683.0;

/// A black body's spectral radiance at `kelvin`, in W/(m² sr nm), at `lambda` nanometres.
pub fn planck(lambda: f64, kelvin: f64) -> f64 {
    const H: f64 = 6.626_070_15e-34;
    const C: f64 = 2.997_924_58e8;
    const K: f64 = 1.380_649e-23;
    let l = lambda * 1e-9;
    // Per metre of wavelength, then per nanometre.
    2.0 * H * C * C / (l.powi(5) * ((H * C / (l * K * kelvin)).exp() - 1.0)) * 1e-9
}

/// The visible range the renderer integrates spectra over, in nanometres, and its step.
pub const VISIBLE: (f64, f64, f64) = (360.0, 830.0, 1.0);

/// CIE XYZ of a spectral radiance `spd(lambda)` (W/(m² sr nm)), Y in cd/m².
pub fn spectrum_to_xyz(spd: impl Fn(f64) -> f64) -> [f64; 3] {
    let (lo, hi, step) = VISIBLE;
    let n = ((hi - lo) / step) as usize;
    let mut xyz = [0.0; 3];
    for i in 0..n {
        let lambda = lo + (i as f64 + 0.5) * step;
        let l = spd(lambda);
        let c = cie_xyz(lambda);
        for k in 0..3 {
            xyz[k] += l * c[k] * step;
        }
    }
    xyz.map(|v| v * LUMINOUS_EFFICACY)
}

/// CIE XYZ to linear sRGB (Rec. 709 primaries, D65 white).
pub fn xyz_to_rgb([x, y, z]: [f64; 3]) -> Color {
    Color::new(
        (3.240_454_2 * x - 1.537_138_5 * y - 0.498_531_4 * z) as f32,
        (-0.969_266_0 * x + 1.876_010_8 * y + 0.041_556_0 * z) as f32,
        (0.055_643_4 * x - 0.204_025_9 * y + 1.057_225_2 * z) as f32,
    )
}

/// CIE XYZ of chromaticity `(x, y)` and luminance `big_y`.
pub fn xyy_to_xyz(x: f64, y: f64, big_y: f64) -> [f64; 3] {
    if y <= 0.0 {
        return [0.0; 3];
    }
    [x * big_y / y, big_y, (1.0 - x - y) * big_y / y]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::luminance;

    /// The fit's peaks and integrals are the CIE tables' (each function integrates to about
    /// 106.9 nm over the visible range; ȳ peaks at 1 near 555 nm).
    #[test]
    fn colour_matching_functions_match_the_tables() {
        let ybar_555 = cie_xyz(555.0)[1];
        assert!((ybar_555 - 1.0).abs() < 0.02, "{ybar_555}");
        let (lo, hi, step) = VISIBLE;
        let mut sums = [0.0; 3];
        let mut l = lo;
        while l < hi {
            let c = cie_xyz(l + 0.5 * step);
            for k in 0..3 {
                sums[k] += c[k] * step;
            }
            l += step;
        }
        for s in sums {
            assert!((s - 106.86).abs() < 1.5, "{sums:?}");
        }
        // Tabulated values: x̄(600) = 1.0622, ȳ(500) = 0.3230, z̄(450) = 1.7471.
        assert!((cie_xyz(600.0)[0] - 1.0622).abs() < 0.03);
        assert!((cie_xyz(500.0)[1] - 0.3230).abs() < 0.02);
        assert!((cie_xyz(450.0)[2] - 1.7471).abs() < 0.06);
    }

    /// D65's chromaticity comes out as RGB (1, 1, 1); a flat spectrum (illuminant E, x = y
    /// = ⅓) as sRGB's (1.2049, 0.9483, 0.9088), a little pink; the matrix keeps luminance.
    #[test]
    fn xyz_to_rgb_keeps_white_and_luminance() {
        let d65 = xyz_to_rgb(xyy_to_xyz(0.312_71, 0.329_02, 1.0));
        assert!((d65 - Color::ONE).abs().max_element() < 2e-3, "{d65}");
        let flat = spectrum_to_xyz(|_| 1.0 / LUMINOUS_EFFICACY);
        let rgb = xyz_to_rgb(flat);
        assert!((luminance(rgb) as f64 - flat[1]).abs() < 1e-3 * flat[1]);
        let e = Color::new(1.2049, 0.9483, 0.9088);
        let (xs, ys) = (
            flat[0] / flat.iter().sum::<f64>(),
            flat[1] / flat.iter().sum::<f64>(),
        );
        assert!(
            (xs - 1.0 / 3.0).abs() < 0.005 && (ys - 1.0 / 3.0).abs() < 0.005,
            "{xs} {ys}"
        );
        assert!((rgb / rgb.y - e / e.y).abs().max_element() < 0.03, "{rgb}");
    }

    /// Planck's law: the peak sits where Wien's law puts it, and a 5778 K body (the sun's
    /// surface) is about 2e9 cd/m² bright.
    #[test]
    fn planck_peaks_and_brightness() {
        let peak = (300..1200)
            .map(|l| l as f64)
            .max_by(|a, b| planck(*a, 5778.0).total_cmp(&planck(*b, 5778.0)))
            .unwrap();
        assert!((peak - 2.897_771_955e6 / 5778.0).abs() < 1.5, "{peak}");
        let y = spectrum_to_xyz(|l| planck(l, 5778.0))[1];
        assert!((1.8e9..2.1e9).contains(&y), "{y}");
    }
}
