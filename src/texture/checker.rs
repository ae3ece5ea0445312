//! The checker pattern: squares of two colours, filtered in closed form over a footprint.

use super::{Paint, Wraps, antialias, footprint_radius, mix};
use crate::math::{Color, Vec2};

/// Squares of side `size`: `even` where `floor(u / size) + floor(v / size)` is even.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checker {
    /// Colour of cells with an even index sum (the cell with corner at (0, 0) and positive
    /// coordinates).
    pub even: Color,
    /// Colour of the other cells.
    pub odd: Color,
    /// Side of a cell, in texture-coordinate units.
    pub size: f32,
}

impl Paint for Checker {
    fn at(&self, uv: Vec2, _wraps: Wraps) -> Color {
        if checker_parity(uv, self.size) == 0 {
            self.even
        } else {
            self.odd
        }
    }

    /// The product of two square waves under a tent filter (`antialias::square_wave`).
    fn filtered(&self, uv: Vec2, dx: Vec2, dy: Vec2, _wraps: Wraps) -> Color {
        let radius = footprint_radius(dx, dy);
        let r = radius / self.size;
        let w = antialias::square_wave(uv.x / self.size, r.x)
            * antialias::square_wave(uv.y / self.size, r.y);
        mix(self.even, self.odd, w)
    }

    /// Both square waves (`filtered`'s) stay inside their cells.
    fn flat_over(&self, uv: Vec2, r: Vec2) -> bool {
        antialias::within_cell(uv.x / self.size, r.x / self.size)
            && antialias::within_cell(uv.y / self.size, r.y / self.size)
    }

    /// The mean of the two colours, whose cells are equal.
    fn mean(&self) -> Color {
        (self.even + self.odd) * 0.5
    }
}

/// 0 for cells where `floor(u / size) + floor(v / size)` is even, 1 otherwise. `floor`
/// (not truncation toward zero) keeps every cell the same size across 0, which was the
/// seed report's checkerboard bug.
pub fn checker_parity(uv: Vec2, size: f32) -> u32 {
    // Far-away uvs saturate the casts to i64::MAX; a wrapping sum keeps the parity (its low
    // bit) exact where a plain `+` would overflow.
    let i = ((uv.x / size).floor() as i64).wrapping_add((uv.y / size).floor() as i64);
    (i & 1) as u32
}
