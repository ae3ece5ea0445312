//! Piecewise-constant densities over the unit square, from a grid of weights (an
//! environment map's texels): a row is chosen by its total, then a column within it by its
//! own weights, each continuous within its cell.

use super::Vec2;
use super::distribution::Distribution1d;

/// A density over `[0, 1)^2`, constant over each cell of a `width` x `height` grid and in
/// proportion to the cell's weight. `x` runs along a row, `y` down the rows.
///
/// Each row's cells are kept as one stretch of cumulative probabilities in `f32` and a guide
/// table of `u16`, all rows in one allocation: sampling a large map is bound by the cache
/// misses of reading them (docs/perf-log.md), and a cell's density comes from the same
/// numbers its samples were drawn by, so the two agree exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution2d {
    /// Over the rows, by their totals.
    rows: Distribution1d,
    width: usize,
    /// Row by row, `width + 1` numbers each: the probability of the cells before each cell
    /// within the row (0 first, 1 last).
    cdf: Vec<f32>,
    /// Row by row, `width` numbers each: entry `k` is the last cell `i` whose `cdf[i]` is at
    /// most `k / width`, where the search for a `u` in that bucket starts. Empty for rows
    /// too wide for `u16` (searched whole).
    guide: Vec<u16>,
}

impl Distribution2d {
    /// From `weights`, row by row (`width` x `height` of them). Negative and non-finite
    /// weights count as 0; with no weight at all every cell is alike.
    pub fn new(weights: &[f32], width: usize, height: usize) -> Self {
        assert_eq!(weights.len(), width * height, "one weight per cell");
        let w = width.max(1);
        let clean = |x: f32| {
            if x.is_finite() && x > 0.0 {
                x as f64
            } else {
                0.0
            }
        };
        let mut cdf = Vec::with_capacity(height * (w + 1));
        let guided = w <= u16::MAX as usize + 1;
        let mut guide = Vec::with_capacity(if guided { height * w } else { 0 });
        let mut totals = Vec::with_capacity(height);
        for row in weights.chunks_exact(w) {
            let total: f64 = row.iter().map(|&x| clean(x)).sum();
            totals.push(total as f32);
            // A row of no weight is never chosen; its cells are made alike all the same.
            let (weight, sum): (&dyn Fn(f32) -> f64, f64) = if total > 0.0 {
                (&clean, total)
            } else {
                (&|_| 1.0, w as f64)
            };
            let start = cdf.len();
            let mut acc = 0.0f64;
            cdf.push(0.0f32);
            for &x in row {
                acc += weight(x);
                cdf.push((acc / sum) as f32);
            }
            cdf[start + w] = 1.0;
            if guided {
                let c = &cdf[start..];
                for k in 0..w {
                    let x = k as f32 / w as f32;
                    let i = (c.partition_point(|&v| v <= x).saturating_sub(1)).min(w - 1);
                    guide.push(i as u16);
                }
            }
        }
        Distribution2d {
            rows: Distribution1d::new(&totals),
            width: w,
            cdf,
            guide,
        }
    }

    /// Row `r`'s cumulative probabilities.
    #[inline]
    fn row_cdf(&self, r: usize) -> &[f32] {
        &self.cdf[r * (self.width + 1)..(r + 1) * (self.width + 1)]
    }

    /// The cell of row `r` that `u` (in `[0, 1)`) falls in: the last `i` with `cdf[i] <= u`,
    /// which has a width (the cells of none before it are passed over).
    #[inline]
    fn column(&self, r: usize, u: f32) -> usize {
        let (w, c) = (self.width, self.row_cdf(r));
        if !self.guide.is_empty() {
            let g = &self.guide[r * w..(r + 1) * w];
            let k = ((u * w as f32) as usize).min(w - 1);
            let lo = g[k] as usize;
            let hi = if k + 1 < w { g[k + 1] as usize + 1 } else { w };
            // Rounding may put `u` just outside its bucket's range: then the whole row.
            if c[lo] <= u && c[hi] > u {
                return lo + c[lo..=hi].partition_point(|&v| v <= u) - 1;
            }
        }
        (c.partition_point(|&v| v <= u).saturating_sub(1)).min(w - 1)
    }

    /// A point of the square chosen by `u`, with its density; `None` for an empty grid.
    pub fn sample(&self, u: Vec2) -> Option<(Vec2, f32)> {
        let (y, py) = self.rows.sample_continuous(u.y)?;
        let r = self.row(y);
        let ux = u.x.clamp(0.0, 1.0 - f32::EPSILON);
        let i = self.column(r, ux);
        let c = self.row_cdf(r);
        let (lo, hi) = (c[i], c[i + 1]);
        let rest = ((ux - lo) / (hi - lo)).clamp(0.0, 1.0);
        let n = self.width as f32;
        let mut x = (i as f32 + rest) / n;
        // Rounding may carry the point onto the next cell's edge: keep it in its own.
        while x > 0.0 && (x * n) as usize > i {
            x = f32::from_bits(x.to_bits() - 1);
        }
        Some((Vec2::new(x, y), py * (hi - lo) * n))
    }

    /// The density of [`Distribution2d::sample`] at `p`.
    #[inline]
    pub fn pdf(&self, p: Vec2) -> f32 {
        if self.rows.is_empty() {
            return 0.0;
        }
        let c = self.row_cdf(self.row(p.y));
        let i = ((p.x * self.width as f32) as usize).min(self.width - 1);
        self.rows.pdf_continuous(p.y) * (c[i + 1] - c[i]) * self.width as f32
    }

    fn row(&self, y: f32) -> usize {
        let h = self.rows.len();
        ((y * h as f32) as usize).min(h - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::super::chi2::chi2_square;
    use super::*;

    /// Points follow the density, cell by cell (a grid of uneven weights with empty cells
    /// and an empty row), by chi-square; each sample's density is the one `pdf` gives, and
    /// the density integrates to 1.
    #[test]
    fn samples_follow_the_density() {
        // Narrow rows, and rows of many cells (whose edges meet the test's bins, so that
        // its integral of the density is exact).
        for (w, h) in [(8, 6), (48, 6)] {
            samples_follow_the_density_of(w, h);
        }
    }

    fn samples_follow_the_density_of(w: usize, h: usize) {
        let weights: Vec<f32> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if y == 2 || (x + y) % 5 == 0 {
                    0.0
                } else {
                    1.0 + ((x * 7 + y * 3) % 11) as f32
                }
            })
            .collect();
        let d = Distribution2d::new(&weights, w, h);
        chi2_square(
            "piecewise-constant 2D",
            24,
            |u| {
                let (p, pdf) = d.sample(u)?;
                assert!(
                    (pdf - d.pdf(p)).abs() <= 1e-4 * pdf,
                    "{p}: {pdf} vs {}",
                    d.pdf(p)
                );
                assert!(pdf > 0.0);
                Some(p)
            },
            |p| d.pdf(p),
        )
        .unwrap();
        let n = 480; // a multiple of every grid's size: the midpoint rule is exact
        let integral: f64 = (0..n * n)
            .map(|k| {
                let p = Vec2::new(
                    ((k % n) as f32 + 0.5) / n as f32,
                    ((k / n) as f32 + 0.5) / n as f32,
                );
                d.pdf(p) as f64
            })
            .sum::<f64>()
            / (n * n) as f64;
        assert!((integral - 1.0).abs() < 1e-3, "{integral}");
        // Cells of no weight are never drawn.
        for (i, &wt) in weights.iter().enumerate() {
            let p = Vec2::new(
                ((i % w) as f32 + 0.5) / w as f32,
                ((i / w) as f32 + 0.5) / h as f32,
            );
            assert_eq!(d.pdf(p) == 0.0, wt == 0.0, "cell {i}");
        }
    }

    /// A density broken by 10 % in one corner fails the same test.
    #[test]
    fn a_wrong_density_fails() {
        let d = Distribution2d::new(&[1.0, 2.0, 3.0, 4.0], 2, 2);
        let broken = |p: Vec2| d.pdf(p) * if p.x < 0.5 && p.y < 0.5 { 1.1 } else { 1.0 };
        assert!(chi2_square("broken", 8, |u| d.sample(u).map(|s| s.0), broken).is_err());
    }
}
