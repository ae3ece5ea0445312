//! `[environment]`: light from every direction, far away: an equirectangular image or one
//! colour.

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

fn yes() -> bool {
    true
}
