//! The film: the reconstruction filter (filter.rs), the weighted sums each pixel's samples
//! add to, pass after pass ([`Film`] of [`FilmPixel`]s, kept tile by tile: tiles.rs), and
//! the finished picture ([`Image`]).

pub mod filter;
mod region;
pub mod splat;
pub mod tiles;

pub use filter::{Filter, FilterKind};
pub use region::Region;
pub use splat::SplatFilm;
pub use tiles::{TILE, TileGrid};

use crate::math::{Color, luminance};
use rayon::prelude::*;

/// What a pixel's samples have added up to: the sums that make its value, so that more
/// samples can be added later (a progressive render, a pass after a checkpoint) and give
/// the same bytes as taking them all at once, and the sum of squares that estimates its
/// error. Plain arrays, 36 bytes, so that a large film stays small.
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Zeroable)]
#[repr(C)]
pub struct FilmPixel {
    /// The samples, each times the sign of its filter weight (linear RGB).
    pub sum: [f32; 3],
    /// The signs added up.
    pub weight: f32,
    /// The samples without their signs (for the rare pixel whose signs cancel).
    pub unsigned: [f32; 3],
    /// How many samples.
    pub samples: u32,
    /// The squares of the samples' luminances added up: with `unsigned` and `samples`, the
    /// spread of the samples, from which the pixel's error is estimated.
    pub sum_sq: f32,
}

// The size the docs give (and the memory estimate in scene/limits.rs counts on).
const _: () = assert!(std::mem::size_of::<FilmPixel>() == 36);

impl FilmPixel {
    /// Adds a sample `c` whose filter weight has sign `sign`.
    #[inline]
    pub fn add(&mut self, c: Color, sign: f32) {
        let l = luminance(c);
        self.add_sums(c * sign, sign, c, l * l, 1);
    }

    /// Adds the sums of `samples` samples taken elsewhere (`sum_sq`: their squared
    /// luminances).
    #[inline]
    pub fn add_sums(
        &mut self,
        sum: Color,
        weight: f32,
        unsigned: Color,
        sum_sq: f32,
        samples: u32,
    ) {
        self.sum = (Color::from(self.sum) + sum).into();
        self.weight += weight;
        self.unsigned = (Color::from(self.unsigned) + unsigned).into();
        self.sum_sq += sum_sq;
        self.samples += samples;
    }

    /// The variance of the pixel's luminance as an estimate (the samples' variance over
    /// their number), from their spread; `None` below two samples, where there is none.
    #[inline]
    pub fn variance_of_mean(&self) -> Option<f32> {
        if self.samples < 2 {
            return None;
        }
        let n = self.samples as f64;
        let mean = luminance(Color::from(self.unsigned)) as f64 / n;
        let var = (self.sum_sq as f64 / n - mean * mean).max(0.0) * n / (n - 1.0);
        Some((var / n) as f32)
    }

    /// The pixel's value: the samples averaged with the signs of their weights, never below
    /// zero; black with no samples.
    #[inline]
    pub fn value(&self) -> Color {
        if self.weight > 0.0 {
            (Color::from(self.sum) / self.weight).max(Color::ZERO)
        } else if self.samples > 0 {
            // Only possible when most samples fall in Mitchell's negative lobes.
            Color::from(self.unsigned) / self.samples as f32
        } else {
            Color::ZERO
        }
    }
}

/// Luminance below which a pixel's error counts as if it were this bright (1 % of white):
/// the error of a nearly black pixel relative to its value would never get small, and
/// cannot be seen once it is far below a step of an 8-bit output.
pub const DARK: f32 = 0.01;

/// A pixel's relative error: the standard error of its estimate (`variance` of its
/// luminance's estimate) over its `luminance` plus [`DARK`]. What adaptive sampling's
/// `noise` threshold and the variance view's colours measure.
#[inline]
pub fn relative_error(variance: f32, luminance: f32) -> f32 {
    variance.max(0.0).sqrt() / (luminance.max(0.0) + DARK)
}

/// One value per pixel of an image, kept tile by tile (see [`TileGrid`]) so that the render
/// loop can hand each thread a tile as one slice. `P` is what a pixel holds: the sums of its
/// samples ([`FilmPixel`], the default), or a debug view's record of what its ray met.
#[derive(Clone, Debug, PartialEq)]
pub struct Film<P = FilmPixel> {
    grid: TileGrid,
    /// Pixels, tile by tile.
    pixels: Vec<P>,
}

impl<P: bytemuck::Zeroable> Film<P> {
    /// A film of zeroed pixels (no samples). Zeroed memory, which the system maps as its
    /// pages are first written, rather than a default value written to every pixel here
    /// and again by the render: a 2048 x 2048 render of an empty scene took a third longer
    /// that way.
    pub fn new(width: u32, height: u32) -> Self {
        Film {
            grid: TileGrid { width, height },
            pixels: bytemuck::zeroed_vec(width as usize * height as usize),
        }
    }
}

impl<P> Film<P> {
    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.grid.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.grid.height
    }

    /// Its tiles.
    pub fn grid(&self) -> TileGrid {
        self.grid
    }

    /// The pixel at `(x, y)`.
    pub fn get(&self, x: u32, y: u32) -> &P {
        &self.pixels[self.grid.index(x, y)]
    }

    /// The pixel at `(x, y)`, to change.
    pub fn get_mut(&mut self, x: u32, y: u32) -> &mut P {
        let i = self.grid.index(x, y);
        &mut self.pixels[i]
    }

    /// Every pixel, in no order a caller may rely on (for counts and checks).
    pub fn pixels(&self) -> &[P] {
        &self.pixels
    }

    /// The pixels of `region` (every pixel where `None`), in no order a caller may rely on.
    pub fn pixels_in(&self, region: Option<Region>) -> Box<dyn Iterator<Item = &P> + '_> {
        match region {
            None => Box::new(self.pixels.iter()),
            Some(r) => {
                Box::new((r.y0..r.y1).flat_map(move |y| (r.x0..r.x1).map(move |x| self.get(x, y))))
            }
        }
    }

    /// Tile `i`'s pixels, row by row.
    pub fn tile(&self, i: u32) -> &[P] {
        let start = self.grid.start(i);
        &self.pixels[start..start + self.grid.len(i)]
    }

    /// Tile `i`'s pixels, to change.
    pub fn tile_mut(&mut self, i: u32) -> &mut [P] {
        let start = self.grid.start(i);
        &mut self.pixels[start..start + self.grid.len(i)]
    }

    /// Every tile as its own slice, in tile order, so that threads can each own some.
    pub fn tiles_mut(&mut self) -> Vec<&mut [P]> {
        let grid = self.grid;
        let mut rest = self.pixels.as_mut_slice();
        let mut tiles = Vec::with_capacity(grid.count() as usize);
        for i in 0..grid.count() {
            let (tile, after) = std::mem::take(&mut rest).split_at_mut(grid.len(i));
            tiles.push(tile);
            rest = after;
        }
        tiles
    }

    /// `f` of every pixel, row by row from the top (on every core).
    pub fn rows<T: Send + bytemuck::Zeroable>(&self, f: impl Fn(&P) -> T + Sync) -> Vec<T>
    where
        P: Sync,
    {
        let (w, grid) = (self.grid.width as usize, self.grid);
        // Zeroed, so that each pixel of the result is written once, below.
        let mut out: Vec<T> = bytemuck::zeroed_vec(self.pixels.len());
        // A band of tile rows at a time: each band's tiles are one stretch of `pixels`.
        out.par_chunks_mut(w * TILE as usize)
            .enumerate()
            .for_each(|(ty, band)| {
                for tx in 0..grid.tiles_x() {
                    let i = ty as u32 * grid.tiles_x() + tx;
                    let (x0, _, x1, _) = grid.rect(i);
                    let tw = (x1 - x0) as usize;
                    for (row, src) in self.tile(i).chunks_exact(tw).enumerate() {
                        let start = row * w + x0 as usize;
                        for (o, p) in band[start..start + tw].iter_mut().zip(src) {
                            *o = f(p);
                        }
                    }
                }
            });
        out
    }
}

impl<P: Copy + Send + Sync> Film<P> {
    /// Its pixels row by row from the top, in the film's own memory: each band of tile rows
    /// (one stretch of the film) is rearranged in place through a copy of the band, so a
    /// large film needs no second buffer as large as itself (fresh memory, whose pages the
    /// system maps one by one as they are first written, costs more than the copy).
    pub fn into_rows(self) -> Vec<P> {
        let (w, grid) = (self.grid.width as usize, self.grid);
        let mut pixels = self.pixels;
        pixels
            .par_chunks_mut(w * TILE as usize)
            .enumerate()
            .for_each_init(Vec::new, |band_copy: &mut Vec<P>, (ty, band)| {
                band_copy.clear();
                band_copy.extend_from_slice(band);
                let mut from = 0;
                for tx in 0..grid.tiles_x() {
                    let i = ty as u32 * grid.tiles_x() + tx;
                    let (x0, _, x1, _) = grid.rect(i);
                    let tw = (x1 - x0) as usize;
                    let tile = &band_copy[from..from + grid.len(i)];
                    for (row, src) in tile.chunks_exact(tw).enumerate() {
                        let start = row * w + x0 as usize;
                        band[start..start + tw].copy_from_slice(src);
                    }
                    from += grid.len(i);
                }
            });
        pixels
    }
}

impl Film<FilmPixel> {
    /// The picture the samples so far make.
    pub fn image(&self) -> Image {
        Image {
            width: self.grid.width,
            height: self.grid.height,
            pixels: self.rows(FilmPixel::value),
        }
    }

    /// The picture's expected mean relative difference from the converged one (the measure
    /// bench/ and the comparisons with Mitsuba use: the sum of the pixels' absolute errors
    /// over the sum of their values, in luminance), estimated from each pixel's spread: a
    /// pixel's expected absolute error is `sqrt(2 / pi)` times its standard error, as for a
    /// normal error. `None` while a pixel has fewer than two samples or the picture is black.
    pub fn estimated_error(&self) -> Option<f32> {
        self.estimated_error_in(None)
    }

    /// [`Film::estimated_error`] of the pixels of `region` (all where `None`).
    pub fn estimated_error_in(&self, region: Option<Region>) -> Option<f32> {
        let (mut err, mut sum) = (0.0f64, 0.0f64);
        for p in self.pixels_in(region) {
            err += (p.variance_of_mean()? as f64).sqrt();
            sum += luminance(p.value()) as f64;
        }
        (sum > 0.0).then(|| (err * (2.0 / std::f64::consts::PI).sqrt() / sum) as f32)
    }
}

/// A rendered image: linear RGB, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixels, row by row.
    pub pixels: Vec<Color>,
}

impl Image {
    /// A black image.
    pub fn new(width: u32, height: u32) -> Self {
        Image {
            width,
            height,
            pixels: vec![Color::ZERO; width as usize * height as usize],
        }
    }

    /// The pixel at `(x, y)`.
    pub fn get(&self, x: u32, y: u32) -> Color {
        self.pixels[y as usize * self.width as usize + x as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A film kept tile by tile reads back row by row: `rows`, `into_rows` and `get` agree
    /// on every pixel, at sizes that cut tiles short on both edges.
    #[test]
    fn rows_read_the_tiles_back_in_image_order() {
        let mut checked = 0;
        for (w, h) in [
            (1, 1),
            (16, 16),
            (33, 17),
            (50, 3),
            (130, 70),
            (64, 129),
            (200, 64),
        ] {
            let mut film: Film<(u32, u32)> = Film::new(w, h);
            let grid = film.grid();
            for i in 0..grid.count() {
                let (x0, y0, x1, _) = grid.rect(i);
                for (k, p) in film.tile_mut(i).iter_mut().enumerate() {
                    let k = k as u32;
                    *p = (x0 + k % (x1 - x0), y0 + k / (x1 - x0));
                }
            }
            let rows = film.rows(|p| *p);
            for y in 0..h {
                for x in 0..w {
                    assert_eq!(rows[(y * w + x) as usize], (x, y));
                    assert_eq!(*film.get(x, y), (x, y));
                    checked += 1;
                }
            }
            assert_eq!(film.into_rows(), rows);
        }
        assert_eq!(checked, 1 + 256 + 561 + 150 + 9100 + 8256 + 12800);
    }

    /// The variance of a pixel's estimate, worked by hand: samples of luminance 1, 2, 3 and 4
    /// spread with variance 5/3, so their mean's is 5/12; none below two samples.
    #[test]
    fn a_pixels_variance_is_its_samples_spread_over_their_number() {
        let mut p = FilmPixel::default();
        p.add(Color::splat(1.0), 1.0);
        assert_eq!(p.variance_of_mean(), None);
        for v in [2.0, 3.0, 4.0] {
            p.add(Color::splat(v), 1.0);
        }
        let v = p.variance_of_mean().unwrap();
        assert!((v - 5.0 / 12.0).abs() < 1e-5, "{v}");
    }

    /// The estimated error of a film whose pixels each hold `n` samples spread evenly about
    /// their mean `m` with standard deviation `sigma` is `sqrt(2 / pi) sigma / sqrt(n) / m`;
    /// a film with a pixel of one sample has none.
    #[test]
    fn a_films_estimated_error_follows_its_spread() {
        let (n, m, sigma) = (16u32, 0.5f32, 0.2f32);
        let mut film: Film = Film::new(8, 4);
        for y in 0..4 {
            for x in 0..8 {
                let p = film.get_mut(x, y);
                for k in 0..n {
                    // Half the samples above the mean, half below: variance sigma² exactly
                    // (over n), which the unbiased estimate scales by n / (n - 1).
                    let d = if k % 2 == 0 { sigma } else { -sigma };
                    p.add(Color::splat(m + d), 1.0);
                }
            }
        }
        let e = film.estimated_error().unwrap();
        let sd = sigma * (n as f32 / (n - 1) as f32).sqrt();
        let want = (2.0 / std::f32::consts::PI).sqrt() * sd / (n as f32).sqrt() / m;
        assert!((e - want).abs() < 1e-4 * want, "{e} {want}");
        film.get_mut(3, 2).samples = 1;
        assert_eq!(film.estimated_error(), None);
    }

    /// A pixel's value is its samples' signed average, never negative, the unsigned average
    /// when the signs cancel, and black with no samples.
    #[test]
    fn a_pixels_value_is_its_signed_average() {
        let mut p = FilmPixel::default();
        assert_eq!(p.value(), Color::ZERO);
        p.add(Color::new(1.0, 2.0, 3.0), 1.0);
        p.add(Color::new(3.0, 0.0, 1.0), 1.0);
        p.add(Color::new(0.5, 4.0, 0.0), -1.0);
        assert_eq!(p.samples, 3);
        assert_eq!(p.value(), Color::new(3.5, 0.0, 4.0));
        let mut q = FilmPixel::default();
        q.add(Color::new(1.0, 1.0, 1.0), 1.0);
        q.add(Color::new(2.0, 3.0, 5.0), -1.0);
        assert_eq!(q.value(), Color::new(1.5, 2.0, 3.0));
    }
}
