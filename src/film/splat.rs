//! A film that takes splats: colours added at any film position from any thread (light
//! tracing's connections land anywhere on the film, not in the pixel being worked on),
//! spread over the pixels around it by the render's filter as a camera sample there would
//! be. Each pixel's sums are fixed-point integers added atomically, so the total is the same
//! bits whatever order the threads add in: a render is the same bytes at any thread count.

use super::{Filter, FilterKind, Image};
use crate::math::Color;
use std::sync::atomic::{AtomicI64, Ordering};

/// Fractional bits of a sum: a splat is rounded to 2^-24 (6e-8), and a pixel's sum may reach
/// 2^40 (1e12) before it saturates.
const FRACTION: f64 = (1u64 << 24) as f64;

/// Per-pixel sums of splats, row by row.
#[derive(Debug)]
pub struct SplatFilm {
    width: u32,
    height: u32,
    /// The filter splats are spread by; `None` for the box of one pixel.
    filter: Option<Filter>,
    sums: Vec<[AtomicI64; 3]>,
}

impl SplatFilm {
    /// An empty film of `width` x `height` pixels whose splats are spread by `filter`.
    pub fn new(width: u32, height: u32, filter: &Filter) -> Self {
        let n = width as usize * height as usize;
        let one_pixel = filter.kind == FilterKind::Box && filter.radius == 0.5;
        SplatFilm {
            width,
            height,
            filter: (!one_pixel).then_some(*filter),
            sums: (0..n).map(|_| Default::default()).collect(),
        }
    }

    /// Adds `c` at film position `(x, y)` (pixels): to each pixel whose centre lies within
    /// the filter's radius, times the filter's weight there over its integral (the share a
    /// camera sample there has of that pixel's value); with the box of one pixel, to the
    /// pixel it lies in. Non-finite or negative colours add nothing.
    pub fn add(&self, x: f32, y: f32, c: Color) {
        if !(c.is_finite() && c.min_element() >= 0.0) {
            return;
        }
        let Some(filter) = &self.filter else {
            if x >= 0.0 && y >= 0.0 && x < self.width as f32 && y < self.height as f32 {
                self.add_to(x as u32, y as u32, c);
            }
            return;
        };
        let r = filter.radius;
        let (x0, x1) = ((x - r - 0.5).ceil().max(0.0), (x + r - 0.5).floor());
        let (y0, y1) = ((y - r - 0.5).ceil().max(0.0), (y + r - 0.5).floor());
        let (x1, y1) = (
            x1.min(self.width as f32 - 1.0),
            y1.min(self.height as f32 - 1.0),
        );
        if !(x0 <= x1 && y0 <= y1) {
            return;
        }
        for py in y0 as u32..=y1 as u32 {
            for px in x0 as u32..=x1 as u32 {
                let w = filter.splat_weight(x - (px as f32 + 0.5), y - (py as f32 + 0.5));
                if w != 0.0 {
                    self.add_to(px, py, c * w);
                }
            }
        }
    }

    /// Adds `c` (finite) to pixel `(x, y)`.
    fn add_to(&self, x: u32, y: u32, c: Color) {
        let i = y as usize * self.width as usize + x as usize;
        for (sum, v) in self.sums[i].iter().zip(c.to_array()) {
            let limit = i64::MAX as f64 / 2.0;
            let fixed = (v as f64 * FRACTION).round().clamp(-limit, limit) as i64;
            if fixed != 0 {
                // Saturating: a sum past the range stays at its end instead of wrapping.
                let _ = sum.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |s| {
                    Some(s.saturating_add(fixed))
                });
            }
        }
    }

    /// The sums as they are now, to go back to ([`SplatFilm::restore`]).
    pub fn snapshot(&self) -> Vec<[i64; 3]> {
        self.sums
            .iter()
            .map(|s| s.each_ref().map(|a| a.load(Ordering::Relaxed)))
            .collect()
    }

    /// Puts the sums back as `snapshot` had them (a pass given up).
    pub fn restore(&self, snapshot: &[[i64; 3]]) {
        for (sum, saved) in self.sums.iter().zip(snapshot) {
            for (a, v) in sum.iter().zip(saved) {
                a.store(*v, Ordering::Relaxed);
            }
        }
    }

    /// The picture: each pixel's sums times `scale`.
    pub fn image(&self, scale: f32) -> Image {
        let k = scale as f64 / FRACTION;
        let pixels = self
            .sums
            .iter()
            .map(|s| {
                let v = |a: &AtomicI64| (a.load(Ordering::Relaxed) as f64 * k) as f32;
                Color::new(v(&s[0]), v(&s[1]), v(&s[2]))
            })
            .collect();
        Image {
            width: self.width,
            height: self.height,
            pixels,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn box_filter() -> Filter {
        Filter::new(FilterKind::Box, None)
    }

    /// Splats land in the pixel their position lies in, add up whatever their order (the
    /// same bits reversed), round to 2^-24, and off-film, negative or NaN ones add nothing.
    #[test]
    fn splats_add_up_in_any_order() {
        let splats: Vec<(f32, f32, Color)> = (0..1000)
            .map(|i| {
                let f = i as f32;
                (
                    (f * 0.37) % 4.0,
                    (f * 0.91) % 3.0,
                    Color::new(0.1 * f, 1e-3, 7.25),
                )
            })
            .collect();
        let a = SplatFilm::new(4, 3, &box_filter());
        let b = SplatFilm::new(4, 3, &box_filter());
        for &(x, y, c) in &splats {
            a.add(x, y, c);
        }
        for &(x, y, c) in splats.iter().rev() {
            b.add(x, y, c);
        }
        let (ia, ib) = (a.image(1.0), b.image(1.0));
        let bits = |i: &Image| -> Vec<u32> {
            i.pixels
                .iter()
                .flat_map(|c| c.to_array().map(f32::to_bits))
                .collect()
        };
        assert_eq!(bits(&ia), bits(&ib));
        let total: f32 = ia.pixels.iter().map(|c| c.z).sum();
        assert!((total - 7250.0).abs() < 1e-2, "{total}");
        let one = SplatFilm::new(2, 2, &box_filter());
        one.add(1.5, 0.2, Color::splat(0.5));
        for (x, y, c) in [
            (-0.1, 0.0, Color::ONE),
            (2.0, 0.0, Color::ONE),
            (0.0, 2.0, Color::ONE),
            (0.5, 0.5, Color::splat(-1.0)),
            (0.5, 0.5, Color::splat(f32::NAN)),
        ] {
            one.add(x, y, c);
        }
        let img = one.image(2.0);
        assert_eq!(img.get(1, 0), Color::splat(1.0));
        assert_eq!(img.pixels.iter().filter(|c| **c != Color::ZERO).count(), 1);
    }

    /// A splat spread by a wider filter gives each pixel near it the filter's weight over
    /// its integral: the pixels' sum is near the splat's (the weights at whole pixels sum
    /// to the integral only roughly, as for a camera sample's shares), a
    /// Gaussian's share falls off from the nearest pixel, and Mitchell's negative lobes take
    /// some away from pixels two away. Off the film's edge, the share is lost.
    #[test]
    fn splats_spread_as_the_filter_weighs() {
        for (kind, negative) in [
            (FilterKind::Gaussian, false),
            (FilterKind::Tent, false),
            (FilterKind::Mitchell, true),
        ] {
            let f = Filter::new(kind, None);
            let film = SplatFilm::new(9, 9, &f);
            film.add(4.3, 4.6, Color::ONE);
            let img = film.image(1.0);
            let sum: f32 = img.pixels.iter().map(|c| c.x).sum();
            assert!((sum - 1.0).abs() < 0.03, "{kind:?}: {sum}");
            let nearest = img.get(4, 4).x;
            assert!(img.pixels.iter().all(|c| c.x <= nearest), "{kind:?}");
            assert_eq!(img.pixels.iter().any(|c| c.x < 0.0), negative, "{kind:?}");
            let want = f.splat_weight(4.3 - 4.5, 4.6 - 4.5);
            assert!((nearest - want).abs() < 1e-6, "{kind:?}");
            let edge = SplatFilm::new(9, 9, &f);
            edge.add(0.1, 4.5, Color::ONE);
            let sum: f32 = edge.image(1.0).pixels.iter().map(|c| c.x).sum();
            assert!(sum < 0.9, "{kind:?}: {sum}");
        }
    }
}
