//! The solid pattern: a colour is the same everywhere, and needs no texture coordinates.

use super::{Paint, Wraps};
use crate::math::{Color, Vec2};

impl Paint for Color {
    fn at(&self, _uv: Vec2, _wraps: Wraps) -> Color {
        *self
    }

    fn filtered(&self, _uv: Vec2, _dx: Vec2, _dy: Vec2, _wraps: Wraps) -> Color {
        *self
    }

    fn mean(&self) -> Color {
        *self
    }

    fn constant(&self) -> Option<Color> {
        Some(*self)
    }
}
