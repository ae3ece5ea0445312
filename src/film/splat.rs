//! A film that takes splats: colours added at any film position from any thread (light
//! tracing's connections land anywhere on the film, not in the pixel being worked on). Each
//! pixel's sums are fixed-point integers added atomically, so the total is the same bits
//! whatever order the threads add in: a render is the same bytes at any thread count.

use super::Image;
use crate::math::Color;
use std::sync::atomic::{AtomicU64, Ordering};

/// Fractional bits of a sum: a splat is rounded to 2^-24 (6e-8), and a pixel's sum may reach
/// 2^40 (1e12) before it saturates.
const FRACTION: f64 = (1u64 << 24) as f64;

/// Per-pixel sums of splats, row by row.
#[derive(Debug)]
pub struct SplatFilm {
    width: u32,
    height: u32,
    sums: Vec<[AtomicU64; 3]>,
}

impl SplatFilm {
    /// An empty film of `width` x `height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        SplatFilm {
            width,
            height,
            sums: (0..n).map(|_| Default::default()).collect(),
        }
    }

    /// Adds `c` to the pixel that film position `(x, y)` (pixels) lies in; off the film,
    /// non-finite or negative values add nothing.
    pub fn add(&self, x: f32, y: f32, c: Color) {
        if !(x >= 0.0 && y >= 0.0 && x < self.width as f32 && y < self.height as f32) {
            return;
        }
        let i = y as usize * self.width as usize + x as usize;
        for (sum, v) in self.sums[i].iter().zip(c.to_array()) {
            if v.is_finite() && v > 0.0 {
                let fixed = (v as f64 * FRACTION).round().min(u64::MAX as f64 / 2.0) as u64;
                // Saturating: a sum past the range stays at its top instead of wrapping.
                let _ = sum.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |s| {
                    Some(s.saturating_add(fixed))
                });
            }
        }
    }

    /// The sums as they are now, to go back to ([`SplatFilm::restore`]).
    pub fn snapshot(&self) -> Vec<[u64; 3]> {
        self.sums
            .iter()
            .map(|s| s.each_ref().map(|a| a.load(Ordering::Relaxed)))
            .collect()
    }

    /// Puts the sums back as `snapshot` had them (a pass given up).
    pub fn restore(&self, snapshot: &[[u64; 3]]) {
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
                let v = |a: &AtomicU64| (a.load(Ordering::Relaxed) as f64 * k) as f32;
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
        let a = SplatFilm::new(4, 3);
        let b = SplatFilm::new(4, 3);
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
        let one = SplatFilm::new(2, 2);
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
}
