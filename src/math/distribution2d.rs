//! Piecewise-constant densities over the unit square, from a grid of weights (an
//! environment map's texels): a row is chosen by its total, then a column within it by its
//! own weights, each continuous within its cell.

use super::Vec2;
use super::distribution::Distribution1d;

/// A density over `[0, 1)^2`, constant over each cell of a `width` x `height` grid and in
/// proportion to the cell's weight. `x` runs along a row, `y` down the rows.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution2d {
    /// Over the rows, by their totals.
    rows: Distribution1d,
    /// Within each row, over its cells.
    columns: Vec<Distribution1d>,
}

impl Distribution2d {
    /// From `weights`, row by row (`width` x `height` of them). Negative and non-finite
    /// weights count as 0; with no weight at all every cell is alike.
    pub fn new(weights: &[f32], width: usize, height: usize) -> Self {
        assert_eq!(weights.len(), width * height, "one weight per cell");
        let columns: Vec<Distribution1d> = weights
            .chunks_exact(width.max(1))
            .map(Distribution1d::new)
            .collect();
        let totals: Vec<f32> = weights
            .chunks_exact(width.max(1))
            .map(|row| {
                row.iter()
                    .filter(|w| w.is_finite() && **w > 0.0)
                    .map(|&w| w as f64)
                    .sum::<f64>() as f32
            })
            .collect();
        Distribution2d {
            rows: Distribution1d::new(&totals),
            columns,
        }
    }

    /// A point of the square chosen by `u`, with its density; `None` for an empty grid.
    pub fn sample(&self, u: Vec2) -> Option<(Vec2, f32)> {
        let (y, py) = self.rows.sample_continuous(u.y)?;
        let row = self.row(y);
        let (x, px) = self.columns[row].sample_continuous(u.x)?;
        Some((Vec2::new(x, y), py * px))
    }

    /// The density of [`Distribution2d::sample`] at `p`.
    pub fn pdf(&self, p: Vec2) -> f32 {
        if self.columns.is_empty() {
            return 0.0;
        }
        self.rows.pdf_continuous(p.y) * self.columns[self.row(p.y)].pdf_continuous(p.x)
    }

    fn row(&self, y: f32) -> usize {
        ((y * self.columns.len() as f32) as usize).min(self.columns.len() - 1)
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
        let (w, h) = (8, 6);
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
        let n = 400;
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
