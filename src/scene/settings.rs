//! A scene's settings beside its contents: the image and sampling (`[image]`, which the
//! command line may override), the integrator's (`[integrator]`) and fog (`[fog]`), with
//! the check on an image side that loading and the command line share.

use super::IntegratorKind;
use crate::film::Filter;
use crate::math::Color;

/// Render settings from the scene's `[image]` table (the command line may override them).
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel, a square number.
    pub spp: u32,
    /// Longest chain of rays, the camera ray included.
    pub max_depth: u32,
    /// Seed of the sample jitter.
    pub seed: u64,
    /// Reconstruction filter.
    pub filter: Filter,
    /// The integrator and its settings.
    pub integrator: IntegratorSettings,
    /// Exposure and tone curve of 8-bit outputs.
    pub tone: crate::output::tone::Tone,
    /// Whether camera rays carry differentials, so textures are filtered over each
    /// pixel's footprint.
    pub filter_textures: bool,
    /// Adaptive sampling's threshold: pixels stop taking samples once their relative error
    /// is below it (`spp` then the most they take); `None` samples every pixel alike.
    pub noise: Option<f32>,
}

/// Which integrator renders, and the path tracer's settings (`[integrator]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegratorSettings {
    /// Whitted or path.
    pub kind: IntegratorKind,
    /// The path tracer's sampler.
    pub sampler: crate::sampler::SamplerKind,
    /// Depth (segments, the camera ray 1) from which Russian roulette may end a path.
    pub rr_depth: u32,
    /// The most a sample may add to a pixel, per channel; `None`: no clamp.
    pub clamp: Option<f32>,
    /// How bidirectional path tracing weighs its strategies.
    pub mis: super::MisHeuristic,
}

impl Default for IntegratorSettings {
    fn default() -> Self {
        IntegratorSettings {
            kind: IntegratorKind::Whitted,
            sampler: crate::sampler::SamplerKind::Sobol,
            rr_depth: 5,
            clamp: None,
            mis: super::MisHeuristic::Power,
        }
    }
}

impl RenderSettings {
    /// Largest image side accepted (pixel coordinates must stay exact in an `f32`).
    pub const MAX_SIDE: u32 = 65_536;

    /// Checks an adaptive sampling threshold: a relative error, above 0 and at most 1.
    pub fn check_noise(v: f32) -> Result<(), String> {
        if v.is_finite() && v > 0.0 && v <= 1.0 {
            Ok(())
        } else {
            Err(format!(
                "the noise threshold is a relative error above 0 and at most 1 (0.01 is 1 %), not {v}"
            ))
        }
    }

    /// Checks an image side.
    pub fn check_side(what: &str, v: u32) -> Result<(), String> {
        if v == 0 || v > Self::MAX_SIDE {
            Err(format!(
                "{what} must be between 1 and {} pixels, not {v}",
                Self::MAX_SIDE
            ))
        } else {
            Ok(())
        }
    }
}

/// Fog over distance travelled outside solids.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fog {
    /// Fog fraction rises linearly from 0 at `start` to 1 at `end`.
    Linear {
        /// Colour of full fog.
        color: Color,
        /// Distance where it starts.
        start: f32,
        /// Distance where it is complete.
        end: f32,
    },
    /// Fog fraction `1 - exp(-density * (distance - start))` beyond `start`.
    Exponential {
        /// Colour of full fog.
        color: Color,
        /// Distance where it starts.
        start: f32,
        /// Per scene unit.
        density: f32,
    },
}

impl Fog {
    /// Blends `c`, seen from `distance` away, toward the fog colour.
    #[inline]
    pub fn apply(&self, c: Color, distance: f32) -> Color {
        let (fog, f) = match *self {
            Fog::Linear { color, start, end } => {
                (color, ((distance - start) / (end - start)).clamp(0.0, 1.0))
            }
            Fog::Exponential {
                color,
                start,
                density,
            } => (color, 1.0 - (-density * (distance - start).max(0.0)).exp()),
        };
        c.lerp(fog, f)
    }
}
