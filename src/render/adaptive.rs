//! Adaptive sampling (`--noise`, `[image] noise`): which pixels of a film go on taking
//! samples. Every pixel takes [`FIRST_DECISION`] samples; from then on, before each pass, a
//! pixel takes more only while its estimated relative error, or a neighbour's, is above the
//! threshold (up to the render's samples per pixel). The decision reads only the film, so
//! a render is the same bytes at any thread count and resumes from a checkpoint as it
//! would have gone on.
//!
//! A pixel's relative error is its standard error over its value
//! ([`crate::film::relative_error`]). Looking at the neighbours too (the largest error in a
//! 3 x 3 window) keeps a pixel whose first samples happened to agree (all of them missing a
//! small light its neighbours see) from stopping early: what would otherwise bias the
//! picture where a stopping rule reads the samples it stops on.

use crate::film::{Film, FilmPixel, Region, TileGrid};

/// Samples every pixel takes before any may stop: enough for its spread to say something.
pub const FIRST_DECISION: u32 = 16;

/// The pixels that take samples in the next pass of an adaptive render.
#[derive(Clone, Debug)]
pub struct Convergence {
    width: u32,
    grid: TileGrid,
    /// Row by row from the top: whether the pixel takes samples.
    active: Vec<bool>,
    /// Tile by tile: whether any of its pixels does.
    tiles: Vec<bool>,
    /// How many do.
    count: u64,
    /// The fewest samples an active pixel has.
    fewest: Option<u32>,
}

impl Convergence {
    /// The pixels of `film` (those of `region`, where given) that go on: fewer than
    /// [`FIRST_DECISION`] samples, or an error above `noise` in their 3 x 3 window; and
    /// fewer than `spp` samples either way.
    pub fn of(film: &Film, noise: f32, spp: u32, region: Option<Region>) -> Self {
        let (w, h) = (film.width() as usize, film.height() as usize);
        let error = film.rows(pixel_error);
        let samples = film.rows(|p: &FilmPixel| p.samples);
        // The largest error in each pixel's window: along rows, then down columns.
        let mut across = vec![0.0f32; w * h];
        for y in 0..h {
            let row = &error[y * w..(y + 1) * w];
            for x in 0..w {
                let lo = x.saturating_sub(1);
                let hi = (x + 2).min(w);
                across[y * w + x] = row[lo..hi].iter().copied().fold(0.0, f32::max);
            }
        }
        let inside = |x: usize, y: usize| {
            region.is_none_or(|r| {
                (r.x0 as usize..r.x1 as usize).contains(&x)
                    && (r.y0 as usize..r.y1 as usize).contains(&y)
            })
        };
        let mut active = vec![false; w * h];
        let (mut count, mut fewest) = (0u64, None::<u32>);
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                let n = samples[i];
                if n >= spp || !inside(x, y) {
                    continue;
                }
                let window = (y.saturating_sub(1)..(y + 2).min(h))
                    .map(|yy| across[yy * w + x])
                    .fold(0.0, f32::max);
                if n < FIRST_DECISION || window > noise {
                    active[i] = true;
                    count += 1;
                    fewest = Some(fewest.map_or(n, |f| f.min(n)));
                }
            }
        }
        let grid = film.grid();
        let tiles = (0..grid.count())
            .map(|t| {
                let (x0, y0, x1, y1) = grid.rect(t);
                (y0..y1).any(|y| (x0..x1).any(|x| active[y as usize * w + x as usize]))
            })
            .collect();
        Convergence {
            width: film.width(),
            grid,
            active,
            tiles,
            count,
            fewest,
        }
    }

    /// Whether pixel `(x, y)` takes samples.
    #[inline]
    pub fn is_active(&self, x: u32, y: u32) -> bool {
        self.active[y as usize * self.width as usize + x as usize]
    }

    /// Whether any pixel of tile `i` does.
    pub fn tile_active(&self, i: u32) -> bool {
        self.tiles[i as usize]
    }

    /// How many pixels do.
    pub fn active(&self) -> u64 {
        self.count
    }

    /// The fewest samples a pixel that goes on has; `None` when every pixel is done.
    pub fn fewest_samples(&self) -> Option<u32> {
        self.fewest
    }

    /// The film's tiles.
    pub fn grid(&self) -> TileGrid {
        self.grid
    }
}

/// A pixel's relative error; infinite below two samples, where there is no estimate.
fn pixel_error(p: &FilmPixel) -> f32 {
    match p.variance_of_mean() {
        Some(v) => crate::film::relative_error(v, crate::math::luminance(p.value())),
        None => f32::INFINITY,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Color;

    /// A film whose pixels all have `n` samples of spread `sigma` around 0.5.
    fn film(w: u32, h: u32, n: u32, sigma: f32) -> Film {
        let mut film: Film = Film::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let p = film.get_mut(x, y);
                for k in 0..n {
                    let d = if k % 2 == 0 { sigma } else { -sigma };
                    p.add(Color::splat(0.5 + d), 1.0);
                }
            }
        }
        film
    }

    /// Pixels below the first decision go on whatever their spread; from it on, only those
    /// whose window holds an error above the threshold; none at the samples' cap.
    #[test]
    fn pixels_go_on_while_they_or_a_neighbour_are_noisy() {
        let quiet = film(40, 36, FIRST_DECISION, 0.01);
        let c = Convergence::of(&quiet, 0.01, 64, None);
        assert_eq!((c.active(), c.fewest_samples()), (0, None));
        // A noisy pixel keeps its 3 x 3 window going (9 pixels), in the tiles it touches.
        let mut noisy = quiet.clone();
        for k in 0..FIRST_DECISION {
            let d = if k % 2 == 0 { 0.4 } else { -0.4 };
            noisy.get_mut(32, 10).add(Color::splat(0.5 + d), 1.0);
        }
        let c = Convergence::of(&noisy, 0.01, 64, None);
        assert_eq!(c.active(), 9);
        assert_eq!(c.fewest_samples(), Some(FIRST_DECISION));
        let mut counted = 0;
        for y in 9..=11 {
            for x in 31..=33 {
                assert!(c.is_active(x, y));
                counted += 1;
            }
        }
        assert_eq!(counted, 9);
        assert!(!c.is_active(30, 10) && !c.is_active(32, 12));
        let grid = c.grid();
        let touched: Vec<u32> = (0..grid.count()).filter(|&t| c.tile_active(t)).collect();
        // Tiles of 16: the window (31..=33) straddles the edge of the second and third.
        assert_eq!(touched, [1, 2]);
        // A threshold above the error lets it stop; the cap stops everything.
        assert_eq!(Convergence::of(&noisy, 0.5, 64, None).active(), 0);
        assert_eq!(
            Convergence::of(&noisy, 0.01, FIRST_DECISION, None).active(),
            0
        );
        // Before the first decision every pixel goes on.
        let early = film(8, 8, FIRST_DECISION - 1, 0.0);
        let c = Convergence::of(&early, 0.5, 64, None);
        assert_eq!(c.active(), 64);
        assert_eq!(c.fewest_samples(), Some(FIRST_DECISION - 1));
        // A region's pixels alone.
        let r = Region {
            x0: 2,
            y0: 2,
            x1: 5,
            y1: 4,
        };
        assert_eq!(Convergence::of(&early, 0.5, 64, Some(r)).active(), 6);
    }
}
