//! Textures: a pattern (solid colour, image, checker, stripes) read through a mapping that
//! turns a surface point into texture coordinates (the shape's own uv, spherical,
//! cylindrical or planar).

mod antialias;
mod checker;
mod image;
mod image_paint;
mod mapping;
mod mipmap;
mod solid;
mod stripes;
mod wrap;

pub use checker::{Checker, checker_parity};
pub use image::{
    ColorSpace, ImageData, ImageLoadError, decode, in_guarded_decoder, srgb_to_linear,
};
pub use mapping::{Footprint, Mapping, TexturePoint};
pub use stripes::Stripes;
pub use wrap::{Wrap, Wraps};

use crate::math::{Color, Vec2};
use std::sync::Arc;

crate::closed_set! {
    /// What every pattern gives, as a function of texture coordinates. Implemented by each
    /// pattern in its file; [`Pattern`] forwards to them.
    pub trait Paint {
        /// The linear colour at `uv` (an image's outside `[0, 1]` as `wraps` says).
        fn at(&self, uv: Vec2, wraps: Wraps) -> Color;

        /// The colour averaged over the footprint at `uv` whose axes are `dx` and `dy`.
        fn filtered(&self, uv: Vec2, dx: Vec2, dy: Vec2, wraps: Wraps) -> Color;

        /// What it gives on average over the pattern, for an emitting texture's power.
        fn mean(&self) -> Color;

        /// Bytes of decoded image data it holds (0 for procedural patterns).
        fn bytes(&self) -> usize {
            0
        }

        /// The colour, where it is the same everywhere (so no coordinates are needed).
        fn constant(&self) -> Option<Color> {
            None
        }

        /// Whether the pattern is certainly one colour over the box `uv - r` to `uv + r`, so
        /// that any footprint within it filters to the colour at `uv`, to the bit (false
        /// where it cannot say).
        fn flat_over(&self, uv: Vec2, r: Vec2) -> bool {
            false
        }
    }

    /// What a texture shows: one of a closed set, one file per pattern.
    #[derive(Clone, Debug)]
    pub enum Pattern {
        /// One colour everywhere.
        Solid(Color),
        /// An image, bilinearly filtered; outside `[0, 1]` as its texture's `wrap` says.
        Image(Arc<ImageData>),
        /// Squares of two colours.
        Checker(Checker),
        /// Bands of two colours across `u`.
        Stripes(Stripes),
    }
}

/// The half-extent of a footprint along `u` and `v`, for the closed-form filters.
#[inline]
fn footprint_radius(dx: Vec2, dy: Vec2) -> Vec2 {
    Vec2::new(dx.x.abs().max(dy.x.abs()), dx.y.abs().max(dy.y.abs()))
}

/// A mix of two colours: `w` is +1 for the first, -1 for the second (each exactly, as the
/// pattern read at a point gives it; and exactly the colour where both are the same).
#[inline]
fn mix(first: Color, second: Color, w: f32) -> Color {
    if w >= 1.0 {
        first
    } else if w <= -1.0 {
        second
    } else {
        second + (first - second) * (0.5 + 0.5 * w)
    }
}

/// A pattern and the mapping that places it on a surface.
#[derive(Clone, Debug)]
pub struct Texture {
    /// What it shows.
    pub pattern: Pattern,
    /// Where it goes.
    pub mapping: Mapping,
    /// An image's wrap modes outside `[0, 1]` (a spherical mapping clamps v at the poles
    /// whatever this says).
    pub wrap: Wraps,
}

impl Texture {
    /// A single colour (needs no coordinates).
    pub fn solid(c: Color) -> Self {
        Texture {
            pattern: Pattern::Solid(c),
            mapping: Mapping::Uv,
            wrap: Wraps::REPEAT,
        }
    }

    /// Bytes of decoded image data it holds (0 for procedural textures).
    pub fn bytes(&self) -> usize {
        self.pattern.bytes()
    }

    /// What the texture gives on average over its pattern (an image's mean texel, the mean
    /// of a checker's or stripes' two colours, whose cells are equal), for an emitting
    /// texture's power.
    pub fn mean(&self) -> Color {
        self.pattern.mean()
    }

    /// The linear colour at a surface point, averaged over its footprint where it has one:
    /// images through their MIP pyramid, checker and stripes in closed form under a tent
    /// filter one footprint wide (see docs/scene-format.md, "Texture filtering").
    #[inline]
    pub fn eval(&self, p: &TexturePoint) -> Color {
        if let Some(c) = self.pattern.constant() {
            return c;
        }
        if p.area().is_some() {
            let (uv, dx, dy) = self.mapping.uv_footprint(p);
            return self.pattern.filtered(uv, dx, dy, self.wraps());
        }
        self.pattern.at(self.mapping.uv(p), self.wraps())
    }

    /// Whether the texture is certainly one colour over every footprint at `p` that reaches
    /// no further than `reach` from it (object-space units): then reading it at the point
    /// gives what filtering gives, to the bit. Planar mappings of checkers and stripes can
    /// say (their coordinates change by at most `reach` times an axis's length); others
    /// cannot (false).
    #[inline]
    pub fn flat_within(&self, p: &TexturePoint, reach: f32) -> bool {
        match self.mapping {
            Mapping::Planar { u_axis, v_axis, .. } => {
                let r = Vec2::new(u_axis.length(), v_axis.length()) * reach;
                self.pattern.flat_over(self.mapping.uv(p), r)
            }
            _ => false,
        }
    }

    /// The image's wrap modes as read through its mapping (a spherical one clamps v).
    #[inline]
    fn wraps(&self) -> Wraps {
        match self.mapping.clamps_v() {
            true => Wraps {
                v: Wrap::Clamp,
                ..self.wrap
            },
            false => self.wrap,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_cells_are_equal_across_zero() {
        // Walk along u in small steps and measure the width of each run of equal parity:
        // with floor every run is exactly `size` wide, including the ones touching 0.
        let size = 3.0;
        let step = 0.01;
        let mut runs = vec![];
        let mut last = checker_parity(Vec2::new(-12.0 + step / 2.0, 0.5), size);
        let mut start = -12.0f32;
        let mut x = -12.0 + step / 2.0;
        while x < 12.0 {
            let p = checker_parity(Vec2::new(x, 0.5), size);
            if p != last {
                runs.push((x - step / 2.0) - start);
                start = x - step / 2.0;
                last = p;
            }
            x += step;
        }
        assert_eq!(runs.len(), 7, "{runs:?}");
        for w in &runs[1..] {
            assert!((w - size).abs() < 0.02, "{runs:?}");
        }
        // The report's truncating version makes the cell at 0 twice as wide.
        let report = |x: f32| ((x / size) as i32 % 2).abs();
        assert_eq!(report(-2.9), report(2.9));
        assert_ne!(
            checker_parity(Vec2::new(-2.9, 0.5), size),
            checker_parity(Vec2::new(2.9, 0.5), size)
        );
    }

    #[test]
    fn checker_parity_of_far_away_uvs_does_not_overflow() {
        // The same saturating cast as the `image` fuzz target found in sample_bilinear: a
        // planar mapping on a distant hit gives uvs past i64, and the sum overflowed.
        for uv in [
            Vec2::new(1e30, 1e30),
            Vec2::new(f32::MAX, 2.0),
            Vec2::new(-1e30, -1e30),
            Vec2::new(f32::MIN, f32::MAX),
        ] {
            assert!(checker_parity(uv, 0.5) <= 1, "{uv}");
        }
    }

    #[test]
    fn seed_checker_rule() {
        // The cell is white when floor((x - 10) / 3) + floor((z + 20) / 3) is even.
        let white = Color::ONE;
        let t = Texture {
            pattern: Pattern::Checker(Checker {
                even: white,
                odd: Color::ZERO,
                size: 3.0,
            }),
            mapping: Mapping::planar(
                crate::math::Vec3A::new(10.0, -15.0, -20.0),
                crate::math::Vec3A::X,
                crate::math::Vec3A::Z,
            ),
            wrap: Wraps::REPEAT,
        };
        for (x, z) in [
            (0.0f32, -50.0f32),
            (-24.5, -41.0),
            (11.0, -19.0),
            (9.5, -100.0),
        ] {
            let expected = ((x - 10.0) / 3.0).floor() + ((z + 20.0) / 3.0).floor();
            let c = t.eval(&TexturePoint::at(crate::math::Vec3A::new(x, -15.0, z)));
            assert_eq!(c == white, expected.rem_euclid(2.0) == 0.0, "at {x}, {z}");
        }
    }

    #[test]
    fn stripes_alternate_by_width() {
        let t = Texture {
            pattern: Pattern::Stripes(Stripes {
                a: Color::ONE,
                b: Color::ZERO,
                width: 0.5,
            }),
            mapping: Mapping::Uv,
            wrap: Wraps::REPEAT,
        };
        let at = |u: f32| t.eval(&TexturePoint::with_uv(Vec2::new(u, 0.0)));
        assert_eq!(at(0.25), Color::ONE);
        assert_eq!(at(0.75), Color::ZERO);
        assert_eq!(at(-0.25), Color::ZERO);
        assert_eq!(at(1.1), Color::ONE);
    }

    #[test]
    fn a_footprint_averages_checker_and_stripes() {
        let checker = Texture {
            pattern: Pattern::Checker(Checker {
                even: Color::ONE,
                odd: Color::ZERO,
                size: 0.5,
            }),
            mapping: Mapping::Uv,
            wrap: Wraps::REPEAT,
        };
        let stripes = Texture {
            pattern: Pattern::Stripes(Stripes {
                a: Color::new(1.0, 0.0, 0.0),
                b: Color::new(0.0, 0.0, 1.0),
                width: 0.5,
            }),
            mapping: Mapping::Uv,
            wrap: Wraps::REPEAT,
        };
        let at = |t: &Texture, uv: Vec2, d: f32| {
            let f = Footprint {
                dpdx: crate::math::Vec3A::X,
                dpdy: crate::math::Vec3A::Y,
                duvdx: Vec2::new(d, 0.0),
                duvdy: Vec2::new(0.0, d),
                ..Default::default()
            };
            t.eval(&TexturePoint {
                footprint: Some(&f),
                ..TexturePoint::with_uv(uv)
            })
        };
        // Far smaller than a cell, inside one: the cell itself.
        assert_eq!(at(&checker, Vec2::new(0.25, 0.25), 0.01), Color::ONE);
        assert_eq!(at(&checker, Vec2::new(0.75, 0.25), 0.01), Color::ZERO);
        // Many cells wide: the mean of the two colours.
        let grey = at(&checker, Vec2::new(0.3, 0.1), 20.0);
        assert!(
            (grey - Color::splat(0.5)).abs().max_element() < 1e-3,
            "{grey}"
        );
        let purple = at(&stripes, Vec2::new(0.3, 0.1), 20.0);
        assert!((purple - Color::new(0.5, 0.0, 0.5)).abs().max_element() < 1e-3);
        // On an edge between cells, half of each.
        let edge = at(&checker, Vec2::new(0.5, 0.25), 0.1);
        assert!(
            (edge - Color::splat(0.5)).abs().max_element() < 1e-5,
            "{edge}"
        );
    }
}
