//! The reconstruction filter: where a pixel's samples are placed around its centre, and the
//! sign of each one's weight.

use serde::{Deserialize, Serialize};

/// Reconstruction filter shapes.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum FilterKind {
    /// Equal weight over the support (default radius 0.5: the pixel itself).
    Box,
    /// Weight falling linearly to 0 at the radius (default 1).
    Tent,
    /// Gaussian with sigma = radius / 3, shifted to reach 0 at the radius (default 1.5).
    Gaussian,
    /// Mitchell-Netravali with B = C = 1/3 (default radius 2): sharper, with small negative
    /// lobes.
    Mitchell,
}

/// A separable reconstruction filter. Each pixel's samples are spread over the filter's
/// support (a square of side `2 * radius` around the pixel centre) and averaged with these
/// weights; samples are not shared between pixels, so tiles stay independent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Filter {
    /// The shape.
    pub kind: FilterKind,
    /// Half-width of the support, in pixels.
    pub radius: f32,
    /// Inverse of the cumulative distribution of `|weight|` over `[-radius, radius]`, at
    /// `INVERSE` even steps of probability: turns a uniform number into an offset whose
    /// density follows the filter.
    inverse: [f32; INVERSE],
    /// Distance from the centre beyond which the weight is negative; infinite for filters
    /// that are never negative. Mitchell (B = C = 1/3) on its native support [0, 2] is
    /// (x - 2)(-7x^2 + 22x - 16) / 18 past 1, negative between 8/7 and 2: 4/7 of the radius.
    negative_beyond: f32,
    /// The 1D weight's integral over the support (signed).
    integral: f32,
}

const INVERSE: usize = 257;
/// Bins of the 1D distribution the inverse is built from.
const BINS: usize = 1024;

impl Filter {
    /// A filter of `kind`, with its default radius unless one is given.
    pub fn new(kind: FilterKind, radius: Option<f32>) -> Self {
        let default = match kind {
            FilterKind::Box => 0.5,
            FilterKind::Tent => 1.0,
            FilterKind::Gaussian => 1.5,
            FilterKind::Mitchell => 2.0,
        };
        let radius = radius.unwrap_or(default);
        let mut filter = Filter {
            kind,
            radius,
            inverse: [0.0; INVERSE],
            negative_beyond: match kind {
                FilterKind::Mitchell => radius * 4.0 / 7.0,
                _ => f32::INFINITY,
            },
            integral: 1.0,
        };
        // Piecewise-constant density of |w| over BINS bins, then its inverse CDF.
        let bin = 2.0 * radius / BINS as f32;
        let mut cdf = vec![0.0f64; BINS + 1];
        let mut integral = 0.0f64;
        for b in 0..BINS {
            let x = -radius + (b as f32 + 0.5) * bin;
            let w = filter.weight_1d(x) as f64;
            cdf[b + 1] = cdf[b] + w.abs();
            integral += w * bin as f64;
        }
        filter.integral = integral as f32;
        let total = cdf[BINS];
        let mut b = 0;
        for (k, slot) in filter.inverse.iter_mut().enumerate() {
            let target = total * k as f64 / (INVERSE - 1) as f64;
            while b < BINS - 1 && cdf[b + 1] < target {
                b += 1;
            }
            let span = cdf[b + 1] - cdf[b];
            let frac = if span > 0.0 {
                ((target - cdf[b]) / span).clamp(0.0, 1.0)
            } else {
                0.5
            };
            *slot = -radius + (b as f32 + frac as f32) * bin;
        }
        filter
    }

    /// Filter importance sampling: an offset from the pixel centre, distributed as `|weight|`
    /// along one axis, for a uniform `u` in `[0, 1)`, and the sign of the weight there (only
    /// Mitchell's lobes are negative). Samples so placed are averaged with equal weights
    /// (pbrt-v4 does the same), so none is wasted where the filter is nearly zero and a
    /// negative lobe cannot make the weights cancel.
    #[inline]
    pub fn sample(&self, u: f32) -> (f32, f32) {
        // `max` and `min` (unlike `clamp`) take NaN to 0, so the offset's `u` is in [0, 1].
        #[expect(clippy::manual_clamp, reason = "clamp keeps NaN; this must not")]
        let x = self.offset_in_unit(u.max(0.0).min(1.0));
        (x, self.sign_at(x))
    }

    /// [`Filter::sample`]'s offset, for a `u` already in `[0, 1]` (the renderer's strata).
    #[inline(always)]
    pub fn offset_in_unit(&self, u: f32) -> f32 {
        debug_assert!((0.0..=1.0).contains(&u), "{u}");
        let f = u * (INVERSE - 1) as f32;
        // Its whole part without a float-to-integer conversion, which Rust makes saturating
        // (a dozen instructions on x86, twice a sample): adding 2^23 to a whole number below
        // 2^23 is exact and leaves it in the low bits.
        let i = ((f.floor() + 8_388_608.0).to_bits() & 0x1ff).min(INVERSE as u32 - 2);
        let (lo, hi) = (self.inverse[i as usize], self.inverse[i as usize + 1]);
        lo + (hi - lo) * (f - i as f32)
    }

    /// The sign of the weight at offset `x` from the centre (see [`Filter::sample`]).
    #[inline(always)]
    pub fn sign_at(&self, x: f32) -> f32 {
        if x.abs() > self.negative_beyond {
            -1.0
        } else {
            1.0
        }
    }

    /// Whether the weight is negative anywhere (Mitchell's lobes).
    #[inline]
    pub fn has_negative_lobes(&self) -> bool {
        self.negative_beyond.is_finite()
    }

    /// Weight of a sample `(dx, dy)` pixels from the pixel centre.
    #[inline]
    pub fn weight(&self, dx: f32, dy: f32) -> f32 {
        self.weight_1d(dx) * self.weight_1d(dy)
    }

    /// The share of a pixel's value that light arriving at offset `(dx, dy)` from its centre
    /// has: the weight over the filter's integral (what a splat gives each pixel near it; the
    /// camera's samples are placed by the filter instead, to the same effect).
    #[inline]
    pub fn splat_weight(&self, dx: f32, dy: f32) -> f32 {
        self.weight(dx, dy) / (self.integral * self.integral)
    }

    /// Samples are placed by the filter, not weighted by it, so this is off the hot path:
    /// only the construction of `inverse` and the tests call it.
    fn weight_1d(&self, x: f32) -> f32 {
        let x = x.abs();
        if x > self.radius {
            return 0.0;
        }
        exact_weight(self.kind, self.radius, x)
    }
}

/// The filter's 1D weight at distance `x` (in `[0, r]`) from the centre.
fn exact_weight(kind: FilterKind, r: f32, x: f32) -> f32 {
    match kind {
        FilterKind::Box => 1.0,
        FilterKind::Tent => 1.0 - x / r,
        FilterKind::Gaussian => {
            let s2 = 2.0 * (r / 3.0) * (r / 3.0);
            (-x * x / s2).exp() - (-r * r / s2).exp()
        }
        FilterKind::Mitchell => {
            let x = 2.0 * x / r; // Mitchell is defined on [-2, 2].
            let (b, c) = (1.0 / 3.0, 1.0 / 3.0);
            if x < 1.0 {
                ((12.0 - 9.0 * b - 6.0 * c) * x * x * x
                    + (-18.0 + 12.0 * b + 6.0 * c) * x * x
                    + (6.0 - 2.0 * b))
                    / 6.0
            } else {
                ((-b - 6.0 * c) * x * x * x
                    + (6.0 * b + 30.0 * c) * x * x
                    + (-12.0 * b - 48.0 * c) * x
                    + (8.0 * b + 24.0 * c))
                    / 6.0
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The inverse CDF's lookup, its index found by bit arithmetic, is the plain linear
    /// interpolation of the table at every `u`: at the table's knots, between them, at 1
    /// (the last knot), and for inputs out of range or NaN (clamped to 0 and 1).
    #[test]
    fn sampling_interpolates_the_table() {
        let f = Filter::new(FilterKind::Mitchell, None);
        let plain = |u: f32| {
            let x = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) } * (INVERSE - 1) as f32;
            let i = (x.floor() as usize).min(INVERSE - 2);
            f.inverse[i] + (f.inverse[i + 1] - f.inverse[i]) * (x - i as f32)
        };
        let mut us: Vec<f32> = (0..=100_000).map(|k| k as f32 / 100_000.0).collect();
        us.extend((0..INVERSE).map(|k| k as f32 / (INVERSE - 1) as f32));
        us.extend([
            -0.5,
            -0.0,
            1.0,
            1.5,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ]);
        for u in us {
            assert_eq!(f.sample(u).0.to_bits(), plain(u).to_bits(), "u = {u}");
        }
        assert_eq!(f.sample(1.0).0, f.inverse[INVERSE - 1]);
    }

    #[test]
    fn filters_peak_at_the_centre_and_vanish_at_the_radius() {
        for kind in [
            FilterKind::Box,
            FilterKind::Tent,
            FilterKind::Gaussian,
            FilterKind::Mitchell,
        ] {
            let f = Filter::new(kind, None);
            let centre = f.weight(0.0, 0.0);
            assert!(centre > 0.0);
            assert!(f.weight(0.3, 0.0) <= centre, "{kind:?}");
            assert_eq!(f.weight(f.radius + 0.01, 0.0), 0.0);
            assert!(f.weight(f.radius, 0.0).abs() < 1e-6 || kind == FilterKind::Box);
            // Sampling follows the filter: symmetric, spanning the support.
            assert!(f.sample(0.5).0.abs() < 1e-3, "{kind:?} is not symmetric");
            assert!(
                (f.sample(0.0).0 + f.radius).abs() < 1e-2
                    && (f.sample(1.0).0 - f.radius).abs() < 1e-2
            );
        }
        // A Gaussian's samples crowd the centre more than a box's.
        let (g, b) = (
            Filter::new(FilterKind::Gaussian, Some(1.0)),
            Filter::new(FilterKind::Box, Some(1.0)),
        );
        assert!(g.sample(0.75).0 < b.sample(0.75).0);
        assert!(
            (b.sample(0.75).0 - 0.5).abs() < 1e-3,
            "a box is sampled uniformly"
        );
        // Mitchell's negative lobes are sampled with weight -1, and only out there.
        let m = Filter::new(FilterKind::Mitchell, None);
        assert_eq!(m.sample(0.5).1, 1.0);
        assert_eq!(m.sample(0.001).1, -1.0);
        // The lobes start where the tabulated weight turns negative.
        for k in 1..200 {
            let x = m.radius * k as f32 / 200.0;
            let negative = m.weight(x, 0.0) < 0.0;
            let edge = m.radius * 4.0 / 7.0;
            assert!(negative == (x > edge) || (x - edge).abs() < 0.02, "at {x}");
        }
        // Mitchell's published value at its centre: (6 - 2B) / 6 = 8/9.
        assert!(
            (Filter::new(FilterKind::Mitchell, None).weight(0.0, 0.0) - (8.0f32 / 9.0).powi(2))
                .abs()
                < 1e-5
        );
    }
}
