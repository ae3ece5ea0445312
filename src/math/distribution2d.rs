//! Piecewise-constant densities over the unit square, from a grid of weights (an
//! environment map's texels): a row is chosen by its total, then a column within it by its
//! own weights, each continuous within its cell.

use super::Vec2;

/// A density over `[0, 1)^2`, constant over each cell of a `width` x `height` grid and in
/// proportion to the cell's weight. `x` runs along a row, `y` down the rows.
///
/// A row is chosen by its total, then a cell within it. Each choice is a search of a
/// stretch of cumulative probabilities in `f32`, started from a guide table of `u16`; the
/// rows' stretches share one allocation. Sampling a large map is bound by the cache misses
/// of reading them (docs/perf-log.md), and a cell's density comes from the same numbers its
/// samples were drawn by, so the two agree exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution2d {
    width: usize,
    height: usize,
    /// Over the rows, by their totals: `height + 1` numbers, the probability of the rows
    /// before each row (0 first, 1 last).
    row_cdf: Vec<f32>,
    /// The guide of `row_cdf` (see [`guide`]).
    row_guide: Vec<u16>,
    /// Row by row, `width + 1` numbers each: the probability of the cells before each cell
    /// within the row (0 first, 1 last).
    cdf: Vec<f32>,
    /// Row by row, the guide of each row's stretch of `cdf`, in [`ROW_BUCKETS`] buckets
    /// (fewer for a narrower row).
    guide: Vec<u16>,
}

/// Appends to `cdf` the `n + 1` cumulative probabilities of `weights` (0 first, 1 last),
/// as [`cumulative_into`] gives them.
fn push_cumulative(cdf: &mut Vec<f32>, weights: &[f32]) -> f64 {
    let start = cdf.len();
    cdf.resize(start + weights.len() + 1, 0.0);
    cumulative_into(&mut cdf[start..], weights)
}

/// Writes into `out` (`n + 1` long) the cumulative probabilities of `weights` (`n` of
/// them; 0 first, 1 last), and returns their total. Negative and non-finite weights count
/// as 0; with no weight at all every piece is alike.
fn cumulative_into(out: &mut [f32], weights: &[f32]) -> f64 {
    let clean = |x: f32| {
        if x.is_finite() && x > 0.0 {
            x as f64
        } else {
            0.0
        }
    };
    let total: f64 = weights.iter().map(|&x| clean(x)).sum();
    let mut acc = 0.0f64;
    out[0] = 0.0;
    if total > 0.0 {
        for (o, &x) in out[1..].iter_mut().zip(weights) {
            acc += clean(x);
            *o = (acc / total) as f32;
        }
    } else {
        let sum = weights.len() as f64;
        for o in &mut out[1..] {
            acc += 1.0;
            *o = (acc / sum) as f32;
        }
    }
    out[weights.len()] = 1.0;
    total
}

/// How many buckets a row's guide has at most. A row's guide narrows a search to a stretch
/// of about `width / ROW_BUCKETS` cells of even weight: a few cache lines, which
/// [`Distribution2d::sample`] asks for at once. A guide of one bucket per cell would narrow
/// it to one line, but its own table (two bytes a cell) then misses the cache as often as
/// the `cdf` it points into, one miss after the other (docs/perf-log.md).
const ROW_BUCKETS: usize = 64;

/// Whether a table of `n` pieces is short enough for a guide (whose entries are `u16`);
/// a longer one is searched whole.
fn guided(n: usize) -> bool {
    n <= u16::MAX as usize + 1
}

/// Appends the guide of `c` (`n + 1` cumulative probabilities) in `m` buckets to `guide`,
/// as [`guide_into`] makes it; nothing for a table too long for a guide.
fn push_guide(guide: &mut Vec<u16>, c: &[f32], m: usize) {
    if !guided(c.len() - 1) {
        return;
    }
    let start = guide.len();
    guide.resize(start + m, 0);
    guide_into(&mut guide[start..], c);
}

/// Writes into `out` the guide of `c` (`n + 1` cumulative probabilities, `n` short enough
/// for a guide) in `out.len()` buckets: entry `k` is the last piece `i` whose `c[i]` is at
/// most `k / m`, where the search for a `u` in that bucket starts.
fn guide_into(out: &mut [u16], c: &[f32]) {
    let (n, m) = (c.len() - 1, out.len());
    // `k / m` rises with `k`, so the piece it falls in only moves on: one walk along `c`
    // finds every entry (the last `i` with `c[i] <= k / m`, at most `n - 1`).
    let mut i = 0;
    for (k, o) in out.iter_mut().enumerate() {
        let x = k as f32 / m as f32;
        while i + 1 < c.len() && c[i + 1] <= x {
            i += 1;
        }
        *o = i.min(n - 1) as u16;
    }
}

/// The stretch of `c` (`n + 1` cumulative probabilities) that guide `g` (of `g.len()`
/// buckets, not empty) gives `u` (in `[0, 1)`) to search: its first and last entries, and
/// where `u` lies within its bucket (from 0 to 1).
#[inline]
fn stretch(n: usize, g: &[u16], u: f32) -> (usize, usize, f32) {
    let m = g.len();
    let k = ((u * m as f32) as usize).min(m - 1);
    let lo = g[k] as usize;
    let hi = if k + 1 < m { g[k + 1] as usize + 1 } else { n };
    (lo, hi, u * m as f32 - k as f32)
}

/// The piece of `c` (`n + 1` cumulative probabilities, with guide `g` or none) that `u`
/// (in `[0, 1)`) falls in: the last `i` with `c[i] <= u`, which has a width (the pieces of
/// none before it are passed over).
#[inline]
fn find(c: &[f32], g: &[u16], u: f32) -> usize {
    let n = c.len() - 1;
    if !g.is_empty() {
        let (lo, hi, _) = stretch(n, g, u);
        // Rounding may put `u` just outside its bucket's range: then the whole table.
        if c[lo] <= u && c[hi] > u {
            return lo + c[lo..=hi].partition_point(|&v| v <= u) - 1;
        }
    }
    (c.partition_point(|&v| v <= u).saturating_sub(1)).min(n - 1)
}

/// Where in `[0, 1)` `u` falls within piece `i` of `c` (`n + 1` cumulative probabilities of
/// `n` equal pieces), and the density there.
#[inline]
fn place(c: &[f32], i: usize, u: f32) -> (f32, f32) {
    let n = (c.len() - 1) as f32;
    let (lo, hi) = (c[i], c[i + 1]);
    let rest = ((u - lo) / (hi - lo)).clamp(0.0, 1.0);
    let mut x = (i as f32 + rest) / n;
    // Rounding may carry the point onto the next piece's edge: keep it in its own.
    while x > 0.0 && (x * n) as usize > i {
        x = f32::from_bits(x.to_bits() - 1);
    }
    (x, (hi - lo) * n)
}

impl Distribution2d {
    /// From `weights`, row by row (`width` x `height` of them). Negative and non-finite
    /// weights count as 0; with no weight at all every cell is alike.
    pub fn new(weights: &[f32], width: usize, height: usize) -> Self {
        use rayon::prelude::*;
        assert_eq!(weights.len(), width * height, "one weight per cell");
        let w = width.max(1);
        let buckets = w.min(ROW_BUCKETS);
        // (A grid of no columns has no rows either.)
        let rows = weights.len() / w;
        // Row by row on every core: each row's tables depend on its own weights alone.
        // A row of no weight is never chosen; its cells are made alike all the same.
        let mut cdf = vec![0.0f32; rows * (w + 1)];
        let mut totals = vec![0.0f32; rows];
        cdf.par_chunks_mut(w + 1)
            .zip(weights.par_chunks(w))
            .zip(totals.par_iter_mut())
            .for_each(|((c, row), total)| *total = cumulative_into(c, row) as f32);
        let mut guide = vec![0u16; if guided(w) { rows * buckets } else { 0 }];
        guide
            .par_chunks_mut(buckets)
            .zip(cdf.par_chunks(w + 1))
            .for_each(|(g, c)| guide_into(g, c));
        let (mut row_cdf, mut row_guide) = (Vec::new(), Vec::new());
        if rows > 0 {
            push_cumulative(&mut row_cdf, &totals);
            push_guide(&mut row_guide, &row_cdf, rows);
        }
        Distribution2d {
            width: w,
            height: rows,
            row_cdf,
            row_guide,
            cdf,
            guide,
        }
    }

    /// Row `r`'s cumulative probabilities and guide.
    #[inline]
    fn row_tables(&self, r: usize) -> (&[f32], &[u16]) {
        let (w, m) = (self.width, self.width.min(ROW_BUCKETS));
        let guide = if self.guide.is_empty() {
            &[][..]
        } else {
            &self.guide[r * m..(r + 1) * m]
        };
        (&self.cdf[r * (w + 1)..(r + 1) * (w + 1)], guide)
    }

    /// A point of the square chosen by `u`, with its density; `None` for an empty grid.
    pub fn sample(&self, u: Vec2) -> Option<(Vec2, f32)> {
        self.sample_hinting(u, |_| ())
    }

    /// [`Distribution2d::sample`], telling `hint` first where the point will be found: its
    /// row's place exactly, its column's as the guide's stretch suggests (where the
    /// cumulative probabilities rise evenly through it). The search's own memory is asked
    /// for at once too, so that both wait on the cache together rather than one after the
    /// other; `hint` may ask for what the caller will read at the point.
    #[inline]
    pub fn sample_hinting(&self, u: Vec2, hint: impl FnOnce(Vec2)) -> Option<(Vec2, f32)> {
        if self.height == 0 {
            return None;
        }
        let uy = u.y.clamp(0.0, 1.0 - f32::EPSILON);
        let r = find(&self.row_cdf, &self.row_guide, uy);
        let (y, py) = place(&self.row_cdf, r, uy);
        let (c, g) = self.row_tables(r);
        let ux = u.x.clamp(0.0, 1.0 - f32::EPSILON);
        if !g.is_empty() {
            let n = c.len() - 1;
            let (lo, hi, along) = stretch(n, g, ux);
            // The stretch's cache lines (a few for a row of even weights; a long stretch
            // is a row's faint part, rarely drawn: its first lines).
            for i in (lo..=hi).step_by(16).take(4) {
                super::prefetch(&c[i]);
            }
            let guess = lo as f32 + along * (hi - lo) as f32;
            hint(Vec2::new(guess / n as f32, y));
        }
        let (x, px) = place(c, find(c, g, ux), ux);
        Some((Vec2::new(x, y), py * px))
    }

    /// The row and the column of the cell holding `p` (the grid has rows).
    #[inline]
    fn cell(&self, p: Vec2) -> (usize, usize) {
        let (h, w) = (self.height, self.width);
        let r = ((p.y * h as f32) as usize).min(h - 1);
        (r, ((p.x * w as f32) as usize).min(w - 1))
    }

    /// Asks for the memory [`Distribution2d::pdf`] at `p` reads, without waiting.
    #[inline]
    pub fn prefetch(&self, p: Vec2) {
        if self.height == 0 {
            return;
        }
        let (r, i) = self.cell(p);
        super::prefetch(&self.cdf[r * (self.width + 1) + i]);
    }

    /// The density of [`Distribution2d::sample`] at `p`.
    #[inline]
    pub fn pdf(&self, p: Vec2) -> f32 {
        if self.height == 0 {
            return 0.0;
        }
        let (h, w) = (self.height, self.width);
        let (r, i) = self.cell(p);
        let (c, _) = self.row_tables(r);
        // As `sample` multiplies them, to the bit.
        let py = (self.row_cdf[r + 1] - self.row_cdf[r]) * h as f32;
        py * ((c[i + 1] - c[i]) * w as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::super::chi2::chi2_square;
    use super::*;

    /// The guide's one walk gives every entry the binary search gives: the last piece whose
    /// start is at most `k / m`, on tables with runs of empty pieces, one heavy piece, and
    /// none at all, in as many buckets as pieces and in fewer; and a search through it finds
    /// the piece a search of the whole table finds.
    #[test]
    fn the_guide_is_the_last_piece_starting_at_or_before_each_bucket() {
        let mut rng = crate::math::Rng::new(11);
        let (mut tables, mut finds) = (0, 0);
        for case in 0..200 {
            let n: usize = 1 + case % 37;
            let weights: Vec<f32> = (0..n)
                .map(|i| match case % 4 {
                    0 => rng.next_f32(),
                    1 if i % 3 == 0 => 0.0,
                    1 => rng.next_f32() * 10.0,
                    2 if i == n / 2 => 1000.0,
                    2 => rng.next_f32() * 0.01,
                    _ => 0.0,
                })
                .collect();
            let mut c = vec![];
            push_cumulative(&mut c, &weights);
            for m in [n, n.div_ceil(3), n.min(4)] {
                let mut guide = vec![];
                push_guide(&mut guide, &c, m);
                assert_eq!(guide.len(), m);
                for (k, &g) in guide.iter().enumerate() {
                    let x = k as f32 / m as f32;
                    let searched = (c.partition_point(|&v| v <= x).saturating_sub(1)).min(n - 1);
                    assert_eq!(
                        g as usize, searched,
                        "table {case}, bucket {k} of {m}: {c:?}"
                    );
                }
                for _ in 0..20 {
                    let u = rng.next_f32();
                    assert_eq!(find(&c, &guide, u), find(&c, &[], u), "table {case}, {u}");
                    finds += 1;
                }
                tables += 1;
            }
        }
        assert_eq!((tables, finds), (600, 12_000));
    }

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

    /// A grid without cells (no columns, or no rows) samples nothing and has no density.
    #[test]
    fn an_empty_grid_samples_nothing() {
        for (w, h) in [(0, 3), (4, 0), (0, 0)] {
            let d = Distribution2d::new(&[], w, h);
            assert_eq!(d.sample(Vec2::new(0.5, 0.5)), None, "{w} x {h}");
            assert_eq!(d.pdf(Vec2::new(0.5, 0.5)), 0.0, "{w} x {h}");
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
