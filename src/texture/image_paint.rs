//! An image as a pattern: bilinear at a point, through its MIP pyramid (mipmap.rs) over a
//! footprint; outside `[0, 1]` as its texture's wrap modes say.

use super::{ImageData, Paint, Wraps, mipmap};
use crate::math::{Color, Vec2};

impl Paint for ImageData {
    fn at(&self, uv: Vec2, wraps: Wraps) -> Color {
        self.sample_bilinear(uv, wraps)
    }

    fn filtered(&self, uv: Vec2, dx: Vec2, dy: Vec2, wraps: Wraps) -> Color {
        mipmap::sample(self, uv, dx, dy, wraps)
    }

    /// The mean texel.
    fn mean(&self) -> Color {
        ImageData::mean(self)
    }

    /// The decoded image data's bytes.
    fn bytes(&self) -> usize {
        ImageData::bytes(self)
    }
}
