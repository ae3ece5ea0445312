//! Region files back into the whole image (`snell merge`): EXRs that `render --region`
//! wrote, each with its place in the whole image (its data window), the fingerprint of the
//! render it belongs to (the scene file's bytes and the settings that change pixels) and
//! the tone a PNG of it takes. A set is refused unless every file is of the same render
//! and together they cover every pixel exactly once; then the image is the whole render's,
//! bit for bit.

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

/// Reads a region file.
pub fn read_region(path: &Path) -> Result<RegionFile, String> {
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
            format!("{shown}: no snell fingerprint: not written by `snell render --region`")
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
    for f in files {
        let name = |g: &RegionFile| g.path.display().to_string();
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
    }
    let (w, h) = first.full;
    // Which file covers each pixel, so that an overlap names both.
    let mut owner: Vec<Option<usize>> = vec![None; w as usize * h as usize];
    let mut image = Image::new(w, h);
    for (k, f) in files.iter().enumerate() {
        let r = f.region;
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                let i = (y * w + x) as usize;
                if let Some(j) = owner[i] {
                    return Err(format!(
                        "{} and {} overlap (both hold pixel ({x}, {y}))",
                        files[j].path.display(),
                        f.path.display()
                    ));
                }
                owner[i] = Some(k);
                image.pixels[i] = f.image.pixels[((y - r.y0) * r.width() + (x - r.x0)) as usize];
            }
        }
    }
    if let Some(i) = owner.iter().position(Option::is_none) {
        let missing = owner.iter().filter(|o| o.is_none()).count();
        return Err(format!(
            "the files leave {missing} pixels of the {w} x {h} image uncovered, the first at ({}, {})",
            i as u32 % w,
            i as u32 / w
        ));
    }
    Ok((image, first.tone))
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
