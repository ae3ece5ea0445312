//! Saving a render's progress to resume it later: the tiles finished so far, with what is
//! needed to check that the resumed render is the same render (the scene file's bytes and
//! the settings) and to continue it without repeating the command line.
//!
//! Tiles are independent and every pixel's samples are seeded from `(seed, x, y)`, so a
//! resumed render gives the same bytes as one that was never stopped.
//!
//! The file is binary, little-endian: the line `snell checkpoint 1`, the fingerprint (u64),
//! width, height, samples per pixel (u32 each), seed (u64), the scene's and the output's
//! paths (u32 length, UTF-8), the tile count (u32), then per tile its index and pixel count
//! (u32 each) and its pixels (three f32 each). It is written to a temporary file and renamed
//! into place, so a checkpoint is never half written.

use crate::math::Color;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const MAGIC: &[u8] = b"snell checkpoint 1\n";

/// A render's progress.
#[derive(Clone, Debug, PartialEq)]
pub struct Checkpoint {
    /// Hash of the scene file's bytes and the settings below; a resume must match it.
    pub fingerprint: u64,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// Sample seed.
    pub seed: u64,
    /// The scene file (absolute).
    pub scene: PathBuf,
    /// Where the image goes.
    pub output: PathBuf,
    /// Finished tiles by index, pixels row by row.
    pub tiles: BTreeMap<u32, Vec<Color>>,
}

/// FNV-1a, 64 bits: stable across Rust versions and platforms (unlike `DefaultHasher`).
fn fnv1a(mut h: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// The fingerprint of a render: the scene file's bytes and the settings that change pixels.
pub fn fingerprint(scene_bytes: &[u8], width: u32, height: u32, spp: u32, seed: u64) -> u64 {
    let mut h = fnv1a(0xcbf2_9ce4_8422_2325, scene_bytes);
    for part in [width as u64, height as u64, spp as u64, seed] {
        h = fnv1a(h, &part.to_le_bytes());
    }
    h
}

impl Checkpoint {
    /// Writes the checkpoint to `path` (through a temporary file renamed into place).
    pub fn save(&self, path: &Path) -> std::io::Result<()> {
        let mut out =
            Vec::with_capacity(64 + self.tiles.values().map(|t| 8 + t.len() * 12).sum::<usize>());
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&self.fingerprint.to_le_bytes());
        for v in [self.width, self.height, self.spp] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&self.seed.to_le_bytes());
        for p in [&self.scene, &self.output] {
            let s = p.to_string_lossy();
            out.extend_from_slice(&(s.len() as u32).to_le_bytes());
            out.extend_from_slice(s.as_bytes());
        }
        out.extend_from_slice(&(self.tiles.len() as u32).to_le_bytes());
        for (&i, pixels) in &self.tiles {
            out.extend_from_slice(&i.to_le_bytes());
            out.extend_from_slice(&(pixels.len() as u32).to_le_bytes());
            for c in pixels {
                for v in c.to_array() {
                    out.extend_from_slice(&v.to_le_bytes());
                }
            }
        }
        crate::output::atomic::write_atomically(path, &out)
    }

    /// Reads a checkpoint. A file that is not one, or is cut short, is an error saying so.
    pub fn load(path: &Path) -> Result<Checkpoint, String> {
        let bytes =
            std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let bad = |what: &str| format!("{} is not a snell checkpoint ({what})", path.display());
        let rest = bytes
            .strip_prefix(MAGIC)
            .ok_or_else(|| bad("it does not start with `snell checkpoint 1`"))?;
        let mut r = Reader { bytes: rest, at: 0 };
        let truncated = || bad("it is cut short");
        let fingerprint = r.u64().ok_or_else(truncated)?;
        let width = r.u32().ok_or_else(truncated)?;
        let height = r.u32().ok_or_else(truncated)?;
        let spp = r.u32().ok_or_else(truncated)?;
        let seed = r.u64().ok_or_else(truncated)?;
        let scene = PathBuf::from(r.string().ok_or_else(truncated)?);
        let output = PathBuf::from(r.string().ok_or_else(truncated)?);
        let count = r.u32().ok_or_else(truncated)?;
        let mut tiles = BTreeMap::new();
        for _ in 0..count {
            let index = r.u32().ok_or_else(truncated)?;
            let n = r.u32().ok_or_else(truncated)? as usize;
            // A tile has at most 16 x 16 pixels; refuse anything else before allocating.
            if n > 256 {
                return Err(bad("a tile is larger than 16 x 16 pixels"));
            }
            let mut pixels = Vec::with_capacity(n);
            for _ in 0..n {
                let c = [r.f32(), r.f32(), r.f32()];
                let [Some(x), Some(y), Some(z)] = c else {
                    return Err(truncated());
                };
                pixels.push(Color::new(x, y, z));
            }
            tiles.insert(index, pixels);
        }
        Ok(Checkpoint {
            fingerprint,
            width,
            height,
            spp,
            seed,
            scene,
            output,
            tiles,
        })
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let b = self.bytes.get(self.at..self.at + N)?;
        self.at += N;
        b.try_into().ok()
    }
    fn u32(&mut self) -> Option<u32> {
        self.take().map(u32::from_le_bytes)
    }
    fn u64(&mut self) -> Option<u64> {
        self.take().map(u64::from_le_bytes)
    }
    fn f32(&mut self) -> Option<f32> {
        self.take().map(f32::from_le_bytes)
    }
    fn string(&mut self) -> Option<String> {
        let n = self.u32()? as usize;
        let b = self.bytes.get(self.at..self.at.checked_add(n)?)?;
        self.at += n;
        String::from_utf8(b.to_vec()).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Checkpoint {
        let mut tiles = BTreeMap::new();
        tiles.insert(3, vec![Color::new(0.1, 0.2, 0.3); 256]);
        tiles.insert(7, vec![Color::new(1.0, -0.0, 5.5); 12]);
        Checkpoint {
            fingerprint: fingerprint(b"[camera]", 640, 480, 16, 7),
            width: 640,
            height: 480,
            spp: 16,
            seed: 7,
            scene: PathBuf::from("/tmp/a scene.toml"),
            output: PathBuf::from("out.png"),
            tiles,
        }
    }

    #[test]
    fn round_trips_exactly() {
        let dir = std::env::temp_dir().join(format!("snell-ckpt-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("c.ckpt");
        let c = sample();
        c.save(&path).unwrap();
        assert_eq!(Checkpoint::load(&path).unwrap(), c);
        // Every shorter file is refused with a message, never a panic.
        let bytes = std::fs::read(&path).unwrap();
        for cut in [0, 5, MAGIC.len(), MAGIC.len() + 9, bytes.len() - 1] {
            std::fs::write(&path, &bytes[..cut]).unwrap();
            let e = Checkpoint::load(&path).unwrap_err();
            assert!(e.contains("not a snell checkpoint"), "{e}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn fingerprint_changes_with_scene_and_settings() {
        let f = fingerprint(b"a", 1, 2, 4, 0);
        assert_ne!(f, fingerprint(b"b", 1, 2, 4, 0));
        assert_ne!(f, fingerprint(b"a", 2, 1, 4, 0));
        assert_ne!(f, fingerprint(b"a", 1, 2, 9, 0));
        assert_ne!(f, fingerprint(b"a", 1, 2, 4, 1));
        assert_eq!(f, fingerprint(b"a", 1, 2, 4, 0));
    }
}
