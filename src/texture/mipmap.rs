//! MIP maps: an image texture's pyramid of ever smaller copies (Williams 1983), and the
//! trilinear lookup that reads the level whose texels are as large as a pixel's footprint,
//! so a far or slanted image is its average there instead of a scatter of single texels.

use super::{ImageData, Wraps};
use crate::math::{Color, Vec2};

/// The levels below `img`, finest first: each half the size of the one above, rounded up,
/// its texels the mean of the (up to) four they cover, averaged in linear light; the last
/// is 1 x 1. An odd size's last column (row) stands alone, weighed as the pairs.
/// Rows of a level are made on every core (a scene's load waits for the pyramid).
pub fn pyramid(img: &ImageData) -> Vec<ImageData> {
    let mut levels: Vec<ImageData> = Vec::new();
    let (mut w, mut h) = (img.width(), img.height());
    while w > 1 || h > 1 {
        let above = levels.last().unwrap_or(img);
        let (nw, nh) = (w.div_ceil(2), h.div_ceil(2));
        let level = ImageData::level_like(img, nw, nh, |x, y| {
            let (x0, y0) = (2 * x, 2 * y);
            let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
            let sum = above.texel(x0, y0)
                + above.texel(x1, y0)
                + above.texel(x0, y1)
                + above.texel(x1, y1);
            sum * 0.25
        });
        levels.push(level);
        (w, h) = (nw, nh);
    }
    levels
}

/// The image read over a footprint: `duvdx` and `duvdy` are how the texture coordinates
/// change to the next pixel right and down. The level is the one whose texels span the
/// footprint's larger side, twice over (pbrt's width); between levels the two nearest are
/// blended, each bilinearly (trilinear filtering). A footprint under a texel reads the image
/// itself, bilinearly, as a point does.
pub fn sample(img: &ImageData, uv: Vec2, duvdx: Vec2, duvdy: Vec2, wrap: Wraps) -> Color {
    let (w, h) = (img.width() as f32, img.height() as f32);
    let width = 2.0
        * (duvdx.x.abs() * w)
            .max(duvdy.x.abs() * w)
            .max(duvdx.y.abs() * h)
            .max(duvdy.y.abs() * h);
    let coarser = img.coarser();
    // Also where the width is NaN (a footprint that lost its way): the plain lookup.
    if width.is_nan() || width <= 1.0 || coarser.is_empty() {
        return img.sample_bilinear(uv, wrap);
    }
    let lod = width.log2().min(coarser.len() as f32);
    let k = lod.floor() as usize;
    let level = |i: usize| if i == 0 { img } else { &coarser[i - 1] };
    let fine = level(k).sample_bilinear(uv, wrap);
    let f = lod - k as f32;
    if f == 0.0 || k == coarser.len() {
        return fine;
    }
    fine.lerp(level(k + 1).sample_bilinear(uv, wrap), f)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::ColorSpace;

    /// A `w` x `h` checker of single texels, black and white, as an 8-bit sRGB image.
    fn texel_checker(w: u32, h: u32) -> ImageData {
        let img = ::image::RgbImage::from_fn(w, h, |x, y| {
            ::image::Rgb(if (x + y) % 2 == 0 { [255; 3] } else { [0; 3] })
        });
        ImageData::from_owned(::image::DynamicImage::ImageRgb8(img), ColorSpace::Srgb)
            .with_mipmaps()
    }

    #[test]
    fn levels_halve_to_one_texel_and_keep_the_mean() {
        let img = texel_checker(37, 10);
        let sizes: Vec<(u32, u32)> = img
            .coarser()
            .iter()
            .map(|l| (l.width(), l.height()))
            .collect();
        assert_eq!(sizes, [(19, 5), (10, 3), (5, 2), (3, 1), (2, 1), (1, 1)]);
        // Every level of an even checker is grey, a linear half: the mean of light, not of
        // sRGB bytes (which would read 0.5 encoded, 0.21 linear). The sRGB step near a
        // linear half is under 0.003.
        let first = &img.coarser()[0];
        for (x, y) in [(0, 0), (5, 3), (17, 4)] {
            let c = first.texel(x, y);
            assert!((c - Color::splat(0.5)).abs().max_element() < 3e-3, "{c}");
        }
        let top = img.coarser().last().unwrap().texel(0, 0);
        assert!((top.x - 0.5).abs() < 0.05, "{top}");
    }

    #[test]
    fn the_footprint_picks_the_level() {
        let img = texel_checker(64, 64);
        let uv = Vec2::new(0.3, 0.6);
        // Under a texel: the image itself.
        let small = Vec2::new(0.2 / 64.0, 0.0);
        assert_eq!(
            sample(&img, uv, small, small.perp(), Wraps::REPEAT),
            img.sample_bilinear(uv, Wraps::REPEAT)
        );
        // Eight texels wide: the checker has averaged out to grey.
        let big = Vec2::new(8.0 / 64.0, 0.0);
        let c = sample(&img, uv, big, big.perp(), Wraps::REPEAT);
        assert!((c - Color::splat(0.5)).abs().max_element() < 3e-3, "{c}");
        // The longer side decides, whichever pixel direction it lies along.
        let c = sample(
            &img,
            uv,
            Vec2::ZERO,
            Vec2::new(0.0, 8.0 / 64.0),
            Wraps::REPEAT,
        );
        assert!((c - Color::splat(0.5)).abs().max_element() < 3e-3, "{c}");
        // A footprint past the whole image reads the last level.
        let huge = Vec2::new(100.0, 0.0);
        let top = img.coarser().last().unwrap().texel(0, 0);
        assert_eq!(sample(&img, uv, huge, huge, Wraps::REPEAT), top);
        // NaN reads the point.
        let nan = Vec2::splat(f32::NAN);
        assert_eq!(
            sample(&img, uv, nan, nan, Wraps::REPEAT),
            img.sample_bilinear(uv, Wraps::REPEAT)
        );
    }

    #[test]
    fn between_levels_the_two_nearest_blend() {
        let img = texel_checker(64, 64);
        let uv = Vec2::new(0.25, 0.25);
        // A width of 2^1.5 texels: halfway between levels 1 and 2.
        let d = Vec2::new(2f32.powf(1.5) / 2.0 / 64.0, 0.0);
        let want = img.coarser()[0]
            .sample_bilinear(uv, Wraps::REPEAT)
            .lerp(img.coarser()[1].sample_bilinear(uv, Wraps::REPEAT), 0.5);
        let got = sample(&img, uv, d, Vec2::ZERO, Wraps::REPEAT);
        assert!((got - want).abs().max_element() < 1e-5, "{got} {want}");
    }
}
