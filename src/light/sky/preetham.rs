//! Preetham, Shirley and Smits' analytic daylight (SIGGRAPH 1999, "A Practical Analytic
//! Model for Daylight"): the Perez et al. all-weather formula for the sky's luminance and
//! chromaticity, with the paper's fits of its five coefficients and of the zenith values to
//! the sun's angle from the zenith and the turbidity (the haze). It gives the clear sky's
//! radiance, not the sun's (see sun.rs).
//!
//! The fits hold for turbidity 2 to 10 and the sun above the horizon; near the horizon and
//! with the sun low they are known to be off (too dark, with the wrong hue: Zotti, Wilkie and
//! Purgathofer 2007), which docs/scene-format.md says.

use crate::math::spectrum::xyy_to_xyz;

/// The sky for one sun and turbidity: the Perez coefficients of Y, x and y, and the zenith
/// values they are scaled to.
#[derive(Clone, Debug)]
pub struct Preetham {
    /// `[A, B, C, D, E]` for luminance, then chromaticity x, then y.
    coeffs: [[f64; 5]; 3],
    /// Luminance (cd/m²) and chromaticity `(x, y)` at the zenith, each over the Perez
    /// function's value there.
    zenith_over_f: [f64; 3],
    /// Unit direction toward the sun, `+y` up.
    sun: [f64; 3],
}

/// The Perez formula `(1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ)` for a direction at
/// `cos_theta` from the zenith and `gamma` radians from the sun.
fn perez([a, b, c, d, e]: [f64; 5], cos_theta: f64, gamma: f64) -> f64 {
    let cos_gamma = gamma.cos();
    (1.0 + a * (b / cos_theta).exp()) * (1.0 + c * (d * gamma).exp() + e * cos_gamma * cos_gamma)
}

/// The zenith's luminance in kcd/m² (the paper's fit), for the sun `theta_s` radians from
/// the zenith.
pub fn zenith_luminance_kcd(turbidity: f64, theta_s: f64) -> f64 {
    let chi = (4.0 / 9.0 - turbidity / 120.0) * (std::f64::consts::PI - 2.0 * theta_s);
    (4.0453 * turbidity - 4.9710) * chi.tan() - 0.2155 * turbidity + 2.4192
}

/// The zenith's chromaticity `(x, y)` (the paper's cubic fits in the sun's angle).
pub fn zenith_chromaticity(turbidity: f64, theta_s: f64) -> (f64, f64) {
    let t = [turbidity * turbidity, turbidity, 1.0];
    let th = [theta_s.powi(3), theta_s * theta_s, theta_s, 1.0];
    let apply = |m: [[f64; 4]; 3]| -> f64 {
        (0..3)
            .map(|i| t[i] * (0..4).map(|j| m[i][j] * th[j]).sum::<f64>())
            .sum()
    };
    let x = apply([
        [0.00166, -0.00375, 0.00209, 0.0],
        [-0.02903, 0.06377, -0.03202, 0.00394],
        [0.11693, -0.21196, 0.06052, 0.25886],
    ]);
    let y = apply([
        [0.00275, -0.00610, 0.00317, 0.0],
        [-0.04214, 0.08970, -0.04153, 0.00516],
        [0.15346, -0.26756, 0.06670, 0.26688],
    ]);
    (x, y)
}

impl Preetham {
    /// The sky of `turbidity` (2 to 10) with the sun toward unit `sun` (`+y` up, at or
    /// above the horizon).
    pub fn new(turbidity: f64, sun: [f64; 3]) -> Self {
        let t = turbidity;
        let coeffs = [
            [
                0.1787 * t - 1.4630,
                -0.3554 * t + 0.4275,
                -0.0227 * t + 5.3251,
                0.1206 * t - 2.5771,
                -0.0670 * t + 0.3703,
            ],
            [
                -0.0193 * t - 0.2592,
                -0.0665 * t + 0.0008,
                -0.0004 * t + 0.2125,
                -0.0641 * t - 0.8989,
                -0.0033 * t + 0.0452,
            ],
            [
                -0.0167 * t - 0.2608,
                -0.0950 * t + 0.0092,
                -0.0079 * t + 0.2102,
                -0.0441 * t - 1.6537,
                -0.0109 * t + 0.0529,
            ],
        ];
        let theta_s = sun[1].clamp(-1.0, 1.0).acos();
        let (zx, zy) = zenith_chromaticity(t, theta_s);
        let zenith = [zenith_luminance_kcd(t, theta_s) * 1000.0, zx, zy];
        let mut zenith_over_f = [0.0; 3];
        for k in 0..3 {
            zenith_over_f[k] = zenith[k] / perez(coeffs[k], 1.0, theta_s);
        }
        Preetham {
            coeffs,
            zenith_over_f,
            sun,
        }
    }

    /// The sky's CIE XYZ radiance (Y in cd/m²) seen along unit direction `d` (`+y` up);
    /// zero below the horizon.
    pub fn xyz(&self, d: [f64; 3]) -> [f64; 3] {
        if d[1] <= 0.0 {
            return [0.0; 3];
        }
        let cos_gamma =
            (d[0] * self.sun[0] + d[1] * self.sun[1] + d[2] * self.sun[2]).clamp(-1.0, 1.0);
        let gamma = cos_gamma.acos();
        let v: [f64; 3] =
            std::array::from_fn(|k| self.zenith_over_f[k] * perez(self.coeffs[k], d[1], gamma));
        xyy_to_xyz(v[1], v[2], v[0].max(0.0))
    }

    /// The sky's luminance (cd/m²) along `d`.
    pub fn luminance(&self, d: [f64; 3]) -> f64 {
        self.xyz(d)[1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toward(elevation_deg: f64, azimuth_deg: f64) -> [f64; 3] {
        let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
        [e.cos() * a.sin(), e.sin(), -e.cos() * a.cos()]
    }

    /// The zenith's luminance and chromaticity, worked by hand from the paper's formulas
    /// for turbidity 3 and the sun 30° from the zenith: χ = (4/9 − 3/120)(π − π/3) =
    /// 0.878 48, Y_z = 7.1649 tan χ + 1.7727 = 10.413 kcd/m²; x_z = 0.2534, y_z = 0.2598
    /// (blue).
    #[test]
    fn zenith_values_match_the_paper() {
        let theta = 30f64.to_radians();
        let y = zenith_luminance_kcd(3.0, theta);
        assert!((y - 10.413).abs() < 0.002, "{y}");
        let (x, yy) = zenith_chromaticity(3.0, theta);
        assert!((x - 0.2534).abs() < 1e-4, "{x}");
        assert!((yy - 0.2598).abs() < 1e-4, "{yy}");
        // The sky's value at the zenith is the zenith's.
        let sky = Preetham::new(3.0, toward(60.0, 0.0));
        let z = sky.xyz([0.0, 1.0, 0.0]);
        assert!((z[1] - 10_413.0).abs() < 2.0, "{z:?}");
        assert!((z[0] / (z[0] + z[1] + z[2]) - x).abs() < 1e-9);
    }

    /// The shape the paper shows: brightest near the sun, darkest about 90° from it,
    /// brighter toward the horizon; a hazier sky is brighter and whiter; nothing below the
    /// horizon; symmetric about the sun's vertical plane.
    #[test]
    fn the_sky_is_shaped_as_the_paper_shows() {
        let sky = Preetham::new(3.0, toward(45.0, 90.0));
        // 7°, 60° and 90° from the sun.
        let near_sun = sky.luminance(toward(45.0, 80.0));
        let sixty = sky.luminance(toward(45.0, 0.0));
        let ninety = sky.luminance(toward(45.0, 270.0));
        assert!(
            near_sun > 3.0 * ninety && sixty > ninety,
            "{near_sun} {sixty} {ninety}"
        );
        // 89° from the sun at the horizon, brighter than 63° from it 40° up.
        assert!(
            sky.luminance(toward(2.0, 0.0)) > sky.luminance(toward(40.0, 0.0)),
            "the horizon brightens"
        );
        assert_eq!(sky.xyz(toward(-1.0, 0.0)), [0.0; 3]);
        let (a, b) = (sky.xyz(toward(30.0, 60.0)), sky.xyz(toward(30.0, 120.0)));
        for k in 0..3 {
            assert!((a[k] - b[k]).abs() < 1e-9 * a[k].abs().max(1.0));
        }
        let blue = |s: &Preetham| {
            let c = s.xyz(toward(60.0, 270.0));
            c[2] / c[1]
        };
        let hazy = Preetham::new(9.0, toward(45.0, 90.0));
        assert!(blue(&sky) > blue(&hazy), "haze whitens the sky");
        assert!(hazy.luminance(toward(60.0, 270.0)) > sky.luminance(toward(60.0, 270.0)));
    }
}
