//! The stripes pattern: bands of two colours across `u`, filtered in closed form over a
//! footprint.

use super::{Paint, Wraps, antialias, footprint_radius, mix};
use crate::math::{Color, Vec2};

/// Bands across `u` of width `width`: `a` where `floor(u / width)` is even, else `b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stripes {
    /// Colour of even bands (starting at u = 0).
    pub a: Color,
    /// Colour of odd bands.
    pub b: Color,
    /// Width of a band, in texture-coordinate units.
    pub width: f32,
}

impl Paint for Stripes {
    fn at(&self, uv: Vec2, _wraps: Wraps) -> Color {
        if (uv.x / self.width).floor() as i64 & 1 == 0 {
            self.a
        } else {
            self.b
        }
    }

    /// A square wave under a tent filter (`antialias::square_wave`).
    fn filtered(&self, uv: Vec2, dx: Vec2, dy: Vec2, _wraps: Wraps) -> Color {
        let radius = footprint_radius(dx, dy);
        mix(
            self.a,
            self.b,
            antialias::square_wave(uv.x / self.width, radius.x / self.width),
        )
    }

    /// The square wave across `u` (`filtered`'s) stays inside its band.
    fn flat_over(&self, uv: Vec2, r: Vec2) -> bool {
        antialias::within_cell(uv.x / self.width, r.x / self.width)
    }

    /// The mean of the two colours, whose bands are equal.
    fn mean(&self) -> Color {
        (self.a + self.b) * 0.5
    }
}
