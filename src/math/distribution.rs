//! Piecewise-constant distributions: choosing one of many things in proportion to a weight
//! (a light by its power), or a point of `[0, 1)` with a density that is constant over each
//! of `n` equal pieces (the rows and columns of an environment map). Built once, then
//! sampled in expected constant time: a guide table sends `u` to the few pieces whose
//! cumulative range can hold it, and a short search among them finds the one (the same
//! piece a search of the whole table finds, so the map from `u` stays monotonic and keeps
//! a low-discrepancy sampler's strata).

/// A distribution over `n` pieces in proportion to their weights.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution1d {
    /// The weights, as given (negative and non-finite ones taken as 0).
    weights: Vec<f32>,
    /// `cdf[i]` is the probability of the pieces before `i`; `cdf[n] = 1`.
    cdf: Vec<f64>,
    total: f64,
    /// `guide[k]`: the last piece `i` with `cdf[i] <= k / guide.len()`.
    guide: Vec<u32>,
}

impl Distribution1d {
    /// A distribution in proportion to `weights`; all zero (or none) gives every piece the
    /// same chance, so that sampling still works.
    pub fn new(weights: &[f32]) -> Self {
        let weights: Vec<f32> = weights
            .iter()
            .map(|&w| if w.is_finite() && w > 0.0 { w } else { 0.0 })
            .collect();
        let mut total: f64 = weights.iter().map(|&w| w as f64).sum();
        let uniform = total <= 0.0;
        if uniform {
            total = weights.len() as f64;
        }
        let mut cdf = Vec::with_capacity(weights.len() + 1);
        let mut acc = 0.0f64;
        cdf.push(0.0);
        for &w in &weights {
            acc += if uniform { 1.0 } else { w as f64 };
            cdf.push(acc / total);
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        let m = weights.len();
        let guide = (0..m)
            .map(|k| {
                let x = k as f64 / m as f64;
                (cdf.partition_point(|&c| c <= x).saturating_sub(1)).min(m - 1) as u32
            })
            .collect();
        Distribution1d {
            guide,
            weights: if uniform {
                vec![1.0; weights.len()]
            } else {
                weights
            },
            cdf,
            total,
        }
    }

    /// How many pieces.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// Whether it has no pieces.
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }

    /// The probability of piece `i`.
    pub fn probability(&self, i: usize) -> f32 {
        (self.weights.get(i).copied().unwrap_or(0.0) as f64 / self.total) as f32
    }

    /// A piece chosen by `u` in `[0, 1)`, with its probability, and `u` rescaled to `[0, 1)`
    /// within the piece (so one number both chooses and positions). `None` when empty.
    pub fn sample_discrete(&self, u: f32) -> Option<(usize, f32, f32)> {
        if self.is_empty() {
            return None;
        }
        let u = (u as f64).clamp(0.0, 1.0);
        // One piece (a scene's only light): what the search below gives, without it.
        if self.len() == 1 {
            return Some((0, self.probability(0), u.min(1.0 - 1e-7) as f32));
        }
        // The last i with cdf[i] <= u, among the pieces of non-zero chance: between the
        // guide's entries for u's bucket and the next (the whole table should rounding put
        // u outside them).
        let n = self.len();
        let k = ((u * n as f64) as usize).min(n - 1);
        let lo = self.guide[k] as usize;
        let hi = self.guide.get(k + 1).map_or(n, |&g| g as usize + 1);
        let mut i = if self.cdf[lo] <= u && self.cdf[hi.min(n)] > u.min(1.0 - f64::EPSILON) {
            lo + self.cdf[lo..=hi].partition_point(|&c| c <= u) - 1
        } else {
            self.cdf.partition_point(|&c| c <= u).saturating_sub(1)
        };
        i = i.min(n - 1);
        while self.weights[i] == 0.0 && i > 0 {
            i -= 1;
        }
        let (lo, hi) = (self.cdf[i], self.cdf[i + 1]);
        let rest = if hi > lo {
            ((u - lo) / (hi - lo)).min(1.0 - 1e-7)
        } else {
            0.0
        };
        Some((i, self.probability(i), rest as f32))
    }

    /// A point of `[0, 1)` whose density is constant over each of the `n` equal pieces, in
    /// proportion to its weight, with that density.
    pub fn sample_continuous(&self, u: f32) -> Option<(f32, f32)> {
        let (i, p, rest) = self.sample_discrete(u)?;
        let n = self.len() as f32;
        let mut x = (i as f32 + rest) / n;
        // Rounding may carry the point onto the next piece's edge: keep it in its own.
        let end = (i + 1) as f32 / n;
        if x >= end {
            x = f32::from_bits(end.to_bits() - 1);
        }
        while x > 0.0 && (x * n) as usize > i {
            x = f32::from_bits(x.to_bits() - 1);
        }
        Some((x, p * n))
    }

    /// The density of [`Distribution1d::sample_continuous`] at `x` in `[0, 1)`.
    pub fn pdf_continuous(&self, x: f32) -> f32 {
        let i = ((x * self.len() as f32) as usize).min(self.len().saturating_sub(1));
        self.probability(i) * self.len() as f32
    }
}

/// Veach's power heuristic (exponent 2) for one sample of each of two strategies: the weight
/// of the strategy that drew the sample with density `f` against the other's `g`.
pub fn power_heuristic(f: f32, g: f32) -> f32 {
    let (f2, g2) = (f * f, g * g);
    if f2.is_infinite() {
        1.0
    } else if f2 + g2 > 0.0 {
        f2 / (f2 + g2)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::super::chi2::chi2_square;
    use super::super::{Rng, Vec2};
    use super::*;

    /// The guide table finds, for every `u`, the piece a search of the whole table finds:
    /// skewed weights, runs of zeros, one piece, and `u` on every edge of the cumulative table.
    #[test]
    fn the_guide_finds_what_a_full_search_finds() {
        let mut rng = Rng::new(7);
        let tables: Vec<Vec<f32>> = vec![
            vec![1.0],
            vec![0.0, 0.0, 5.0, 0.0],
            (0..97)
                .map(|i| if i % 7 < 3 { 0.0 } else { (i * i) as f32 })
                .collect(),
            (0..300)
                .map(|i| if i == 150 { 1e6 } else { 1e-3 })
                .collect(),
            (0..64).map(|_| rng.next_f32() * rng.next_f32()).collect(),
        ];
        for w in &tables {
            let d = Distribution1d::new(w);
            let full = |u: f32| {
                let u = (u as f64).clamp(0.0, 1.0);
                let mut i = d.cdf.partition_point(|&c| c <= u).saturating_sub(1);
                i = i.min(d.len() - 1);
                while d.weights[i] == 0.0 && i > 0 {
                    i -= 1;
                }
                i
            };
            let mut us: Vec<f32> = (0..20_000).map(|_| rng.next_f32()).collect();
            for &c in &d.cdf {
                let c = c as f32;
                us.extend([
                    c,
                    f32::from_bits(c.to_bits().saturating_sub(1)),
                    c.next_up(),
                ]);
            }
            us.extend([0.0, 1.0, 1.0 - f32::EPSILON]);
            for u in us {
                assert_eq!(d.sample_discrete(u).unwrap().0, full(u), "u = {u} of {w:?}");
            }
        }
        // One piece: chosen for sure, the number passed on as it came (below 1).
        let one = Distribution1d::new(&[2.5]);
        for u in [0.0f32, 0.3, 0.999_999, 1.0] {
            assert_eq!(one.sample_discrete(u), Some((0, 1.0, u.min(1.0 - 1e-7))));
        }
    }

    #[test]
    fn pieces_are_chosen_in_proportion_to_their_weights() {
        let weights = [1.0f32, 0.0, 3.0, 6.0, -2.0, f32::NAN, 10.0];
        let d = Distribution1d::new(&weights);
        let total = 20.0;
        let mut rng = Rng::new(4);
        let mut counts = [0u32; 7];
        let n = 200_000;
        for _ in 0..n {
            let (i, p, rest) = d.sample_discrete(rng.next_f32()).unwrap();
            assert!((0.0..1.0).contains(&rest));
            assert_eq!(p, d.probability(i));
            counts[i] += 1;
        }
        for (i, &w) in weights.iter().enumerate() {
            let expected = if w.is_finite() && w > 0.0 {
                w / total
            } else {
                0.0
            };
            assert!((d.probability(i) - expected).abs() < 1e-6, "piece {i}");
            let got = counts[i] as f32 / n as f32;
            let sigma = (expected * (1.0 - expected) / n as f32).sqrt();
            assert!(
                (got - expected).abs() <= 5.0 * sigma + 1e-6,
                "piece {i}: {got} against {expected}"
            );
        }
        // No weight at all: every piece alike; nothing at all: nothing to choose.
        let flat = Distribution1d::new(&[0.0, 0.0]);
        assert_eq!(flat.probability(1), 0.5);
        assert!(Distribution1d::new(&[]).sample_discrete(0.5).is_none());
    }

    /// The continuous form, as a 2D density over the square (`x` from the distribution,
    /// `y` uniform), by chi-square.
    #[test]
    fn the_continuous_form_matches_its_density() {
        let d = Distribution1d::new(&[0.5, 2.0, 0.0, 1.0, 4.0, 0.25, 3.0, 1.0]);
        chi2_square(
            "piecewise constant",
            16,
            |u| {
                let (x, pdf) = d.sample_continuous(u.x).unwrap();
                assert!((pdf - d.pdf_continuous(x)).abs() < 1e-5);
                Some(Vec2::new(x, u.y))
            },
            |p| d.pdf_continuous(p.x),
        )
        .unwrap();
    }

    #[test]
    fn the_power_heuristic_weighs_two_strategies_to_one() {
        for (f, g) in [(1.0f32, 1.0f32), (3.0, 1.0), (0.2, 5.0)] {
            assert!((power_heuristic(f, g) + power_heuristic(g, f) - 1.0).abs() < 1e-6);
        }
        assert_eq!(power_heuristic(3.0, 1.0), 0.9);
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
        assert_eq!(power_heuristic(f32::INFINITY, 1.0), 1.0);
    }
}
