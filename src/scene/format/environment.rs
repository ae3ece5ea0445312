//! `[environment]`: light from every direction, far away: an equirectangular image, a
//! daylight sky, or one colour.

use super::{ColorDef, V3};
use schemars::JsonSchema;
use serde::Deserialize;

/// `[environment]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum EnvironmentDef {
    /// A latitude-longitude (equirectangular) image: Radiance `.hdr`, OpenEXR, or an 8-bit
    /// image (read as sRGB). Its top row is straight up (+y), its centre column lies toward
    /// -z, and u grows toward +x.
    Image {
        /// Path, relative to the scene file's folder.
        file: String,
        /// Turns the image about the world's axes, in degrees (about x, then y, then z):
        /// `[0, 90, 0]` brings what faced -z to face -x.
        #[serde(default)]
        rotate: V3,
        /// Multiplies the image's values (a number or a colour; default 1).
        #[serde(default = "unit")]
        scale: ColorDef,
        /// Whether the camera sees it (otherwise camera rays see `[image] background`); it
        /// lights the scene either way. Default true.
        #[serde(default = "yes")]
        visible: bool,
    },
    /// A clear daylight sky (Preetham et al. 1999) with the sun's disk, placed by
    /// `sun_direction`, by `sun_elevation` and `sun_azimuth`, or by `latitude`, `day` and
    /// `hour` (one of the three).
    Sky {
        /// Unit direction toward the sun (at or above the horizon, `y >= 0`).
        #[serde(default)]
        sun_direction: Option<V3>,
        /// The sun's height above the horizon, degrees, 0 to 90.
        #[serde(default)]
        sun_elevation: Option<f32>,
        /// The sun's bearing, degrees from north (-z) toward east (+x); default 180 (south).
        #[serde(default)]
        sun_azimuth: Option<f32>,
        /// Degrees north of the equator, -90 to 90 (with `day` and `hour`).
        #[serde(default)]
        latitude: Option<f32>,
        /// Degrees east of Greenwich, -180 to 180; default 0.
        #[serde(default)]
        longitude: Option<f32>,
        /// Hours east of UTC of the clock `hour` reads, -12 to 14; default 0.
        #[serde(default)]
        timezone: Option<f32>,
        /// Day of the year, 1 to 366.
        #[serde(default)]
        day: Option<f32>,
        /// Clock time, hours, 0 to 24 (16.5 is half past four).
        #[serde(default)]
        hour: Option<f32>,
        /// Haze, 2 (very clear) to 10 (hazy); default 3.
        #[serde(default = "three")]
        turbidity: f32,
        /// Multiplies the sky and the sun; default 1 (1 in the image is 20 000 cd/m²).
        #[serde(default = "one")]
        scale: f32,
        /// Multiplies the sun alone; 0 leaves only the sky. Default 1.
        #[serde(default = "one")]
        sun_scale: f32,
        /// The sun's angular diameter, degrees, greater than 0 and at most 30; a larger sun
        /// gives the same light with softer shadows. Default 0.533.
        #[serde(default = "sun_size")]
        sun_size: f32,
        /// Whether the camera sees it (otherwise camera rays see `[image] background`).
        #[serde(default = "yes")]
        visible: bool,
    },
    /// The same radiance from every direction.
    Constant {
        /// The radiance, linear RGB.
        color: ColorDef,
        /// Whether the camera sees it (otherwise camera rays see `[image] background`).
        #[serde(default = "yes")]
        visible: bool,
    },
}

fn unit() -> ColorDef {
    ColorDef([1.0; 3])
}

fn three() -> f32 {
    3.0
}

fn one() -> f32 {
    1.0
}

fn sun_size() -> f32 {
    crate::light::sky::SUN_DIAMETER_DEG as f32
}

fn yes() -> bool {
    true
}
