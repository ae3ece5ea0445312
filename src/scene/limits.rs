//! What a scene and a render may ask for, and the memory a render will take.

use super::Scene;

/// Sane maximums for what a scene and a render may ask for, so a typo (an extra zero) gets a
/// clear message instead of exhausting the machine. Each can be raised from the command line
/// (`--max-pixels`, `--max-spp`, `--max-depth`, `--max-texture-pixels`, `--max-triangles`),
/// up to the hard ceilings in [`Limits::CEILING`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Pixels in the image (width x height).
    pub max_pixels: u64,
    /// Samples per pixel.
    pub max_spp: u32,
    /// Longest chain of rays, the camera ray included.
    pub max_depth: u32,
    /// Texels in one image texture (width x height).
    pub max_texture_pixels: u64,
    /// Triangles in all the scene's meshes (each mesh counted once, however often placed).
    pub max_triangles: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_pixels: 1 << 28,         // 16384 x 16384: 14 GiB of film and image
            max_spp: 65_536,             // 256 x 256
            max_depth: 64,               // far beyond what a picture shows
            max_texture_pixels: 1 << 28, // 16384 x 16384: 3 GiB decoded
            max_triangles: 1 << 28,      // about 20 GiB of meshes and BVHs
        }
    }
}

impl Limits {
    /// The most any limit may be raised to: what the renderer can represent (a ray tree's
    /// recursion, `u32` indices), whatever memory the machine has.
    pub const CEILING: Limits = Limits {
        max_pixels: 1 << 32,
        max_spp: 1 << 24,
        max_depth: 256,
        max_texture_pixels: 1 << 32,
        max_triangles: 1 << 32,
    };

    /// Checks these limits against [`Limits::CEILING`]: the flag and the ceiling when one
    /// is above it.
    pub fn check(&self) -> Result<(), String> {
        let c = Limits::CEILING;
        for (flag, v, max) in [
            ("--max-pixels", self.max_pixels, c.max_pixels),
            ("--max-spp", self.max_spp as u64, c.max_spp as u64),
            ("--max-depth", self.max_depth as u64, c.max_depth as u64),
            (
                "--max-texture-pixels",
                self.max_texture_pixels,
                c.max_texture_pixels,
            ),
            ("--max-triangles", self.max_triangles, c.max_triangles),
        ] {
            if v == 0 || v > max {
                return Err(format!("{flag} must be between 1 and {max}, not {v}"));
            }
        }
        Ok(())
    }

    /// Checks a sample count: within the limit, and a square number (n x n strata) where
    /// `square` (the Whitted integrator's jitter).
    pub fn check_spp(&self, spp: u32, square: bool) -> Result<(), (String, Option<String>)> {
        let n = (spp as f64).sqrt().round() as u32;
        if spp == 0 || spp > self.max_spp {
            Err((
                format!(
                    "samples per pixel must be between 1 and {}, not {spp}",
                    self.max_spp
                ),
                (spp > self.max_spp).then(|| "raise the limit with --max-spp".to_string()),
            ))
        } else if square && n * n != spp {
            let lo = ((spp as f64).sqrt().floor() as u32).max(1);
            Err((
                format!(
                    "samples per pixel must be a square number (n x n stratified) for the Whitted integrator, not {spp}"
                ),
                Some(format!(
                    "use {} ({lo} x {lo}) or {} ({} x {}); the path integrator takes any number",
                    lo * lo,
                    (lo + 1) * (lo + 1),
                    lo + 1,
                    lo + 1
                )),
            ))
        } else {
            Ok(())
        }
    }

    /// Checks the pixel count, so a huge image is refused instead of exhausting memory.
    pub fn check_pixels(&self, width: u32, height: u32) -> Result<(), (String, Option<String>)> {
        let pixels = width as u64 * height as u64;
        if pixels > self.max_pixels {
            Err((
                format!(
                    "{width} x {height} is {pixels} pixels, more than the {} a render may have; the image alone would need {:.1} GiB",
                    self.max_pixels,
                    pixels as f64 * Self::BYTES_PER_PIXEL as f64 / GIB
                ),
                Some("make it smaller, or raise the limit with --max-pixels".into()),
            ))
        } else {
            Ok(())
        }
    }

    /// Checks the longest ray chain.
    pub fn check_depth(&self, depth: u32) -> Result<(), (String, Option<String>)> {
        if depth == 0 || depth > self.max_depth {
            Err((
                format!(
                    "must be between 1 (camera rays only) and {}, not {depth}",
                    self.max_depth
                ),
                (depth > self.max_depth).then(|| "raise the limit with --max-depth".to_string()),
            ))
        } else {
            Ok(())
        }
    }

    /// Bytes a render keeps per pixel, the larger of the two ways: the path tracer's film
    /// of sums (a 36-byte `FilmPixel`), or Whitted's film of colours and the finished
    /// tiles kept for checkpoints (16 bytes each); then the finished image (16) and the
    /// encoded output (4).
    pub const BYTES_PER_PIXEL: u64 = 36 + 16 + 4;
}

const GIB: f64 = (1u64 << 30) as f64;

/// Memory a render of `scene` at its settings needs, roughly, in bytes: the image (see
/// [`Limits::BYTES_PER_PIXEL`]), the meshes and BVHs, and the decoded textures.
pub fn memory_estimate(scene: &Scene) -> MemoryEstimate {
    let s = &scene.settings;
    MemoryEstimate {
        image: s.width as u64 * s.height as u64 * Limits::BYTES_PER_PIXEL,
        geometry: (scene.stats.bvh_bytes + scene.stats.mesh_bytes) as u64,
        textures: scene.textures.iter().map(|t| t.bytes() as u64).sum(),
    }
}

/// What a render will take in memory, by part.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// Film, tiles and output.
    pub image: u64,
    /// Meshes and BVHs.
    pub geometry: u64,
    /// Decoded image textures.
    pub textures: u64,
}

impl MemoryEstimate {
    /// All of it.
    pub fn total(&self) -> u64 {
        self.image + self.geometry + self.textures
    }

    /// Refuses the render when it would need more than `available` bytes, with the estimate.
    pub fn check(&self, available: u64) -> Result<(), String> {
        if self.total() > available {
            Err(format!(
                "this render would need about {:.1} GiB (image {:.1} GiB, meshes and BVHs {:.1} GiB, textures {:.1} GiB), but only {:.1} GiB of memory is available",
                self.total() as f64 / GIB,
                self.image as f64 / GIB,
                self.geometry as f64 / GIB,
                self.textures as f64 / GIB,
                available as f64 / GIB
            ))
        } else {
            Ok(())
        }
    }
}

/// Memory the system can still give (Linux's `MemAvailable`); `None` where unknown.
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
