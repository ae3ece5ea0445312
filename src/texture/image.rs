//! Image textures: pixels decoded once (8-bit ones kept as bytes read through a table of
//! linear values), bilinear lookups through the texture's wrap, and the loading limits.

use super::Wraps;
use crate::math::{Color, Vec2};
use std::cell::Cell;
use std::path::Path;

/// How the numbers in an image file relate to light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ColorSpace {
    /// sRGB-encoded (photographs, painted textures): decoded to linear on load.
    Srgb,
    /// Already linear (data such as normal maps): used as stored.
    Linear,
}

/// A decoded image, read as linear RGB, row 0 at the top.
#[derive(Clone, Debug)]
pub struct ImageData {
    width: u32,
    height: u32,
    texels: Texels,
    /// The MIP pyramid below this image: each level half the size of the one above (rounded
    /// up), to 1 x 1 (empty for the levels themselves).
    coarser: Vec<ImageData>,
}

/// An image's texels as stored.
#[derive(Clone, Debug)]
enum Texels {
    /// 8-bit files (JPEG, most PNGs) keep their bytes, `R, G, B` per texel, read through a
    /// 256-entry table of linear values: a quarter of the memory of floats, and no pass
    /// over a fresh buffer at load, which a scene with a large image would wait on before
    /// its first pixel.
    Bytes {
        rgb: Vec<u8>,
        linear: Box<[f32; 256]>,
    },
    /// Deeper files (16-bit PNG, OpenEXR) as linear floats.
    Floats(Vec<[f32; 3]>),
}

/// Why an image texture could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum ImageLoadError {
    /// The file could not be opened or read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The image has more texels than allowed.
    #[error(
        "{path} is {width} x {height}, more than the {max_pixels} texels an image texture may have (raise the limit with --max-texture-pixels)"
    )]
    TooLarge {
        /// The file.
        path: String,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
        /// The limit.
        max_pixels: u64,
    },
    /// The file could be read but not decoded.
    #[error("cannot decode image {path}: {source}")]
    Decode {
        /// The file.
        path: String,
        /// The cause.
        source: ::image::ImageError,
    },
}

impl ImageData {
    /// Loads a PNG, JPEG, BMP or OpenEXR file (the format is read from its content).
    pub fn load(path: &Path, space: ColorSpace) -> Result<Self, ImageLoadError> {
        Self::load_limited(path, space, 1 << 28)
    }

    /// As [`ImageData::load`], refusing images of more than `max_pixels` texels before
    /// decoding them (the header says the size), so a huge or corrupt file cannot exhaust
    /// memory.
    pub fn load_limited(
        path: &Path,
        space: ColorSpace,
        max_pixels: u64,
    ) -> Result<Self, ImageLoadError> {
        let shown = path.display().to_string();
        let bytes = crate::read_regular_file(path).map_err(|source| ImageLoadError::Io {
            path: shown.clone(),
            source,
        })?;
        let decode_error = |source| ImageLoadError::Decode {
            path: shown.clone(),
            source,
        };
        // The size from the header first (a header, too, can be crafted to upset a decoder),
        // then the pixels, each within the decoder guard.
        let (w, h) = guarded(|| {
            ::image::ImageReader::new(std::io::Cursor::new(&bytes))
                .with_guessed_format()
                .map_err(::image::ImageError::IoError)?
                .into_dimensions()
        })
        .map_err(decode_error)?;
        if w as u64 * h as u64 > max_pixels {
            return Err(ImageLoadError::TooLarge {
                path: shown.clone(),
                width: w,
                height: h,
                max_pixels,
            });
        }
        // Decoders allocate by the header, so the header's size is all the limit needs; let
        // them take what that size requires (the image crate's own default is 512 MiB).
        let mut limits = ::image::Limits::default();
        limits.max_alloc = Some(max_pixels.saturating_mul(16).max(1 << 29));
        let img = decode(&bytes, limits).map_err(decode_error)?;
        Ok(Self::from_owned(img, space))
    }

    /// From a decoded image.
    pub fn from_dynamic(img: &::image::DynamicImage, space: ColorSpace) -> Self {
        Self::from_owned(img.clone(), space)
    }

    /// From a decoded image, reusing its buffer where it already holds 8-bit RGB.
    pub fn from_owned(img: ::image::DynamicImage, space: ColorSpace) -> Self {
        let (width, height) = (img.width(), img.height());
        let texels = if img.color().bytes_per_pixel() / img.color().channel_count() == 1 {
            // 8-bit: a 256-entry table decodes sRGB exactly and fast.
            let linear = Box::new(std::array::from_fn(|i| {
                let x = i as f32 / 255.0;
                match space {
                    ColorSpace::Srgb => srgb_to_linear(x),
                    ColorSpace::Linear => x,
                }
            }));
            Texels::Bytes {
                rgb: img.into_rgb8().into_raw(),
                linear,
            }
        } else {
            // Floating-point images (EXR) hold linear light whatever the setting says.
            let float = matches!(
                img.color(),
                ::image::ColorType::Rgb32F | ::image::ColorType::Rgba32F
            );
            // RGB floats already: their buffer, reinterpreted in place (a large map's copy
            // was a fresh buffer the size of the image, and the kernel's work of handing
            // it out cost more than the copy).
            let floats: Vec<f32> = img.into_rgb32f().into_raw();
            let mut texels: Vec<[f32; 3]> = bytemuck::allocation::try_cast_vec(floats)
                .unwrap_or_else(|(_, floats)| {
                    floats.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect()
                });
            if space == ColorSpace::Srgb && !float {
                for p in &mut texels {
                    *p = p.map(srgb_to_linear);
                }
            }
            Texels::Floats(texels)
        };
        ImageData {
            width,
            height,
            texels,
            coarser: Vec::new(),
        }
    }

    /// The image with its MIP pyramid, for a texture read through a footprint (an image
    /// without one is read at its full size whatever the footprint).
    pub fn with_mipmaps(mut self) -> Self {
        self.coarser = super::mipmap::pyramid(&self);
        self
    }

    /// An image of `width` x `height` linear texels, `texel(x, y)` each (column `x`, row `y`
    /// from the top), stored as `like` stores its own: as bytes through its table, to the
    /// nearest entry, or as floats. Made row by row on every core, straight into the
    /// storage (a level of floats first would be a fresh buffer four times the bytes').
    pub(super) fn level_like(
        like: &ImageData,
        width: u32,
        height: u32,
        texel: impl Fn(u32, u32) -> Color + Sync,
    ) -> Self {
        use rayon::prelude::*;
        let (w, n) = (width as usize, width as usize * height as usize);
        let texels = match &like.texels {
            Texels::Bytes { linear, .. } => {
                let nearest = NearestByte::new(linear);
                let mut rgb = vec![0u8; n * 3];
                rgb.par_chunks_mut(3 * w.max(1))
                    .enumerate()
                    .for_each(|(y, row)| {
                        for (x, o) in row.chunks_exact_mut(3).enumerate() {
                            let c = texel(x as u32, y as u32);
                            o.copy_from_slice(&[nearest.of(c.x), nearest.of(c.y), nearest.of(c.z)]);
                        }
                    });
                Texels::Bytes {
                    rgb,
                    linear: linear.clone(),
                }
            }
            Texels::Floats(_) => {
                let mut floats = vec![[0.0f32; 3]; n];
                floats
                    .par_chunks_mut(w.max(1))
                    .enumerate()
                    .for_each(|(y, row)| {
                        for (x, o) in row.iter_mut().enumerate() {
                            *o = texel(x as u32, y as u32).to_array();
                        }
                    });
                Texels::Floats(floats)
            }
        };
        ImageData {
            width,
            height,
            texels,
            coarser: Vec::new(),
        }
    }

    /// The MIP levels below the image, finest first.
    pub(super) fn coarser(&self) -> &[ImageData] {
        &self.coarser
    }

    /// Bytes the texels take.
    pub fn bytes(&self) -> usize {
        let own = match &self.texels {
            Texels::Bytes { rgb, .. } => rgb.len() + 256 * 4,
            Texels::Floats(t) => t.len() * 12,
        };
        own + self.coarser.iter().map(ImageData::bytes).sum::<usize>()
    }

    /// The mean of its texels (linear), for what a texture gives on the whole: an emitting
    /// texture's power. One pass over the image.
    pub fn mean(&self) -> Color {
        let n = (self.width as f64 * self.height as f64).max(1.0);
        // In f64: a large image's sum in f32 would lose the last texels' share.
        let mut sum = [0.0f64; 3];
        match &self.texels {
            Texels::Bytes { rgb, linear } => {
                for t in rgb.chunks_exact(3) {
                    for (s, &b) in sum.iter_mut().zip(t) {
                        *s += linear[b as usize] as f64;
                    }
                }
            }
            Texels::Floats(texels) => {
                for t in texels {
                    for (s, &v) in sum.iter_mut().zip(t) {
                        *s += v as f64;
                    }
                }
            }
        }
        Color::new(
            (sum[0] / n) as f32,
            (sum[1] / n) as f32,
            (sum[2] / n) as f32,
        )
    }

    /// The texel at column `x`, row `y` (from the top), linear; black outside the image.
    pub fn texel(&self, x: u32, y: u32) -> Color {
        if x >= self.width || y >= self.height {
            return Color::ZERO;
        }
        let i = y as usize * self.width as usize + x as usize;
        match &self.texels {
            Texels::Bytes { rgb, linear } => Color::new(
                linear[rgb[3 * i] as usize],
                linear[rgb[3 * i + 1] as usize],
                linear[rgb[3 * i + 2] as usize],
            ),
            Texels::Floats(t) => Color::from_array(t[i]),
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Bilinear lookup at texture coordinates (texel centres at `(i + 0.5) / size`),
    /// outside `[0, 1]` as `wrap` says on each axis.
    /// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
    #[inline(always)]
    pub fn sample_bilinear(&self, uv: Vec2, wrap: Wraps) -> Color {
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        // Checked after scaling: a finite uv near f32::MAX becomes infinite here, and the
        // fractions below would be NaN.
        // An image with no texels (which no file should give, but the API can) is black.
        if !(x.is_finite() && y.is_finite()) || self.width == 0 || self.height == 0 {
            return Color::ZERO;
        }
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        // A far-away uv (a planar mapping on a distant hit) saturates the cast to i64::MAX;
        // its neighbour is then found by wrapping, never by overflowing. At that distance
        // f32 has no fraction left anyway.
        let (x0, y0) = (x0 as i64, y0 as i64);
        let (w, h) = (self.width as i64, self.height as i64);
        // The four texels' columns and rows.
        let xa = wrap.u.index(x0, w);
        let xb = wrap.u.index(x0.saturating_add(1), w);
        let ya = wrap.v.index(y0, h);
        let yb = wrap.v.index(y0.saturating_add(1), h);
        let at = |x: i64, y: i64| (y * w + x) as usize;
        // One match per lookup, not per texel.
        match &self.texels {
            Texels::Bytes { rgb, linear } => {
                let texel = |x, y| {
                    let i = 3 * at(x, y);
                    Color::new(
                        linear[rgb[i] as usize],
                        linear[rgb[i + 1] as usize],
                        linear[rgb[i + 2] as usize],
                    )
                };
                bilinear(texel, [xa, xb], [ya, yb], fx, fy)
            }
            Texels::Floats(t) => bilinear(
                |x, y| Color::from_array(t[at(x, y)]),
                [xa, xb],
                [ya, yb],
                fx,
                fy,
            ),
        }
    }
}

/// Blends the texels at columns `xs` and rows `ys`, `fx` of the way from the first column
/// to the second and `fy` from the first row to the second.
#[inline(always)]
fn bilinear(
    texel: impl Fn(i64, i64) -> Color,
    xs: [i64; 2],
    ys: [i64; 2],
    fx: f32,
    fy: f32,
) -> Color {
    let top = texel(xs[0], ys[0]).lerp(texel(xs[1], ys[0]), fx);
    let bottom = texel(xs[0], ys[1]).lerp(texel(xs[1], ys[1]), fx);
    top.lerp(bottom, fy)
}

/// The even steps of `[0, 1]` at which [`NearestByte`] knows the nearest byte.
const STEPS: usize = 4096;

/// The byte whose entry in a rising table of 256 linear values is nearest a value (the lower
/// on a tie), from a table instead of a search: the nearest byte at each of [`STEPS`] even
/// steps of `[0, 1]`, and one comparison to say whether the value has passed the boundary
/// to the next byte. A step holds at most one boundary: sRGB's entries, the closest of any
/// table, are at least 1 / 3300 apart, and so are the boundaries halfway between them.
struct NearestByte<'a> {
    linear: &'a [f32; 256],
    /// For each step `k`, the nearest byte to `k / STEPS`.
    byte: Box<[u8; STEPS + 1]>,
}

impl<'a> NearestByte<'a> {
    fn new(linear: &'a [f32; 256]) -> Self {
        let mut byte = Box::new([0u8; STEPS + 1]);
        for (k, b) in byte.iter_mut().enumerate() {
            *b = nearest_by_search(linear, k as f32 / STEPS as f32);
        }
        NearestByte { linear, byte }
    }

    /// The nearest entry's byte, as [`nearest_by_search`] finds it: the nearest byte only
    /// grows with the value, so a value in step `k` has the step's byte or the next, and
    /// the next where it is nearer that byte's entry (the search's own comparison).
    #[inline]
    fn of(&self, x: f32) -> u8 {
        let t = self.linear;
        // Multiplying by a power of two is exact: `k / STEPS <= x`. NaN goes to step 0.
        let k = (x * STEPS as f32).clamp(0.0, STEPS as f32) as usize;
        let b = self.byte[k];
        let i = b as usize;
        // Without branches: which way the comparison goes is as good as random from texel to
        // texel, and its mispredictions made a MIP level's bytes take 10 ns each.
        let next = t[(i + 1).min(255)];
        b + ((i < 255) & ((x - t[i]) > (next - x))) as u8
    }
}

/// The byte whose entry in `linear` is nearest `x`, the lower on a tie:
/// `linear.partition_point(|&v| v < x)` (clamped to 255) and the entry before it, whichever
/// is nearer.
fn nearest_by_search(linear: &[f32; 256], x: f32) -> u8 {
    let i = linear.partition_point(|&v| v < x).min(255);
    if i > 0 && (x - linear[i - 1]) <= (linear[i] - x) {
        (i - 1) as u8
    } else {
        i as u8
    }
}

thread_local! {
    static IN_DECODER: Cell<bool> = const { Cell::new(false) };
}

/// Decodes an image file held in memory (PNG, JPEG, BMP or OpenEXR, told apart by its
/// content) within `limits` (`Limits::default()` is what `image::load_from_memory` uses).
///
/// A decoder that panics on a corrupt file gives an error, not a crash: zune-jpeg, the
/// image crate's JPEG decoder, asserts in its upsampler on some crafted files (found by the
/// `image` fuzz target). While it runs, [`in_guarded_decoder`] is true on this thread, so a
/// panic hook can keep quiet about a panic that is about to become this error.
pub fn decode(
    bytes: &[u8],
    limits: ::image::Limits,
) -> Result<::image::DynamicImage, ::image::ImageError> {
    let format = ::image::guess_format(bytes)?;
    guarded(move || {
        let mut reader = ::image::ImageReader::with_format(std::io::Cursor::new(bytes), format);
        reader.limits(limits);
        reader.decode()
    })
}

/// Runs a decoder call with panics turned into a decoding error (see [`decode`]).
fn guarded<T>(
    f: impl FnOnce() -> Result<T, ::image::ImageError> + std::panic::UnwindSafe,
) -> Result<T, ::image::ImageError> {
    let was = IN_DECODER.replace(true);
    let result = std::panic::catch_unwind(f);
    IN_DECODER.set(was);
    result.unwrap_or_else(|_| {
        Err(::image::ImageError::Decoding(
            ::image::error::DecodingError::new(
                ::image::error::ImageFormatHint::Unknown,
                "the decoder failed on this file (it is corrupt)",
            ),
        ))
    })
}

/// Whether this thread is inside [`decode`], where a panic is caught and becomes an error.
pub fn in_guarded_decoder() -> bool {
    IN_DECODER.get()
}

/// The sRGB transfer function, inverted: encoded value to linear light.
pub fn srgb_to_linear(x: f32) -> f32 {
    if x <= 0.04045 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::Wrap;

    /// Spherical mappings' wraps: around in u, clamped at the poles in v.
    const CLAMP_V: Wraps = Wraps {
        u: Wrap::Repeat,
        v: Wrap::Clamp,
    };

    fn two_by_one(space: ColorSpace) -> ImageData {
        let mut img = ::image::RgbImage::new(2, 1);
        img.put_pixel(0, 0, ::image::Rgb([0, 0, 0]));
        img.put_pixel(1, 0, ::image::Rgb([255, 128, 255]));
        ImageData::from_dynamic(&::image::DynamicImage::ImageRgb8(img), space)
    }

    /// The guessed nearest byte is the binary search's, for sRGB and linear tables, at
    /// every entry, between entries, on ties, beyond both ends and at NaN.
    #[test]
    fn the_nearest_byte_is_the_binary_searchs() {
        let srgb: [f32; 256] = std::array::from_fn(|i| srgb_to_linear(i as f32 / 255.0));
        let linear: [f32; 256] = std::array::from_fn(|i| i as f32 / 255.0);
        let mut checked = 0;
        for table in [&srgb, &linear] {
            let slow = |x: f32| nearest_by_search(table, x);
            let fast = NearestByte::new(table);
            let mut values = vec![-1.0f32, 0.0, 1.0, 2.0, f32::NAN, f32::INFINITY];
            for i in 0..256 {
                values.push(table[i]);
                if i < 255 {
                    values.push((table[i] + table[i + 1]) / 2.0);
                    values.push(table[i] + (table[i + 1] - table[i]) * 0.3);
                }
            }
            values.extend((0..=100_000).map(|k| k as f32 / 100_000.0));
            // Each step's start and the floats either side of it.
            for k in 0..=STEPS {
                let x = k as f32 / STEPS as f32;
                values.extend([x.next_down(), x, x.next_up()]);
            }
            for x in values {
                assert_eq!(fast.of(x), slow(x), "x = {x}");
                checked += 1;
            }
        }
        assert_eq!(checked, 2 * (6 + 256 + 2 * 255 + 100_001 + 3 * (STEPS + 1)));
    }

    /// Deep images keep their values: RGB floats (their buffer taken over), RGBA floats
    /// (alpha dropped), and 16-bit RGB, linear or decoded from sRGB; every texel checked.
    #[test]
    fn float_and_16_bit_images_keep_their_values() {
        use ::image::{DynamicImage, ImageBuffer, Rgb, Rgba};
        let (w, h) = (5u32, 3u32);
        let v = |x: u32, y: u32, k: u32| (x * 7 + y * 3 + k) as f32 / 40.0;
        let rgb = DynamicImage::ImageRgb32F(ImageBuffer::from_fn(w, h, |x, y| {
            Rgb([v(x, y, 0), v(x, y, 1), v(x, y, 2)])
        }));
        let rgba = DynamicImage::ImageRgba32F(ImageBuffer::from_fn(w, h, |x, y| {
            Rgba([v(x, y, 0), v(x, y, 1), v(x, y, 2), 0.5])
        }));
        let deep = DynamicImage::ImageRgb16(ImageBuffer::from_fn(w, h, |x, y| {
            Rgb([0, 1, 2].map(|k| (v(x, y, k) * 65535.0 / 2.0) as u16))
        }));
        let mut checked = 0;
        for (img, space) in [
            (&rgb, ColorSpace::Srgb),
            (&rgba, ColorSpace::Linear),
            (&deep, ColorSpace::Linear),
            (&deep, ColorSpace::Srgb),
        ] {
            let data = ImageData::from_owned(img.clone(), space);
            let want = img.to_rgb32f();
            for y in 0..h {
                for x in 0..w {
                    let p = want.get_pixel(x, y).0;
                    let p = match (img, space) {
                        (DynamicImage::ImageRgb16(_), ColorSpace::Srgb) => p.map(srgb_to_linear),
                        _ => p,
                    };
                    assert_eq!(data.texel(x, y).to_array(), p, "({x}, {y}) of {space:?}");
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 4 * 15);
    }

    #[test]
    fn srgb_is_decoded_to_linear() {
        let img = two_by_one(ColorSpace::Srgb);
        let c = img.sample_bilinear(Vec2::new(0.75, 0.5), Wraps::REPEAT);
        assert!((c.x - 1.0).abs() < 1e-6);
        assert!((c.y - 0.2158605).abs() < 1e-4, "{}", c.y); // sRGB 128 is 21.6 % light
        let lin =
            two_by_one(ColorSpace::Linear).sample_bilinear(Vec2::new(0.75, 0.5), Wraps::REPEAT);
        assert!((lin.y - 128.0 / 255.0).abs() < 1e-6);
    }

    #[test]
    fn png_jpeg_and_bmp_files_load_with_their_colours() {
        let dir = std::env::temp_dir().join(format!("snell-image-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut img = ::image::RgbImage::new(4, 2);
        for (x, y, p) in img.enumerate_pixels_mut() {
            *p = if x < 2 {
                ::image::Rgb([255, 0, 0])
            } else {
                ::image::Rgb([0, 0, 255])
            };
            let _ = y;
        }
        for name in ["t.png", "t.bmp", "t.jpg"] {
            let path = dir.join(name);
            img.save(&path).unwrap();
            let loaded = ImageData::load(&path, ColorSpace::Srgb).unwrap();
            assert_eq!((loaded.width(), loaded.height()), (4, 2), "{name}");
            // Left half red, right half blue (JPEG within its loss).
            let left = loaded.sample_bilinear(Vec2::new(0.125, 0.25), Wraps::REPEAT);
            let right = loaded.sample_bilinear(Vec2::new(0.875, 0.75), Wraps::REPEAT);
            assert!(left.x > 0.8 && left.z < 0.1, "{name}: {left}");
            assert!(right.z > 0.8 && right.x < 0.1, "{name}: {right}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// 8-bit images keep their bytes and read them through a table; deeper ones are
    /// stored as floats. Both give the same colours everywhere, wrapped and clamped alike.
    #[test]
    fn byte_and_float_texels_sample_alike() {
        let (w, h) = (5, 3);
        let mut bytes = ::image::RgbImage::new(w, h);
        let mut floats = ::image::Rgb32FImage::new(w, h);
        for (x, y, p) in bytes.enumerate_pixels_mut() {
            let v = [x * 50 + y, 255 - y * 70, (x * 31 + y * 17) % 256].map(|c| c as u8);
            *p = ::image::Rgb(v);
            floats.put_pixel(x, y, ::image::Rgb(v.map(|c| c as f32 / 255.0)));
        }
        let b = ImageData::from_owned(::image::DynamicImage::ImageRgb8(bytes), ColorSpace::Linear);
        let f = ImageData::from_owned(
            ::image::DynamicImage::ImageRgb32F(floats),
            ColorSpace::Linear,
        );
        assert!(matches!(b.texels, Texels::Bytes { .. }));
        assert!(matches!(f.texels, Texels::Floats(_)));
        assert_eq!(b.bytes(), 5 * 3 * 3 + 1024);
        assert_eq!(f.bytes(), 5 * 3 * 12);
        for i in -40..40 {
            for j in -30..30 {
                let uv = Vec2::new(i as f32 * 0.0731, j as f32 * 0.0917);
                for clamp_v in [Wraps::REPEAT, CLAMP_V, Wraps::both(Wrap::Mirror)] {
                    let (cb, cf) = (
                        b.sample_bilinear(uv, clamp_v),
                        f.sample_bilinear(uv, clamp_v),
                    );
                    assert_eq!(cb, cf, "uv {uv}, {clamp_v:?}");
                }
            }
        }
        // Texel centres give the texels themselves, wrapped across the edges.
        let centre = |x: f32, y: f32| Vec2::new((x + 0.5) / 5.0, (y + 0.5) / 3.0);
        let c = b.sample_bilinear(centre(-1.0, 3.0), Wraps::REPEAT);
        assert_eq!(c, Color::new(200.0, 255.0, 124.0) / 255.0);
        // Clamped rows repeat the edge row instead.
        let c = b.sample_bilinear(centre(4.0, 5.0), CLAMP_V);
        assert_eq!(c, Color::new(202.0, 115.0, 158.0) / 255.0);
    }

    #[test]
    fn an_image_without_texels_samples_black() {
        for img in [
            ::image::DynamicImage::new_rgb8(0, 0),
            ::image::DynamicImage::new_rgb8(0, 4),
            ::image::DynamicImage::new_rgb32f(3, 0),
        ] {
            let tex = ImageData::from_owned(img, ColorSpace::Srgb);
            for clamp_v in [Wraps::REPEAT, CLAMP_V, Wraps::both(Wrap::Mirror)] {
                assert_eq!(
                    tex.sample_bilinear(Vec2::new(0.3, 0.7), clamp_v),
                    Color::ZERO
                );
            }
        }
    }

    #[test]
    fn bilinear_blends_between_texel_centres_and_wraps() {
        let img = two_by_one(ColorSpace::Linear);
        let mid = img.sample_bilinear(Vec2::new(0.5, 0.5), Wraps::REPEAT);
        assert!((mid.x - 0.5).abs() < 1e-6);
        // At u = 0 the left texel blends with the right one wrapped round.
        let edge = img.sample_bilinear(Vec2::new(0.0, 0.5), Wraps::REPEAT);
        assert!((edge.x - 0.5).abs() < 1e-6);
        let wrapped = img.sample_bilinear(Vec2::new(1.25, 0.5), Wraps::REPEAT);
        assert!(wrapped.x.abs() < 1e-6);
    }

    #[test]
    fn a_jpeg_that_panics_the_decoder_is_an_error() {
        // Found by the `image` fuzz target: zune-jpeg's AVX2 upsampler asserts on this file
        // (on machines without AVX2 its scalar twin may decode or refuse it).
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad/jpeg-decoder-panic.jpg");
        match ImageData::load(&path, ColorSpace::Srgb) {
            Err(e) => assert!(e.to_string().contains("cannot decode image"), "{e}"),
            Ok(img) => assert!(img.width() > 0),
        }
        assert!(!in_guarded_decoder());
    }

    #[test]
    fn far_away_uvs_sample_without_overflow() {
        // Found by the `image` fuzz target: uv 1e30 saturated x0 to i64::MAX and x0 + 1
        // overflowed (a panic in debug builds).
        let img = two_by_one(ColorSpace::Linear);
        for uv in [
            Vec2::new(1e30, 0.5),
            Vec2::new(0.5, 1e30),
            Vec2::new(-1e30, -1e30),
            Vec2::new(f32::MAX, f32::MAX),
            Vec2::new(f32::MIN, f32::MAX),
        ] {
            for clamp_v in [Wraps::REPEAT, CLAMP_V, Wraps::both(Wrap::Mirror)] {
                let c = img.sample_bilinear(uv, clamp_v);
                assert!(c.is_finite() && c.min_element() >= 0.0, "{uv}: {c}");
            }
        }
    }
}
