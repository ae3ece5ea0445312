//! One wavelength for a sample, for dispersion: a path that meets glass whose index changes
//! with wavelength follows one wavelength, and its light is weighed by what that wavelength
//! adds to each of red, green and blue.
//!
//! The weights come from a smooth RGB basis: the CIE 1931 colour-matching functions taken to
//! linear sRGB ([`super::spectrum`]), their negative lobes cut to 0, each channel scaled to
//! integrate to 1 over 360-830 nm. A wavelength is drawn in proportion to the three
//! channels' sum, so its weight, the basis over the density, never exceeds 3 in any channel
//! and has mean `(1, 1, 1)` exactly: light that meets no dispersive surface keeps its colour,
//! and white light split by a prism and gathered again is white. The cut makes spectral
//! colours a little less saturated than the eye sees them (their negative red between 440
//! and 550 nm is lost), never negative.

use super::Color;
use super::distribution::Distribution1d;
use super::spectrum::{VISIBLE, cie_xyz, xyz_to_rgb};
use std::sync::LazyLock;

/// A wavelength drawn for a sample, and what a path followed at it is weighed by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wavelength {
    /// In nanometres, within 360-830.
    pub nm: f32,
    /// The RGB basis at the wavelength over its density: mean `(1, 1, 1)` over the draws.
    pub weight: Color,
}

/// The basis tabulated per nanometre, and the density wavelengths are drawn with.
struct Table {
    /// Each 1-nm piece's basis value, per channel; each channel sums to 1 over the pieces.
    basis: Vec<Color>,
    /// In proportion to the sum of the channels.
    distribution: Distribution1d,
}

static TABLE: LazyLock<Table> = LazyLock::new(|| {
    let (lo, hi, step) = VISIBLE;
    let n = ((hi - lo) / step) as usize;
    let raw: Vec<Color> = (0..n)
        .map(|i| xyz_to_rgb(cie_xyz(lo + (i as f64 + 0.5) * step)).max(Color::ZERO))
        .collect();
    let sum = raw.iter().fold(Color::ZERO, |a, &c| a + c);
    let basis: Vec<Color> = raw.iter().map(|&c| c / sum).collect();
    let weights: Vec<f32> = basis.iter().map(|c| c.element_sum()).collect();
    Table {
        distribution: Distribution1d::new(&weights),
        basis,
    }
});

impl Wavelength {
    /// The shortest and longest wavelengths drawn, in nanometres.
    pub const RANGE: (f32, f32) = (VISIBLE.0 as f32, VISIBLE.1 as f32);

    /// The wavelength for a uniform number `u` in `[0, 1)` (monotonic in `u`, so a
    /// stratified `u` gives stratified wavelengths).
    pub fn sample(u: f32) -> Wavelength {
        let t = &*TABLE;
        let n = t.basis.len();
        let (x, density) = t
            .distribution
            .sample_continuous(u)
            .expect("the table is not empty");
        let i = ((x * n as f32) as usize).min(n - 1);
        let (lo, hi) = Self::RANGE;
        // The density over [0, 1) is per unit of x; per nanometre it is spread over the range.
        let per_nm = density / (hi - lo);
        Wavelength {
            nm: lo + x * (hi - lo),
            weight: t.basis[i] / per_nm,
        }
    }

    /// The RGB basis at `nm` nanometres (per nanometre; zero outside the range): each
    /// channel integrates to 1.
    pub fn basis(nm: f32) -> Color {
        let t = &*TABLE;
        let (lo, hi) = Self::RANGE;
        if !(lo..hi).contains(&nm) {
            return Color::ZERO;
        }
        t.basis[((nm - lo) as usize).min(t.basis.len() - 1)]
    }

    /// The density [`Wavelength::sample`] draws `nm` with, per nanometre.
    pub fn pdf(nm: f32) -> f32 {
        Self::basis(nm).element_sum() / 3.0
    }
}

/// A sample's wavelength as one path follows it (the path tracer's, light tracing's): drawn
/// where the scene disperses light, its weight taken once, at the first surface whose index
/// depends on it.
#[derive(Clone, Copy, Debug, Default)]
pub struct Followed {
    wavelength: Option<Wavelength>,
    weighed: bool,
}

impl Followed {
    /// A wavelength from `u()` where `disperses`, else none (and no number drawn).
    pub fn draw(disperses: bool, u: impl FnOnce() -> f32) -> Self {
        Followed {
            wavelength: disperses.then(|| Wavelength::sample(u())),
            weighed: false,
        }
    }

    /// The wavelength, in nanometres, if the sample has one.
    pub fn nm(&self) -> Option<f32> {
        self.wavelength.map(|w| w.nm)
    }

    /// What the path's throughput is multiplied by at a surface, `dispersive` or not: the
    /// wavelength's weight at the first dispersive one, 1 everywhere else.
    pub fn weigh(&mut self, dispersive: bool) -> Color {
        match self.wavelength {
            Some(w) if dispersive && !self.weighed => {
                self.weighed = true;
                w.weight
            }
            _ => Color::ONE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::chi2::compare;

    /// The weights average to white: by quadrature over the draws' own strata, exactly up to
    /// rounding, and no channel is ever negative or above 3.
    #[test]
    fn the_weights_average_to_white_and_are_bounded() {
        let n = 100_000;
        let mut sum = glam::DVec3::ZERO;
        for k in 0..n {
            let w = Wavelength::sample((k as f32 + 0.5) / n as f32);
            assert!(
                w.weight.min_element() >= 0.0 && w.weight.max_element() <= 3.0 + 1e-4,
                "{w:?}"
            );
            assert!((360.0..830.0).contains(&w.nm), "{w:?}");
            sum += w.weight.as_dvec3();
        }
        let mean = sum / n as f64;
        assert!(
            (mean - glam::DVec3::ONE).abs().max_element() < 2e-3,
            "{mean}"
        );
    }

    /// Each channel of the basis integrates to 1, and it peaks where the eye's red, green
    /// and blue do.
    #[test]
    fn the_basis_is_normalised_and_peaks_in_order() {
        let mut sum = Color::ZERO;
        let mut peak = [(0.0f32, 0.0f32); 3];
        for nm in 360..830 {
            let b = Wavelength::basis(nm as f32 + 0.5);
            sum += b;
            for (c, p) in peak.iter_mut().enumerate() {
                if b[c] > p.1 {
                    *p = (nm as f32, b[c]);
                }
            }
        }
        assert!((sum - Color::ONE).abs().max_element() < 1e-4, "{sum}");
        let [r, g, b] = peak.map(|p| p.0);
        assert!(
            (590.0..620.0).contains(&r)
                && (520.0..560.0).contains(&g)
                && (430.0..470.0).contains(&b),
            "peaks at {r}, {g}, {b} nm"
        );
        assert_eq!(Wavelength::basis(300.0), Color::ZERO);
        assert_eq!(Wavelength::basis(900.0), Color::ZERO);
    }

    /// Chi-square: wavelengths drawn from independent numbers land in 10-nm bins as
    /// [`Wavelength::pdf`] says.
    #[test]
    fn wavelengths_are_drawn_with_their_density() {
        let bins = 47;
        let n = 200_000;
        let mut rng = crate::math::Rng::new(8);
        let mut observed = vec![0.0f64; bins];
        for _ in 0..n {
            let w = Wavelength::sample(rng.next_f32());
            observed[((w.nm - 360.0) / 10.0) as usize] += 1.0;
        }
        let expected: Vec<f64> = (0..bins)
            .map(|b| {
                (0..10)
                    .map(|k| Wavelength::pdf(360.0 + (b * 10 + k) as f32 + 0.5) as f64)
                    .sum::<f64>()
                    * n as f64
            })
            .collect();
        let result = compare(&observed, &expected);
        assert!(result.passed(), "{result:?}");
    }
}
