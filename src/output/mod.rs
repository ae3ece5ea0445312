//! Writing images: PNG (sRGB, 8-bit) or EXR (linear, 32-bit float), chosen by the file's
//! extension, always through a temporary file in the same folder that is renamed into place,
//! so a failed render never leaves a broken image or destroys an old one.

pub mod atomic;
pub mod inputs;
pub mod merge;
pub mod tone;

use crate::film::Image;
use atomic::PendingFile;
use std::path::{Path, PathBuf};

/// Image file formats snell writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFormat {
    /// 8-bit sRGB PNG.
    Png,
    /// Linear 32-bit float OpenEXR.
    Exr,
}

/// Why an image could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The extension is not one snell writes.
    #[error("cannot tell the image format of {0}: use a name ending in .png or .exr")]
    UnknownFormat(PathBuf),
    /// Creating, writing or renaming failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The output path.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Encoding failed.
    #[error("cannot encode {path}: {source}")]
    Encode {
        /// The output path.
        path: PathBuf,
        /// The cause.
        source: image::ImageError,
    },
}

impl OutputFormat {
    /// The format named by `path`'s extension.
    pub fn from_path(path: &Path) -> Result<Self, OutputError> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("png") => Ok(OutputFormat::Png),
            Some("exr") => Ok(OutputFormat::Exr),
            _ => Err(OutputError::UnknownFormat(path.to_path_buf())),
        }
    }
}

/// The sRGB transfer function: linear light to encoded value, both in `[0, 1]`.
pub fn linear_to_srgb(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// The image as 8-bit sRGB, clamped, row by row (`R, G, B` per pixel). On every core: a
/// megapixel is three million `powf`, which on one core kept the others idle at the end of
/// every render.
pub fn to_srgb8(img: &Image) -> Vec<u8> {
    to_srgb8_toned(img, &tone::Tone::default())
}

/// [`to_srgb8`] after the exposure and curve of `tone`.
pub fn to_srgb8_toned(img: &Image, tone: &tone::Tone) -> Vec<u8> {
    use rayon::prelude::*;
    let mut out = vec![0u8; img.pixels.len() * 3];
    let scale = tone.scale();
    out.par_chunks_mut(3 * 4096)
        .zip(img.pixels.par_chunks(4096))
        .for_each(|(out, pixels)| {
            for (o, v) in out.iter_mut().zip(pixels.iter().flat_map(|c| c.to_array())) {
                *o = (linear_to_srgb(tone.apply(v, scale)) * 255.0 + 0.5) as u8;
            }
        });
    out
}

/// The image as an 8-bit picture for a screen, after `tone`: a JPEG of `quality` (1 to
/// 100), or where `quality` is `None` a PNG.
pub fn encode_display(
    img: &Image,
    tone: &tone::Tone,
    quality: Option<u8>,
) -> Result<Vec<u8>, image::ImageError> {
    use image::ImageEncoder;
    let rgb = to_srgb8_toned(img, tone);
    let mut bytes = vec![];
    match quality {
        Some(q) => image::codecs::jpeg::JpegEncoder::new_with_quality(&mut bytes, q.clamp(1, 100))
            .write_image(&rgb, img.width, img.height, image::ExtendedColorType::Rgb8)?,
        None => image::codecs::png::PngEncoder::new(&mut bytes).write_image(
            &rgb,
            img.width,
            img.height,
            image::ExtendedColorType::Rgb8,
        )?,
    }
    Ok(bytes)
}

/// Encodes the image in `format` (a PNG as it is, clamped).
pub fn encode(img: &Image, format: OutputFormat, path: &Path) -> Result<Vec<u8>, OutputError> {
    encode_toned(img, format, path, &tone::Tone::default())
}

/// Encodes the image in `format`: a PNG after `tone`'s exposure and curve, an EXR linear as
/// it is (the tone is the viewer's to choose there).
pub fn encode_toned(
    img: &Image,
    format: OutputFormat,
    path: &Path,
    tone: &tone::Tone,
) -> Result<Vec<u8>, OutputError> {
    use image::ImageEncoder;
    let mut bytes = vec![];
    let result = match format {
        OutputFormat::Png => image::codecs::png::PngEncoder::new(&mut bytes).write_image(
            &to_srgb8_toned(img, tone),
            img.width,
            img.height,
            image::ExtendedColorType::Rgb8,
        ),
        // exr's own writer, for the tiles' order (see `ENCODING`).
        OutputFormat::Exr => return encode_exr_layers(img, &[], path),
    };
    result.map_err(|source| OutputError::Encode {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(bytes)
}

/// One layer of a multi-layer EXR: its name and its channels (name, one value per pixel).
pub type ExrLayer<'a> = (&'a str, Vec<(&'a str, Vec<f32>)>);

/// An OpenEXR file with layers: the picture as channels `R G B`, and each extra layer's
/// channels named `LAYER.CHANNEL` (`normal.X`, `depth.Z` ...), the OpenEXR convention for
/// layers within one part, which compositors and viewers list as layers. All 32-bit float,
/// lossless.
pub fn encode_exr_layers(
    img: &Image,
    layers: &[ExrLayer],
    path: &Path,
) -> Result<Vec<u8>, OutputError> {
    use exr::prelude::*;
    let size = (img.width as usize, img.height as usize);
    let channel = |name: &str, values: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(values));
    let mut channels = rgb_channels(img);
    for (layer, list) in layers {
        for (c, values) in list {
            channels.push(channel(&format!("{layer}.{c}"), values.clone()));
        }
    }
    let image = exr::image::Image::from_layer(Layer::new(
        size,
        LayerAttributes::default(),
        ENCODING,
        AnyChannels::sort(SmallVec::from_vec(channels)),
    ));
    let mut bytes = vec![];
    image
        .write()
        .to_buffered(std::io::Cursor::new(&mut bytes))
        .map_err(|e| exr_error(path, e))?;
    Ok(bytes)
}

/// An OpenEXR file of `img`, a region of a `full` (width, height) image whose top left
/// pixel is `at`: the region's pixels in its data window, the whole image's rectangle as its
/// display window, so that viewers and `snell merge` put it in its place. 32-bit float,
/// lossless.
pub fn encode_exr_region(
    img: &Image,
    at: (u32, u32),
    full: (u32, u32),
    meta: &[(&str, String)],
    path: &Path,
) -> Result<Vec<u8>, OutputError> {
    use exr::prelude::*;
    let mut layer = Layer::new(
        (img.width as usize, img.height as usize),
        LayerAttributes::default(),
        ENCODING,
        AnyChannels::sort(SmallVec::from_vec(rgb_channels(img))),
    );
    layer.attributes.layer_position = Vec2(at.0 as i32, at.1 as i32);
    let display = IntegerBounds::new(Vec2(0, 0), Vec2(full.0 as usize, full.1 as usize));
    let mut image = exr::image::Image::new(ImageAttributes::new(display), layer);
    for (key, value) in meta {
        image.attributes.other.insert(
            Text::from(*key),
            AttributeValue::Text(Text::from(value.as_str())),
        );
    }
    let mut bytes = vec![];
    image
        .write()
        .to_buffered(std::io::Cursor::new(&mut bytes))
        .map_err(|e| exr_error(path, e))?;
    Ok(bytes)
}

/// How EXR files are encoded: exr's fast lossless encoding (RLE in tiles of 64 x 64), its
/// tiles in increasing order. Its default order is whatever order the threads that compress
/// the tiles finish in, which made two writes of the same picture differ in their bytes.
const ENCODING: exr::prelude::Encoding = exr::prelude::Encoding {
    line_order: exr::prelude::LineOrder::Increasing,
    ..exr::prelude::Encoding::FAST_LOSSLESS
};

/// The picture's `R`, `G` and `B` channels, 32-bit float.
fn rgb_channels(img: &Image) -> Vec<exr::prelude::AnyChannel<exr::prelude::FlatSamples>> {
    use exr::prelude::*;
    let plane = |k: usize| FlatSamples::F32(img.pixels.iter().map(|c| c[k]).collect());
    vec![
        AnyChannel::new("R", plane(0)),
        AnyChannel::new("G", plane(1)),
        AnyChannel::new("B", plane(2)),
    ]
}

/// An EXR writer's failure, as an encoding error of the file at `path`.
fn exr_error(path: &Path, e: exr::error::Error) -> OutputError {
    OutputError::Encode {
        path: path.to_path_buf(),
        source: image::ImageError::Encoding(image::error::EncodingError::new(
            image::error::ImageFormatHint::Exact(image::ImageFormat::OpenExr),
            e,
        )),
    }
}

/// An image file reserved before rendering: its format checked and its temporary file
/// created up front (see [`atomic::PendingFile`]), so a bad or unwritable destination fails
/// before the work starts. Dropping it without committing leaves any old image alone.
#[derive(Debug)]
pub struct PendingOutput {
    file: PendingFile,
    format: OutputFormat,
}

impl PendingOutput {
    /// Checks the format and the destination, and creates the temporary file.
    pub fn create(path: &Path) -> Result<Self, OutputError> {
        let format = OutputFormat::from_path(path)?;
        let file = PendingFile::create(path).map_err(|source| OutputError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Ok(PendingOutput { file, format })
    }

    /// The format the destination's name asks for.
    pub fn format(&self) -> OutputFormat {
        self.format
    }

    /// The destination.
    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// Writes to [`partial_path`] of the destination instead: an unfinished picture never
    /// replaces a finished one.
    pub fn make_partial(&mut self) {
        let partial = partial_path(self.file.path());
        if let Some(name) = partial.file_name() {
            self.file.redirect(name);
        }
    }

    /// Encodes the image, writes it to the temporary file, flushes it to disk and renames it
    /// over the destination.
    pub fn commit(self, img: &Image) -> Result<(), OutputError> {
        self.commit_toned(img, &tone::Tone::default())
    }

    /// [`PendingOutput::commit`] with a PNG's values after `tone` (an EXR stays linear).
    pub fn commit_toned(self, img: &Image, tone: &tone::Tone) -> Result<(), OutputError> {
        let bytes = encode_toned(img, self.format, self.path(), tone)?;
        self.commit_bytes(&bytes)
    }

    /// Writes the `region` of `img` (a whole render's image, only the region rendered): a
    /// PNG of the region alone, tone mapped; an EXR of it at its place in the whole image,
    /// with its tone and the render's `fingerprint` for `snell merge` (`None` for an
    /// unfinished region, which merge then refuses).
    pub fn commit_region(
        self,
        img: &Image,
        region: crate::film::Region,
        tone: &tone::Tone,
        fingerprint: Option<u64>,
    ) -> Result<(), OutputError> {
        let part = region.crop(img);
        let mut meta = vec![(merge::TONE, merge::tone_text(tone))];
        if let Some(f) = fingerprint {
            meta.push((merge::FINGERPRINT, format!("{f:016x}")));
        }
        let bytes = match self.format {
            OutputFormat::Exr => encode_exr_region(
                &part,
                (region.x0, region.y0),
                (img.width, img.height),
                &meta,
                self.path(),
            )?,
            _ => encode_toned(&part, self.format, self.path(), tone)?,
        };
        self.commit_bytes(&bytes)
    }

    /// Writes already encoded bytes (in this output's format) and renames them into place.
    pub fn commit_bytes(self, bytes: &[u8]) -> Result<(), OutputError> {
        let path = self.path().to_path_buf();
        self.file
            .commit(bytes)
            .map_err(|source| OutputError::Io { path, source })
    }
}

/// Where an interrupted render writes its picture: `NAME.partial.EXT` beside `NAME.EXT`
/// (`keep.png` gives `keep.partial.png`, `a.b.exr` gives `a.b.partial.exr`).
pub fn partial_path(path: &Path) -> PathBuf {
    let mut name = path.file_stem().unwrap_or_default().to_os_string();
    name.push(".partial");
    if let Some(ext) = path.extension() {
        name.push(".");
        name.push(ext);
    }
    path.with_file_name(name)
}

/// Writes `img` to `path` atomically (format from the extension).
pub fn write_image(img: &Image, path: &Path) -> Result<(), OutputError> {
    PendingOutput::create(path)?.commit(img)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Color;

    #[test]
    fn srgb_encoding_landmarks() {
        assert_eq!(linear_to_srgb(0.0), 0.0);
        assert!((linear_to_srgb(1.0) - 1.0).abs() < 1e-6);
        assert!((linear_to_srgb(0.2158605) - 128.0 / 255.0).abs() < 1e-3);
        let mut img = Image::new(2, 1);
        img.pixels[0] = Color::new(2.0, -1.0, f32::NAN);
        img.pixels[1] = Color::splat(0.5);
        assert_eq!(to_srgb8(&img), vec![255, 0, 0, 188, 188, 188]);
    }

    /// An EXR is the same bytes however its tiles' compression is shared among threads: its
    /// tiles go in increasing order, which the file's header says, for a picture with layers
    /// and for a plain one alike. (Eight encodings of a picture of 48 tiles, in the
    /// unspecified order, came out in at least two orders; a plain render's EXR, written by
    /// `image`'s encoder in that order, differed from run to run in 3 of 12.)
    #[test]
    fn an_exr_is_the_same_bytes_every_time() {
        let mut img = Image::new(512, 384);
        for (i, p) in img.pixels.iter_mut().enumerate() {
            *p = Color::new((i % 511) as f32, (i % 37) as f32 * 0.1, (i / 512) as f32);
        }
        let path = Path::new("x.exr");
        let first = encode_exr_layers(&img, &[], path).unwrap();
        let tone = tone::Tone::default();
        let mut compared = 0;
        for _ in 0..8 {
            assert!(encode_exr_layers(&img, &[], path).unwrap() == first);
            // The plain picture's writer is the same.
            assert!(encode_toned(&img, OutputFormat::Exr, path, &tone).unwrap() == first);
            compared += 2;
        }
        assert_eq!(compared, 16);
        let meta =
            exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(&first), false).unwrap();
        assert_eq!(
            meta.headers[0].line_order,
            exr::prelude::LineOrder::Increasing
        );
    }

    /// Encoded in parallel chunks, every value still lands at its own place (an image of
    /// two chunks and a part).
    #[test]
    fn every_pixel_is_encoded_in_place() {
        let mut img = Image::new(97, 101);
        for (i, p) in img.pixels.iter_mut().enumerate() {
            *p = Color::new(
                i as f32 / 9797.0,
                (i % 7) as f32 / 6.0,
                1.0 - i as f32 / 9797.0,
            );
        }
        let bytes = to_srgb8(&img);
        assert_eq!(bytes.len(), 97 * 101 * 3);
        for (i, p) in img.pixels.iter().enumerate() {
            for (k, v) in p.to_array().into_iter().enumerate() {
                let expected = (linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8;
                assert_eq!(bytes[3 * i + k], expected, "pixel {i}, channel {k}");
            }
        }
    }

    #[test]
    fn partial_pictures_go_beside_the_destination() {
        assert_eq!(
            partial_path(Path::new("keep.png")),
            Path::new("keep.partial.png")
        );
        assert_eq!(
            partial_path(Path::new("out/a.b.exr")),
            Path::new("out/a.b.partial.exr")
        );
    }

    #[test]
    fn unknown_extension_is_refused() {
        assert!(matches!(
            OutputFormat::from_path(Path::new("a.jpg")),
            Err(OutputError::UnknownFormat(_))
        ));
        assert_eq!(
            OutputFormat::from_path(Path::new("a.EXR")).unwrap(),
            OutputFormat::Exr
        );
    }
}
