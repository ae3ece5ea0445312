//! Region files back into the whole image (`snell merge`): EXRs that `render --region`
//! wrote, each with its place in the whole image (its data window), the fingerprint of the
//! render it belongs to (the scene file's bytes and the settings that change pixels) and
//! the tone a PNG of it takes. A set is refused unless every file is of the same render
//! and together they cover every pixel exactly once; then the image is the whole render's,
//! bit for bit. The fingerprint holds the scene file's bytes and the settings, not the
//! meshes and textures it reads: regions rendered while one of those changed are not told
//! apart. An interrupted region carries no fingerprint, and is refused.

use super::tone::{Tone, ToneCurve};
use crate::film::{Image, Region};
use crate::math::Color;
use std::path::{Path, PathBuf};

/// The attribute holding the render's fingerprint (hexadecimal).
pub const FINGERPRINT: &str = "snell.fingerprint";
/// The attribute holding the tone of the render's PNG (`EXPOSURE CURVE`).
pub const TONE: &str = "snell.tone";

/// One region file, read.
#[derive(Clone, Debug)]
pub struct RegionFile {
    /// Where it was read from.
    pub path: PathBuf,
    /// Its place in the whole image.
    pub region: Region,
    /// The whole image's width and height.
    pub full: (u32, u32),
    /// The render's fingerprint.
    pub fingerprint: u64,
    /// The tone of the render's PNG.
    pub tone: Tone,
    /// Its pixels, row by row.
    pub image: Image,
}

/// The text of a tone, as a region file keeps it.
pub fn tone_text(t: &Tone) -> String {
    format!("{} {}", t.exposure, t.curve.name())
}

fn parse_tone(s: &str) -> Option<Tone> {
    let (e, c) = s.split_once(' ')?;
    Some(Tone {
        exposure: e.parse().ok().filter(|x: &f32| x.is_finite())?,
        curve: ToneCurve::from_name(c)?,
    })
}

/// Reads a region file. Its header is checked first (one part, a whole image of at most
/// `max_pixels`, as many as a render may have, and a few channels), so a hostile file cannot
/// make the reader allocate without bound; a reader that panics on a corrupt file is an
/// error too.
pub fn read_region(path: &Path, max_pixels: u64) -> Result<RegionFile, String> {
    let shown = path.display();
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| format!("{shown}: not an EXR snell can read: {e}"))?;
    let [header] = &meta.headers[..] else {
        return Err(format!(
            "{shown}: an EXR of {} parts; a region file has one",
            meta.headers.len()
        ));
    };
    let display = header.shared_attributes.display_window;
    let full = display.size.0 as u64 * display.size.1 as u64;
    if full > max_pixels || header.channels.list.len() > 8 || header.deep {
        return Err(format!(
            "{shown}: an image of {} x {} with {} channels is not a region file snell writes",
            display.size.0,
            display.size.1,
            header.channels.list.len()
        ));
    }
    std::panic::catch_unwind(|| read_checked(path))
        .unwrap_or_else(|_| Err(format!("{shown}: a corrupt EXR (its reader gave up)")))
}

/// [`read_region`] after its header is checked.
fn read_checked(path: &Path) -> Result<RegionFile, String> {
    use exr::prelude::*;
    let shown = path.display();
    let image = read_first_flat_layer_from_file(path)
        .map_err(|e| format!("{shown}: not an EXR snell can read: {e}"))?;
    // Custom attributes of a one-part file may be read as the image's or as its layer's.
    let text = |key: &str| {
        let key = Text::from(key);
        let found = image
            .attributes
            .other
            .get(&key)
            .or_else(|| image.layer_data.attributes.other.get(&key));
        match found {
            Some(AttributeValue::Text(t)) => Some(t.to_string()),
            _ => None,
        }
    };
    let fingerprint = text(FINGERPRINT)
        .and_then(|f| u64::from_str_radix(&f, 16).ok())
        .ok_or_else(|| {
            format!(
                "{shown}: no snell fingerprint: not written by `snell render --region`, or an interrupted one"
            )
        })?;
    let tone = text(TONE)
        .and_then(|t| parse_tone(&t))
        .ok_or_else(|| format!("{shown}: no tone: not written by `snell render --region`"))?;
    let display = image.attributes.display_window;
    let layer = image.layer_data;
    let (x0, y0) = (
        layer.attributes.layer_position.0,
        layer.attributes.layer_position.1,
    );
    let (w, h) = (layer.size.0, layer.size.1);
    let full = (display.size.0, display.size.1);
    let inside = display.position.0 == 0
        && display.position.1 == 0
        && x0 >= 0
        && y0 >= 0
        && x0 as usize + w <= full.0
        && y0 as usize + h <= full.1
        && w > 0
        && h > 0
        && full.0 <= u32::MAX as usize
        && full.1 <= u32::MAX as usize;
    if !inside {
        return Err(format!(
            "{shown}: its data window ({w} x {h} at {x0}, {y0}) does not lie within its image ({} x {})",
            full.0, full.1
        ));
    }
    let channel = |name: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == *name)
            .map(|c| c.sample_data.values_as_f32().collect::<Vec<f32>>())
            .ok_or_else(|| format!("{shown}: no {name} channel"))
    };
    let (r, g, b) = (channel("R")?, channel("G")?, channel("B")?);
    if [r.len(), g.len(), b.len()].iter().any(|&n| n != w * h) {
        return Err(format!(
            "{shown}: its channels do not hold {w} x {h} values each"
        ));
    }
    let region = Region {
        x0: x0 as u32,
        y0: y0 as u32,
        x1: x0 as u32 + w as u32,
        y1: y0 as u32 + h as u32,
    };
    Ok(RegionFile {
        path: path.to_path_buf(),
        region,
        full: (full.0 as u32, full.1 as u32),
        fingerprint,
        tone,
        image: crate::film::Image {
            width: w as u32,
            height: h as u32,
            pixels: (0..r.len()).map(|i| Color::new(r[i], g[i], b[i])).collect(),
        },
    })
}

/// The whole image of `files`, and the tone its PNG takes; an error unless they are of one
/// render (image size, fingerprint, tone) and cover every pixel exactly once.
pub fn merge(files: &[RegionFile]) -> Result<(Image, Tone), String> {
    let Some(first) = files.first() else {
        return Err("no region files to merge".into());
    };
    let name = |g: &RegionFile| g.path.display().to_string();
    for (k, f) in files.iter().enumerate() {
        if f.full != first.full {
            return Err(format!(
                "{} is of a {} x {} image and {} of a {} x {} one",
                name(f),
                f.full.0,
                f.full.1,
                name(first),
                first.full.0,
                first.full.1
            ));
        }
        if f.fingerprint != first.fingerprint {
            return Err(format!(
                "{} and {} are of different renders (another scene, or other settings: size, samples, seed or integrator)",
                name(first),
                name(f)
            ));
        }
        if f.tone != first.tone {
            return Err(format!(
                "{} and {} were rendered for different tones ({} and {})",
                name(first),
                name(f),
                tone_text(&first.tone),
                tone_text(&f.tone)
            ));
        }
        // Overlaps, rectangle against rectangle (no per-pixel table: a whole image may
        // be large).
        if let Some(g) = files[..k].iter().find(|g| {
            let r = g.region;
            f.region.overlaps((r.x0, r.y0, r.x1, r.y1))
        }) {
            let (a, b) = (f.region, g.region);
            let message = if f.path == g.path {
                format!("{} is given twice", name(f))
            } else {
                format!(
                    "{} and {} overlap (both hold pixel ({}, {}))",
                    name(g),
                    name(f),
                    a.x0.max(b.x0),
                    a.y0.max(b.y0)
                )
            };
            return Err(message);
        }
    }
    let (w, h) = first.full;
    // Without overlaps, the files cover the image exactly when their areas add up to it.
    let covered: u64 = files.iter().map(|f| f.region.pixels()).sum();
    if covered != w as u64 * h as u64 {
        let (x, y) = first_uncovered(files, w, h);
        return Err(format!(
            "the files leave {} pixels of the {w} x {h} image uncovered, the first at ({x}, {y})",
            w as u64 * h as u64 - covered
        ));
    }
    let mut image = Image::new(w, h);
    for f in files {
        let r = f.region;
        for (y, row) in (r.y0..r.y1).zip(f.image.pixels.chunks_exact(r.width() as usize)) {
            let at = y as usize * w as usize + r.x0 as usize;
            image.pixels[at..at + row.len()].copy_from_slice(row);
        }
    }
    Ok((image, first.tone))
}

/// The first pixel, row by row, that none of `files` covers (there is one).
fn first_uncovered(files: &[RegionFile], w: u32, h: u32) -> (u32, u32) {
    for y in 0..h {
        let mut spans: Vec<(u32, u32)> = files
            .iter()
            .map(|f| f.region)
            .filter(|r| r.y0 <= y && y < r.y1)
            .map(|r| (r.x0, r.x1))
            .collect();
        spans.sort_unstable();
        let mut x = 0;
        for (x0, x1) in spans {
            if x0 > x {
                return (x, y);
            }
            x = x.max(x1);
        }
        if x < w {
            return (x, y);
        }
    }
    (0, 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tone_survives_its_text() {
        for t in [
            Tone::default(),
            Tone {
                exposure: -1.5,
                curve: ToneCurve::Reinhard,
            },
        ] {
            assert_eq!(parse_tone(&tone_text(&t)), Some(t));
        }
        assert_eq!(parse_tone("nan clamp"), None);
        assert_eq!(parse_tone("1 sepia"), None);
        assert_eq!(merge(&[]).unwrap_err(), "no region files to merge");
    }
}
