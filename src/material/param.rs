//! A material's parameters: each a constant or read from a texture at the surface point.

use crate::math::Color;
use crate::texture::{Texture, TexturePoint};

/// A number: a constant, or the mean of a texture's channels at the point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scalar {
    /// The same everywhere.
    Value(f32),
    /// Index of a texture in the scene's list.
    Texture(usize),
}

impl Scalar {
    /// The value at a surface point.
    #[inline]
    pub fn at(&self, textures: &[Texture], p: &TexturePoint) -> f32 {
        match *self {
            Scalar::Value(v) => v,
            Scalar::Texture(t) => textures[t].eval(p).element_sum() / 3.0,
        }
    }
}

/// A colour: a constant, or a texture's colour at the point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ColorParam {
    /// The same everywhere.
    Value(Color),
    /// Index of a texture in the scene's list.
    Texture(usize),
}

impl ColorParam {
    /// The colour at a surface point.
    #[inline]
    pub fn at(&self, textures: &[Texture], p: &TexturePoint) -> Color {
        match *self {
            ColorParam::Value(c) => c,
            ColorParam::Texture(t) => textures[t].eval(p),
        }
    }

    /// The colour on average over the surface (the texture's mean).
    pub fn mean(&self, textures: &[Texture]) -> Color {
        match *self {
            ColorParam::Value(c) => c,
            ColorParam::Texture(t) => textures[t].mean(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec2;
    use crate::texture::{Mapping, Pattern};

    /// Constants are themselves everywhere; textured parameters read the texture at the
    /// point (a scalar the mean of its channels), and average to the pattern's mean.
    #[test]
    fn parameters_read_their_texture_at_the_point() {
        let textures = vec![Texture {
            pattern: Pattern::Stripes(crate::texture::Stripes {
                a: Color::new(0.3, 0.6, 0.9),
                b: Color::new(1.0, 2.0, 3.0),
                width: 0.5,
            }),
            mapping: Mapping::Uv,
            wrap: crate::texture::Wraps::REPEAT,
        }];
        let at = |u: f32| TexturePoint::with_uv(Vec2::new(u, 0.0));
        let c = ColorParam::Texture(0);
        assert_eq!(c.at(&textures, &at(0.25)), Color::new(0.3, 0.6, 0.9));
        assert_eq!(c.at(&textures, &at(0.75)), Color::new(1.0, 2.0, 3.0));
        assert_eq!(c.mean(&textures), Color::new(0.65, 1.3, 1.95));
        let s = Scalar::Texture(0);
        assert!((s.at(&textures, &at(0.25)) - 0.6).abs() < 1e-6);
        assert!((s.at(&textures, &at(0.75)) - 2.0).abs() < 1e-6);
        let k = ColorParam::Value(Color::splat(4.0));
        assert_eq!(k.at(&textures, &at(0.75)), Color::splat(4.0));
        assert_eq!(Scalar::Value(0.5).at(&textures, &at(0.25)), 0.5);
    }
}
