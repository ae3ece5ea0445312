//! Saving a render's progress to resume it later: the tiles finished so far (a render of
//! all samples at once, tile by tile), the film's sums (a progressive render, pass after
//! pass) or the splats and film of light tracing's and bdpt's passes, with what is needed
//! to check that the resumed render is the same render (the scene file's bytes and the
//! settings) and to continue it without repeating the command line.
//!
//! Tiles are independent and every pixel's samples are seeded from `(seed, x, y)` (and a
//! sample's index), so a resumed render gives the same bytes as one that was never stopped.
//!
//! The file is binary, little-endian: the line `snell checkpoint 4`, the fingerprint (u64),
//! width, height, samples per pixel (u32 each), seed (u64), the integrator (u32: 0 Whitted,
//! 1 path, 2 light, 3 bdpt), its sampler (u32: 0 independent, 1 Sobol), clamp (u32 1 and an
//! f32, or 0 and 0.0 for none) and adaptive sampling's noise threshold (the same way), the scene's and the output's paths (u32 length, UTF-8), then what is done:
//! u32 0, the tile count (u32), then per tile its index and pixel count (u32 each) and its
//! pixels (three f32 each); or u32 2 and the film, row by row, each pixel its sums (three
//! f32), weight (f32), unsigned sums (three f32), sample count (u32) and sum of squared
//! luminances (f32); or, for light tracing and bdpt, u32 3, the samples a pixel of the
//! passes done (u32), u32 1 and the camera's film as above (bdpt) or u32 0 (light tracing),
//! then the splats' fixed-point sums, row by row, three i64 a pixel. Films saved without
//! the squares (u32 1) are still read, their pixels' spread taken as none (so the error estimate of a render resumed from one counts only
//! the samples after it as noisy). It is written to a
//! temporary file and renamed into place, so a checkpoint is never half written. Version 3
//! files (without the noise threshold), version 2 files (tiles only, without the u32 0 too)
//! and version 1 files (without the integrator too) are still read.

use crate::film::{Film, FilmPixel};
use crate::math::Color;
use crate::sampler::SamplerKind;
use crate::scene::{IntegratorKind, RenderSettings};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const MAGIC: &[u8] = b"snell checkpoint 4\n";
const MAGIC_3: &[u8] = b"snell checkpoint 3\n";
const MAGIC_2: &[u8] = b"snell checkpoint 2\n";
const MAGIC_1: &[u8] = b"snell checkpoint 1\n";

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
    /// The integrator, its sampler and clamp, as the render had them (`None` in a version 1
    /// file, which did not keep them: the scene's and the command line's then).
    pub integrator: Option<CheckpointIntegrator>,
    /// The scene file (absolute).
    pub scene: PathBuf,
    /// Where the image goes.
    pub output: PathBuf,
    /// Finished tiles by index, pixels row by row (a render of all samples at once).
    pub tiles: BTreeMap<u32, Vec<Color>>,
    /// The film's sums (a progressive render): every pixel with the samples it has.
    pub film: Option<Film>,
    /// A light-traced or bidirectional render's passes (whose light lands anywhere on the
    /// film).
    pub splatted: Option<Splatted>,
}

/// What the passes of a render whose light lands anywhere (light tracing, bdpt) have done:
/// the samples a pixel, the camera's film of sums (bdpt's; light tracing has none), and
/// the splats' fixed-point sums, pixel by pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Splatted {
    /// Samples (light tracing: paths) a pixel in every pass done.
    pub spp: u32,
    /// The film of the camera's strategies (bdpt).
    pub film: Option<Film>,
    /// [`crate::film::SplatFilm::snapshot`]: per pixel, three fixed-point sums.
    pub splats: Vec<[i64; 3]>,
}

impl Splatted {
    /// Whether these passes can go on in a render with settings `s` by bdpt (`bdpt`) or by
    /// light tracing: passes of that integrator (bdpt's have a camera film, light
    /// tracing's none), of the render's size, holding no more samples than it takes; why
    /// not, where not.
    pub fn fits(&self, s: &RenderSettings, bdpt: bool) -> Result<(), &'static str> {
        match (&self.film, bdpt) {
            (Some(_), false) => return Err("they are bdpt's"),
            (None, true) => return Err("they are light tracing's"),
            _ => {}
        }
        let film_size = self.film.as_ref().map(|f| (f.width(), f.height()));
        if film_size.is_some_and(|size| size != (s.width, s.height))
            || self.splats.len() != s.width as usize * s.height as usize
        {
            return Err("their film is of another size");
        }
        if self.spp > s.spp {
            return Err(if bdpt {
                "they hold more samples than the render takes"
            } else {
                "they hold more paths than the render takes"
            });
        }
        Ok(())
    }
}

/// The integrator settings a checkpoint keeps, so that `--resume` needs no flags again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckpointIntegrator {
    /// Whitted or path.
    pub kind: IntegratorKind,
    /// The path tracer's sampler.
    pub sampler: SamplerKind,
    /// The path tracer's clamp.
    pub clamp: Option<f32>,
    /// Adaptive sampling's threshold (`[image] noise`, `--noise`).
    pub noise: Option<f32>,
}

impl CheckpointIntegrator {
    /// What a render with settings `s` keeps.
    pub fn of(s: &RenderSettings) -> Self {
        let i = &s.integrator;
        CheckpointIntegrator {
            kind: i.kind,
            sampler: i.sampler,
            clamp: i.clamp,
            noise: s.noise,
        }
    }

    /// Puts these settings into `s`.
    pub fn apply(&self, s: &mut RenderSettings) {
        let i = &mut s.integrator;
        (i.kind, i.sampler, i.clamp) = (self.kind, self.sampler, self.clamp);
        s.noise = self.noise;
    }
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
            Vec::with_capacity(96 + self.tiles.values().map(|t| 8 + t.len() * 12).sum::<usize>());
        let u32s = |out: &mut Vec<u8>, vs: &[u32]| {
            for v in vs {
                out.extend_from_slice(&v.to_le_bytes());
            }
        };
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&self.fingerprint.to_le_bytes());
        u32s(&mut out, &[self.width, self.height, self.spp]);
        out.extend_from_slice(&self.seed.to_le_bytes());
        let i = self.integrator.unwrap_or(CheckpointIntegrator {
            kind: IntegratorKind::Whitted,
            sampler: SamplerKind::Sobol,
            clamp: None,
            noise: None,
        });
        u32s(
            &mut out,
            &[
                match i.kind {
                    IntegratorKind::Whitted => 0,
                    IntegratorKind::Path => 1,
                    IntegratorKind::Light => 2,
                    IntegratorKind::Bdpt => 3,
                },
                match i.sampler {
                    SamplerKind::Independent => 0,
                    SamplerKind::Sobol => 1,
                },
                i.clamp.is_some() as u32,
                i.clamp.unwrap_or(0.0).to_bits(),
                i.noise.is_some() as u32,
                i.noise.unwrap_or(0.0).to_bits(),
            ],
        );
        for p in [&self.scene, &self.output] {
            let s = p.to_string_lossy();
            u32s(&mut out, &[s.len() as u32]);
            out.extend_from_slice(s.as_bytes());
        }
        let film_sums = |out: &mut Vec<u8>, film: &Film| {
            for y in 0..film.height() {
                for x in 0..film.width() {
                    let p = film.get(x, y);
                    u32s(out, &p.sum.map(f32::to_bits));
                    u32s(out, &[p.weight.to_bits()]);
                    u32s(out, &p.unsigned.map(f32::to_bits));
                    u32s(out, &[p.samples, p.sum_sq.to_bits()]);
                }
            }
        };
        if let Some(sp) = &self.splatted {
            u32s(&mut out, &[3, sp.spp, sp.film.is_some() as u32]);
            if let Some(film) = &sp.film {
                film_sums(&mut out, film);
            }
            for p in &sp.splats {
                for v in p {
                    out.extend_from_slice(&v.to_le_bytes());
                }
            }
        } else if let Some(film) = &self.film {
            u32s(&mut out, &[2]);
            film_sums(&mut out, film);
        } else {
            u32s(&mut out, &[0, self.tiles.len() as u32]);
            for (&i, pixels) in &self.tiles {
                u32s(&mut out, &[i, pixels.len() as u32]);
                for c in pixels {
                    u32s(&mut out, &c.to_array().map(f32::to_bits));
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
        let (rest, version) =
            match [MAGIC, MAGIC_3, MAGIC_2, MAGIC_1].map(|m| bytes.strip_prefix(m)) {
                [Some(rest), ..] => (rest, 4),
                [None, Some(rest), ..] => (rest, 3),
                [None, None, Some(rest), _] => (rest, 2),
                [None, None, None, Some(rest)] => (rest, 1),
                _ => return Err(bad("it does not start with `snell checkpoint 4`")),
            };
        let mut r = Reader { bytes: rest, at: 0 };
        let truncated = || bad("it is cut short");
        let fingerprint = r.u64().ok_or_else(truncated)?;
        let width = r.u32().ok_or_else(truncated)?;
        let height = r.u32().ok_or_else(truncated)?;
        let spp = r.u32().ok_or_else(truncated)?;
        let seed = r.u64().ok_or_else(truncated)?;
        let integrator = if version == 1 {
            None
        } else {
            let [kind, sampler, clamped, clamp] =
                [r.u32(), r.u32(), r.u32(), r.u32()].map(|v| v.ok_or_else(truncated));
            Some(CheckpointIntegrator {
                kind: match kind? {
                    0 => IntegratorKind::Whitted,
                    1 => IntegratorKind::Path,
                    2 => IntegratorKind::Light,
                    3 => IntegratorKind::Bdpt,
                    _ => return Err(bad("it names an integrator snell does not have")),
                },
                sampler: match sampler? {
                    0 => SamplerKind::Independent,
                    1 => SamplerKind::Sobol,
                    _ => return Err(bad("it names a sampler snell does not have")),
                },
                clamp: match (clamped?, f32::from_bits(clamp?)) {
                    (0, _) => None,
                    (1, c) if c > 0.0 && c.is_finite() => Some(c),
                    _ => return Err(bad("its clamp is not a positive number")),
                },
                noise: if version >= 4 {
                    let [given, noise] = [r.u32(), r.u32()].map(|v| v.ok_or_else(truncated));
                    match (given?, f32::from_bits(noise?)) {
                        (0, _) => None,
                        (1, v) if RenderSettings::check_noise(v).is_ok() => Some(v),
                        _ => return Err(bad("its noise threshold is not a number in (0, 1]")),
                    }
                } else {
                    None
                },
            })
        };
        let scene = PathBuf::from(r.string().ok_or_else(truncated)?);
        let output = PathBuf::from(r.string().ok_or_else(truncated)?);
        let kind = if version >= 3 {
            r.u32().ok_or_else(truncated)?
        } else {
            0
        };
        let (mut tiles, mut splatted) = (BTreeMap::new(), None);
        let film = match kind {
            0 => {
                let count = r.u32().ok_or_else(truncated)?;
                for _ in 0..count {
                    let index = r.u32().ok_or_else(truncated)?;
                    let n = r.u32().ok_or_else(truncated)? as usize;
                    // A tile has at most 16 x 16 pixels; refuse anything else before
                    // allocating.
                    if n > (crate::film::TILE * crate::film::TILE) as usize {
                        return Err(bad("a tile is larger than 16 x 16 pixels"));
                    }
                    let mut pixels = Vec::with_capacity(n);
                    for _ in 0..n {
                        pixels.push(r.color().ok_or_else(truncated)?);
                    }
                    tiles.insert(index, pixels);
                }
                None
            }
            1 | 2 => Some(read_film(&mut r, width, height, kind == 2).ok_or_else(truncated)?),
            3 => {
                let spp = r.u32().ok_or_else(truncated)?;
                let film = match r.u32().ok_or_else(truncated)? {
                    0 => None,
                    1 => Some(read_film(&mut r, width, height, true).ok_or_else(truncated)?),
                    _ => return Err(bad("its film is neither there nor missing")),
                };
                let n = width as usize * height as usize;
                // The size the header gives, checked against the bytes there first.
                if (r.bytes.len() - r.at) / 24 < n {
                    return Err(truncated());
                }
                let mut splats = Vec::with_capacity(n);
                for _ in 0..n {
                    let mut v = || r.u64().map(|v| v as i64).ok_or_else(truncated);
                    splats.push([v()?, v()?, v()?]);
                }
                splatted = Some(Splatted { spp, film, splats });
                None
            }
            _ => return Err(bad("it keeps its progress in a way snell does not know")),
        };
        Ok(Checkpoint {
            fingerprint,
            width,
            height,
            spp,
            seed,
            integrator,
            scene,
            output,
            tiles,
            film,
            splatted,
        })
    }
}

/// A film of `width` x `height` pixels' sums, as [`Checkpoint::save`] writes them (with
/// the squared luminances, or without: `squares` false, a version 3 film); `None` where
/// the bytes end first.
fn read_film(r: &mut Reader, width: u32, height: u32, squares: bool) -> Option<Film> {
    // The header's size, checked against the bytes there before allocating.
    let n = width as u64 * height as u64;
    let size = if squares { 36 } else { 32 };
    if (r.bytes.len() - r.at) as u64 / size < n {
        return None;
    }
    let mut film = Film::new(width, height);
    for y in 0..height {
        for x in 0..width {
            let (sum, weight) = ([r.f32()?, r.f32()?, r.f32()?], r.f32()?);
            let unsigned = [r.f32()?, r.f32()?, r.f32()?];
            let samples = r.u32()?;
            let sum_sq = if squares {
                r.f32()?
            } else if samples > 0 {
                // No spread known: every sample taken to be the mean.
                let l = crate::math::luminance(Color::from(unsigned));
                l * l / samples as f32
            } else {
                0.0
            };
            *film.get_mut(x, y) = FilmPixel {
                sum,
                weight,
                unsigned,
                samples,
                sum_sq,
            };
        }
    }
    Some(film)
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
    fn color(&mut self) -> Option<Color> {
        Some(Color::new(self.f32()?, self.f32()?, self.f32()?))
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
            integrator: Some(CheckpointIntegrator {
                kind: IntegratorKind::Path,
                sampler: SamplerKind::Independent,
                clamp: Some(10.0),
                noise: Some(0.02),
            }),
            scene: PathBuf::from("/tmp/a scene.toml"),
            output: PathBuf::from("out.png"),
            tiles,
            film: None,
            splatted: None,
        }
    }

    /// A progressive render's checkpoint: the film's sums, pixels at uneven sample counts.
    #[test]
    fn a_film_round_trips_exactly() {
        let mut c = sample();
        (c.width, c.height, c.tiles) = (37, 21, BTreeMap::new());
        let mut film: Film = Film::new(37, 21);
        for y in 0..21 {
            for x in 0..37 {
                let p = film.get_mut(x, y);
                p.add(Color::new(x as f32 * 0.1, y as f32, 1e-7), 1.0);
                if (x + y) % 3 == 0 {
                    p.add(Color::new(2.0, -0.0, 5.0), -1.0);
                }
            }
        }
        c.film = Some(film);
        let path = std::env::temp_dir().join(format!("snell-ckpt3-{}", std::process::id()));
        c.save(&path).unwrap();
        assert_eq!(Checkpoint::load(&path).unwrap(), c);
        let bytes = std::fs::read(&path).unwrap();
        std::fs::write(&path, &bytes[..bytes.len() - 4]).unwrap();
        let e = Checkpoint::load(&path).unwrap_err();
        assert!(e.contains("cut short"), "{e}");
        std::fs::remove_file(&path).unwrap();
    }

    /// A light-traced or bidirectional render's passes: the samples a pixel, bdpt's camera
    /// film (or none), and the splats' sums, to the bit, negative and huge ones too.
    #[test]
    fn splatted_passes_round_trip_exactly() {
        let mut checked = 0;
        for with_film in [true, false] {
            let mut c = sample();
            (c.width, c.height, c.tiles) = (5, 3, BTreeMap::new());
            let mut film: Film = Film::new(5, 3);
            film.get_mut(2, 1).add(Color::new(0.5, 1.5, 2.5), 1.0);
            c.splatted = Some(Splatted {
                spp: 12,
                film: with_film.then_some(film),
                splats: (0..15)
                    .map(|i| [i, -i * 1_000_000_007, i64::MAX - i])
                    .collect(),
            });
            let path = std::env::temp_dir()
                .join(format!("snell-ckpt-sp-{}-{with_film}", std::process::id()));
            c.save(&path).unwrap();
            assert_eq!(Checkpoint::load(&path).unwrap(), c);
            let bytes = std::fs::read(&path).unwrap();
            std::fs::write(&path, &bytes[..bytes.len() - 8]).unwrap();
            let e = Checkpoint::load(&path).unwrap_err();
            assert!(e.contains("cut short"), "{e}");
            std::fs::remove_file(&path).unwrap();
            checked += 1;
        }
        assert_eq!(checked, 2);
    }

    /// Version 3 files (no noise threshold) and version 2 files (tiles only, no progress
    /// kind either) are read.
    #[test]
    fn version_2_and_3_files_are_read() {
        let c = sample();
        let path = std::env::temp_dir().join(format!("snell-ckpt2-{}", std::process::id()));
        c.save(&path).unwrap();
        let v4 = std::fs::read(&path).unwrap();
        // Version 4 is version 3 with the noise threshold (u32 1, f32) after the clamp.
        let noise = MAGIC.len() + 8 + 12 + 8 + 16;
        assert_eq!(v4[noise..noise + 4], [1, 0, 0, 0]);
        assert_eq!(v4[noise + 4..noise + 8], 0.02f32.to_le_bytes());
        let mut v3 = MAGIC_3.to_vec();
        v3.extend_from_slice(&v4[MAGIC.len()..noise]);
        v3.extend_from_slice(&v4[noise + 8..]);
        let mut without = c.clone();
        if let Some(i) = &mut without.integrator {
            i.noise = None;
        }
        std::fs::write(&path, &v3).unwrap();
        assert_eq!(Checkpoint::load(&path).unwrap(), without);
        // Version 3 is version 2 with its progress kind (u32 0 for tiles) before the tiles.
        let at = v3.len() - 4 - c.tiles.values().map(|t| 8 + 12 * t.len()).sum::<usize>() - 4;
        assert_eq!(v3[at..at + 4], [0, 0, 0, 0]);
        let mut v2 = MAGIC_2.to_vec();
        v2.extend_from_slice(&v3[MAGIC_3.len()..at]);
        v2.extend_from_slice(&v3[at + 4..]);
        std::fs::write(&path, &v2).unwrap();
        assert_eq!(Checkpoint::load(&path).unwrap(), without);
        std::fs::remove_file(&path).unwrap();
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
        // An integrator this snell does not have is refused by name.
        let at = MAGIC.len() + 8 + 12 + 8;
        let mut other = bytes.clone();
        other[at] = 7;
        std::fs::write(&path, &other).unwrap();
        let e = Checkpoint::load(&path).unwrap_err();
        assert!(e.contains("names an integrator"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// An earlier snell's checkpoint (version 1, without the integrator) is read, its
    /// integrator left to the scene and the command line.
    #[test]
    fn version_1_files_are_read() {
        let mut v1 = MAGIC_1.to_vec();
        v1.extend_from_slice(&42u64.to_le_bytes());
        for v in [32u32, 16, 4] {
            v1.extend_from_slice(&v.to_le_bytes());
        }
        v1.extend_from_slice(&9u64.to_le_bytes());
        for p in ["/s.toml", "o.png"] {
            v1.extend_from_slice(&(p.len() as u32).to_le_bytes());
            v1.extend_from_slice(p.as_bytes());
        }
        let colors = [Color::new(0.25, 1.5, 0.0), Color::new(3.0, 0.125, 7.75)];
        for v in [1u32, 1, 2] {
            v1.extend_from_slice(&v.to_le_bytes());
        }
        for c in colors {
            for v in c.to_array() {
                v1.extend_from_slice(&v.to_le_bytes());
            }
        }
        let path = std::env::temp_dir().join(format!("snell-ckpt1-{}", std::process::id()));
        std::fs::write(&path, &v1).unwrap();
        let c = Checkpoint::load(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(
            (c.fingerprint, c.width, c.height, c.spp, c.seed),
            (42, 32, 16, 4, 9)
        );
        assert_eq!(c.integrator, None);
        assert_eq!(c.output, PathBuf::from("o.png"));
        assert_eq!(c.tiles[&1], colors);
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
